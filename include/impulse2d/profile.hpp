// Where a step's time goes, stage by stage (as Box2D's b2Profile). World::setProfiling(true)
// turns the clocks on; World::profile() is then the last step's.
#pragma once

#include <array>
#include <utility>
#include <vector>

namespace impulse2d {

/// Wall time of each stage of the last step, in milliseconds. A solver leaves the stages it does
/// not have at 0 (the one-pass solvers have no colouring and no relax pass; only `ngs` and
/// `substep` have position passes).
struct StepProfile {
  double total = 0.0;        // the whole step
  double broadPhase = 0.0;   // fat boxes refitted, new overlapping pairs found
  double narrowPhase = 0.0;  // each touching pair's manifold; impulses matched by contact id
  double coloring = 0.0;     // sub-stepping: constraints coloured and laid out in SIMD lanes
  double prepare = 0.0;      // solver bodies gathered; contact and joint rows set up
  double warmStart = 0.0;    // last step's impulses applied (each sub-step's)
  double solve = 0.0;        // velocity iterations (sub-stepping: the biased pass)
  double relax = 0.0;        // sub-stepping: the pass without bias
  double restitution = 0.0;  // bounces; impulses stored for the next step
  double positions = 0.0;    // NGS position passes
  double integrate = 0.0;    // velocities from forces, positions from velocities
  double continuous = 0.0;   // fast bodies swept; bodies pushed out of static ones
  double sleep = 0.0;        // islands put to sleep; escaped bodies removed

  /// Each stage's name and member, in the order the step runs them (total left out).
  struct Stage {
    const char* name;
    double StepProfile::*time;
  };
  static const std::array<Stage, 12>& stageTable() {
    static const std::array<Stage, 12> table = {{{"broad phase", &StepProfile::broadPhase},
                                                 {"narrow phase", &StepProfile::narrowPhase},
                                                 {"colouring", &StepProfile::coloring},
                                                 {"prepare", &StepProfile::prepare},
                                                 {"warm start", &StepProfile::warmStart},
                                                 {"solve", &StepProfile::solve},
                                                 {"relax", &StepProfile::relax},
                                                 {"restitution", &StepProfile::restitution},
                                                 {"positions", &StepProfile::positions},
                                                 {"integrate", &StepProfile::integrate},
                                                 {"continuous", &StepProfile::continuous},
                                                 {"sleep", &StepProfile::sleep}}};
    return table;
  }

  /// Each stage and its time, in the order the step runs them (total left out).
  std::vector<std::pair<const char*, double>> stages() const {
    std::vector<std::pair<const char*, double>> out;
    for (const Stage& stage : stageTable()) out.emplace_back(stage.name, this->*stage.time);
    return out;
  }
  StepProfile& operator+=(const StepProfile& o) {
    total += o.total;
    for (const Stage& stage : stageTable()) this->*stage.time += o.*stage.time;
    return *this;
  }
};

// A stage added to StepProfile must join stageTable() too (and then this count).
static_assert(sizeof(StepProfile) == 13 * sizeof(double), "every stage is in stageTable()");

}  // namespace impulse2d
