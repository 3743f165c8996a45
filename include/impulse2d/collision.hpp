// Narrow phase: contact manifolds between pairs of shapes.
#pragma once

#include <impulse2d/shape.hpp>

#include <cstdint>

namespace impulse2d {

/// One contact point of a manifold, in world coordinates.
struct ManifoldPoint {
  Vec2 point = Vec2::Zero();  ///< midway between the two surfaces, world frame (m)
  double separation = 0.0;    ///< signed distance along the normal, negative = penetrating (m)
  /// Feature id: which features (edges/vertices of A and B) made this point. The same pair of
  /// features gives the same id on every step, so the solver can carry its impulse over.
  uint32_t id = 0;
};

/// Up to two contact points sharing one normal.
struct Manifold {
  Vec2 normal = Vec2::Zero();  ///< unit, world frame, points from shape A towards shape B
  ManifoldPoint points[2];
  int pointCount = 0;
};

/// Contact generation keeps points whose separation is at most `speculativeDistance` (m), so the
/// solver can stop bodies that are about to touch within the next step.
Manifold collideCircles(const Circle& a, const Transform& xfA, const Circle& b,
                        const Transform& xfB, double speculativeDistance);
Manifold collidePolygonCircle(const Polygon& a, const Transform& xfA, const Circle& b,
                              const Transform& xfB, double speculativeDistance);
Manifold collidePolygons(const Polygon& a, const Transform& xfA, const Polygon& b,
                         const Transform& xfB, double speculativeDistance);

/// Dispatches on the shape types; the normal always points from `a` to `b`.
Manifold collideShapes(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                       double speculativeDistance);

}  // namespace impulse2d
