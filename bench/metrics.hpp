// Error figures measured the same way for every engine: from the poses and velocities the engine
// reports, on the scene's own geometry (impulse2d's narrow phase), never from an engine's own
// contact data, whose slop and skin differ. Definitions: docs/benchmarks.md.
#pragma once

#include <impulse2d/shape.hpp>

#include "bench_scene.hpp"
#include "engine_adapter.hpp"

#include <vector>

namespace impulse2d_bench {

/// The linear slop the penetration figure allows (m): impulse2d's and Box2D's default.
constexpr double kPenetrationSlop = 0.005;

struct ErrorFigures {
  double penetrationMean = 0.0;  ///< m beyond the slop, mean over touching points and samples
  double penetrationMax = 0.0;   ///< m beyond the slop, largest in any sample
  double driftMax = 0.0;         ///< m, largest sideways displacement (resting scenes)
  double sinkMax = 0.0;          ///< m, largest downward displacement (resting scenes)
  double jointGapMean = 0.0;     ///< m, anchor separation, mean over joints and samples
  double jointGapMax = 0.0;      ///< m, largest in any sample
  double energyDrift = 0.0;      ///< (E_end - E_start) / scale, see docs/benchmarks.md
  bool energyMeaningful = true;  ///< false when motors or events add or remove energy
  int escaped = 0;               ///< bodies outside the container at the end (Contained)
  double momentumDrift = 0.0;    ///< |P_end - P_start| / |P_start| (Impact)
  bool stood = true;
  bool finite = true;  ///< every state stayed finite
};

class ErrorMeter {
 public:
  explicit ErrorMeter(const SceneSpec& scene);
  /// Measures penetration and joint gaps of one sample of the run.
  void sample(const std::vector<BodyState>& states);
  /// The figures of the whole run, given its final states.
  ErrorFigures finish(const std::vector<BodyState>& finalStates);

 private:
  double energy(const std::vector<BodyState>& states) const;
  Vec2 momentum(const std::vector<BodyState>& states) const;
  bool inside(const std::vector<BodyState>& states, size_t body) const;

  const SceneSpec& scene_;
  std::vector<std::vector<impulse2d::Shape>> shapes_;  // per body, in its frame
  std::vector<double> mass_, inertia_;
  std::vector<BodyState> initial_;
  std::vector<Vec2> localAnchorA_, localAnchorB_;
  std::vector<std::pair<int, int>> jointPairs_;  // sorted, lower body first
  double startEnergy_ = 0.0, energyScale_ = 1.0;
  Vec2 startMomentum_ = Vec2::Zero();
  ErrorFigures figures_;
  double penetrationSum_ = 0.0, gapSum_ = 0.0;
  size_t penetrationCount_ = 0, gapCount_ = 0;
  std::vector<int> order_;
  std::vector<impulse2d::Aabb> boxes_;
};

}  // namespace impulse2d_bench
