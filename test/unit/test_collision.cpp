// Narrow phase: hand-computed manifolds and a randomized property test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <impulse2d/collision.hpp>
#include <limits>
#include <random>
#include <vector>

#include "test_scenes.hpp"

namespace impulse2d {
namespace {

using test::boxShape;
using test::circleShape;

constexpr double kExact = 1e-9;
constexpr double kSpeculative = 0.02;

Transform pose(double x, double y, double angle = 0.0) { return Transform(Vec2(x, y), Rot(angle)); }

std::vector<ManifoldPoint> sortedByX(const Manifold& m) {
  std::vector<ManifoldPoint> points(m.points, m.points + m.pointCount);
  std::sort(points.begin(), points.end(), [](const ManifoldPoint& p, const ManifoldPoint& q) {
    return p.point.x() < q.point.x();
  });
  return points;
}

void expectPoint(const ManifoldPoint& p, double x, double y, double separation) {
  EXPECT_NEAR(p.point.x(), x, kExact);
  EXPECT_NEAR(p.point.y(), y, kExact);
  EXPECT_NEAR(p.separation, separation, kExact);
}

void expectNormal(const Manifold& m, double x, double y) {
  EXPECT_NEAR(m.normal.x(), x, kExact);
  EXPECT_NEAR(m.normal.y(), y, kExact);
}

double segmentDistance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.dot(ab), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

// Distance from world point p to the boundary of the shape (outline, not area).
double boundaryDistance(const Shape& s, const Transform& xf, const Vec2& p) {
  if (s.type == ShapeType::Circle) {
    return std::abs((p - xf.apply(s.circle.center)).norm() - s.circle.radius);
  }
  double best = std::numeric_limits<double>::infinity();
  const Polygon& poly = s.polygon;
  for (int i = 0; i < poly.count; ++i) {
    best = std::min(best, segmentDistance(p, xf.apply(poly.vertices[i]),
                                          xf.apply(poly.vertices[(i + 1) % poly.count])));
  }
  return best;
}

// Signed distance from a world point to a polygon: negative inside.
double signedDistance(const Polygon& poly, const Transform& xf, const Vec2& p) {
  double maxFace = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < poly.count; ++i) {
    maxFace = std::max(maxFace, xf.q.apply(poly.normals[i]).dot(p - xf.apply(poly.vertices[i])));
  }
  if (maxFace <= 0.0) return maxFace;
  Shape s;
  s.polygon = poly;
  return boundaryDistance(s, xf, p);
}

TEST(CollidePolygons, BoxRestingOnGround) {
  const Shape ground = boxShape(10.0, 1.0);  // top face at y = 0.5
  const Shape box = boxShape(1.0, 1.0);
  const Transform xfGround = pose(0.0, 0.0);
  const Transform xfBox = pose(0.3, 0.99);  // bottom at y = 0.49: 0.01 m of overlap

  const Manifold m = collideShapes(ground, xfGround, box, xfBox, kSpeculative);
  ASSERT_EQ(m.pointCount, 2);
  expectNormal(m, 0.0, 1.0);
  auto points = sortedByX(m);
  expectPoint(points[0], -0.2, 0.495, -0.01);
  expectPoint(points[1], 0.8, 0.495, -0.01);

  const Manifold swapped = collideShapes(box, xfBox, ground, xfGround, kSpeculative);
  ASSERT_EQ(swapped.pointCount, 2);
  expectNormal(swapped, 0.0, -1.0);
  points = sortedByX(swapped);
  expectPoint(points[0], -0.2, 0.495, -0.01);
  expectPoint(points[1], 0.8, 0.495, -0.01);
}

TEST(CollidePolygons, SeparatedBoxesOnlyWithinTheSpeculativeDistance) {
  const Shape ground = boxShape(10.0, 1.0);
  const Shape box = boxShape(1.0, 1.0);
  EXPECT_EQ(collideShapes(ground, pose(0, 0), box, pose(0.3, 1.03), kSpeculative).pointCount, 0);

  const Manifold m = collideShapes(ground, pose(0, 0), box, pose(0.3, 1.01), kSpeculative);
  ASSERT_EQ(m.pointCount, 2);
  expectNormal(m, 0.0, 1.0);
  const auto points = sortedByX(m);
  expectPoint(points[0], -0.2, 0.505, 0.01);
  expectPoint(points[1], 0.8, 0.505, 0.01);
}

TEST(CollidePolygons, BoxStandingOnACorner) {
  const double halfDiagonal = std::sqrt(0.5);
  const Transform xfBox = pose(0.0, 0.5 + halfDiagonal - 0.01, kPi / 4.0);
  const Manifold m =
      collideShapes(boxShape(10, 1), pose(0, 0), boxShape(1, 1), xfBox, kSpeculative);
  ASSERT_EQ(m.pointCount, 1);
  expectNormal(m, 0.0, 1.0);
  expectPoint(m.points[0], 0.0, 0.495, -0.01);
}

// The solver matches points by id between steps, so a slightly moved contact must keep them.
// The box (B, or A when `moveA`) is shifted by 1 mm and turned by 1 mrad.
void expectStableIds(const Shape& a, Transform xfA, const Shape& b, Transform xfB,
                     bool moveA = false) {
  const Manifold before = collideShapes(a, xfA, b, xfB, kSpeculative);
  Transform& moved = moveA ? xfA : xfB;
  moved = Transform(moved.p + Vec2(1e-3, 1e-3), moved.q * Rot(1e-3));
  const Manifold after = collideShapes(a, xfA, b, xfB, kSpeculative);
  ASSERT_EQ(before.pointCount, 2);
  ASSERT_EQ(after.pointCount, 2);
  EXPECT_NE(before.points[0].id, before.points[1].id);
  EXPECT_EQ(before.points[0].id, after.points[0].id);
  EXPECT_EQ(before.points[1].id, after.points[1].id);
}

TEST(CollidePolygons, FeatureIdsStableUnderSmallMotion) {
  const Shape ground = boxShape(10.0, 1.0);
  const Shape box = boxShape(1.0, 1.0);
  {
    SCOPED_TRACE("box on ground");
    expectStableIds(ground, pose(0, 0), box, pose(0.3, 0.99));
  }
  {
    // Flat, both faces are equally deep and A's (the box's) is the reference; tilted, the
    // ground's corners 5 m away rise 5 mm above the box's face line and the ground's face
    // becomes the reference. The ids name features by shape, so they survive the flip.
    SCOPED_TRACE("ground under box, reference flips");
    expectStableIds(box, pose(0.3, 0.99), ground, pose(0, 0), true);
  }
  {
    SCOPED_TRACE("equal boxes stacked, the flip-flop case");
    expectStableIds(box, pose(0, 0), box, pose(0.1, 0.99));
    expectStableIds(box, pose(0.1, 0.99), box, pose(0, 0), true);
  }
  {
    SCOPED_TRACE("wide box on a narrow one, clipped on both sides");
    expectStableIds(box, pose(0, 0), boxShape(3, 1), pose(0.1, 0.99));
  }
}

// Found by the randomized test: a thin bar A deep (0.85 m) in a heptagon B. A's shallowest
// face is the bar's short end cap, and the face of B most opposed to it lies beside the bar,
// beyond the cap's side planes, so clipping against the cap leaves nothing. B's best face must
// then be used: the cap vertices against B's face (-0.68, -0.27) -> (-0.45, 0.23).
// Boxes whose opposite normals are exact negatives (makeBox's) take a shortcut in the separating
// axis test; the same boxes with one normal off by an ulp take the general loop. The manifolds
// must agree to round-off, over random sizes and poses, touching or not.
TEST(CollidePolygons, BoxShortcutMatchesTheGeneralPolygonPath) {
  std::mt19937 rng(20261123);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto general = [](Polygon box) {
    box.normals[2].x() = std::nextafter(box.normals[2].x(), 2.0);
    return box;
  };
  int touching = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    SCOPED_TRACE(trial);
    const Polygon a = makeBox(0.05 + 3.0 * unit(rng), 0.05 + 3.0 * unit(rng));
    const Polygon b = makeBox(0.05 + 3.0 * unit(rng), 0.05 + 3.0 * unit(rng));
    const Transform xfA(Vec2(unit(rng) - 0.5, unit(rng) - 0.5), Rot(2.0 * kPi * unit(rng)));
    const Transform xfB(Vec2(4.0 * unit(rng) - 2.0, 4.0 * unit(rng) - 2.0),
                        Rot(trial % 4 == 0 ? 0.0 : 2.0 * kPi * unit(rng)));
    const Manifold fast = collidePolygons(a, xfA, b, xfB, kSpeculative);
    const Manifold slow = collidePolygons(general(a), xfA, general(b), xfB, kSpeculative);
    ASSERT_EQ(fast.pointCount, slow.pointCount);
    if (fast.pointCount > 0) ++touching;
    for (int k = 0; k < fast.pointCount; ++k) {
      EXPECT_EQ(fast.points[k].id, slow.points[k].id);
      EXPECT_NEAR(fast.points[k].separation, slow.points[k].separation, 1e-12);
      EXPECT_NEAR((fast.points[k].point - slow.points[k].point).norm(), 0.0, 1e-12);
      EXPECT_NEAR((fast.normal - slow.normal).norm(), 0.0, 1e-12);
    }
  }
  EXPECT_GT(touching, 1000);  // the comparison covered contacts, not only misses
}

TEST(CollidePolygons, DeepOverlapBehindAShortReferenceFace) {
  Shape bar, heptagon;
  ASSERT_EQ(
      makePolygon({Vec2(-1.26, 0.46), Vec2(-1.39, 0.22), Vec2(0.73, -0.96), Vec2(0.86, -0.73)},
                  &bar.polygon),
      "");
  ASSERT_EQ(makePolygon({Vec2(-0.45, 0.23), Vec2(-0.32, 0.66), Vec2(-1.17, 1.79), Vec2(-1.37, 1.62),
                         Vec2(-1.21, -1.08), Vec2(-0.84, -0.55), Vec2(-0.68, -0.27)},
                        &heptagon.polygon),
            "");
  const Manifold m = collideShapes(bar, Transform(), heptagon, Transform(), kSpeculative);
  ASSERT_EQ(m.pointCount, 2);
  const Vec2 faceStart(-0.68, -0.27);
  const Vec2 faceNormal = Vec2(0.50, -0.23).normalized();  // outward normal of B's face
  expectNormal(m, -faceNormal.x(), -faceNormal.y());
  auto points = sortedByX(m);
  const Vec2 cap[2] = {Vec2(-1.39, 0.22), Vec2(-1.26, 0.46)};
  for (int k = 0; k < 2; ++k) {
    const double separation = faceNormal.dot(cap[k] - faceStart);
    const Vec2 mid = cap[k] - 0.5 * separation * faceNormal;
    expectPoint(points[k], mid.x(), mid.y(), separation);
  }
}

TEST(CollideCircles, OverlapSeparatedCoincident) {
  const Circle a{Vec2::Zero(), 0.5};
  const Circle b{Vec2(0.1, 0.0), 0.5};  // body-frame offset, rotated by B's transform below
  Manifold m = collideCircles(a, pose(0, 0), b, pose(0.9, 0.1, kPi / 2.0), kSpeculative);
  ASSERT_EQ(m.pointCount, 1);  // centre of B at (0.9, 0.2)
  const double d = std::hypot(0.9, 0.2);
  expectNormal(m, 0.9 / d, 0.2 / d);
  EXPECT_NEAR(m.points[0].separation, d - 1.0, kExact);

  m = collideCircles(a, pose(0, 0), a, pose(0, -0.9), kSpeculative);
  ASSERT_EQ(m.pointCount, 1);
  expectNormal(m, 0.0, -1.0);
  expectPoint(m.points[0], 0.0, -0.45, -0.1);

  m = collideCircles(a, pose(0, 0), a, pose(1.01, 0), kSpeculative);
  ASSERT_EQ(m.pointCount, 1);
  expectPoint(m.points[0], 0.505, 0.0, 0.01);
  EXPECT_EQ(collideCircles(a, pose(0, 0), a, pose(1.03, 0), kSpeculative).pointCount, 0);

  m = collideCircles(a, pose(2, 3), a, pose(2, 3), kSpeculative);
  ASSERT_EQ(m.pointCount, 1);
  expectNormal(m, 0.0, 1.0);
  expectPoint(m.points[0], 2.0, 3.0, -1.0);
}

TEST(CollidePolygonCircle, CircleOnFace) {
  const Manifold m =
      collideShapes(boxShape(2, 2), pose(0, 0), circleShape(0.5), pose(0.3, 1.4), kSpeculative);
  ASSERT_EQ(m.pointCount, 1);
  expectNormal(m, 0.0, 1.0);
  expectPoint(m.points[0], 0.3, 0.95, -0.1);
}

TEST(CollidePolygonCircle, CircleAtCornerUsesTheVertexDirection) {
  const Manifold m =
      collideShapes(boxShape(2, 2), pose(0, 0), circleShape(0.5), pose(1.3, 1.3), kSpeculative);
  ASSERT_EQ(m.pointCount, 1);
  const double h = std::sqrt(0.5);
  expectNormal(m, h, h);
  const double distance = 0.3 * std::sqrt(2.0);
  const double mid = 0.5 * (1.0 + (1.3 - 0.5 * h));  // between the corner and the circle
  expectPoint(m.points[0], mid, mid, distance - 0.5);
  // Just outside the speculative distance along the diagonal: nothing.
  const double far = 1.0 + (0.5 + 0.021) * h;
  EXPECT_EQ(
      collideShapes(boxShape(2, 2), pose(0, 0), circleShape(0.5), pose(far, far), kSpeculative)
          .pointCount,
      0);
}

TEST(CollidePolygonCircle, CentreInsideUsesTheShallowestFace) {
  const Manifold m =
      collideShapes(boxShape(2, 2), pose(0, 0), circleShape(0.5), pose(0.2, 0.7), kSpeculative);
  ASSERT_EQ(m.pointCount, 1);
  expectNormal(m, 0.0, 1.0);
  expectPoint(m.points[0], 0.2, 0.6, -0.8);
}

TEST(CollidePolygonCircle, CentreOnVertexOrEdgeGivesNoNaN) {
  for (const Vec2& c : {Vec2(1.0, 1.0), Vec2(0.3, 1.0), Vec2(1.0, -1.0)}) {
    const Manifold m = collideShapes(boxShape(2, 2), pose(0, 0), circleShape(0.5),
                                     Transform(c, Rot()), kSpeculative);
    ASSERT_EQ(m.pointCount, 1);
    EXPECT_NEAR(m.normal.norm(), 1.0, kExact);
    EXPECT_TRUE(isFinite(m.points[0].point));
    EXPECT_NEAR(m.points[0].separation, -0.5, kExact);
  }
}

TEST(CollideShapes, NormalPointsFromAToBForEveryPair) {
  // Pointers, not copies: copying a circle Shape copies its never-initialised polygon, which
  // GCC 12 at -O3 reports as maybe-uninitialized.
  const Shape box = boxShape(1, 1);
  const Shape ball = circleShape(0.5);
  const Transform low = pose(0.0, 0.0, 0.1);
  const Transform high = pose(0.2, 0.9, -0.2);
  for (const Shape* a : {&box, &ball}) {
    for (const Shape* b : {&box, &ball}) {
      const Manifold up = collideShapes(*a, low, *b, high, kSpeculative);
      const Manifold down = collideShapes(*a, high, *b, low, kSpeculative);
      ASSERT_GE(up.pointCount, 1);
      ASSERT_GE(down.pointCount, 1);
      EXPECT_GT(up.normal.y(), 0.5);
      EXPECT_LT(down.normal.y(), -0.5);
    }
  }
  // Circle A against polygon B is polygon/circle with the normal flipped, nothing else.
  const Manifold direct = collidePolygonCircle(box.polygon, high, ball.circle, low, kSpeculative);
  const Manifold swapped = collideShapes(ball, low, box, high, kSpeculative);
  ASSERT_EQ(swapped.pointCount, 1);
  EXPECT_NEAR((swapped.normal + direct.normal).norm(), 0.0, kExact);
  EXPECT_NEAR((swapped.points[0].point - direct.points[0].point).norm(), 0.0, kExact);
  EXPECT_NEAR(swapped.points[0].separation, direct.points[0].separation, kExact);
}

// ---------------------------------------------------------------------------------------------
// Randomized properties.

Shape randomShape(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ShapeDef def;
  def.offset = Vec2(unit(rng) - 0.5, unit(rng) - 0.5);
  def.angle = 2.0 * kPi * unit(rng);
  const int kind = static_cast<int>(3.0 * unit(rng));
  if (kind == 0) {
    def.kind = ShapeKind::Box;
    def.size = Vec2(0.05 + 3.0 * unit(rng), 0.05 + 3.0 * unit(rng));
  } else if (kind == 1) {
    def.kind = ShapeKind::Circle;
    def.radius = 0.05 + 1.5 * unit(rng);
  } else {
    // Points of a circle at sorted angles, stretched into an ellipse: always convex, though
    // makePolygon may still refuse near-degenerate draws, which are simply redrawn.
    def.kind = ShapeKind::Polygon;
    const int n = 3 + static_cast<int>(6.0 * unit(rng));
    const double sx = 0.1 + 2.0 * unit(rng), sy = 0.1 + 2.0 * unit(rng);
    std::vector<double> angles;
    for (int i = 0; i < n; ++i) angles.push_back(2.0 * kPi * unit(rng));
    std::sort(angles.begin(), angles.end());
    for (double t : angles) def.vertices.push_back(Vec2(sx * std::cos(t), sy * std::sin(t)));
  }
  Shape shape;
  if (!makeShape(def, &shape).empty()) return randomShape(rng);
  return shape;
}

double aabbGap(const Aabb& a, const Aabb& b) {
  return std::max({b.lower.x() - a.upper.x(), a.lower.x() - b.upper.x(), b.lower.y() - a.upper.y(),
                   a.lower.y() - b.upper.y()});
}

double faceDistance(const Polygon& p, const Transform& xf, int face, const Vec2& point) {
  return xf.q.apply(p.normals[face]).dot(point - xf.apply(p.vertices[face]));
}

// Largest separation along all face normals of both polygons: for convex polygons the signed
// distance when positive, minus the penetration depth when negative.
double trueFaceSeparation(const Polygon& a, const Transform& xfA, const Polygon& b,
                          const Transform& xfB) {
  double best = -std::numeric_limits<double>::infinity();
  for (int pass = 0; pass < 2; ++pass) {
    const Polygon& p = pass == 0 ? a : b;
    const Polygon& q = pass == 0 ? b : a;
    const Transform& xp = pass == 0 ? xfA : xfB;
    const Transform& xq = pass == 0 ? xfB : xfA;
    for (int i = 0; i < p.count; ++i) {
      double deepest = std::numeric_limits<double>::infinity();
      for (int j = 0; j < q.count; ++j) {
        deepest = std::min(deepest, faceDistance(p, xp, i, xq.apply(q.vertices[j])));
      }
      best = std::max(best, deepest);
    }
  }
  return best;
}

bool hasVertexInside(const Polygon& p, const Transform& xp, const Polygon& q, const Transform& xq) {
  for (int j = 0; j < p.count; ++j) {
    if (signedDistance(q, xq, xp.apply(p.vertices[j])) < -1e-6) return true;
  }
  return false;
}

TEST(CollideShapes, RandomizedProperties) {
  std::mt19937 rng(20060301);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int far = 0, touching = 0, vertexInside = 0, twoPoints = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    SCOPED_TRACE(trial);
    const Shape a = randomShape(rng);
    const Shape b = randomShape(rng);
    const Transform xfA(Vec2(unit(rng) - 0.5, unit(rng) - 0.5), Rot(2.0 * kPi * unit(rng)));
    const Transform xfB(Vec2(6.0 * unit(rng) - 3.0, 6.0 * unit(rng) - 3.0),
                        Rot(2.0 * kPi * unit(rng)));
    const Manifold m = collideShapes(a, xfA, b, xfB, kSpeculative);

    ASSERT_GE(m.pointCount, 0);
    ASSERT_LE(m.pointCount, 2);
    double minSeparation = std::numeric_limits<double>::infinity();
    for (int k = 0; k < m.pointCount; ++k) {
      const ManifoldPoint& p = m.points[k];
      ASSERT_TRUE(isFinite(p.point));
      ASSERT_TRUE(std::isfinite(p.separation));
      EXPECT_LE(p.separation, kSpeculative);
      // The point is midway: half the separation back along the normal lies on A, forward on B.
      EXPECT_LT(boundaryDistance(a, xfA, p.point - 0.5 * p.separation * m.normal), kExact);
      EXPECT_LT(boundaryDistance(b, xfB, p.point + 0.5 * p.separation * m.normal), kExact);
      minSeparation = std::min(minSeparation, p.separation);
    }
    if (m.pointCount > 0) {
      ASSERT_TRUE(isFinite(m.normal));
      EXPECT_NEAR(m.normal.norm(), 1.0, kExact);
      ++touching;
    }
    if (m.pointCount == 2) {
      EXPECT_NE(m.points[0].id, m.points[1].id);
      ++twoPoints;
    }
    if (aabbGap(computeAabb(a, xfA), computeAabb(b, xfB)) > kSpeculative) {
      EXPECT_EQ(m.pointCount, 0);
      ++far;
    }

    // Circles are exact: the separation is the signed distance minus the radii.
    if (a.type == ShapeType::Circle || b.type == ShapeType::Circle) {
      double expected = 0.0;
      if (a.type == ShapeType::Circle && b.type == ShapeType::Circle) {
        expected = (xfB.apply(b.circle.center) - xfA.apply(a.circle.center)).norm() -
                   a.circle.radius - b.circle.radius;
      } else {
        const bool circleIsB = b.type == ShapeType::Circle;
        const Shape& poly = circleIsB ? a : b;
        const Shape& circle = circleIsB ? b : a;
        const Transform& xfPoly = circleIsB ? xfA : xfB;
        const Transform& xfCircle = circleIsB ? xfB : xfA;
        expected = signedDistance(poly.polygon, xfPoly, xfCircle.apply(circle.circle.center)) -
                   circle.circle.radius;
      }
      if (expected <= kSpeculative - 1e-9) {
        ASSERT_EQ(m.pointCount, 1);
        EXPECT_NEAR(m.points[0].separation, expected, kExact);
        if (expected < 0.0) ++vertexInside;
      } else if (expected > kSpeculative + 1e-9) {
        EXPECT_EQ(m.pointCount, 0);
      }
      continue;
    }

    const double faceSeparation = trueFaceSeparation(a.polygon, xfA, b.polygon, xfB);
    if (hasVertexInside(a.polygon, xfA, b.polygon, xfB) ||
        hasVertexInside(b.polygon, xfB, a.polygon, xfA)) {
      ++vertexInside;
      ASSERT_GE(m.pointCount, 1);
      EXPECT_LT(minSeparation, 0.0);
    }
    if (m.pointCount > 0) {
      // Never deeper than the penetration depth, up to the flip-flop tolerance (see
      // collision.cpp: 0.0005 m plus 2 % of the depth).
      EXPECT_GE(minSeparation, faceSeparation - 0.0006 - 0.03 * std::abs(faceSeparation));
    }
  }
  // The draw must exercise every branch, or the properties above prove little.
  EXPECT_GT(far, 500);
  EXPECT_GT(touching, 500);
  EXPECT_GT(vertexInside, 300);
  EXPECT_GT(twoPoints, 100);
}

}  // namespace
}  // namespace impulse2d
