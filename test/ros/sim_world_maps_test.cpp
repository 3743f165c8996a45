// SimWorld's followed map (~map_topic) without a master: each grid's walls replace the last
// grid's, and only those: a user's body that took a deleted wall's name stays.
#include "../../src/ros/sim_world.hpp"

#include <gtest/gtest.h>

namespace impulse2d {
namespace bridge {
namespace {

// A 4 x 4 grid of 1 m cells at the origin with its left column occupied.
OccupancyGrid leftWall() {
  OccupancyGrid grid;
  grid.width = 4;
  grid.height = 4;
  grid.resolution = 1.0;
  grid.data.assign(16, 0);
  for (int row = 0; row < 4; ++row) grid.data[static_cast<size_t>(row) * 4] = 100;
  return grid;
}

TEST(SimWorldMaps, AFollowedGridReplacesItsOwnWallsOnly) {
  SimWorld sim;
  std::string error;
  ASSERT_TRUE(sim.loadStartScene("world: {plane: xy, gravity: [0, 0]}\n", &error)) << error;
  ASSERT_TRUE(sim.followMap("slam", leftWall(), &error)) << error;
  ASSERT_EQ(sim.bodyCount(), 1u);
  BodySnapshot wall;
  ASSERT_TRUE(sim.getBodyState("slam", &wall, &error)) << error;

  // The user deletes the wall and spawns a body of their own under its name.
  ASSERT_TRUE(sim.deleteBody("slam", &error)) << error;
  BodyDef mine;
  mine.name = "slam";
  mine.position = Vec2(10.0, 10.0);
  ShapeDef box;
  box.size = Vec2(1.0, 1.0);
  mine.shapes.push_back(box);
  ASSERT_TRUE(sim.spawnBody(mine, &error)) << error;

  // The next grid cannot be added under the taken name: it is refused, and the user's body
  // stays where it was.
  EXPECT_FALSE(sim.followMap("slam", leftWall(), &error));
  EXPECT_NE(error.find("slam"), std::string::npos) << error;
  BodySnapshot kept;
  ASSERT_TRUE(sim.getBodyState("slam", &kept, &error)) << error;
  EXPECT_EQ(kept.position, Vec2(10.0, 10.0));
  EXPECT_EQ(sim.bodyCount(), 1u);

  // Under another name the walls come and replace only their predecessors.
  ASSERT_TRUE(sim.followMap("scan_map", leftWall(), &error)) << error;
  ASSERT_TRUE(sim.followMap("scan_map", leftWall(), &error)) << error;
  EXPECT_EQ(sim.bodyCount(), 2u);
  ASSERT_TRUE(sim.getBodyState("slam", &kept, &error)) << error;
  EXPECT_EQ(kept.position, Vec2(10.0, 10.0));
}

}  // namespace
}  // namespace bridge
}  // namespace impulse2d
