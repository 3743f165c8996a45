// Scenes: the contract's YAML schema as plain data, its parser, and adding a scene to a world.
// ROS-free (yaml-cpp is used only inside the implementation).
#pragma once

#include <impulse2d/defs.hpp>
#include <impulse2d/device_defs.hpp>
#include <impulse2d/model.hpp>
#include <impulse2d/occupancy_map.hpp>
#include <impulse2d/world.hpp>

#include <functional>
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

/// One entry of `maps:`: an occupancy map in map_server's format as static walls.
struct SceneMap {
  std::string name;  ///< its first body's; the others are name/1, name/2, ...
  std::string file;  ///< the map_server YAML, as resolved
  OccupancyGrid grid;
  size_t bodies = 0;  ///< how many of the scene's bodies are this map's
};

/// Where a scene's files are found.
struct ScenePaths {
  /// Relative file names are read from here ("": the working directory).
  std::string folder;
  /// The folder of a ROS package, for package://PACKAGE/...; empty with `error` set when there is
  /// none. Without it, package:// names are refused.
  std::function<std::string(const std::string& package, std::string* error)> findPackage;
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
  /// Occupancy maps (`maps:`): their walls are static bodies at the end of `bodies`.
  std::vector<SceneMap> maps;
  /// Models (`models:`): their bodies, joints and devices are in the lists above, placed.
  std::vector<SceneModel> models;
};

/// Parses and validates YAML text against the schema. On failure returns false and sets `error`
/// to one line naming the key and the body or joint, e.g.
///   "bodies[3] 'box3': shapes[0].size: must be two numbers > 0".
bool parseScene(const std::string& yamlText, Scene* out, std::string* error);
/// The same, with the files it names (maps) found through `paths`.
bool parseScene(const std::string& yamlText, const ScenePaths& paths, Scene* out,
                std::string* error);
/// Reads a scene file; the files it names are relative to its folder.
bool loadSceneFile(const std::string& path, Scene* out, std::string* error);
/// The same, with `findPackage` for package:// names (paths.folder is the file's own).
bool loadSceneFile(const std::string& path, const ScenePaths& paths, Scene* out,
                   std::string* error);
/// A file name as scenes give them: absolute, relative to paths.folder, or
/// package://PACKAGE/PATH; "" with `error` set when it cannot be resolved.
std::string resolveSceneFile(const std::string& name, const ScenePaths& paths, std::string* error);
/// A package finder without ROS (impulse2d_sim): for the first entry E of $ROS_PACKAGE_PATH
/// (colon-separated, as a sourced workspace sets it) where E/PACKAGE/package.xml exists, or
/// whose own package.xml names PACKAGE, that folder; else "" with `error` set.
std::string findPackageOnPath(const std::string& package, std::string* error);

/// Reads a model: YAML with a scene's `bodies`, `joints` and `devices` (no `world`, `maps` or
/// `models`), every body named; joints and devices name the model's own bodies.
bool parseModel(const std::string& yamlText, Scene* out, std::string* error);
/// Reads a model file.
bool loadModelFile(const std::string& path, Scene* out, std::string* error);
/// Appends `model` to `scene` as `where` places it: names prefixed, poses, velocities, joint
/// anchors and axes carried by the model's pose, relative topics and frames put in its
/// namespace; recorded in scene->models. Refused, with `scene` unchanged, when the model's name
/// is taken by a model of the scene, or a body, joint or device name by the scene's.
bool placeModel(const Scene& model, const ModelPlacement& where, Scene* scene, std::string* error,
                const std::string& file = "");

/// Adds every body and joint of `scene` to `world`, or nothing: names must not clash with bodies
/// or joints already in the world, and joints and devices may name bodies of the scene or of the
/// world (a diff_drive's must be dynamic). The devices are only checked here, not created.
/// The scene's `world:` settings are not applied here: `world.settings() = scene.world` does that.
bool addScene(const Scene& scene, World& world, std::string* error,
              std::vector<BodyId>* createdBodies = nullptr,
              std::vector<JointId>* createdJoints = nullptr);

}  // namespace impulse2d
