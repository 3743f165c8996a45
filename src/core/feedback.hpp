// How the velocity passes of every solver turn position errors into target velocities, shared by
// contacts and joints.
#pragma once

#include <impulse2d/math.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace impulse2d {

/// How a velocity pass feeds the position error C of a rigid row back. The row aims at
/// Cdot = -rate C, and its impulse is  massScale m (target - Cdot) - impulseScale accumulated:
/// massScale 1 and impulseScale 0 make it rigid (Baumgarte with rate beta/dt, or NGS and the soft
/// step's relax pass with rate 0); the soft step's biased pass makes it a damped spring.
struct Feedback {
  double rate = 0.0;  // 1/s
  double massScale = 1.0;
  double impulseScale = 0.0;
  /// m/s, the fastest a joint's feedback pushes an error apart (WorldDef::maxPushVelocity, as
  /// for contacts). Uncapped, a joint set that cannot all be met (a loop that does not close, a
  /// pin anchored 10 m away) was pushed at rate x error, hundreds of m/s, for ever.
  double maxPush = std::numeric_limits<double>::infinity();
};

/// A damped spring of `hertz` and damping ratio `zeta` on a row of any effective mass m,
/// integrated implicitly over a step h: the impulse L with
///   L = -h (k (C + h Cdot') + c Cdot'),  k = m w^2,  c = 2 m zeta w,  Cdot' = Cdot + L / m
/// rearranges to  L = massScale m (-Cdot - rate C) - impulseScale L_accumulated  with
///   rate = w / (2 zeta + h w),  massScale = a / (1 + a),  impulseScale = 1 / (1 + a),
///   a = h w (2 zeta + h w),  w = 2 pi hertz.
/// The effective mass cancels, so one Feedback serves every row.
inline Feedback springFeedback(double hertz, double zeta, double h) {
  const double omega = 2.0 * kPi * hertz;
  const double a1 = 2.0 * zeta + h * omega;
  const double a2 = h * omega * a1;
  Feedback fb;
  fb.rate = omega / a1;
  fb.massScale = a2 / (1.0 + a2);
  fb.impulseScale = 1.0 / (1.0 + a2);
  return fb;
}

/// A one-sided row's accumulated impulse after one iteration: `rate` is Cdot + bias now.
inline double solveOneSided(double accumulated, double mass, double rate, const Feedback& fb) {
  return std::max(accumulated - fb.massScale * mass * rate - fb.impulseScale * accumulated, 0.0);
}

}  // namespace impulse2d
