// Polygon validation and the narrow phase on shapes and poses decoded from the input.
//
// Polygon validation: makeShape either refuses (with a reason) or yields a counter-clockwise,
// strictly convex polygon with 3..16 finite vertices, unit outward normals and its centroid
// inside.
//
// Narrow phase, against a brute-force answer computed here from the world-space vertices:
// - no NaN or inf, at most two points, a unit normal;
// - no points only when the shapes are apart (circles: farther than the speculative distance);
// - every point within the speculative distance;
// - overlapping shapes get a penetrating point, and the deepest point is never deeper than the
//   exact separation (circles) or the worse of the two polygons' best face separations (the
//   feature flip-flop allowance and the short-face fallback in collision.cpp may pick either).
// All within kTolerance: 1e-7 m on shapes a few metres across, far above the round-off of the
// few dozen operations involved, far below any tolerance the solver works to.
#include "fuzz_input.hpp"

#include <impulse2d/collision.hpp>
#include <impulse2d/shape.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace {

using impulse2d::Vec2;
using impulse2d::fuzz::FuzzInput;

constexpr double kTolerance = 1e-7;

bool decodeShape(FuzzInput& in, impulse2d::Shape* out) {
  impulse2d::ShapeDef def;
  switch (in.byte() % 3) {
    case 0:
      def.kind = impulse2d::ShapeKind::Box;
      def.size = Vec2(in.number(0.0, 3.0), in.number(0.0, 3.0));
      break;
    case 1:
      def.kind = impulse2d::ShapeKind::Circle;
      def.radius = in.number(0.0, 1.5);
      break;
    default: {
      def.kind = impulse2d::ShapeKind::Polygon;
      const int count = in.byte() % 20;  // beyond 16 on purpose: must be refused
      for (int i = 0; i < count; ++i) {
        def.vertices.emplace_back(in.number(-1.5, 1.5), in.number(-1.5, 1.5));
      }
    }
  }
  def.offset = Vec2(in.inRange(-0.5, 0.5), in.inRange(-0.5, 0.5));
  def.angle = in.inRange(-4.0, 4.0);
  const std::string why = impulse2d::makeShape(def, out);
  IMPULSE2D_FUZZ_CHECK(why.empty() || why.find(':') != std::string::npos);
  return why.empty();
}

void checkPolygon(const impulse2d::Polygon& p) {
  IMPULSE2D_FUZZ_CHECK(p.count >= 3 && p.count <= impulse2d::kMaxPolygonVertices);
  IMPULSE2D_FUZZ_CHECK(impulse2d::isFinite(p.centroid));
  for (int i = 0; i < p.count; ++i) {
    IMPULSE2D_FUZZ_CHECK(impulse2d::isFinite(p.vertices[i]));
    IMPULSE2D_FUZZ_CHECK(std::abs(p.normals[i].norm() - 1.0) < 1e-12);
    const Vec2 edge = p.vertices[(i + 1) % p.count] - p.vertices[i];
    // The stored vertices are rounded to their own magnitude: a 0.1 mm edge 10 km from the
    // body's origin points up to 1e-8 rad away from its (exactly rotated) normal.
    const double rounding = 8.0 * std::numeric_limits<double>::epsilon() *
                            (p.vertices[i].norm() + p.vertices[(i + 1) % p.count].norm());
    IMPULSE2D_FUZZ_CHECK(std::abs(p.normals[i].dot(edge)) <= 1e-9 * edge.norm() + rounding);
    IMPULSE2D_FUZZ_CHECK(impulse2d::cross(edge, p.normals[i]) < 0.0);  // right of a CCW edge
    IMPULSE2D_FUZZ_CHECK(p.normals[i].dot(p.centroid - p.vertices[i]) < 0.0);
    for (int j = 0; j < p.count; ++j) {
      IMPULSE2D_FUZZ_CHECK(p.normals[i].dot(p.vertices[j] - p.vertices[i]) <= 1e-9);
    }
  }
}

// World-space outline: a polygon's vertices and normals, or a circle.
struct Outline {
  bool circle = false;
  Vec2 center = Vec2::Zero();
  double radius = 0.0;
  std::vector<Vec2> vertices, normals;
};

Outline outline(const impulse2d::Shape& s, const impulse2d::Transform& xf) {
  Outline o;
  if (s.type == impulse2d::ShapeType::Circle) {
    o.circle = true;
    o.center = xf.apply(s.circle.center);
    o.radius = s.circle.radius;
    return o;
  }
  for (int i = 0; i < s.polygon.count; ++i) {
    o.vertices.push_back(xf.apply(s.polygon.vertices[i]));
    o.normals.push_back(xf.q.apply(s.polygon.normals[i]));
  }
  return o;
}

double pointSegmentDistance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

// Signed distance from p to a convex polygon: negative inside (minus the depth to the nearest
// edge).
double signedDistance(const Vec2& p, const Outline& poly) {
  double inside = -std::numeric_limits<double>::infinity();
  double outside = std::numeric_limits<double>::infinity();
  const size_t n = poly.vertices.size();
  for (size_t i = 0; i < n; ++i) {
    inside = std::max(inside, poly.normals[i].dot(p - poly.vertices[i]));
    outside =
        std::min(outside, pointSegmentDistance(p, poly.vertices[i], poly.vertices[(i + 1) % n]));
  }
  return inside > 0.0 ? outside : inside;
}

// Largest separation along the face normals of `ref`: the distance along that axis when
// positive, minus the penetration depth along it when negative.
double bestFaceSeparation(const Outline& ref, const Outline& inc) {
  double best = -std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < ref.normals.size(); ++i) {
    double s = std::numeric_limits<double>::infinity();
    for (const Vec2& v : inc.vertices) s = std::min(s, ref.normals[i].dot(v - ref.vertices[i]));
    best = std::max(best, s);
  }
  return best;
}

// The true signed separation (distance apart, or minus the penetration depth); the deepest
// separation the narrow phase may report; and whether it must find every pair within the
// speculative distance (circles) or only every overlapping pair (polygons: two corners facing
// no face give no points until they touch, collision.cpp).
struct Truth {
  double separation;
  double deepestAllowed;
  bool exactSpeculative;
};

Truth bruteForce(const Outline& a, const Outline& b) {
  if (a.circle && b.circle) {
    const double s = (b.center - a.center).norm() - a.radius - b.radius;
    return {s, s, true};
  }
  if (a.circle || b.circle) {
    const Outline& circle = a.circle ? a : b;
    const Outline& poly = a.circle ? b : a;
    const double s = signedDistance(circle.center, poly) - circle.radius;
    return {s, s, true};
  }
  const double faceA = bestFaceSeparation(a, b), faceB = bestFaceSeparation(b, a);
  double separation = std::max(faceA, faceB);  // the penetration depth when overlapping
  if (separation > 0.0) {
    separation = std::numeric_limits<double>::infinity();
    for (const auto* pair : {&a, &b}) {
      const Outline& p = *pair;
      const Outline& q = pair == &a ? b : a;
      for (const Vec2& v : p.vertices) {
        for (size_t i = 0; i < q.vertices.size(); ++i) {
          separation = std::min(
              separation,
              pointSegmentDistance(v, q.vertices[i], q.vertices[(i + 1) % q.vertices.size()]));
        }
      }
    }
  }
  // Points lie on the incident edge, so never deeper than the chosen reference face's
  // separation; the flip-flop allowance, and the fallback to the other polygon's face when a
  // short reference face misses the incident edge, may choose either polygon's best face.
  return {separation, std::min(faceA, faceB), false};
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzInput in(data, size);
  impulse2d::Shape shapes[2];
  for (impulse2d::Shape& shape : shapes) {
    if (!decodeShape(in, &shape)) return 0;
    if (shape.type == impulse2d::ShapeType::Polygon) checkPolygon(shape.polygon);
  }
  impulse2d::Transform xf[2];
  for (impulse2d::Transform& t : xf) {
    t = impulse2d::Transform(Vec2(in.inRange(-3.0, 3.0), in.inRange(-3.0, 3.0)),
                             impulse2d::Rot(in.inRange(-4.0, 4.0)));
  }
  const double speculative = in.inRange(0.0, 0.1);
  const impulse2d::Manifold m =
      impulse2d::collideShapes(shapes[0], xf[0], shapes[1], xf[1], speculative);
  const Truth truth = bruteForce(outline(shapes[0], xf[0]), outline(shapes[1], xf[1]));

  IMPULSE2D_FUZZ_CHECK(m.pointCount >= 0 && m.pointCount <= 2);
  if (m.pointCount == 0) {
    IMPULSE2D_FUZZ_CHECK(truth.separation >
                         (truth.exactSpeculative ? speculative : 0.0) - kTolerance);
    return 0;
  }
  IMPULSE2D_FUZZ_CHECK(impulse2d::isFinite(m.normal));
  IMPULSE2D_FUZZ_CHECK(std::abs(m.normal.norm() - 1.0) < 1e-9);
  double shallowest = -std::numeric_limits<double>::infinity();
  double deepest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < m.pointCount; ++i) {
    IMPULSE2D_FUZZ_CHECK(impulse2d::isFinite(m.points[i].point));
    IMPULSE2D_FUZZ_CHECK(std::isfinite(m.points[i].separation));
    IMPULSE2D_FUZZ_CHECK(m.points[i].separation <= speculative + kTolerance);
    shallowest = std::max(shallowest, m.points[i].separation);
    deepest = std::min(deepest, m.points[i].separation);
  }
  const bool overlapping = truth.separation < 0.0;
  if ((overlapping && !(deepest <= kTolerance)) ||
      !(deepest >= truth.deepestAllowed - kTolerance)) {
    std::fprintf(stderr, "points %d deepest %.17g shallowest %.17g true %.17g allowed %.17g\n",
                 m.pointCount, deepest, shallowest, truth.separation, truth.deepestAllowed);
  }
  // Overlapping shapes always get a penetrating point. (Separated ones may get a speculative
  // point farther than the true distance: clipping against a reference face measures a vertex
  // that the side plane cut off along the face normal, not to the nearest feature; README
  // "Reliability" gives the size seen.)
  if (overlapping) IMPULSE2D_FUZZ_CHECK(deepest <= kTolerance);
  IMPULSE2D_FUZZ_CHECK(deepest >= truth.deepestAllowed - kTolerance);
  return 0;
}
