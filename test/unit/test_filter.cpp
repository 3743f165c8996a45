// Collision filtering: categories, masks and groups decide which shapes touch (Box2D's rule), per
// shape, in the contacts and in continuous collision alike.
#include <gtest/gtest.h>
#include <impulse2d/world.hpp>

#include "test_scenes.hpp"

namespace impulse2d {
namespace {

CollisionFilter filter(uint64_t category, uint64_t mask, int32_t group = 0) {
  CollisionFilter f;
  f.categoryBits = category;
  f.maskBits = mask;
  f.groupIndex = group;
  return f;
}

TEST(Filter, FollowsBox2dsRule) {
  const CollisionFilter everything;
  EXPECT_TRUE(filtersAllowContact(everything, everything));
  // Both masks must name the other's category.
  EXPECT_FALSE(filtersAllowContact(filter(2, ~uint64_t(2)), filter(2, ~uint64_t(2))));
  EXPECT_TRUE(filtersAllowContact(filter(2, ~uint64_t(2)), everything));
  EXPECT_FALSE(filtersAllowContact(filter(2, 1), filter(2, 3)));
  EXPECT_FALSE(filtersAllowContact(filter(2, 3), filter(2, 1)));
  EXPECT_TRUE(filtersAllowContact(filter(2, 1), filter(1, 2)));
  // A shared group decides alone: negative never, positive always.
  EXPECT_FALSE(filtersAllowContact(filter(1, ~uint64_t(0), -4), filter(1, ~uint64_t(0), -4)));
  EXPECT_TRUE(filtersAllowContact(filter(2, 0, 4), filter(2, 0, 4)));
  // Different groups fall back to the masks.
  EXPECT_TRUE(filtersAllowContact(filter(1, ~uint64_t(0), -4), filter(1, ~uint64_t(0), -5)));
  EXPECT_FALSE(filtersAllowContact(filter(2, 0, 4), filter(2, 0, 5)));
}

BodyId addFilteredCircle(World& world, const std::string& name, const Vec2& position,
                         const CollisionFilter& f) {
  BodyDef def;
  def.name = name;
  def.position = position;
  ShapeDef shape;
  shape.kind = ShapeKind::Circle;
  shape.radius = 0.5;
  shape.filter = f;
  def.shapes.push_back(shape);
  return world.createBody(def);
}

double restingHeight(World& world, BodyId id) {
  for (int i = 0; i < 300; ++i) world.step();
  return world.body(id).center.y();
}

// A ball dropped onto another ball resting on the ground: on top of it when they may touch
// (centre at 3 radii), on the ground through it when their filters part them (1 radius).
TEST(Filter, ABallFallsThroughABallItMayNotTouch) {
  struct Case {
    const char* what;
    CollisionFilter lower, upper;
    double height;
  };
  const Case cases[] = {
      {"default filters", CollisionFilter(), CollisionFilter(), 1.5},
      {"masks exclude each other", filter(2, ~uint64_t(2)), filter(2, ~uint64_t(2)), 0.5},
      {"one mask excludes the other", filter(2, 1), filter(2, 3), 0.5},
      {"same negative group", filter(1, ~uint64_t(0), -1), filter(1, ~uint64_t(0), -1), 0.5},
      {"same positive group over masks", filter(2, 1, 7), filter(2, 1, 7), 1.5},
  };
  for (const Case& c : cases) {
    World world;
    test::addGround(world);
    addFilteredCircle(world, "lower", Vec2(0.0, 0.5), c.lower);
    const BodyId upper = addFilteredCircle(world, "upper", Vec2(0.0, 2.0), c.upper);
    // Within the linear slop of the exact resting height.
    EXPECT_NEAR(restingHeight(world, upper), c.height, 0.006) << c.what;
  }
}

BodyId addFilteredBox(World& world, const std::string& name, const Vec2& position,
                      const CollisionFilter& f) {
  BodyDef def;
  def.name = name;
  def.position = position;
  ShapeDef shape;
  shape.filter = f;
  def.shapes.push_back(shape);
  return world.createBody(def);
}

// A body whose two shapes filter differently (like a leg whose foot touches only the ground,
// category 1): a box of category 4 lying on the foot falls through it, one lying on the shin
// rests on it.
TEST(Filter, AppliesPerShapeWithinOneBody) {
  World world;
  test::addGround(world);
  BodyDef leg;
  leg.name = "leg";
  leg.type = BodyType::Static;
  ShapeDef foot, shin;
  foot.size = Vec2(2.0, 0.2);
  foot.offset = Vec2(-3.0, 1.0);
  foot.filter = filter(2, 1);
  shin.size = Vec2(2.0, 0.2);
  shin.offset = Vec2(3.0, 1.0);
  leg.shapes = {foot, shin};
  ASSERT_TRUE(world.createBody(leg).valid());
  const CollisionFilter box = filter(4, ~uint64_t(0));
  const BodyId onFoot = addFilteredBox(world, "on_foot", Vec2(-3.0, 1.6), box);
  const BodyId onShin = addFilteredBox(world, "on_shin", Vec2(3.0, 1.6), box);
  for (int i = 0; i < 300; ++i) world.step();
  EXPECT_NEAR(world.body(onFoot).center.y(), 0.5, 0.006) << "on the ground, through the foot";
  EXPECT_NEAR(world.body(onShin).center.y(), 1.6, 0.006) << "resting on the shin";
}

// Continuous collision obeys the filter per shape too: a fast ball stops at a plate it may touch
// and passes a plate it may not, though the same static body also holds a plate (far beyond)
// that it may touch.
TEST(Filter, ContinuousCollisionSkipsFilteredShapes) {
  for (const bool filtered : {false, true}) {
    WorldDef def;
    def.gravity = Vec2::Zero();
    World world(def);
    BodyDef wall;
    wall.name = "wall";
    wall.type = BodyType::Static;
    ShapeDef near, far;
    near.size = far.size = Vec2(0.1, 4.0);
    near.offset = Vec2(5.0, 0.0);
    far.offset = Vec2(50.0, 0.0);
    if (filtered) near.filter = filter(2, ~uint64_t(1));
    wall.shapes = {near, far};
    ASSERT_TRUE(world.createBody(wall).valid());
    BodyDef ball;
    ball.name = "ball";
    ball.linearVelocity = Vec2(300.0, 0.0);  // 3 m per step at 100 Hz, far beyond the margin
    ShapeDef round;
    round.kind = ShapeKind::Circle;
    round.radius = 0.05;
    ball.shapes.push_back(round);
    const BodyId id = world.createBody(ball);
    for (int i = 0; i < 4; ++i) world.step();
    if (filtered) {
      EXPECT_GT(world.body(id).center.x(), 10.0) << "passed the plate it may not touch";
    } else {
      EXPECT_LT(world.body(id).center.x(), 4.95 + 1e-9) << "stopped at the near plate's face";
    }
  }
}

}  // namespace
}  // namespace impulse2d
