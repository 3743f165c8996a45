// Shared by the hard-case suites: load a scene of test/scenes/ under a given solver, measure how
// far it moved, and print one "hard-case:" line per case and solver, which the README's table of
// solvers quotes.
#pragma once

#include <gtest/gtest.h>
#include <impulse2d/scene.hpp>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

namespace impulse2d {
namespace hard_case {

inline constexpr const auto& kSolvers = kAllSolvers;

/// Solvers that sub-step: the ones that hold the largest cases.
inline bool holdsLargeCases(SolverType solver) { return usesSubsteps(solver); }

/// Loads test/scenes/NAME into `world` with the scene's settings and the given solver.
inline void load(const std::string& name, SolverType solver, World& world) {
  Scene scene;
  std::string error;
  const std::string path = std::string(IMPULSE2D_SOURCE_DIR) + "/test/scenes/" + name;
  ASSERT_TRUE(loadSceneFile(path, &scene, &error)) << error;
  world.settings() = scene.world;
  world.settings().solver = solver;
  ASSERT_TRUE(addScene(scene, world, &error)) << error;
}

inline void report(const std::string& scene, SolverType solver, const std::string& figures) {
  std::printf("hard-case: %s %s %s\n", scene.c_str(), solverName(solver), figures.c_str());
}

inline std::map<std::string, Vec2> positions(const World& world) {
  std::map<std::string, Vec2> out;
  for (BodyId id : world.bodies()) {
    if (world.body(id).type == BodyType::Dynamic) out[world.body(id).name] = world.body(id).xf.p;
  }
  return out;
}

inline bool allFinite(const World& world) {
  for (BodyId id : world.bodies()) {
    const Body& b = world.body(id);
    if (!isFinite(b.xf.p) || !std::isfinite(b.angle) || !isFinite(b.linearVelocity)) return false;
  }
  return true;
}

inline double deepestPenetration(const World& world) {
  double deepest = 0.0;
  for (const ContactInfo& c : world.contacts()) deepest = std::max(deepest, -c.separation);
  return deepest;
}

struct Drift {
  double sideways = 0.0, down = 0.0, total = 0.0;
};

inline Drift driftSince(const std::map<std::string, Vec2>& start, const World& world) {
  Drift d;
  for (const auto& [name, p] : positions(world)) {
    const Vec2 delta = p - start.at(name);
    d.sideways = std::max(d.sideways, std::abs(delta.x()));
    d.down = std::max(d.down, -delta.y());
    d.total = std::max(d.total, delta.norm());
  }
  return d;
}

inline void run(World& world, double seconds) {
  while (world.time() < seconds - 1e-9) world.step();
}

inline std::string figures(const char* format, double a, double b = 0.0, double c = 0.0) {
  char text[256];
  std::snprintf(text, sizeof(text), format, a, b, c);
  return text;
}

}  // namespace hard_case
}  // namespace impulse2d
