// The clocks behind World::profile(): a scope that adds its wall time to one stage of the step's
// profile, or does nothing (not even read the clock) while profiling is off.
#pragma once

#include <impulse2d/profile.hpp>

#include <chrono>

namespace impulse2d {

class StageClock {
 public:
  /// Times the scope into `*stage` (ms); a null stage: profiling is off.
  explicit StageClock(double* stage) : stage_(stage) {
    if (stage_) start_ = std::chrono::steady_clock::now();
  }
  ~StageClock() {
    if (stage_) {
      *stage_ +=
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
              .count();
    }
  }
  StageClock(const StageClock&) = delete;
  StageClock& operator=(const StageClock&) = delete;

 private:
  double* stage_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace impulse2d

namespace impulse2d {

/// Stages that follow one another in one function: each lap() adds the time since the last lap
/// (or since construction) to a stage. A null profile: profiling is off.
class StageLaps {
 public:
  explicit StageLaps(StepProfile* profile) : profile_(profile) {
    if (profile_) last_ = std::chrono::steady_clock::now();
  }
  void lap(double StepProfile::*stage) {
    if (!profile_) return;
    const auto now = std::chrono::steady_clock::now();
    profile_->*stage += std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
  }

 private:
  StepProfile* profile_;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace impulse2d
