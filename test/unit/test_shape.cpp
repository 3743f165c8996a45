// Shape construction, validation, mass properties and bounding boxes.
#include <gtest/gtest.h>

#include <cmath>
#include <impulse2d/shape.hpp>
#include <limits>
#include <string>
#include <vector>

namespace impulse2d {
namespace {

constexpr double kExact = 1e-9;

// A valid polygon is counter-clockwise with unit outward normals perpendicular to its edges.
void expectWellFormed(const Polygon& poly) {
  ASSERT_GE(poly.count, 3);
  for (int i = 0; i < poly.count; ++i) {
    const Vec2& a = poly.vertices[i];
    const Vec2& b = poly.vertices[(i + 1) % poly.count];
    const Vec2& c = poly.vertices[(i + 2) % poly.count];
    EXPECT_GT(cross(b - a, c - b), 0.0) << "vertex " << i + 1 << " is not a left turn";
    EXPECT_NEAR(poly.normals[i].norm(), 1.0, kExact);
    EXPECT_NEAR(poly.normals[i].dot(b - a), 0.0, kExact);
    for (int k = 0; k < poly.count; ++k) {
      EXPECT_LE(poly.normals[i].dot(poly.vertices[k] - a), kExact) << "normal " << i;
    }
  }
}

std::vector<Vec2> reversed(std::vector<Vec2> points) { return {points.rbegin(), points.rend()}; }

TEST(ShapeMakePolygon, AcceptsBothWindingsOfATriangle) {
  const std::vector<Vec2> ccw = {Vec2(0, 0), Vec2(2, 0), Vec2(0, 1)};
  for (const auto& points : {ccw, reversed(ccw)}) {
    Polygon poly;
    ASSERT_EQ(makePolygon(points, &poly), "");
    EXPECT_EQ(poly.count, 3);
    expectWellFormed(poly);
    EXPECT_NEAR(poly.centroid.x(), 2.0 / 3.0, kExact);
    EXPECT_NEAR(poly.centroid.y(), 1.0 / 3.0, kExact);
  }
}

TEST(ShapeMakePolygon, AcceptsBothWindingsOfASquare) {
  const std::vector<Vec2> ccw = {Vec2(1, 1), Vec2(3, 1), Vec2(3, 3), Vec2(1, 3)};
  for (const auto& points : {ccw, reversed(ccw)}) {
    Polygon poly;
    ASSERT_EQ(makePolygon(points, &poly), "");
    EXPECT_EQ(poly.count, 4);
    expectWellFormed(poly);
    EXPECT_NEAR(poly.centroid.x(), 2.0, kExact);
    EXPECT_NEAR(poly.centroid.y(), 2.0, kExact);
  }
}

TEST(ShapeMakePolygon, RefusesDegenerateInputAndLeavesOutputUntouched) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Vec2> tooMany;
  for (int i = 0; i <= kMaxPolygonVertices; ++i) {
    const double angle = 2.0 * kPi * i / (kMaxPolygonVertices + 1);
    tooMany.push_back(Vec2(std::cos(angle), std::sin(angle)));
  }
  const std::vector<std::vector<Vec2>> bad = {
      {Vec2(0, 0), Vec2(1, 0), Vec2(2, 0)},                  // collinear
      {Vec2(0, 0), Vec2(1, 0), Vec2(1, 0), Vec2(0, 1)},      // duplicate point
      {Vec2(0, 0), Vec2(2, 0), Vec2(0.5, 0.5), Vec2(0, 2)},  // reflex vertex (dart)
      {Vec2(0, 0), Vec2(1, 0)},                              // too few
      tooMany,                                               // too many
      {Vec2(0, 0), Vec2(1, 0), Vec2(nan, 1)},                // NaN
      {Vec2(0, 0), Vec2(1, 0), Vec2(std::numeric_limits<double>::infinity(), 1)},  // infinite
      {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0.5, 1), Vec2(0, 1)},  // collinear vertex
  };
  for (size_t i = 0; i < bad.size(); ++i) {
    Polygon poly;
    poly.count = 42;
    EXPECT_NE(makePolygon(bad[i], &poly), "") << "case " << i;
    EXPECT_EQ(poly.count, 42) << "case " << i;
  }
}

TEST(ShapeMakePolygon, AcceptsTheMaximumVertexCount) {
  std::vector<Vec2> points;
  for (int i = 0; i < kMaxPolygonVertices; ++i) {
    const double angle = 2.0 * kPi * i / kMaxPolygonVertices;
    points.push_back(Vec2(std::cos(angle), std::sin(angle)));
  }
  Polygon poly;
  ASSERT_EQ(makePolygon(points, &poly), "");
  expectWellFormed(poly);
}

// Disabled until shape.cpp is fixed: every turn of a pentagram is a left turn and its signed
// area is positive (the inner pentagon counts twice), so the local convexity test accepts it.
TEST(ShapeMakePolygon, RefusesSelfIntersectingStar) {
  std::vector<Vec2> star;
  for (int i = 0; i < 5; ++i) {
    const double angle = 2.0 * kPi * (2 * i % 5) / 5.0;
    star.push_back(Vec2(std::cos(angle), std::sin(angle)));
  }
  Polygon poly;
  EXPECT_NE(makePolygon(star, &poly), "");
}

// The message must start with the YAML key so a scene error points at the right line.
void expectRefused(const ShapeDef& def, const std::string& key) {
  Shape shape;
  shape.friction = 123.0;
  const std::string why = makeShape(def, &shape);
  EXPECT_EQ(why.rfind(key + ":", 0), 0u) << "message '" << why << "' should name " << key;
  EXPECT_EQ(shape.friction, 123.0);
}

TEST(ShapeMakeShape, RefusesInvalidDefinitionsNamingTheKey) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ShapeDef def;
  def.size = Vec2(0.0, 1.0);
  expectRefused(def, "size");
  def.size = Vec2(1.0, -1.0);
  expectRefused(def, "size");

  def = ShapeDef();
  def.kind = ShapeKind::Circle;
  def.radius = 0.0;
  expectRefused(def, "radius");
  def.radius = -0.5;
  expectRefused(def, "radius");

  def = ShapeDef();
  def.offset = Vec2(nan, 0.0);
  expectRefused(def, "offset");

  def = ShapeDef();
  def.restitution = 1.5;
  expectRefused(def, "restitution");

  def = ShapeDef();
  def.density = -1.0;
  expectRefused(def, "density");

  def = ShapeDef();
  def.friction = -0.1;
  expectRefused(def, "friction");

  def = ShapeDef();
  def.kind = ShapeKind::Polygon;
  def.vertices = {Vec2(0, 0), Vec2(1, 0), Vec2(2, 0)};
  expectRefused(def, "vertices");
}

TEST(ShapeMakeShape, AppliesOffsetAndAngle) {
  ShapeDef def;
  def.kind = ShapeKind::Polygon;
  def.vertices = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  def.offset = Vec2(2.0, 3.0);
  def.angle = kPi / 2.0;
  Shape shape;
  ASSERT_EQ(makeShape(def, &shape), "");
  ASSERT_EQ(shape.type, ShapeType::Polygon);
  expectWellFormed(shape.polygon);
  // (1, 0) rotated a quarter turn is (0, 1), then shifted by the offset.
  bool found = false;
  for (int i = 0; i < shape.polygon.count; ++i) {
    found |= (shape.polygon.vertices[i] - Vec2(2.0, 4.0)).norm() < kExact;
  }
  EXPECT_TRUE(found);
}

TEST(ShapeComputeMass, Box2x1) {
  ShapeDef def;
  def.size = Vec2(2.0, 1.0);
  def.density = 3.0;
  Shape shape;
  ASSERT_EQ(makeShape(def, &shape), "");
  const MassData md = computeMass(shape);
  EXPECT_NEAR(md.mass, 6.0, kExact);
  EXPECT_NEAR(md.center.norm(), 0.0, kExact);
  EXPECT_NEAR(md.inertia, 6.0 * (4.0 + 1.0) / 12.0, kExact);
}

TEST(ShapeComputeMass, Circle) {
  ShapeDef def;
  def.kind = ShapeKind::Circle;
  def.radius = 0.5;
  def.density = 2.0;
  def.offset = Vec2(1.0, -1.0);
  Shape shape;
  ASSERT_EQ(makeShape(def, &shape), "");
  const MassData md = computeMass(shape);
  const double mass = 2.0 * kPi * 0.25;
  EXPECT_NEAR(md.mass, mass, kExact);
  EXPECT_NEAR(md.inertia, 0.5 * mass * 0.25, kExact);
  EXPECT_NEAR(md.center.x(), 1.0, kExact);
  EXPECT_NEAR(md.center.y(), -1.0, kExact);
}

TEST(ShapeComputeMass, RightTriangle) {
  ShapeDef def;
  def.kind = ShapeKind::Polygon;
  def.vertices = {Vec2(0, 0), Vec2(0, 3), Vec2(3, 0)};  // clockwise on purpose
  Shape shape;
  ASSERT_EQ(makeShape(def, &shape), "");
  const MassData md = computeMass(shape);
  EXPECT_NEAR(md.mass, 4.5, kExact);
  EXPECT_NEAR(md.center.x(), 1.0, kExact);  // mean of the vertices
  EXPECT_NEAR(md.center.y(), 1.0, kExact);
  // Polar moment of a right triangle with legs a, b about its centroid: A (a^2 + b^2) / 18.
  EXPECT_NEAR(md.inertia, 4.5 * 18.0 / 18.0, kExact);
}

TEST(ShapeComputeMass, OffsetRotatedBoxKeepsItsCentroidInertia) {
  ShapeDef def;
  def.size = Vec2(2.0, 1.0);
  def.offset = Vec2(1.0, 2.0);
  def.angle = 0.3;
  Shape shape;
  ASSERT_EQ(makeShape(def, &shape), "");
  const MassData md = computeMass(shape);
  EXPECT_NEAR(md.mass, 2.0, kExact);
  EXPECT_NEAR(md.center.x(), 1.0, kExact);
  EXPECT_NEAR(md.center.y(), 2.0, kExact);
  EXPECT_NEAR(md.inertia, 2.0 * 5.0 / 12.0, kExact);
}

TEST(ShapeComputeAabb, RotatedBox) {
  Shape shape;
  shape.polygon = makeBox(2.0, 1.0);
  // A quarter turn swaps the extents.
  Aabb box = computeAabb(shape, Transform(Vec2(1.0, 1.0), Rot(kPi / 2.0)));
  EXPECT_NEAR(box.lower.x(), 0.5, kExact);
  EXPECT_NEAR(box.lower.y(), 0.0, kExact);
  EXPECT_NEAR(box.upper.x(), 1.5, kExact);
  EXPECT_NEAR(box.upper.y(), 2.0, kExact);
  // A unit square at 45 degrees reaches half its diagonal in every direction.
  shape.polygon = makeBox(1.0, 1.0);
  box = computeAabb(shape, Transform(Vec2(-1.0, 0.0), Rot(kPi / 4.0)));
  const double h = std::sqrt(0.5);
  EXPECT_NEAR(box.lower.x(), -1.0 - h, kExact);
  EXPECT_NEAR(box.lower.y(), -h, kExact);
  EXPECT_NEAR(box.upper.x(), -1.0 + h, kExact);
  EXPECT_NEAR(box.upper.y(), h, kExact);
}

TEST(ShapeComputeAabb, CircleWithOffset) {
  Shape shape;
  shape.type = ShapeType::Circle;
  shape.circle.center = Vec2(1.0, 0.0);
  shape.circle.radius = 0.5;
  const Aabb box = computeAabb(shape, Transform(Vec2(0.0, 2.0), Rot(kPi / 2.0)));
  EXPECT_NEAR(box.lower.x(), -0.5, kExact);
  EXPECT_NEAR(box.lower.y(), 2.5, kExact);
  EXPECT_NEAR(box.upper.x(), 0.5, kExact);
  EXPECT_NEAR(box.upper.y(), 3.5, kExact);
}

}  // namespace
}  // namespace impulse2d
