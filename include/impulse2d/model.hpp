// Models: one file of bodies, joints and devices placed once per robot, each under its own name
// and namespace (scene.hpp's `models:` and placeModel, the node's ~spawn_model). Plain data,
// apart from the scene so that the node's headers may hold it.
#pragma once

#include <impulse2d/math.hpp>

#include <string>
#include <vector>

namespace impulse2d {

/// Where a model goes and under which names (`models:`, the node's ~spawn_model).
struct ModelPlacement {
  std::string name;  ///< unique among the world's models
  /// "": the name. The model's bodies, joints and devices are named NS/..., its relative topics
  /// become /NS/..., its frames NS/... (a drive's odom frame, a laser's frame).
  std::string ns;
  Vec2 position = Vec2::Zero();  ///< m: the model's frame in the world
  double angle = 0.0;            ///< rad
};

/// A model placed in a scene: what the node's ~delete_model and ~move_model act on.
struct SceneModel {
  std::string name;
  std::string ns;
  std::string file;  ///< as resolved; "" for YAML text
  /// Its bodies, joints and devices as the world names them (NS/...), in the file's order.
  std::vector<std::string> bodies, joints, devices;
  /// Each body's pose in the model's frame, as the file gives it (move_model places the first
  /// body that is left by it).
  std::vector<Vec2> localPositions;
  std::vector<double> localAngles;
};

}  // namespace impulse2d
