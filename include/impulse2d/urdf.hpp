// URDF robot descriptions projected onto the world's plane, as a Scene that addScene() adds
// all or nothing. ROS-free: urdfdom parses the text, and no file is ever read (meshes are
// skipped, not loaded). README "URDF" documents the mapping.
#pragma once

#include <impulse2d/defs.hpp>
#include <impulse2d/scene.hpp>

#include <Eigen/Geometry>

#include <functional>
#include <string>
#include <vector>

namespace impulse2d {

/// Where and under which name a URDF model goes.
struct UrdfPlacement {
  std::string modelName;         ///< prefix of every body and joint: "model_name/link"
  Vec2 position = Vec2::Zero();  ///< m, the model's root frame in the world
  double angle = 0.0;            ///< rad
  std::string plane = "xz";      ///< the world's plane: "xz" (normal 3D y) or "xy" (normal z)
  /// Top-down worlds (xy): false folds a link that turns about an axis in the floor's plane (a
  /// wheel) into its parent body; true refuses such a model, as the xz plane always does.
  bool strict = false;
  /// The folder of a ROS package, for collision meshes named package://PACKAGE/PATH (read with
  /// assimp, their footprints become polygons); "" with `error` set when there is none. Unset,
  /// meshes are skipped with a warning. Meshes named otherwise (file://, relative) are never read.
  std::function<std::string(const std::string& package, std::string* error)> findPackage;
};

/// A revolute or prismatic URDF joint as created in the world, for joint_states and commands.
struct UrdfJointInfo {
  std::string name;  ///< the world's joint name, "model_name/joint"
  JointType type = JointType::Revolute;
  /// URDF position = sign * the world joint's position (and likewise velocity and motor speed):
  /// -1 when a revolute axis points against the plane's counter-clockwise normal.
  double sign = 1.0;
  double maxEffort = 0.0;    ///< N m or N from <limit effort>; 0 when not given
  double maxVelocity = 0.0;  ///< rad/s or m/s from <limit velocity>; 0 when not given
};

/// A revolute or continuous joint about an axis in the floor's plane (a wheel's, a tilting
/// sensor's) that a top-down world folded into its parent body: rigid in the world, still listed
/// in joint_states with the position its wheel would have rolled to.
struct UrdfFoldedJoint {
  std::string name;  ///< "model_name/joint"
  std::string body;  ///< the body it was folded into ("model_name/top_link")
  std::string link;  ///< its child link's frame ("model_name/link")
  /// The child link's frame in the body's 3D frame at joint position 0, and the joint's axis in
  /// that frame (the URDF's, a unit vector): at position q the link's frame is
  /// pose * rotation(axis, q).
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  /// Where the wheel turns: its centre in the body frame (2D) and its axis there (2D, unit).
  Vec2 center = Vec2::Zero();
  Vec2 planeAxis = Vec2::UnitY();
  /// m: the radius of a cylinder of the link coaxial with the joint (a wheel), which rolls; 0
  /// for anything else (a caster's sphere, a tilting sensor), which stays at position 0.
  double wheelRadius = 0.0;
};

/// The frame of a link that is no body of its own, for tf: a link merged into a body by a fixed
/// joint, the root link named "world", and links fixed to it without collision geometry. Only
/// bodies lie in the plane (their top link's offset along the normal is dropped); such a link
/// keeps its URDF pose relative to its body (or to the world link), offset along the normal and
/// roll and pitch included, so that RViz's RobotModel draws each rigid part as the URDF builds
/// it.
struct UrdfFrame {
  std::string name;  ///< "model_name/link"
  /// The body it is fixed to ("model_name/top_link"); empty: fixed to the world.
  std::string body;
  /// The link's frame in the body's 3D frame (the body's tf frame), or in the world frame's.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

struct UrdfModel {
  /// Bodies and joints, names prefixed; plane and frame as placed, world settings default.
  Scene scene;
  std::vector<UrdfJointInfo> joints;
  /// Joints a top-down world folded into rigid bodies (UrdfPlacement::strict).
  std::vector<UrdfFoldedJoint> folded;
  /// Frames of the links that are not bodies (UrdfFrame); skipped links have none.
  std::vector<UrdfFrame> frames;
  /// What was left out (meshes, links without collision geometry, mimic tags), one line each.
  std::vector<std::string> warnings;
};

/// Parses URDF text and projects it onto the plane. On failure returns false and sets `error` to
/// one line naming the link or joint, e.g. "joint 'elbow': axis (1 0 0) lies in the xz plane; a
/// revolute joint must turn about the plane normal (3D y)".
bool parseUrdf(const std::string& urdfXml, const UrdfPlacement& placement, UrdfModel* out,
               std::string* error);

}  // namespace impulse2d
