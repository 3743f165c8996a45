#include "distance.hpp"

#include <algorithm>
#include <cmath>

namespace impulse2d {
namespace {

// A shape reduced to its core for GJK: the polygon's vertices, or a circle's centre, in world
// coordinates, plus the radius to add at the end.
struct Core {
  Vec2 points[kMaxPolygonVertices];
  int count = 0;
  double radius = 0.0;

  Core(const Shape& shape, const Transform& xf) {
    for (Vec2& p : points) p.setZero();  // quiets GCC's -O3 maybe-uninitialized false alarm
    if (shape.type == ShapeType::Circle) {
      points[0] = xf.apply(shape.circle.center);
      count = 1;
      radius = shape.circle.radius;
    } else {
      count = shape.polygon.count;
      for (int i = 0; i < count; ++i) points[i] = xf.apply(shape.polygon.vertices[i]);
    }
  }
  int support(const Vec2& d) const {
    int best = 0;
    double bestDot = points[0].dot(d);
    for (int i = 1; i < count; ++i) {
      const double dot = points[i].dot(d);
      if (dot > bestDot) {
        best = i;
        bestDot = dot;
      }
    }
    return best;
  }
};

struct SimplexVertex {
  Vec2 wA, wB, w;  // support points on A and B, and w = wB - wA
  int indexA, indexB;
  double a;  // barycentric weight of the closest point
};

struct Simplex {
  SimplexVertex v[3];
  int count = 0;

  // The closest point of the segment v0-v1 to the origin: weights from the projections of the
  // endpoints on the edge direction (the Voronoi regions of the two vertices and the edge).
  void solve2() {
    const Vec2 e = v[1].w - v[0].w;
    const double d2 = -v[0].w.dot(e), d1 = v[1].w.dot(e);
    if (d2 <= 0.0) {
      v[0].a = 1.0;
      count = 1;
    } else if (d1 <= 0.0) {
      v[1].a = 1.0;
      v[0] = v[1];
      count = 1;
    } else {
      v[0].a = d1 / (d1 + d2);
      v[1].a = d2 / (d1 + d2);
    }
  }

  // The triangle: test the regions of the vertices, then the edges, then the interior; the
  // signed areas d123_i say on which side of each edge the origin lies.
  void solve3() {
    const Vec2 &w1 = v[0].w, &w2 = v[1].w, &w3 = v[2].w;
    const Vec2 e12 = w2 - w1, e13 = w3 - w1, e23 = w3 - w2;
    const double d12_1 = w2.dot(e12), d12_2 = -w1.dot(e12);
    const double d13_1 = w3.dot(e13), d13_2 = -w1.dot(e13);
    const double d23_1 = w3.dot(e23), d23_2 = -w2.dot(e23);
    const double n123 = cross(e12, e13);
    const double d123_1 = n123 * cross(w2, w3);
    const double d123_2 = n123 * cross(w3, w1);
    const double d123_3 = n123 * cross(w1, w2);
    auto keepEdge = [&](int i, int j, double di, double dj) {  // weights: di for i, dj for j
      const SimplexVertex vi = v[i], vj = v[j];
      v[0] = vi;
      v[1] = vj;
      v[0].a = di / (di + dj);
      v[1].a = dj / (di + dj);
      count = 2;
    };
    auto keepVertex = [&](int i) {
      v[0] = v[i];
      v[0].a = 1.0;
      count = 1;
    };
    if (d12_2 <= 0.0 && d13_2 <= 0.0) return keepVertex(0);
    if (d12_1 > 0.0 && d12_2 > 0.0 && d123_3 <= 0.0) return keepEdge(0, 1, d12_1, d12_2);
    if (d13_1 > 0.0 && d13_2 > 0.0 && d123_2 <= 0.0) return keepEdge(0, 2, d13_1, d13_2);
    if (d12_1 <= 0.0 && d23_2 <= 0.0) return keepVertex(1);
    if (d13_1 <= 0.0 && d23_1 <= 0.0) return keepVertex(2);
    if (d23_1 > 0.0 && d23_2 > 0.0 && d123_1 <= 0.0) return keepEdge(1, 2, d23_1, d23_2);
    const double sum = d123_1 + d123_2 + d123_3;  // the origin is inside: overlap
    v[0].a = d123_1 / sum;
    v[1].a = d123_2 / sum;
    v[2].a = d123_3 / sum;
  }

  Vec2 closest() const {
    Vec2 p = Vec2::Zero();
    for (int i = 0; i < count; ++i) p += v[i].a * v[i].w;
    return p;
  }
};

}  // namespace

DistanceResult shapeDistance(const Shape& a, const Transform& xfA, const Shape& b,
                             const Transform& xfB) {
  const Core coreA(a, xfA), coreB(b, xfB);
  Simplex simplex;
  SimplexVertex& first = simplex.v[0];
  first.indexA = first.indexB = 0;
  first.wA = coreA.points[0];
  first.wB = coreB.points[0];
  first.w = first.wB - first.wA;
  first.a = 1.0;
  simplex.count = 1;

  DistanceResult result;
  constexpr int kMaxIterations = 30;
  while (result.iterations < kMaxIterations) {
    ++result.iterations;
    if (simplex.count == 2) simplex.solve2();
    if (simplex.count == 3) simplex.solve3();
    if (simplex.count == 3) break;  // the origin is inside the Minkowski difference

    const Vec2 d = -simplex.closest();  // towards the origin
    if (d.squaredNorm() < 1e-28) break;
    SimplexVertex next;
    next.indexA = coreA.support(-d);
    next.indexB = coreB.support(d);
    next.wA = coreA.points[next.indexA];
    next.wB = coreB.points[next.indexB];
    next.w = next.wB - next.wA;
    next.a = 0.0;
    // A support point already in the simplex means no progress: converged.
    bool duplicate = false;
    for (int i = 0; i < simplex.count; ++i) {
      duplicate |= simplex.v[i].indexA == next.indexA && simplex.v[i].indexB == next.indexB;
    }
    if (duplicate) break;
    simplex.v[simplex.count++] = next;
  }

  result.pointA.setZero();
  result.pointB.setZero();
  for (int i = 0; i < simplex.count; ++i) {
    result.pointA += simplex.v[i].a * simplex.v[i].wA;
    result.pointB += simplex.v[i].a * simplex.v[i].wB;
  }
  const double coreDistance = (result.pointB - result.pointA).norm();
  const double radii = coreA.radius + coreB.radius;
  if (simplex.count == 3 || coreDistance <= radii) {
    result.distance = 0.0;
    const Vec2 mid = 0.5 * (result.pointA + result.pointB);
    result.pointA = result.pointB = mid;
    return result;
  }
  const Vec2 normal = (result.pointB - result.pointA) / coreDistance;
  result.pointA += coreA.radius * normal;
  result.pointB -= coreB.radius * normal;
  result.distance = coreDistance - radii;
  return result;
}

namespace {
// The farthest point of a shape from the body's centre of mass: rotation moves no point faster
// than this radius times the angular speed.
double sweepRadius(const Shape& shape, const Vec2& localCenter) {
  if (shape.type == ShapeType::Circle) {
    return (shape.circle.center - localCenter).norm() + shape.circle.radius;
  }
  double r = 0.0;
  for (int i = 0; i < shape.polygon.count; ++i) {
    r = std::max(r, (shape.polygon.vertices[i] - localCenter).norm());
  }
  return r;
}
}  // namespace

double timeOfImpact(const Shape& a, const Sweep& sweepA, const Shape& b, const Sweep& sweepB,
                    double target) {
  const double radiusA = sweepRadius(a, sweepA.localCenter);
  const double radiusB = sweepRadius(b, sweepB.localCenter);
  const Vec2 dA = sweepA.c1 - sweepA.c0, dB = sweepB.c1 - sweepB.c0;  // per unit t
  const double rotationBound =
      std::abs(sweepA.a1 - sweepA.a0) * radiusA + std::abs(sweepB.a1 - sweepB.a0) * radiusB;
  double t = 0.0;
  constexpr int kMaxIterations = 50;
  for (int i = 0; i < kMaxIterations; ++i) {
    const DistanceResult d = shapeDistance(a, sweepA.at(t), b, sweepB.at(t));
    if (d.distance <= target + 0.25 * target) return t;
    const Vec2 n = (d.pointB - d.pointA) / d.distance;
    // The gap along n closes no faster than the relative translation along n plus what rotation
    // can add anywhere on either shape.
    const double closing = (dA - dB).dot(n) + rotationBound;
    if (closing <= 0.0) return 1.0;
    t += (d.distance - target) / closing;
    if (t >= 1.0) return 1.0;
  }
  return t;
}

}  // namespace impulse2d
