// Asking the world where things are: ray casts (one segment, or a fan of them from one origin for
// scanners) and the bodies at a point or in a box. World's query methods (world.hpp) answer with
// these types; the shape-level tests below are what they run on each candidate shape.
#pragma once

#include <impulse2d/defs.hpp>
#include <impulse2d/shape.hpp>

#include <algorithm>
#include <vector>

namespace impulse2d {

/// Where a segment first meets a shape, or a world.
///
///   from ------------------x----------- to        fraction = |from x| / |from to|
///                          |\ normal (outward, at x)
///                        [ shape ]
///
/// A segment that starts inside a shape (or on its boundary) hits it at fraction 0, at `from`,
/// with the normal pointing back along the segment (zero for a segment of zero length). Touching
/// counts: a segment that grazes a circle or runs along an edge hits where it first touches.
struct RayHit {
  BodyId body;                 ///< invalid when nothing was hit
  int shape = -1;              ///< index into the body's shapes
  Vec2 point = Vec2::Zero();   ///< m, world
  Vec2 normal = Vec2::Zero();  ///< unit, world, the surface's outward normal at `point`
  double fraction = 1.0;       ///< along the segment, in [0, 1]
  bool hit() const { return body.valid(); }
};

/// Bodies a ray passes through without hitting, e.g. the robot that carries the scanner.
struct RayFilter {
  std::vector<BodyId> ignore;
  bool ignores(BodyId id) const {
    return std::find(ignore.begin(), ignore.end(), id) != ignore.end();
  }
};

/// Where the segment from -> to (world) first meets one shape placed at `xf`; the same rules as
/// RayHit.
struct ShapeRayHit {
  double fraction = 2.0;       ///< in [0, 1] on a hit, > 1 on a miss
  Vec2 normal = Vec2::Zero();  ///< unit, world (see RayHit for a start inside)
  bool hit() const { return fraction <= 1.0; }
};
ShapeRayHit rayCastShape(const Shape& shape, const Transform& xf, const Vec2& from, const Vec2& to);

/// Whether the world point lies in the shape placed at `xf` (its boundary included).
bool shapeContains(const Shape& shape, const Transform& xf, const Vec2& point);

/// Whether the shape placed at `xf` overlaps the box (touching included): exact, not just the
/// shape's bounding box.
bool shapeOverlaps(const Shape& shape, const Transform& xf, const Aabb& box);

}  // namespace impulse2d
