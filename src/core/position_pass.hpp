// The limits of the non-linear Gauss-Seidel position passes (`ngs`, and `substep` after its
// sub-steps), shared by contacts and joints of both solver paths.
#pragma once

#include <impulse2d/math.hpp>

namespace impulse2d {

/// The largest linear correction one pass applies to a body (m), so that deep overlaps (bodies
/// spawned inside each other) and wide joint gaps close over several steps instead of flinging
/// the bodies apart.
constexpr double kMaxLinearCorrection = 0.2;
constexpr double kMaxAngularCorrection = 8.0 * kPi / 180.0;  // rad per pass
constexpr double kAngularSlop = 2.0 * kPi / 180.0;           // rad a joint's angle is left alone

/// Whether the deepest overlap a pass measured (a separation, m, < 0 when overlapping) is small
/// enough to stop the passes: within three linear slops.
inline bool overlapsResolved(double deepest, double linearSlop) {
  return deepest >= -3.0 * linearSlop;
}

}  // namespace impulse2d
