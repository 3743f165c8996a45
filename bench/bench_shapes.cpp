// Scene shapes: their masses on the true outline, and the outline of rounded shapes as polygons
// for the engines that have none (impulse2d, Box2D 2.4).
#include <impulse2d/limits.hpp>

#include <algorithm>
#include <cmath>

#include "bench_scene.hpp"

namespace impulse2d_bench {
namespace {

// Area, centroid and second moment of area about the origin of a counter-clockwise polygon.
void polygonMoments(const std::vector<Vec2>& points, double* area, Vec2* centroid, double* polar) {
  *area = 0.0;
  *polar = 0.0;
  Vec2 moment = Vec2::Zero();
  const size_t n = points.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2& p = points[i];
    const Vec2& q = points[(i + 1) % n];
    const double cross = p.x() * q.y() - p.y() * q.x();
    *area += 0.5 * cross;
    moment += cross * (p + q) / 6.0;
    *polar += cross * (p.squaredNorm() + p.dot(q) + q.squaredNorm()) / 12.0;
  }
  *centroid = moment / *area;
}

// Points on the arc of `radius` about `center` from angle `from` to `to` (counter-clockwise),
// `count` of them including both ends.
void appendArc(const Vec2& center, double radius, double from, double to, int count,
               std::vector<Vec2>* out) {
  for (int k = 0; k < count; ++k) {
    const double a = count == 1 ? 0.5 * (from + to) : from + (to - from) * k / (count - 1);
    out->push_back(center + radius * Vec2(std::cos(a), std::sin(a)));
  }
}

// Enough points that the outline's area and inertia match the true shape's to about 1e-5.
constexpr int kFineOutline = 256;

}  // namespace

bool isRounded(const BenchShape& shape) {
  return shape.kind == BenchShape::Kind::Capsule ||
         (shape.kind == BenchShape::Kind::Polygon && shape.radius > 0.0);
}

std::vector<Vec2> outlinePolygon(const BenchShape& shape, int maxVertices) {
  if (shape.kind == BenchShape::Kind::Capsule) {
    //   p1 (----------) p2   each end a half circle of `perEnd` points, from one side to the other
    const Vec2 p1 = shape.vertices[0], p2 = shape.vertices[1];
    const Vec2 axis = (p2 - p1).normalized();
    const double heading = std::atan2(axis.y(), axis.x());
    const int perEnd = maxVertices / 2;
    std::vector<Vec2> out;
    appendArc(p2, shape.radius, heading - 0.5 * impulse2d::kPi, heading + 0.5 * impulse2d::kPi,
              perEnd, &out);
    appendArc(p1, shape.radius, heading + 0.5 * impulse2d::kPi, heading + 1.5 * impulse2d::kPi,
              perEnd, &out);
    return out;
  }
  if (shape.kind != BenchShape::Kind::Polygon || shape.radius <= 0.0) return shape.vertices;
  // Rounded polygon: each corner's arc turns from the normal of the edge before it to the normal
  // of the edge after it.
  const size_t n = shape.vertices.size();
  const int perCorner = std::max(1, maxVertices / static_cast<int>(n));
  std::vector<Vec2> out;
  for (size_t i = 0; i < n; ++i) {
    const Vec2& prev = shape.vertices[(i + n - 1) % n];
    const Vec2& here = shape.vertices[i];
    const Vec2& next = shape.vertices[(i + 1) % n];
    const Vec2 in = here - prev, onward = next - here;
    const double from = std::atan2(-in.x(), in.y());  // outward normal of prev -> here
    double to = std::atan2(-onward.x(), onward.y());
    while (to < from) to += 2.0 * impulse2d::kPi;
    if (perCorner == 1) {
      // One point per corner: where the two offset edges meet, so the flat faces stay whole.
      const double half = 0.5 * (to - from);
      appendArc(here, shape.radius / std::cos(half), from + half, from + half, 1, &out);
    } else {
      appendArc(here, shape.radius, from, to, perCorner, &out);
    }
  }
  return out;
}

void shapeMass(const BenchShape& shape, double* mass, double* inertia, Vec2* centroid) {
  double area = 0.0, polar = 0.0;  // polar: second moment of area about the centroid
  Vec2 center = Vec2::Zero();
  switch (shape.kind) {
    case BenchShape::Kind::Box: {
      const double w = shape.size.x(), h = shape.size.y();
      area = w * h;
      polar = area * (w * w + h * h) / 12.0;
      center = shape.center;
      break;
    }
    case BenchShape::Kind::Circle:
      area = impulse2d::kPi * shape.radius * shape.radius;
      polar = 0.5 * area * shape.radius * shape.radius;
      center = shape.center;
      break;
    case BenchShape::Kind::Polygon:
    case BenchShape::Kind::Capsule: {
      const std::vector<Vec2> outline =
          isRounded(shape) ? outlinePolygon(shape, kFineOutline) : shape.vertices;
      double aboutOrigin = 0.0;
      polygonMoments(outline, &area, &center, &aboutOrigin);
      polar = aboutOrigin - area * center.squaredNorm();
      break;
    }
  }
  *mass = shape.density * area;
  *inertia = shape.density * polar;
  *centroid = center;
}

void nominalMass(const BenchBody& body, double* mass, double* inertia) {
  *mass = 0.0;
  *inertia = 0.0;
  for (const BenchShape& shape : body.shapes) {
    double m = 0.0, i = 0.0;
    Vec2 c;
    shapeMass(shape, &m, &i, &c);
    *mass += m;
    *inertia += i + m * c.squaredNorm();
  }
}

void centreOnMass(BenchBody* body) {
  double total = 0.0;
  Vec2 weighted = Vec2::Zero();
  for (const BenchShape& shape : body->shapes) {
    double m = 0.0, i = 0.0;
    Vec2 c;
    shapeMass(shape, &m, &i, &c);
    total += m;
    weighted += m * c;
  }
  if (!(total > 0.0)) return;
  const Vec2 shift = weighted / total;
  for (BenchShape& shape : body->shapes) {
    shape.center -= shift;
    for (Vec2& v : shape.vertices) v -= shift;
  }
  body->position += impulse2d::Rot(body->angle).apply(shift);
}

impulse2d::ShapeDef toShapeDef(const BenchShape& shape) {
  impulse2d::ShapeDef def;
  def.density = shape.density;
  def.friction = shape.friction;
  def.restitution = shape.restitution;
  def.filter = shape.filter;
  switch (shape.kind) {
    case BenchShape::Kind::Box:
      def.kind = impulse2d::ShapeKind::Box;
      def.size = shape.size;
      def.offset = shape.center;
      break;
    case BenchShape::Kind::Circle:
      def.kind = impulse2d::ShapeKind::Circle;
      def.radius = shape.radius;
      def.offset = shape.center;
      break;
    case BenchShape::Kind::Polygon:
    case BenchShape::Kind::Capsule:
      def.kind = impulse2d::ShapeKind::Polygon;
      def.vertices = outlinePolygon(shape, impulse2d::kMaxPolygonVertices);
      break;
  }
  return def;
}

}  // namespace impulse2d_bench
