// The ~markers topic: body outlines, names, contact points and normals, and joints, for RViz.
#pragma once

#include "conversions.hpp"
#include "sim_world.hpp"

#include <ros/time.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>
#include <vector>

namespace impulse2d {
namespace bridge {

struct MarkerInput {
  Plane plane = Plane::XZ;
  std::string frameId = "world";
  ros::Time stamp;
  double timeStep = 0.01;  ///< turns contact impulses into forces for the normals' lengths
  std::vector<BodySnapshot> bodies;  ///< with shapes
  std::vector<ContactSnapshot> contacts;
  std::vector<JointSnapshot> joints;
};

/// Starts with a DELETEALL so bodies that are gone vanish, then one marker per body in
/// namespace "bodies" (LINE_LIST, id = body slot; grey static, orange kinematic, green awake,
/// blue asleep), its name in "names" (TEXT_VIEW_FACING), contact points in "contact_points"
/// (SPHERE_LIST), contact normals in "contact_normals" (LINE_LIST, 0.1 m + 1 cm per newton of
/// normal force, at most 1 m) and joints in "joints" (LINE_LIST) and "joint_anchors" (SPHERE_LIST).
visualization_msgs::MarkerArray buildMarkers(const MarkerInput& in);

}  // namespace bridge
}  // namespace impulse2d
