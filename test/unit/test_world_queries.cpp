// World's ray casts and queries: the nearest hit among bodies, the filter, the fan form, and the
// bodies at a point or in a box; the AABB tree's pruning checked against testing every shape.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "test_scenes.hpp"

namespace impulse2d {
namespace {

using test::addBox;
using test::addCircle;

constexpr double kExact = 1e-12;

TEST(WorldRayCast, NearestBodyWithPointNormalAndShape) {
  World world;
  const BodyId near = addBox(world, "near", Vec2(3, 0), 2.0, 1.0, BodyType::Static);
  addCircle(world, "far", Vec2(8, 0), 1.0, BodyType::Dynamic);
  // A compound body whose second shape is the one in the way.
  BodyDef compound;
  compound.name = "compound";
  compound.position = Vec2(0, 5);
  compound.shapes.resize(2);
  compound.shapes[1].offset = Vec2(0, 2);
  const BodyId twoShapes = world.createBody(compound);

  const RayHit hit = world.rayCast(Vec2(0, 0), Vec2(10, 0));
  ASSERT_TRUE(hit.hit());
  EXPECT_EQ(hit.body, near);
  EXPECT_EQ(hit.shape, 0);
  EXPECT_NEAR(hit.fraction, 0.2, kExact);
  EXPECT_NEAR(hit.point.x(), 2.0, kExact);
  EXPECT_NEAR(hit.point.y(), 0.0, kExact);
  EXPECT_NEAR(hit.normal.x(), -1.0, kExact);

  // Down from (0, 10): the offset shape's top face at y = 7.5.
  const RayHit down = world.rayCast(Vec2(0, 10), Vec2(0, 0));
  EXPECT_EQ(down.body, twoShapes);
  EXPECT_EQ(down.shape, 1);
  EXPECT_NEAR(down.point.y(), 7.5, kExact);
  EXPECT_NEAR(down.normal.y(), 1.0, kExact);

  EXPECT_FALSE(world.rayCast(Vec2(0, 0), Vec2(1.9, 0)).hit());
  EXPECT_FALSE(world.rayCast(Vec2(0, 0), Vec2(0, -10)).hit());
  EXPECT_FALSE(world.rayCast(Vec2(0, 0), Vec2(NAN, 0)).hit());
  EXPECT_FALSE(World().rayCast(Vec2(0, 0), Vec2(10, 0)).hit());
}

TEST(WorldRayCast, FilterSkipsBodiesAndRaysFromInsideHitTheirOwnBody) {
  World world;
  const BodyId robot = addCircle(world, "robot", Vec2(0, 0), 0.5, BodyType::Dynamic);
  const BodyId wall = addBox(world, "wall", Vec2(3.1, 0), 0.2, 4.0, BodyType::Static);
  // From the robot's centre the robot is hit at once; ignoring it, the wall 3 m away.
  const RayHit own = world.rayCast(Vec2(0, 0), Vec2(10, 0));
  EXPECT_EQ(own.body, robot);
  EXPECT_EQ(own.fraction, 0.0);
  RayFilter filter;
  filter.ignore.push_back(robot);
  const RayHit seen = world.rayCast(Vec2(0, 0), Vec2(10, 0), filter);
  EXPECT_EQ(seen.body, wall);
  EXPECT_NEAR(seen.fraction * 10.0, 3.0, kExact);
  filter.ignore.push_back(wall);
  EXPECT_FALSE(world.rayCast(Vec2(0, 0), Vec2(10, 0), filter).hit());
}

TEST(WorldRayCast, EqualFractionsGoToTheLowerBody) {
  World world;
  const BodyId first = addBox(world, "first", Vec2(5, 1), 2.0, 2.0, BodyType::Static);
  addBox(world, "second", Vec2(5, -1), 2.0, 2.0, BodyType::Static);
  // Along y = 0, the line where the two boxes meet: both faces at x = 4.
  const RayHit hit = world.rayCast(Vec2(0, 0), Vec2(10, 0));
  EXPECT_EQ(hit.body, first);
  EXPECT_NEAR(hit.fraction, 0.4, kExact);
}

// A ray that starts inside two overlapping shapes hits both at fraction 0: the lower body wins,
// as for any tie, whichever the tree reaches first (a hit at 0 once ended the tree's walk).
TEST(WorldRayCast, AStartInsideTwoShapesGoesToTheLowerBody) {
  for (const bool lowerOnTheLeft : {true, false}) {
    World world;
    const double side = lowerOnTheLeft ? -1.0 : 1.0;
    const BodyId lower = addBox(world, "lower", Vec2(0.4 * side, 0.0), 2.0, 2.0, BodyType::Static);
    for (int i = 0; i < 20; ++i) {  // bodies around, so that the tree has some depth
      addBox(world, "other" + std::to_string(i), Vec2(10.0 + 3.0 * i, 5.0), 1.0, 1.0,
             BodyType::Static);
    }
    addBox(world, "higher", Vec2(-0.4 * side, 0.0), 2.0, 2.0, BodyType::Static);
    for (const Vec2& end : {Vec2(5.0, 0.3), Vec2(-5.0, -0.2), Vec2(0.1, 6.0)}) {
      const RayHit hit = world.rayCast(Vec2(0.0, 0.0), end);
      EXPECT_EQ(hit.body, lower);
      EXPECT_EQ(hit.fraction, 0.0);
      std::vector<RayHit> fan;
      world.rayCastFan(Vec2(0.0, 0.0), {end}, RayFilter(), &fan);
      EXPECT_EQ(fan[0].body, lower);
    }
  }
}

// Random shapes and rays: the tree must prune nothing the brute force over every shape would hit,
// and the fan form must answer as single rays do.
TEST(WorldRayCast, MatchesTestingEveryShapeAndTheFanMatchesSingleRays) {
  World world;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(-20.0, 20.0), size(0.2, 2.0), angle(-kPi, kPi);
  for (int i = 0; i < 300; ++i) {
    BodyDef def;
    def.name = "b" + std::to_string(i);
    def.type = i % 3 == 0 ? BodyType::Static : BodyType::Dynamic;
    def.position = Vec2(pos(rng), pos(rng));
    def.angle = angle(rng);
    ShapeDef shape;
    shape.kind = i % 2 == 0 ? ShapeKind::Box : ShapeKind::Circle;
    shape.size = Vec2(size(rng), size(rng));
    shape.radius = 0.5 * size(rng);
    def.shapes.push_back(shape);
    ASSERT_TRUE(world.createBody(def).valid());
  }
  for (int i = 0; i < 30; ++i) world.step();  // bodies move: fat boxes differ from the shapes

  const Vec2 origin(0.5, -0.25);
  std::vector<Vec2> ends;
  for (int i = 0; i < 720; ++i) {
    const double a = 2.0 * kPi * i / 720.0;
    ends.push_back(origin + 30.0 * Vec2(std::cos(a), std::sin(a)));
  }
  std::vector<RayHit> fan;
  world.rayCastFan(origin, ends, RayFilter(), &fan);
  ASSERT_EQ(fan.size(), ends.size());
  int hits = 0;
  for (size_t i = 0; i < ends.size(); ++i) {
    double nearest = 2.0;
    for (const BodyId id : world.bodies()) {
      const Body& body = world.body(id);
      for (const Shape& shape : body.shapes) {
        nearest = std::min(nearest, rayCastShape(shape, body.xf, origin, ends[i]).fraction);
      }
    }
    const RayHit single = world.rayCast(origin, ends[i]);
    ASSERT_EQ(single.hit(), nearest <= 1.0) << "ray " << i;
    if (!single.hit()) continue;
    ++hits;
    EXPECT_EQ(single.fraction, nearest) << "ray " << i;
    EXPECT_EQ(fan[i].body, single.body) << "ray " << i;
    EXPECT_EQ(fan[i].fraction, single.fraction) << "ray " << i;
  }
  EXPECT_GT(hits, 300);  // the test saw hits, not only misses

  // Fans of every length from inside a body (ignored or not), from the edge of one, across the
  // -pi/pi seam, with a beam of no length and one that is not finite: as single rays, bit for bit.
  std::uniform_real_distribution<double> length(0.0, 30.0);
  const BodyId inside = world.bodies()[7];
  const Body& host = world.body(inside);
  const Vec2 edge = host.xf.apply(host.shapes[0].type == ShapeType::Circle
                                      ? Vec2(host.shapes[0].circle.radius, 0.0)
                                      : host.shapes[0].polygon.vertices[0]);
  for (const Vec2& from : {host.center, edge, Vec2(-15.0, 12.0)}) {
    for (const bool ignoreHost : {false, true}) {
      RayFilter filter;
      if (ignoreHost) filter.ignore.push_back(inside);
      std::vector<Vec2> spokes;
      for (int i = 0; i < 500; ++i) {
        const double a = kPi - 2.0 * kPi * i / 499.0;  // from pi down to -pi
        spokes.push_back(from + length(rng) * Vec2(std::cos(a), std::sin(a)));
      }
      spokes.push_back(from);
      spokes.push_back(Vec2(NAN, 0.0));
      world.rayCastFan(from, spokes, filter, &fan);
      for (size_t i = 0; i < spokes.size(); ++i) {
        const RayHit single = world.rayCast(from, spokes[i], filter);
        ASSERT_EQ(fan[i].body, single.body) << "spoke " << i;
        ASSERT_EQ(fan[i].shape, single.shape) << "spoke " << i;
        ASSERT_EQ(fan[i].fraction, single.fraction) << "spoke " << i;
        ASSERT_EQ(fan[i].point, single.point) << "spoke " << i;
        ASSERT_EQ(fan[i].normal, single.normal) << "spoke " << i;
      }
    }
  }
}

// Beams aimed exactly at the corners of boxes, where a shape's bounding box (which the fan sorts
// shapes into beams by) is the shape itself: the fan must not lose them.
TEST(WorldRayCast, FanBeamsThroughBoxCornersHitAsSingleRays) {
  World world;
  std::vector<Vec2> ends;
  const Vec2 origin(0.3, -0.2);
  for (const Vec2& center : {Vec2(5, 0), Vec2(-3, 4), Vec2(0.5, -6), Vec2(-7, -0.2)}) {
    addBox(world, "box" + std::to_string(ends.size()), center, 2.0, 1.0, BodyType::Static);
    for (const Vec2& corner :
         {Vec2(-1.0, -0.5), Vec2(1.0, -0.5), Vec2(1.0, 0.5), Vec2(-1.0, 0.5)}) {
      const Vec2 aim = center + corner - origin;
      for (const double turn : {-1e-12, 0.0, 1e-12}) {
        ends.push_back(origin + 3.0 * Rot(turn).apply(aim));
      }
    }
  }
  std::vector<RayHit> fan;
  world.rayCastFan(origin, ends, RayFilter(), &fan);
  int hits = 0;
  for (size_t i = 0; i < ends.size(); ++i) {
    const RayHit single = world.rayCast(origin, ends[i]);
    EXPECT_EQ(fan[i].body, single.body) << "beam " << i;
    EXPECT_EQ(fan[i].fraction, single.fraction) << "beam " << i;
    hits += single.hit() ? 1 : 0;
  }
  EXPECT_GE(hits, 16);  // every corner seen from outside is hit by its exact beam at least
}

TEST(WorldQueries, BodiesAtAPoint) {
  World world;
  const BodyId a = addBox(world, "a", Vec2(0, 0), 2.0, 2.0, BodyType::Static);
  const BodyId b = addCircle(world, "b", Vec2(1.5, 0), 1.0, BodyType::Dynamic);
  EXPECT_EQ(world.queryPoint(Vec2(-0.5, 0)), std::vector<BodyId>{a});
  EXPECT_EQ(world.queryPoint(Vec2(0.75, 0)), (std::vector<BodyId>{a, b}));
  EXPECT_EQ(world.queryPoint(Vec2(1.0, 1.0)), std::vector<BodyId>{a});  // a's corner
  EXPECT_EQ(world.queryPoint(Vec2(2.4, 0)), std::vector<BodyId>{b});
  EXPECT_TRUE(world.queryPoint(Vec2(2.4, 0.9)).empty());  // in b's bounding box only
  EXPECT_TRUE(world.queryPoint(Vec2(NAN, 0)).empty());
}

TEST(WorldQueries, BodiesInABox) {
  World world;
  const BodyId a = addBox(world, "a", Vec2(0, 0), 2.0, 2.0, BodyType::Static);
  const BodyId b = addCircle(world, "b", Vec2(5, 0), 1.0, BodyType::Dynamic);
  EXPECT_EQ(world.queryAabb(Aabb{Vec2(-10, -10), Vec2(10, 10)}), (std::vector<BodyId>{a, b}));
  EXPECT_EQ(world.queryAabb(Aabb{Vec2(0.5, -0.1), Vec2(3.9, 0.1)}), std::vector<BodyId>{a});
  // Inside the circle's bounding box but clear of the circle.
  EXPECT_TRUE(world.queryAabb(Aabb{Vec2(5.8, 0.8), Vec2(7, 2)}).empty());
  EXPECT_EQ(world.queryAabb(Aabb{Vec2(5.6, 0.6), Vec2(7, 2)}), std::vector<BodyId>{b});
  EXPECT_TRUE(world.queryAabb(Aabb{Vec2(1, 1), Vec2(-1, -1)}).empty());  // lower above upper
}

}  // namespace
}  // namespace impulse2d
