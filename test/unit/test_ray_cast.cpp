// Ray casts against single shapes: hits computed by hand for each shape type, grazing rays,
// rays starting inside or on a shape, rays that stop short or point away; and the point and box
// tests of the queries.
#include <gtest/gtest.h>

#include <cmath>
#include <impulse2d/queries.hpp>

#include "test_scenes.hpp"

namespace impulse2d {
namespace {

using test::boxShape;
using test::circleShape;

constexpr double kExact = 1e-12;

Transform at(double x, double y, double angle = 0.0) { return Transform(Vec2(x, y), Rot(angle)); }

Shape polygonShape(const std::vector<Vec2>& points) {
  Shape s;
  s.type = ShapeType::Polygon;
  EXPECT_EQ(makePolygon(points, &s.polygon), "");
  return s;
}

void expectHit(const ShapeRayHit& hit, double fraction, double nx, double ny) {
  ASSERT_TRUE(hit.hit()) << "fraction " << hit.fraction;
  EXPECT_NEAR(hit.fraction, fraction, kExact);
  EXPECT_NEAR(hit.normal.x(), nx, kExact);
  EXPECT_NEAR(hit.normal.y(), ny, kExact);
}

TEST(RayCastShape, BoxFaceOnAndRotated) {
  // A 2 x 1 box at (3, 0): its left face is x = 2.
  expectHit(rayCastShape(boxShape(2.0, 1.0), at(3, 0), Vec2(0, 0), Vec2(10, 0)), 0.2, -1, 0);
  // Turned 90 degrees it is 1 wide and 2 tall: the left face is x = 4.5.
  expectHit(rayCastShape(boxShape(2.0, 1.0), at(5, 0, kPi / 2), Vec2(0, 0), Vec2(10, 0)), 0.45, -1,
            0);
  // Coming down onto the top face of the upright box (y = 1) from (5, 5).
  expectHit(rayCastShape(boxShape(2.0, 1.0), at(5, 0, kPi / 2), Vec2(5, 5), Vec2(5, -5)), 0.4, 0,
            1);
  // A square of side sqrt 2 turned 45 degrees about (5, 0): a diamond with corners (4, 0),
  // (5, 1), (6, 0), (5, -1). At y = 0.5 the lower-left edge x - y = 4 is at x = 4.5.
  const double s = std::sqrt(2.0);
  expectHit(rayCastShape(boxShape(s, s), at(5, 0, kPi / 4), Vec2(0, 0.5), Vec2(10, 0.5)), 0.45,
            -1 / s, 1 / s);
}

TEST(RayCastShape, CircleCentredAndOffCentre) {
  expectHit(rayCastShape(circleShape(1.0), at(5, 0), Vec2(0, 0), Vec2(10, 0)), 0.4, -1, 0);
  // At y = 0.6 the circle's left side is at x = 5 - sqrt(1 - 0.36) = 4.2, normal (-0.8, 0.6).
  expectHit(rayCastShape(circleShape(1.0), at(5, 0), Vec2(0, 0.6), Vec2(10, 0.6)), 0.42, -0.8, 0.6);
  // A circle offset in its body: centre (1, 0) in a body at (4, 0) turned 90 degrees is at
  // (4, 1); straight down from (4, 5) it is met at (4, 1.5).
  Shape offset = circleShape(0.5);
  offset.circle.center = Vec2(1.0, 0.0);
  expectHit(rayCastShape(offset, at(4, 0, kPi / 2), Vec2(4, 5), Vec2(4, -5)), 0.35, 0, 1);
}

TEST(RayCastShape, ConvexPolygon) {
  // A right triangle whose hypotenuse x + y = 5 runs from (6, -1) to (4, 1); from the right
  // along y = 0 it is met at x = 5, normal (1, 1) / sqrt 2.
  const Shape triangle = polygonShape({{4, -1}, {6, -1}, {4, 1}});
  const double s = std::sqrt(2.0);
  expectHit(rayCastShape(triangle, at(0, 0), Vec2(10, 0), Vec2(0, 0)), 0.5, 1 / s, 1 / s);
  // From below, onto the bottom edge y = -1 at x = 4.5.
  expectHit(rayCastShape(triangle, at(0, 0), Vec2(4.5, -3), Vec2(4.5, 1)), 0.5, 0, -1);
  // A pentagon seen through a vertex: straight down onto its top corner (0, 2).
  const Shape pentagon = polygonShape({{-2, 0}, {-1, -2}, {1, -2}, {2, 0}, {0, 2}});
  const ShapeRayHit corner = rayCastShape(pentagon, at(0, 0), Vec2(0, 6), Vec2(0, -6));
  ASSERT_TRUE(corner.hit());
  EXPECT_NEAR(corner.fraction, 4.0 / 12.0, kExact);
  EXPECT_GT(corner.normal.y(), 0.0);  // either face of the corner, facing up
}

TEST(RayCastShape, GrazingRaysTouchOrMiss) {
  // Tangent to the circle's top at (5, 1): a touch is a hit, with the normal straight up.
  expectHit(rayCastShape(circleShape(1.0), at(5, 0), Vec2(0, 1), Vec2(10, 1)), 0.5, 0, 1);
  EXPECT_FALSE(
      rayCastShape(circleShape(1.0), at(5, 0), Vec2(0, 1 + 1e-9), Vec2(10, 1 + 1e-9)).hit());
  // Along the top edge y = 1 of a 2 x 2 box at (5, 0): it enters through the left face.
  expectHit(rayCastShape(boxShape(2, 2), at(5, 0), Vec2(0, 1), Vec2(10, 1)), 0.4, -1, 0);
  EXPECT_FALSE(rayCastShape(boxShape(2, 2), at(5, 0), Vec2(0, 1 + 1e-9), Vec2(10, 1 + 1e-9)).hit());
  // Touching the corner (4, 1) only, diagonally: it enters the left face's half-plane there.
  expectHit(rayCastShape(boxShape(2, 2), at(5, 0), Vec2(2, -1), Vec2(6, 3)), 0.5, -1, 0);
  EXPECT_FALSE(rayCastShape(boxShape(2, 2), at(5, 0), Vec2(2, -0.999), Vec2(6, 3.001)).hit());
}

TEST(RayCastShape, StartingInsideOrOnTheBoundaryHitsAtTheStart) {
  // Inside: fraction 0, the normal pointing back along the ray.
  expectHit(rayCastShape(boxShape(2, 2), at(5, 0), Vec2(5, 0), Vec2(10, 0)), 0.0, -1, 0);
  expectHit(rayCastShape(circleShape(1.0), at(5, 0), Vec2(5.5, 0), Vec2(5.5, -4)), 0.0, 0, 1);
  const Shape triangle = polygonShape({{4, -1}, {6, -1}, {4, 1}});
  expectHit(rayCastShape(triangle, at(0, 0), Vec2(4.5, -0.5), Vec2(4.5, 9.5)), 0.0, 0, -1);
  // On the boundary, leaving or entering.
  expectHit(rayCastShape(boxShape(2, 2), at(5, 0), Vec2(6, 0), Vec2(10, 0)), 0.0, -1, 0);
  expectHit(rayCastShape(circleShape(1.0), at(5, 0), Vec2(4, 0), Vec2(10, 0)), 0.0, -1, 0);
  const double s = std::sqrt(2.0);
  expectHit(rayCastShape(boxShape(2, 2), at(5, 0), Vec2(5, 1), Vec2(6, 0)), 0.0, -1 / s, 1 / s);
  // A segment of zero length: a point test, with no direction to face.
  expectHit(rayCastShape(boxShape(2, 2), at(5, 0), Vec2(5, 0), Vec2(5, 0)), 0.0, 0, 0);
  EXPECT_FALSE(rayCastShape(boxShape(2, 2), at(5, 0), Vec2(0, 0), Vec2(0, 0)).hit());
}

TEST(RayCastShape, ShortAndAwayRaysMiss) {
  for (const Shape& shape : {boxShape(2, 2), circleShape(1.0)}) {
    EXPECT_FALSE(rayCastShape(shape, at(5, 0), Vec2(0, 0), Vec2(3.9, 0)).hit());  // stops short
    EXPECT_FALSE(rayCastShape(shape, at(5, 0), Vec2(0, 0), Vec2(-10, 0)).hit());  // points away
    EXPECT_FALSE(rayCastShape(shape, at(5, 0), Vec2(7, 0), Vec2(17, 0)).hit());   // beyond it
    EXPECT_FALSE(rayCastShape(shape, at(5, 0), Vec2(0, 3), Vec2(10, 3)).hit());   // passes by
    // Reaching the surface exactly at its end is a hit at fraction 1.
    expectHit(rayCastShape(shape, at(5, 0), Vec2(0, 0), Vec2(4, 0)), 1.0, -1, 0);
  }
}

TEST(ShapeQueries, PointsInsideOnAndOutside) {
  const Shape triangle = polygonShape({{4, -1}, {6, -1}, {4, 1}});
  EXPECT_TRUE(shapeContains(triangle, at(0, 0), Vec2(4.5, -0.5)));
  EXPECT_TRUE(shapeContains(triangle, at(0, 0), Vec2(5, 0)));  // on the hypotenuse
  EXPECT_FALSE(shapeContains(triangle, at(0, 0), Vec2(5.1, 0)));
  EXPECT_TRUE(shapeContains(circleShape(1.0), at(5, 0), Vec2(5, 1)));  // on the circle
  EXPECT_FALSE(shapeContains(circleShape(1.0), at(5, 0), Vec2(5, 1.01)));
  EXPECT_TRUE(shapeContains(circleShape(1.0), at(5, 0), Vec2(5.6, 0.7)));
  // A 2 x 1 box turned 90 degrees at (5, 0) spans x 4.5..5.5, y -1..1.
  EXPECT_TRUE(shapeContains(boxShape(2, 1), at(5, 0, kPi / 2), Vec2(5.4, 0.9)));
  EXPECT_FALSE(shapeContains(boxShape(2, 1), at(5, 0, kPi / 2), Vec2(5.6, 0.0)));
}

TEST(ShapeQueries, BoxOverlapIsExactNotByBoundingBoxes) {
  // A diamond |x| + |y| <= 1: its bounding box covers [0.6, 1]^2, the diamond does not.
  const double s = std::sqrt(2.0);
  const Shape diamond = boxShape(s, s);
  EXPECT_FALSE(shapeOverlaps(diamond, at(0, 0, kPi / 4), Aabb{Vec2(0.6, 0.6), Vec2(1, 1)}));
  EXPECT_TRUE(shapeOverlaps(diamond, at(0, 0, kPi / 4), Aabb{Vec2(0.4, 0.4), Vec2(1, 1)}));
  EXPECT_TRUE(shapeOverlaps(diamond, at(0, 0, kPi / 4), Aabb{Vec2(-5, -5), Vec2(5, 5)}));  // inside
  EXPECT_FALSE(shapeOverlaps(diamond, at(0, 0, kPi / 4), Aabb{Vec2(1.1, -5), Vec2(2, 5)}));
  // Corners touching count.
  EXPECT_TRUE(shapeOverlaps(boxShape(2, 2), at(0, 0), Aabb{Vec2(1, 1), Vec2(2, 2)}));
  EXPECT_FALSE(shapeOverlaps(boxShape(2, 2), at(0, 0), Aabb{Vec2(1, 1.001), Vec2(2, 2)}));
  // The unit circle against boxes off its diagonal: nearest corner 0.8 * sqrt 2 = 1.13 away, or
  // 0.6 * sqrt 2 = 0.85.
  EXPECT_FALSE(shapeOverlaps(circleShape(1.0), at(0, 0), Aabb{Vec2(0.8, 0.8), Vec2(2, 2)}));
  EXPECT_TRUE(shapeOverlaps(circleShape(1.0), at(0, 0), Aabb{Vec2(0.6, 0.6), Vec2(2, 2)}));
  EXPECT_TRUE(shapeOverlaps(circleShape(1.0), at(0, 0), Aabb{Vec2(-0.1, -0.1), Vec2(0.1, 0.1)}));
}

}  // namespace
}  // namespace impulse2d
