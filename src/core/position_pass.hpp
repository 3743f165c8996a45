// The limits of the non-linear Gauss-Seidel position passes (`ngs`, and `substep` after its
// sub-steps), shared by contacts and joints of both solver paths.
#pragma once

#include <impulse2d/math.hpp>

#include <cmath>

namespace impulse2d {

/// The largest linear correction one pass applies to a body (m), so that deep overlaps (bodies
/// spawned inside each other) and wide joint gaps close over several steps instead of flinging
/// the bodies apart.
constexpr double kMaxLinearCorrection = 0.2;
constexpr double kMaxAngularCorrection = 8.0 * kPi / 180.0;  // rad per pass
constexpr double kAngularSlop = 2.0 * kPi / 180.0;           // rad a joint's angle is left alone

/// A row (a body, or a welded cluster moving as one) reaching further than this from its centre
/// (m) can be swung by a pass's kMaxAngularCorrection further than kMaxLinearCorrection moves its
/// centre.
constexpr double kLongestFreeReach = kMaxLinearCorrection / kMaxAngularCorrection;

/// The share of a step's position correction (its centre `moved` m, turned `turn` rad) that a row
/// reaching `reach` m keeps after `passes` passes: all of it unless a point of it moved further
/// than 2 kMaxLinearCorrection a pass (world_substeps.cpp, boundFarReach). 1 for a NaN, which the
/// world's bounds remove.
inline double farReachShare(double moved, double turn, double reach, int passes) {
  const double limit = passes * 2.0 * kMaxLinearCorrection;
  const double farthest = moved + std::abs(turn) * reach;
  return farthest > limit ? limit / farthest : 1.0;
}

/// Whether the deepest overlap a pass measured (a separation, m, < 0 when overlapping) is small
/// enough to stop the passes: within three linear slops.
inline bool overlapsResolved(double deepest, double linearSlop) {
  return deepest >= -3.0 * linearSlop;
}

}  // namespace impulse2d
