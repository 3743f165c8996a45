// The core soak: seeded random edits between the steps of one world, through the World API only,
// with invariants checked after every step. The ROS soak (ros_soak.py) does the same through the
// node's services. Both exist because a user editing a running world does things no hand-written
// test thought of: joints anchored anywhere, teleports into piles, forces on tiny bodies.
//
//   +--------------------------- 24 m ---------------------------+
//   |##################### ceiling (static, 2 m) #################|
//   |##|                                                      |##|
//   |##|   spawns, joints, teleports, forces, kinematic       |##|  the walled arena:
//   |##|   bodies driven around the middle, sleep on/off      |##|  20 m x 20 m inside
//   |##|                                                      |##|
//   |##################### ground (static, 2 m) ###############|
//   +--------------------------------------------------------------+
//
// A run is `steps` steps of edits, then a quiet phase (no edits, no forces, kinematic bodies
// stopped) in which the energy must not grow and resting piles must come apart.
#pragma once

#include <impulse2d/defs.hpp>

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

namespace impulse2d {
namespace soak {

struct Options {
  uint64_t seed = 1;
  int steps = 600;  ///< steps with edits; a quiet phase of kQuietSteps follows
  SolverType solver = SolverType::SubstepNgs;
  int threads = 1;
  bool gravity = true;  ///< false: a top-down world (no gravity)
  std::string watch;    ///< a body's name: its pose, velocity and contacts on stderr each step
  /// Wrenches push at a point drawn within 0.5 m of the body's centre, as the ROS soak's clients
  /// give them (a torque from the force too), not at the centre. Off by default: the draws are
  /// the same either way, but the pushes change every seed's path, and the seeds kept as
  /// regression tests replay the paths that found their bugs.
  bool wrenchesAtPoints = false;
};

/// Whether the soak's run of `seed` has gravity: one seed in five is a top-down world.
inline bool gravityOf(uint64_t seed) { return seed % 5 != 4; }

/// Steps of the quiet phase at the end of every run.
constexpr int kQuietSteps = 400;

struct Report {
  uint64_t steps = 0;       ///< steps taken, quiet phase included
  uint64_t edits = 0;       ///< edits made (valid and bad requests)
  uint64_t badRefused = 0;  ///< bad requests, each refused
  uint64_t checks = 0;      ///< invariant checks made (one per body per invariant per step)
  size_t maxBodies = 0, maxJoints = 0;
  std::vector<std::string> violations;  ///< empty when every invariant held
  std::deque<std::string> lastEdits;    ///< the last few edits, oldest first
  /// One line: seed, solver, what was made and checked, and the first violation.
  std::string summary(const Options& options) const;
};

/// Runs one soak; stops at the first step with a violation.
Report run(const Options& options);

}  // namespace soak
}  // namespace impulse2d
