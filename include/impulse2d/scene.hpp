// Scenes: the contract's YAML schema as plain data, its parser, and adding a scene to a world.
// ROS-free (yaml-cpp is used only inside the implementation).
#pragma once

#include <impulse2d/defs.hpp>
#include <impulse2d/device_defs.hpp>
#include <impulse2d/world.hpp>

#include <string>
#include <vector>

namespace impulse2d {

/// A joint as a scene names it: bodies by name instead of by id.
struct SceneJoint {
  JointDef def;  ///< bodyA/bodyB are left invalid; the names below are resolved on adding
  std::string bodyA;
  std::string bodyB;
  bool hasLength = false;  ///< distance joints: `length` given, else the current distance
};

struct Scene {
  WorldDef world;
  std::string plane = "xz";  ///< xz: vertical plane (2D y -> 3D z); xy: top-down
  std::string frameId = "world";
  std::vector<BodyDef> bodies;
  std::vector<SceneJoint> joints;
  /// Devices attached to bodies of the scene or the world (device_defs.hpp). The world does not
  /// run them: a DeviceSet (devices.hpp) does, in the node and in impulse2d_sim.
  std::vector<DeviceDef> devices;
};

/// Parses and validates YAML text against the schema. On failure returns false and sets `error`
/// to one line naming the key and the body or joint, e.g.
///   "bodies[3] 'box3': shapes[0].size: must be two numbers > 0".
bool parseScene(const std::string& yamlText, Scene* out, std::string* error);
bool loadSceneFile(const std::string& path, Scene* out, std::string* error);

/// Adds every body and joint of `scene` to `world`, or nothing: names must not clash with bodies
/// or joints already in the world, and joints and devices may name bodies of the scene or of the
/// world (a diff_drive's must be dynamic). The devices are only checked here, not created.
/// The scene's `world:` settings are not applied here: `world.settings() = scene.world` does that.
bool addScene(const Scene& scene, World& world, std::string* error,
              std::vector<BodyId>* createdBodies = nullptr,
              std::vector<JointId>* createdJoints = nullptr);

}  // namespace impulse2d
