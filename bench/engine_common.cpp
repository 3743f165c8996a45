// What every adapter shares: the event groups of a scene and the single-thread refusal.
#include <algorithm>

#include "engine_adapter.hpp"

namespace impulse2d_bench {

SceneGroups::SceneGroups(const SceneSpec& scene) {
  int groups = 0;
  for (const BenchBody& body : scene.bodies) groups = std::max(groups, body.group + 1);
  bodies_.resize(groups + 1);
  joints_.resize(groups + 1);
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    bodies_[scene.bodies[i].group + 1].push_back(static_cast<int>(i));
  }
  for (size_t j = 0; j < scene.joints.size(); ++j) {
    joints_[scene.bodies[scene.joints[j].bodyB].group + 1].push_back(static_cast<int>(j));
  }
}

std::string singleThreadOnly(const std::string& engine, const EngineSettings& settings) {
  if (settings.threads == 1) return "";
  return engine + " runs on one thread only; --threads " + std::to_string(settings.threads) +
         " is refused rather than run single-threaded";
}

}  // namespace impulse2d_bench
