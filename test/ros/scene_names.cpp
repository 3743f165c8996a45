// Reads a scene's body names with the engine's own loader (see scene_names.hpp).
#include "scene_names.hpp"

#include <impulse2d/scene.hpp>

namespace impulse2d_test {

std::vector<std::string> sceneBodyNames(const std::string& path) {
  impulse2d::Scene scene;
  std::string error;
  std::vector<std::string> names;
  if (!impulse2d::loadSceneFile(path, &scene, &error)) return names;
  for (const impulse2d::BodyDef& body : scene.bodies) names.push_back(body.name);
  return names;
}

}  // namespace impulse2d_test
