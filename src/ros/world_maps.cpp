// WorldNode's maps: package:// for the scenes' map files, ~map (the map as RViz's Map display
// reads it, latched) and a map topic to follow (~map_topic), whose grids become walls.
#include "world_node.hpp"

#include <ros/package.h>

#include <Eigen/Geometry>

#include <cmath>

namespace impulse2d {
namespace bridge {
namespace {

nav_msgs::OccupancyGrid toMsg(const OccupancyGrid& grid, const std::string& frame,
                              const ros::Time& stamp) {
  nav_msgs::OccupancyGrid msg;
  msg.header.frame_id = frame;
  msg.header.stamp = stamp;
  msg.info.map_load_time = stamp;
  msg.info.resolution = static_cast<float>(grid.resolution);
  msg.info.width = static_cast<uint32_t>(grid.width);
  msg.info.height = static_cast<uint32_t>(grid.height);
  msg.info.origin.position.x = grid.origin.x();
  msg.info.origin.position.y = grid.origin.y();
  msg.info.origin.orientation.z = std::sin(0.5 * grid.originYaw);
  msg.info.origin.orientation.w = std::cos(0.5 * grid.originYaw);
  msg.data = grid.data;
  return msg;
}

OccupancyGrid fromMsg(const nav_msgs::OccupancyGrid& msg) {
  OccupancyGrid grid;
  grid.width = static_cast<int>(std::min<uint32_t>(msg.info.width, 1u << 30));
  grid.height = static_cast<int>(std::min<uint32_t>(msg.info.height, 1u << 30));
  grid.resolution = msg.info.resolution;
  grid.origin = Vec2(msg.info.origin.position.x, msg.info.origin.position.y);
  const geometry_msgs::Quaternion& q = msg.info.origin.orientation;
  // The yaw of the origin's orientation (a map lies in the floor's plane).
  grid.originYaw = std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
  grid.data = msg.data;
  return grid;
}

}  // namespace

void WorldNode::setUpMaps() {
  sim_.setPackageFinder([](const std::string& package, std::string* error) {
    const std::string folder = ros::package::getPath(package);
    if (folder.empty()) *error = "no ROS package named '" + package + "' (ROS_PACKAGE_PATH)";
    return folder;
  });
}

void WorldNode::advertiseMaps() {
  mapPub_ = pnh_.advertise<nav_msgs::OccupancyGrid>("map", 1, true);
  std::string topic;
  pnh_.param<std::string>("map_topic", topic, "");
  pnh_.param<std::string>("map_name", followedMapName_, "map");
  if (topic.empty()) return;
  if (nh_.resolveName(topic) == pnh_.resolveName("map")) {
    ROS_ERROR("[%s] ~map_topic: %s is this node's own ~map; not following it", name_.c_str(),
              topic.c_str());
    return;
  }
  mapSub_ = nh_.subscribe(topic, 1, &WorldNode::onMap, this);
}

void WorldNode::onMap(const nav_msgs::OccupancyGrid::ConstPtr& msg) {
  std::string error;
  {
    Lock lock(*this);
    sim_.followMap(followedMapName_, fromMsg(*msg), &error);
  }
  if (!error.empty()) {
    ROS_WARN("[%s] ~map_topic: %s; the world keeps its walls", name_.c_str(), error.c_str());
  }
}

void WorldNode::publishMap() {
  nav_msgs::OccupancyGrid msg;
  {
    Lock lock(*this);
    if (mapPublished_ && sim_.mapVersion() == publishedMapVersion_) return;
    publishedMapVersion_ = sim_.mapVersion();
    mapPublished_ = true;
    const LoadedMap* map = sim_.latestMap();
    // A grid lies in the xy plane: a side view's map is not one RViz could overlay.
    if (map == nullptr || sim_.plane() != "xy") return;
    msg = toMsg(map->grid, sim_.frameId(), stampFor(sim_.simTimeNs()));
  }
  mapPub_.publish(msg);
}

}  // namespace bridge
}  // namespace impulse2d
