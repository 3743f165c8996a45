// What World's ray casts share (world_queries.cpp, ray_fan.cpp): the rule that picks one hit
// among equally near ones, and the fan form's entry point.
#pragma once

#include "world_impl.hpp"

#include <impulse2d/queries.hpp>

#include <vector>

namespace impulse2d {

/// Whether a hit at `fraction` on (slot, shape) beats `best`. Equal fractions go to the lower
/// body slot, then the lower shape index, so the answer does not depend on the order in which
/// the shapes are tried.
inline bool nearerHit(double fraction, int slot, int shape, const RayHit& best) {
  if (!best.hit()) return true;
  if (fraction != best.fraction) return fraction < best.fraction;
  return slot != best.body.index ? slot < best.body.index : shape < best.shape;
}

/// The nearest hit of one segment, through the AABB tree.
RayHit castRay(const WorldImpl& w, const Vec2& from, const Vec2& to, const RayFilter& filter);

/// (*hits)[i] = castRay(w, origin, ends[i], filter) for every i, computed as one fan: the shapes
/// near the origin are gathered once and each beam tries only those in its direction, nearest
/// first (ray_fan.cpp). `origin` must be finite; ends that are not give no hit.
void castFan(const WorldImpl& w, const Vec2& origin, const std::vector<Vec2>& ends,
             const RayFilter& filter, std::vector<RayHit>* hits);

}  // namespace impulse2d
