// Shape construction (polygon validation), mass properties and bounding boxes.
#include <impulse2d/shape.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace impulse2d {
namespace {

// Twice the signed area of the polygon; positive for counter-clockwise winding.
double twiceSignedArea(const std::vector<Vec2>& p) {
  double sum = 0.0;
  for (size_t i = 0; i < p.size(); ++i) sum += cross(p[i], p[(i + 1) % p.size()]);
  return sum;
}

void finishPolygon(Polygon* poly) {
  const int n = poly->count;
  for (int i = 0; i < n; ++i) {
    const Vec2 edge = poly->vertices[(i + 1) % n] - poly->vertices[i];
    poly->normals[i] = cross(edge, 1.0).normalized();  // outward for counter-clockwise winding
  }
  // Centroid of a triangle fan around the first vertex (exact for any convex polygon).
  Vec2 centroid = Vec2::Zero();
  double area = 0.0;
  const Vec2 origin = poly->vertices[0];
  for (int i = 1; i + 1 < n; ++i) {
    const Vec2 e1 = poly->vertices[i] - origin;
    const Vec2 e2 = poly->vertices[i + 1] - origin;
    const double a = 0.5 * cross(e1, e2);
    centroid += a * (e1 + e2) / 3.0;
    area += a;
  }
  poly->centroid = origin + centroid / area;
}

}  // namespace

std::string makePolygon(const std::vector<Vec2>& points, Polygon* out) {
  const int n = static_cast<int>(points.size());
  if (n < 3) return "needs at least 3 vertices";
  if (n > kMaxPolygonVertices) {
    return "has " + std::to_string(n) + " vertices, at most " +
           std::to_string(kMaxPolygonVertices) + " are allowed";
  }
  for (const Vec2& p : points) {
    if (!isFinite(p)) return "vertices must be finite numbers";
    // Beyond this the area and inertia products overflow long before doubles do.
    if (p.cwiseAbs().maxCoeff() > kMaxCoordinate) return "vertices must be within 1e6 m";
  }
  std::vector<Vec2> ccw = points;
  if (twiceSignedArea(ccw) < 0.0) std::reverse(ccw.begin(), ccw.end());
  double maxExtent = 0.0;
  for (const Vec2& p : ccw) maxExtent = std::max(maxExtent, (p - ccw[0]).norm());
  for (int i = 0; i < n; ++i) {
    const Vec2& a = ccw[i];
    const Vec2& b = ccw[(i + 1) % n];
    const Vec2& c = ccw[(i + 2) % n];
    if ((b - a).norm() < kMinFeatureSize) return "has an edge shorter than 0.1 mm";
    // Every turn must be strictly to the left; a tolerance relative to the size rejects
    // collinear and reflex vertices alike.
    if (cross(b - a, c - b) <= 1e-9 * maxExtent * maxExtent) return "is not strictly convex";
  }
  // Left turns everywhere still admit a star that winds twice around its centre: every vertex
  // must also lie inside every edge.
  for (int i = 0; i < n; ++i) {
    const Vec2 edge = ccw[(i + 1) % n] - ccw[i];
    for (int j = 0; j < n; ++j) {
      if (j != i && j != (i + 1) % n && cross(edge, ccw[j] - ccw[i]) <= 0.0) {
        return "is not strictly convex";
      }
    }
  }
  if (0.5 * twiceSignedArea(ccw) < kMinFeatureSize * kMinFeatureSize) return "has no area";
  Polygon poly;
  poly.count = n;
  for (int i = 0; i < n; ++i) poly.vertices[i] = ccw[i];
  finishPolygon(&poly);
  *out = poly;
  return "";
}

Polygon makeBox(double w, double h, const Vec2& center, double angle) {
  Polygon box;
  box.count = 4;
  const double hx = 0.5 * w, hy = 0.5 * h;
  const Transform xf(center, Rot(angle));
  box.vertices[0] = xf.apply(Vec2(-hx, -hy));
  box.vertices[1] = xf.apply(Vec2(hx, -hy));
  box.vertices[2] = xf.apply(Vec2(hx, hy));
  box.vertices[3] = xf.apply(Vec2(-hx, hy));
  finishPolygon(&box);
  return box;
}

Polygon transformed(const Polygon& polygon, const Transform& xf) {
  Polygon out = polygon;
  for (int i = 0; i < polygon.count; ++i) {
    out.vertices[i] = xf.apply(polygon.vertices[i]);
    out.normals[i] = xf.q.apply(polygon.normals[i]);
  }
  out.centroid = xf.apply(polygon.centroid);
  return out;
}

std::string makeShape(const ShapeDef& def, Shape* out) {
  if (!isFinite(def.offset)) return "offset: must be finite";
  if (def.offset.cwiseAbs().maxCoeff() > kMaxCoordinate) return "offset: must be within 1e6 m";
  if (!std::isfinite(def.angle)) return "angle: must be finite";
  if (!std::isfinite(def.density) || def.density < 0.0) return "density: must be finite and >= 0";
  if (!std::isfinite(def.friction) || def.friction < 0.0)
    return "friction: must be finite and >= 0";
  if (!std::isfinite(def.restitution) || def.restitution < 0.0 || def.restitution > 1.0) {
    return "restitution: must be in [0, 1]";
  }
  if (!std::isfinite(def.reflectance) || def.reflectance < 0.0 || def.reflectance > 1e6) {
    return "reflectance: must be finite, >= 0 and at most 1e6";
  }
  const Transform xf(def.offset, Rot(def.angle));
  Shape shape;
  shape.density = def.density;
  shape.friction = def.friction;
  shape.restitution = def.restitution;
  shape.reflectance = def.reflectance;
  shape.filter = def.filter;
  switch (def.kind) {
    case ShapeKind::Box:
      if (!isFinite(def.size) || def.size.x() < kMinFeatureSize || def.size.y() < kMinFeatureSize) {
        return "size: width and height must be finite and > 0.1 mm";
      }
      if (def.size.maxCoeff() > kMaxCoordinate) return "size: must be at most 1e6 m";
      shape.type = ShapeType::Polygon;
      shape.polygon = makeBox(def.size.x(), def.size.y(), def.offset, def.angle);
      break;
    case ShapeKind::Circle:
      if (!std::isfinite(def.radius) || def.radius < kMinFeatureSize) {
        return "radius: must be finite and > 0.1 mm";
      }
      if (def.radius > kMaxCoordinate) return "radius: must be at most 1e6 m";
      shape.type = ShapeType::Circle;
      shape.circle.center = def.offset;
      shape.circle.radius = def.radius;
      break;
    case ShapeKind::Polygon: {
      Polygon local;
      const std::string why = makePolygon(def.vertices, &local);
      if (!why.empty()) return "vertices: polygon " + why;
      shape.type = ShapeType::Polygon;
      shape.polygon = transformed(local, xf);
      break;
    }
  }
  *out = shape;
  return "";
}

MassData computeMass(const Shape& shape) {
  MassData md;
  if (shape.type == ShapeType::Circle) {
    const double r2 = shape.circle.radius * shape.circle.radius;
    md.mass = shape.density * kPi * r2;
    md.center = shape.circle.center;
    md.inertia = 0.5 * md.mass * r2;
    return md;
  }
  // Triangle fan about the centroid: each triangle (c, v_i, v_i+1) adds its area and its
  // second moment about c, which is area/6 * (e1.e1 + e1.e2 + e2.e2).
  const Polygon& poly = shape.polygon;
  const Vec2 c = poly.centroid;
  double area = 0.0, secondMoment = 0.0;
  for (int i = 0; i < poly.count; ++i) {
    const Vec2 e1 = poly.vertices[i] - c;
    const Vec2 e2 = poly.vertices[(i + 1) % poly.count] - c;
    const double a = 0.5 * cross(e1, e2);
    area += a;
    secondMoment += a / 6.0 * (e1.dot(e1) + e1.dot(e2) + e2.dot(e2));
  }
  md.mass = shape.density * area;
  md.center = c;
  md.inertia = shape.density * secondMoment;
  return md;
}

double innerRadius(const Shape& shape) {
  if (shape.type == ShapeType::Circle) return shape.circle.radius;
  const Polygon& poly = shape.polygon;
  double r = std::numeric_limits<double>::infinity();
  for (int i = 0; i < poly.count; ++i) {
    r = std::min(r, poly.normals[i].dot(poly.vertices[i] - poly.centroid));
  }
  return r;
}

Aabb computeAabb(const Shape& shape, const Transform& xf) {
  if (shape.type == ShapeType::Circle) {
    const Vec2 p = xf.apply(shape.circle.center);
    const Vec2 r = Vec2::Constant(shape.circle.radius);
    return Aabb{p - r, p + r};
  }
  // Called for every moving shape on every step, and twice more for each fast one. The box of
  // the turned vertices is found first and moved by p once: rounding is monotonic, so
  // max_i (p + r_i) = p + max_i r_i bit for bit, and the box is xf.apply's to the last bit (a
  // zero's sign aside, which no comparison sees).
  const Polygon& poly = shape.polygon;
#if defined(__SSE2__)
  // A vertex [x y] a register: [c s] x + [-s c] y = [c x - s y, s x + c y], xf.q.apply's own
  // operations ((-s) y is -(s y) exactly).
  const __m128d cs = _mm_set_pd(xf.q.s, xf.q.c), minusSc = _mm_set_pd(xf.q.c, -xf.q.s);
  auto turned = [&](const Vec2& v) {
    const __m128d xy = _mm_loadu_pd(v.data());
    return _mm_add_pd(_mm_mul_pd(cs, _mm_unpacklo_pd(xy, xy)),
                      _mm_mul_pd(minusSc, _mm_unpackhi_pd(xy, xy)));
  };
  __m128d lower = turned(poly.vertices[0]), upper = lower;
  for (int i = 1; i < poly.count; ++i) {
    const __m128d r = turned(poly.vertices[i]);
    lower = _mm_min_pd(lower, r);
    upper = _mm_max_pd(upper, r);
  }
  const __m128d p = _mm_loadu_pd(xf.p.data());
  Aabb box;
  _mm_storeu_pd(box.lower.data(), _mm_add_pd(p, lower));
  _mm_storeu_pd(box.upper.data(), _mm_add_pd(p, upper));
  return box;
#else
  const Vec2 first = xf.q.apply(poly.vertices[0]);
  double minX = first.x(), minY = first.y(), maxX = minX, maxY = minY;
  for (int i = 1; i < poly.count; ++i) {
    const Vec2 v = xf.q.apply(poly.vertices[i]);
    minX = std::min(minX, v.x());
    minY = std::min(minY, v.y());
    maxX = std::max(maxX, v.x());
    maxY = std::max(maxY, v.y());
  }
  return Aabb{Vec2(xf.p.x() + minX, xf.p.y() + minY), Vec2(xf.p.x() + maxX, xf.p.y() + maxY)};
#endif
}

}  // namespace impulse2d
