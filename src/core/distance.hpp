// Distance between convex shapes (GJK) and the time of impact of two moving shapes
// (conservative advancement on that distance), for continuous collision.
#pragma once

#include <impulse2d/shape.hpp>

namespace impulse2d {

struct DistanceResult {
  Vec2 pointA = Vec2::Zero();  ///< closest point on A, world
  Vec2 pointB = Vec2::Zero();  ///< closest point on B, world
  double distance = 0.0;       ///< >= 0; 0 when the shapes overlap
  int iterations = 0;
};

/// GJK on the Minkowski difference B - A; circles are points with a radius added afterwards.
DistanceResult shapeDistance(const Shape& a, const Transform& xfA, const Shape& b,
                             const Transform& xfB);

/// The fraction in [0, 1] of the segment p0 -> p1 at which it enters the shape (0 when p0 is
/// inside), or a value > 1 when it misses: rayCastShape's fraction (ray_cast.cpp, queries.hpp).
double raycastShape(const Shape& shape, const Transform& xf, const Vec2& p0, const Vec2& p1);

/// A body's motion over one step: its centre of mass and angle at the start (t = 0) and end
/// (t = 1), interpolated linearly in between.
struct Sweep {
  Vec2 localCenter = Vec2::Zero();
  Vec2 c0 = Vec2::Zero(), c1 = Vec2::Zero();
  double a0 = 0.0, a1 = 0.0;
  Transform at(double t) const {
    const Rot q((1.0 - t) * a0 + t * a1);
    const Vec2 c = (1.0 - t) * c0 + t * c1;
    return Transform(c - q.apply(localCenter), q);
  }
};

/// The first t in [0, 1] at which the shapes come within `target` of each other, or 1 when they
/// do not. Conservative advancement: each iteration moves t forward by the current distance over
/// an upper bound of the closing speed, so it never steps past the impact.
double timeOfImpact(const Shape& a, const Sweep& sweepA, const Shape& b, const Sweep& sweepB,
                    double target);

}  // namespace impulse2d
