// The bound on how fast a dynamic body may move and turn (WorldDef::maxLinearSpeed and
// maxRotation), shared by both solver paths. Applied where velocities become motion: after the
// forces are integrated (so no impulse is ever computed from an absurd velocity) and before the
// poses move (so no solve can push past it), and on the velocity a step leaves behind.
#pragma once

#include <impulse2d/defs.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace impulse2d {

struct MotionLimits {
  double maxSpeed = 0.0;         // m/s
  double maxSpeedSquared = 0.0;  // (m/s)^2
  double maxTurnRate = 0.0;      // rad/s: maxRotation over one pass's step

  /// The limits for a pass of step h (the step, or a sub-step).
  static MotionLimits of(const WorldDef& def, double h) {
    MotionLimits limits;
    limits.maxSpeed = def.maxLinearSpeed;
    limits.maxSpeedSquared = def.maxLinearSpeed * def.maxLinearSpeed;
    limits.maxTurnRate = def.maxRotation / h;
    return limits;
  }

  /// Scales the linear velocity down to the speed limit (its direction kept) and clamps the
  /// turn rate. A NaN passes through unchanged, for the overflow guard to find.
  void apply(double& vx, double& vy, double& w) const { apply(vx, vy, w, maxTurnRate); }
  /// The same with a body's own turn-rate limit (TurnCaps).
  void apply(double& vx, double& vy, double& w, double turnRate) const {
    const double speedSquared = vx * vx + vy * vy;
    if (speedSquared > maxSpeedSquared) {
      const double scale = std::sqrt(maxSpeedSquared / speedSquared);
      vx *= scale;
      vy *= scale;
    }
    if (w > turnRate) w = turnRate;
    if (w < -turnRate) w = -turnRate;
  }
  void apply(Vec2& v, double& w) const {
    double vx = v.x(), vy = v.y();
    apply(vx, vy, w);
    v = Vec2(vx, vy);
  }
  void apply(Vec2& v, double& w, double turnRate) const {
    double vx = v.x(), vy = v.y();
    apply(vx, vy, w, turnRate);
    v = Vec2(vx, vy);
  }
};

/// Turn-rate limits of single bodies, below MotionLimits::maxTurnRate: a body with a joint
/// anchored `reach` m from its centre of mass turns no faster than moves that anchor at the speed
/// limit, maxSpeed / reach.
///
///          w
///       .-->-.        anchor, reach r out: it moves at w r
///   [box]------------o~~~~[light body]
///
/// Measured (issue 26, the core soak's substep seeds 375 and 437): a box on a 5-8 Hz spring
/// anchored 15-18 m from its centre spun up to 200-500 rad/s, its anchor at 3-9 km/s; at a radian
/// a sub-step its turning was not resolved and each turn fed the spring (energy 6.4 -> 39 kJ).
/// Capped so, a turn moves the anchor at most what the speed limit moves a centre: only bodies
/// with such a far anchor and such a spin are touched, and the cap only takes energy away.
class TurnCaps {
 public:
  /// Drops every cap (none until note() finds one that binds).
  void clear() { rates_.clear(); }
  /// A joint anchored `reach` m from the centre of dynamic entry `entry` (of `entries`).
  void note(int entry, int entries, double reach, const MotionLimits& limits) {
    if (!(reach * limits.maxTurnRate > limits.maxSpeed)) return;  // the step's own limit binds
    if (rates_.empty()) rates_.assign(static_cast<size_t>(entries), limits.maxTurnRate);
    rates_[entry] = std::min(rates_[entry], limits.maxSpeed / reach);
  }
  /// The turn-rate limit of entry `entry` (a kinematic one's is never read for its motion).
  double rate(int entry, const MotionLimits& limits) const {
    return static_cast<size_t>(entry) < rates_.size() ? rates_[entry] : limits.maxTurnRate;
  }

 private:
  std::vector<double> rates_;  // by dynamic entry; empty while no cap binds
};

}  // namespace impulse2d
