// The bound on how fast a dynamic body may move and turn (WorldDef::maxLinearSpeed and
// maxRotation), shared by both solver paths. Applied where velocities become motion: after the
// forces are integrated (so no impulse is ever computed from an absurd velocity) and before the
// poses move (so no solve can push past it), and on the velocity a step leaves behind.
#pragma once

#include <impulse2d/defs.hpp>

#include <cmath>

namespace impulse2d {

struct MotionLimits {
  double maxSpeedSquared = 0.0;  // (m/s)^2
  double maxTurnRate = 0.0;      // rad/s: maxRotation over one pass's step

  /// The limits for a pass of step h (the step, or a sub-step).
  static MotionLimits of(const WorldDef& def, double h) {
    MotionLimits limits;
    limits.maxSpeedSquared = def.maxLinearSpeed * def.maxLinearSpeed;
    limits.maxTurnRate = def.maxRotation / h;
    return limits;
  }

  /// Scales the linear velocity down to the speed limit (its direction kept) and clamps the
  /// turn rate. A NaN passes through unchanged, for the overflow guard to find.
  void apply(double& vx, double& vy, double& w) const {
    const double speedSquared = vx * vx + vy * vy;
    if (speedSquared > maxSpeedSquared) {
      const double scale = std::sqrt(maxSpeedSquared / speedSquared);
      vx *= scale;
      vy *= scale;
    }
    if (w > maxTurnRate) w = maxTurnRate;
    if (w < -maxTurnRate) w = -maxTurnRate;
  }
  void apply(Vec2& v, double& w) const {
    double vx = v.x(), vy = v.y();
    apply(vx, vy, w);
    v = Vec2(vx, vy);
  }
};

}  // namespace impulse2d
