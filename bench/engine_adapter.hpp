// One interface for every engine the benchmark drives: build a SceneSpec, step it, read the bodies
// back. Box2D and Chipmunk adapters are compiled in only when their libraries were found.
#pragma once

#include "bench_scene.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace impulse2d_bench {

struct EngineSettings {
  std::string solver;  ///< one of EngineInfo::solvers
  double timeStep = 1.0 / 60.0;
  int velocityIterations = 8;
  int positionIterations = 3;  ///< ignored by engines without a position pass (Chipmunk)
};

/// A body's state as the metrics read it: the centre of mass and its velocities.
struct BodyState {
  Vec2 position = Vec2::Zero();
  double angle = 0.0;
  Vec2 velocity = Vec2::Zero();
  double angularVelocity = 0.0;
};

class EngineAdapter {
 public:
  virtual ~EngineAdapter() = default;
  /// Builds the scene with gravity (0, -9.81) and sleeping off (every engine does the same work
  /// each step, so the times compare the solvers rather than when each one dozes off).
  virtual void build(const SceneSpec& scene, const EngineSettings& settings) = 0;
  virtual void step() = 0;
  /// One state per SceneSpec body, in the scene's order.
  virtual void read(std::vector<BodyState>* states) const = 0;
  /// Contact points the engine holds as touching now.
  virtual size_t contactCount() const = 0;
};

struct EngineInfo {
  std::string name;
  std::vector<std::string> solvers;  ///< the first is the engine's default
  bool hasPositionIterations = true;
  std::vector<std::string> solversWithoutPositionIterations;
  EngineSettings defaults;  ///< the engine's own defaults at 60 Hz
  std::function<std::unique_ptr<EngineAdapter>()> make;
};

/// impulse2d first, then whichever peers were compiled in.
std::vector<EngineInfo> availableEngines();

EngineInfo impulse2dEngine();
#ifdef IMPULSE2D_BENCH_BOX2D
EngineInfo box2dEngine();
#endif
#ifdef IMPULSE2D_BENCH_CHIPMUNK
EngineInfo chipmunkEngine();
#endif

}  // namespace impulse2d_bench
