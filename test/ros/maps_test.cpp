// Occupancy maps against the world node or nodelet (maps.test, maps_nodelet.test,
// maps_scene.yaml): the scene's map_server map, found through package://, becomes walls where
// its cells are and is published latched on ~map; a map followed from /slam_map replaces its
// walls with every grid, refuses a malformed one, and stays through ~reset.
#include "world_test_util.hpp"

#include <impulse2d/QueryPoint.h>
#include <impulse2d/RayCast.h>
#include <nav_msgs/OccupancyGrid.h>

#include <cmath>

namespace impulse2d_test {
namespace {

constexpr double kWait = 20.0;

std::vector<std::string> bodiesAt(double x, double y) {
  impulse2d::QueryPoint query;
  query.request.point.x = x;
  query.request.point.y = y;
  EXPECT_TRUE(call("query_point", query) && query.response.success);
  return query.response.bodies;
}

impulse2d::RayCast::Response cast(double x0, double y0, double x1, double y1) {
  impulse2d::RayCast ray;
  ray.request.start.x = x0;
  ray.request.start.y = y0;
  ray.request.end.x = x1;
  ray.request.end.y = y1;
  EXPECT_TRUE(call("ray_cast", ray) && ray.response.success);
  return ray.response;
}

// A 10 x 10 grid of 0.5 m cells at (10, 10), free but for column `wall`.
nav_msgs::OccupancyGrid slamGrid(int wall) {
  nav_msgs::OccupancyGrid grid;
  grid.header.frame_id = "world";
  grid.info.resolution = 0.5;
  grid.info.width = 10;
  grid.info.height = 10;
  grid.info.origin.position.x = 10.0;
  grid.info.origin.position.y = 10.0;
  grid.info.origin.orientation.w = 1.0;
  grid.data.assign(100, 0);
  for (int y = 0; y < 10; ++y) grid.data[10 * y + wall] = 100;
  return grid;
}

TEST(Maps, TheScenesMapIsWallsWhereItsCellsAre) {
  // The east wall's inner face: the last column starts at -2 + 39 x 0.1 = 1.9 m.
  const impulse2d::RayCast::Response east = cast(0.0, 0.0, 5.0, 0.0);
  ASSERT_TRUE(east.hit);
  EXPECT_EQ(east.body.rfind("room", 0), 0u) << east.body;
  EXPECT_NEAR(east.point.x, 1.9, 1e-9);
  // The pillar: x 0.5..0.9, y 0.1..0.5.
  const impulse2d::RayCast::Response pillar = cast(0.0, 0.3, 5.0, 0.3);
  EXPECT_NEAR(pillar.point.x, 0.5, 1e-9);
  EXPECT_EQ(bodiesAt(0.7, 0.3).size(), 1u);
  EXPECT_TRUE(bodiesAt(0.7, 0.6).empty());
}

TEST(Maps, TheMapIsPublishedLatchedForRViz) {
  Latest<nav_msgs::OccupancyGrid> map(worldNs() + "/map");
  ASSERT_TRUE(waitFor([&] { return map.get() != nullptr; }, kWait));
  const nav_msgs::OccupancyGrid::ConstPtr grid = map.get();
  EXPECT_EQ(grid->header.frame_id, "world");
  // Either the scene's room or, if the following test ran first, the followed grid.
  if (grid->info.width == 40) {
    EXPECT_EQ(grid->info.height, 30u);
    EXPECT_NEAR(grid->info.resolution, 0.1, 1e-7);
    EXPECT_EQ(grid->info.origin.position.x, -2.0);
    EXPECT_EQ(grid->info.origin.position.y, -1.5);
    ASSERT_EQ(grid->data.size(), 1200u);
    EXPECT_EQ(grid->data[0], 100);             // the bottom-left corner: wall
    EXPECT_EQ(grid->data[40 + 1], 0);          // inside
    EXPECT_EQ(grid->data[40 * 17 + 26], 100);  // the pillar
  } else {
    EXPECT_EQ(grid->info.width, 10u);
  }
}

TEST(Maps, AFollowedMapReplacesItsWallsRefusesBadGridsAndOutlivesAReset) {
  ros::NodeHandle nh;
  ros::Publisher slam = nh.advertise<nav_msgs::OccupancyGrid>("/slam_map", 1, true);
  Latest<nav_msgs::OccupancyGrid> map(worldNs() + "/map");
  // Column 2's centre: x = 10 + 2.25, y anywhere in 10..15.
  slam.publish(slamGrid(2));
  ASSERT_TRUE(waitFor([&] { return !bodiesAt(11.25, 12.0).empty(); }, kWait));
  EXPECT_EQ(bodiesAt(11.25, 12.0), std::vector<std::string>{"slam"});
  ASSERT_TRUE(waitFor([&] { return map.get() && map.get()->info.width == 10; }, kWait));
  // A new grid moves the wall to column 6; the old one is gone.
  slam.publish(slamGrid(6));
  ASSERT_TRUE(waitFor([&] { return !bodiesAt(13.25, 12.0).empty(); }, kWait));
  EXPECT_TRUE(bodiesAt(11.25, 12.0).empty());
  // A grid whose data does not match its size is refused: the walls stay.
  nav_msgs::OccupancyGrid bad = slamGrid(8);
  bad.data.resize(7);
  slam.publish(bad);
  ros::WallDuration(1.0).sleep();
  EXPECT_FALSE(bodiesAt(13.25, 12.0).empty());
  EXPECT_TRUE(bodiesAt(14.25, 12.0).empty());
  // ~reset restores the scene and puts the followed walls back.
  emptyCall("reset");
  EXPECT_EQ(bodiesAt(13.25, 12.0), std::vector<std::string>{"slam"});
  EXPECT_EQ(bodiesAt(0.7, 0.3).size(), 1u);
}

}  // namespace
}  // namespace impulse2d_test
