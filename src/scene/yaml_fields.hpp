// Strict, typed access to the keys of one YAML map of a scene: unknown or repeated keys and values
// of the wrong type throw SceneError naming the key, so nothing is silently ignored.
#pragma once

#include <impulse2d/math.hpp>

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace impulse2d {
namespace scene_detail {

/// One reason a scene is refused: the key path ("shapes[0].size", empty for the map itself) and
/// why. The loader adds the "bodies[i] 'name': " context on the way out.
class SceneError : public std::runtime_error {
 public:
  SceneError(const std::string& key, const std::string& reason)
      : std::runtime_error(key.empty() ? reason : key + ": " + reason),
        key_(key),
        reason_(reason) {}
  /// The same error seen from the enclosing map, e.g. "size" within "shapes[0]".
  SceneError within(const std::string& parent) const {
    return SceneError(key_.empty() ? parent : parent + "." + key_, reason_);
  }

 private:
  std::string key_;
  std::string reason_;
};

class Fields {
 public:
  /// `node` must be a map (or null, read as empty) whose keys are all in `allowed`; merge keys
  /// ("<<") are resolved.
  /// `what` describes the map for the error when it is not one ("a body", "a shape").
  Fields(const YAML::Node& node, const char* what, std::initializer_list<const char*> allowed);

  bool has(const char* key) const { return find(key) != nullptr; }
  /// The value of a present key; throws when it is absent.
  const YAML::Node& node(const char* key) const;

  // Each returns `fallback` when the key is absent and throws when it has the wrong type.
  double number(const char* key, double fallback) const;
  int integer(const char* key, int fallback) const;
  /// A bit set: decimal or 0x-prefixed hexadecimal, at most 64 bits.
  uint64_t bits(const char* key, uint64_t fallback) const;
  bool boolean(const char* key, bool fallback) const;
  std::string string(const char* key, const std::string& fallback) const;
  Vec2 vec2(const char* key, const Vec2& fallback) const;
  Eigen::Vector3d vec3(const char* key, const Eigen::Vector3d& fallback) const;
  /// A required body, joint or frame name (see checkName).
  std::string name(const char* key) const;
  std::vector<Vec2> points(const char* key) const;

 private:
  void add(const YAML::Node& map, std::initializer_list<const char*> allowed, bool merged,
           int* mergeBudget);
  const YAML::Node* find(const char* key) const;

  std::vector<std::pair<std::string, YAML::Node>> entries_;
};

/// A YAML scalar as a number: decimal or scientific notation and YAML's .inf/.nan spellings.
bool toNumber(const YAML::Node& node, double* out);

}  // namespace scene_detail
}  // namespace impulse2d
