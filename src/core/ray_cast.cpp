// Shape-level queries: where a segment first meets a shape, whether a point lies in it, whether
// it overlaps a box. World's ray casts and queries (world_queries.cpp) run these on the shapes the
// AABB tree hands them; continuous collision uses the ray cast through raycastShape.
#include <impulse2d/queries.hpp>

#include "distance.hpp"

#include <algorithm>
#include <cmath>

namespace impulse2d {
namespace {

// A start inside (or on) the shape: the hit is the start itself, facing back along the segment.
ShapeRayHit startsInside(const Transform& xf, const Vec2& localDirection) {
  ShapeRayHit hit;
  hit.fraction = 0.0;
  const double length = localDirection.norm();
  if (length > 0.0) hit.normal = xf.q.apply(Vec2(-localDirection / length));
  return hit;
}

// |a + t d - c|^2 = r^2 in the shape's frame: the smaller root is where the segment enters.
//
//        .-'''-.
//  a ---x---c---x---> d      t = (-m.d - sqrt((m.d)^2 - |d|^2 (|m|^2 - r^2))) / |d|^2, m = a - c
//        '-...-'
ShapeRayHit rayCastCircle(const Circle& circle, const Transform& xf, const Vec2& a, const Vec2& d) {
  ShapeRayHit miss;
  const Vec2 m = a - circle.center;
  const double r2 = circle.radius * circle.radius;
  if (m.squaredNorm() <= r2) return startsInside(xf, d);
  const double dd = d.squaredNorm(), md = m.dot(d);
  const double disc = md * md - dd * (m.squaredNorm() - r2);
  if (dd == 0.0 || disc < 0.0) return miss;
  const double t = (-md - std::sqrt(disc)) / dd;
  if (!(t >= 0.0 && t <= 1.0)) return miss;
  ShapeRayHit hit;
  hit.fraction = t;
  hit.normal = xf.q.apply(Vec2((m + t * d) / circle.radius));
  return hit;
}

// Clips the segment by each face's half-plane: faces it crosses inwards raise the entry, faces it
// crosses outwards lower the exit; it hits when entry <= exit, at the entry, on the face that set
// it. A face it runs along (den = 0) keeps it when it is on the inner side or on the face itself.
ShapeRayHit rayCastPolygon(const Polygon& poly, const Transform& xf, const Vec2& a, const Vec2& d) {
  ShapeRayHit miss;
  double enter = 0.0, exit = 1.0;
  int face = -1;
  for (int i = 0; i < poly.count; ++i) {
    const double num = poly.normals[i].dot(poly.vertices[i] - a);  // > 0: a is inside this face
    const double den = poly.normals[i].dot(d);
    if (den == 0.0) {
      if (num < 0.0) return miss;  // parallel and outside
      continue;
    }
    const double t = num / den;
    if (den < 0.0) {
      if (t > enter) face = i;
      enter = std::max(enter, t);
    } else {
      exit = std::min(exit, t);
    }
    if (enter > exit) return miss;
  }
  if (face < 0) return startsInside(xf, d);  // no face lies ahead: the start is inside or on one
  ShapeRayHit hit;
  hit.fraction = enter;
  hit.normal = xf.q.apply(poly.normals[face]);
  return hit;
}

}  // namespace

ShapeRayHit rayCastShape(const Shape& shape, const Transform& xf, const Vec2& from,
                         const Vec2& to) {
  const Vec2 a = xf.applyInverse(from), b = xf.applyInverse(to);
  const Vec2 d = b - a;
  return shape.type == ShapeType::Circle ? rayCastCircle(shape.circle, xf, a, d)
                                         : rayCastPolygon(shape.polygon, xf, a, d);
}

double raycastShape(const Shape& shape, const Transform& xf, const Vec2& p0, const Vec2& p1) {
  return rayCastShape(shape, xf, p0, p1).fraction;
}

bool shapeContains(const Shape& shape, const Transform& xf, const Vec2& point) {
  const Vec2 p = xf.applyInverse(point);
  if (shape.type == ShapeType::Circle) {
    return (p - shape.circle.center).squaredNorm() <= shape.circle.radius * shape.circle.radius;
  }
  const Polygon& poly = shape.polygon;
  for (int i = 0; i < poly.count; ++i) {
    if (poly.normals[i].dot(p - poly.vertices[i]) > 0.0) return false;
  }
  return true;
}

bool shapeOverlaps(const Shape& shape, const Transform& xf, const Aabb& box) {
  if (shape.type == ShapeType::Circle) {
    // The box's point nearest the centre.
    const Vec2 c = xf.apply(shape.circle.center);
    const Vec2 nearest = c.cwiseMax(box.lower).cwiseMin(box.upper);
    return (c - nearest).squaredNorm() <= shape.circle.radius * shape.circle.radius;
  }
  // Separating axes: the box's two (its bounds against the polygon's) and the polygon's normals
  // (the box corner deepest behind each face must not lie in front of it).
  if (!computeAabb(shape, xf).overlaps(box)) return false;
  const Polygon& poly = shape.polygon;
  const Vec2 corners[4] = {box.lower, box.upper, Vec2(box.lower.x(), box.upper.y()),
                           Vec2(box.upper.x(), box.lower.y())};
  for (int i = 0; i < poly.count; ++i) {
    const Vec2 n = xf.q.apply(poly.normals[i]);
    const Vec2 v = xf.apply(poly.vertices[i]);
    double deepest = n.dot(corners[0] - v);
    for (const Vec2& corner : corners) deepest = std::min(deepest, n.dot(corner - v));
    if (deepest > 0.0) return false;
  }
  return true;
}

}  // namespace impulse2d
