// impulse2d_sim's command line.
#pragma once

#include <impulse2d/defs.hpp>

#include <cstdint>
#include <string>

namespace impulse2d {
namespace sim {

struct Options {
  std::string scenePath;
  bool stepsGiven = false;
  uint64_t steps = 0;
  double duration = 10.0;  ///< s, used when no --steps
  bool timeStepGiven = false;
  double timeStep = 0.0;
  bool velocityIterationsGiven = false;
  int velocityIterations = 0;
  bool positionIterationsGiven = false;
  int positionIterations = 0;
  bool threadsGiven = false;
  int threads = 1;
  bool solverGiven = false;
  SolverType solver = SolverType::Baumgarte;
  std::string csvPath;       ///< empty: none
  std::string contactsPath;  ///< empty: none
  uint64_t every = 1;
  bool hash = false;
  bool profile = false;  ///< print the stages' mean times
  bool help = false;
};

/// Reads argv into `out`. Returns false with one line in `error` for a bad command line.
bool parseOptions(int argc, const char* const* argv, Options* out, std::string* error);

/// The scene's settings with the command line's overrides applied.
WorldDef applyOverrides(const Options& options, WorldDef settings);

/// The number of steps to run: --steps, or --duration rounded up to whole steps of `timeStep`.
/// Returns false with a reason when the duration needs more steps than can be counted.
bool stepsToRun(const Options& options, double timeStep, uint64_t* steps, std::string* error);

extern const char* const kUsage;

}  // namespace sim
}  // namespace impulse2d
