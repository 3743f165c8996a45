// World bookkeeping: handles, names, destruction, joints, validation and contact reporting.
#include <gtest/gtest.h>
#include <impulse2d/world.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "test_scenes.hpp"

namespace impulse2d {
namespace {

using test::addBox;
using test::addCircle;

TEST(World, HandlesGoStaleWhenTheirBodyIsDestroyed) {
  World world;
  const BodyId a = addBox(world, "a", Vec2(0, 0), 1, 1, BodyType::Dynamic);
  ASSERT_TRUE(world.isValid(a));
  EXPECT_EQ(world.findBody("a"), a);
  EXPECT_TRUE(world.destroyBody(a));
  EXPECT_FALSE(world.isValid(a));
  EXPECT_FALSE(world.findBody("a").valid());
  EXPECT_FALSE(world.destroyBody(a));
  const BodyId b = addBox(world, "b", Vec2(0, 0), 1, 1, BodyType::Dynamic);
  EXPECT_EQ(b.index, a.index) << "the slot is reused";
  EXPECT_FALSE(world.isValid(a)) << "but the old handle stays stale";
  EXPECT_EQ(world.bodyCount(), 1u);
}

TEST(World, BodiesInReusedSlotsMoveAsTheirTypeSays) {
  // The step goes through the moving bodies' slots only: slots freed and taken again by bodies
  // of another type, below and above the others, must still move exactly the moving ones.
  World world;  // gravity -9.81 on y, no ground: everything that moves falls freely
  const BodyId a = addBox(world, "a", Vec2(0, 0), 1, 1, BodyType::Dynamic);
  const BodyId b = addBox(world, "b", Vec2(3, 0), 1, 1, BodyType::Dynamic);
  const BodyId c = addBox(world, "c", Vec2(6, 0), 1, 1, BodyType::Dynamic);
  ASSERT_TRUE(world.destroyBody(b));
  const BodyId wall = addBox(world, "wall", Vec2(3, 0), 1, 1, BodyType::Static);  // b's slot
  ASSERT_EQ(wall.index, b.index);
  ASSERT_TRUE(world.destroyBody(a));
  const BodyId d = addBox(world, "d", Vec2(0, 0), 1, 1, BodyType::Dynamic);  // a's slot, lowest
  ASSERT_EQ(d.index, a.index);
  ASSERT_TRUE(world.destroyBody(c));
  const BodyId e = addBox(world, "e", Vec2(6, 0), 1, 1, BodyType::Kinematic);  // c's slot
  world.setVelocity(e, Vec2(1, 0), 0.0);
  for (int i = 0; i < 60; ++i) world.step();
  const double t = 60 * world.settings().timeStep;
  EXPECT_NEAR(world.body(d).xf.p.y(), -0.5 * 9.81 * t * t, 0.05 * 9.81 * t * t);
  EXPECT_EQ(world.body(wall).xf.p, Vec2(3, 0));
  EXPECT_NEAR(world.body(e).xf.p.x(), 6.0 + t, 1e-9);
  EXPECT_EQ(world.body(e).xf.p.y(), 0.0);
  // Destroying the static body leaves the moving ones moving.
  ASSERT_TRUE(world.destroyBody(wall));
  const double y = world.body(d).xf.p.y();
  world.step();
  EXPECT_LT(world.body(d).xf.p.y(), y);
}

TEST(World, ContactsOfDestroyedBodiesAreGoneAtOnceAndStayGoneWhenTheirSlotIsTaken) {
  // Destroying a body leaves its contacts to be dropped at the next step: until then no query
  // may see them, an edit in between may not bring them back, and a body born in the freed
  // slot must not inherit them.
  World world;
  const BodyId ground = addBox(world, "ground", Vec2(0, -0.5), 20, 1, BodyType::Static);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 6; ++i) {
    boxes.push_back(
        addBox(world, "b" + std::to_string(i), Vec2(2.0 * i - 5.0, 0.5), 1, 1, BodyType::Dynamic));
  }
  const BodyId top = addBox(world, "top", Vec2(-5.0, 1.5), 1, 1, BodyType::Dynamic);
  for (int i = 0; i < 30; ++i) world.step();
  auto touches = [&](BodyId id) {
    for (const ContactInfo& c : world.contacts()) {
      if (c.bodyA == id || c.bodyB == id) return true;
    }
    return false;
  };
  ASSERT_TRUE(touches(boxes[0]));
  ASSERT_TRUE(touches(top));
  const size_t before = world.contactCount();
  ASSERT_TRUE(world.destroyBody(boxes[0]));  // under `top`: two contacts go
  ASSERT_TRUE(world.destroyBody(boxes[3]));
  EXPECT_FALSE(touches(boxes[0]));
  EXPECT_FALSE(touches(boxes[3]));
  EXPECT_EQ(world.contactCount(), world.contacts().size());
  EXPECT_LT(world.contactCount(), before);
  EXPECT_TRUE(world.body(top).awake) << "what rested on a destroyed body wakes";
  // An edit that erases contacts in between (a joint between touching bodies that may not
  // collide), then a body in a freed slot before any step.
  JointDef hinge;
  hinge.bodyA = ground;
  hinge.bodyB = boxes[1];
  hinge.anchor = Vec2(-3.0, 0.0);
  ASSERT_TRUE(world.createJoint(hinge).valid());
  EXPECT_FALSE(touches(boxes[0]));
  const BodyId reborn = addBox(world, "reborn", Vec2(8.0, 5.0), 1, 1, BodyType::Dynamic);
  ASSERT_TRUE(reborn.index == boxes[0].index || reborn.index == boxes[3].index);
  EXPECT_FALSE(touches(reborn));
  world.step();
  EXPECT_FALSE(touches(reborn)) << "it falls from 5 m: nothing of the old body's contacts";
  for (const ContactInfo& c : world.contacts()) {
    EXPECT_TRUE(world.isValid(c.bodyA) && world.isValid(c.bodyB));
  }
  for (int i = 0; i < 120; ++i) world.step();
  EXPECT_TRUE(touches(reborn)) << "it lands and touches the ground";
  EXPECT_LT(world.body(top).xf.p.y(), 0.6) << "top fell where boxes[0] was";
}

TEST(World, RefusesDuplicateNamesAndBadBodiesWithoutChangingAnything) {
  World world;
  addBox(world, "a", Vec2(0, 0), 1, 1, BodyType::Dynamic);
  std::string error;
  BodyDef dup;
  dup.name = "a";
  dup.shapes.emplace_back();
  EXPECT_FALSE(world.createBody(dup, &error).valid());
  EXPECT_NE(error.find("name"), std::string::npos) << error;

  BodyDef nan;
  nan.name = "nan";
  nan.position = Vec2(std::numeric_limits<double>::quiet_NaN(), 0.0);
  nan.shapes.emplace_back();
  EXPECT_FALSE(world.createBody(nan, &error).valid());
  EXPECT_NE(error.find("position"), std::string::npos) << error;

  BodyDef massless;
  massless.name = "massless";
  massless.shapes.emplace_back();
  massless.shapes[0].density = 0.0;
  EXPECT_FALSE(world.createBody(massless, &error).valid());
  EXPECT_NE(error.find("mass"), std::string::npos) << error;
  EXPECT_EQ(world.bodyCount(), 1u);
}

TEST(World, CompoundBodyMassAndInertiaFollowTheParallelAxisTheorem) {
  World world;
  BodyDef def;
  def.name = "dumbbell";
  ShapeDef left, right;
  left.size = right.size = Vec2(1.0, 1.0);
  left.offset = Vec2(-2.0, 0.0);
  right.offset = Vec2(2.0, 0.0);
  def.shapes = {left, right};
  const Body& b = world.body(world.createBody(def));
  EXPECT_NEAR(b.mass, 2.0, 1e-12);
  EXPECT_NEAR(b.localCenter.norm(), 0.0, 1e-12);
  EXPECT_NEAR(b.inertia, 2.0 * (1.0 / 6.0 + 4.0), 1e-12);

  def.name = "heavy";
  def.mass = 10.0;  // explicit mass scales the inertia with it
  const Body& h = world.body(world.createBody(def));
  EXPECT_NEAR(h.mass, 10.0, 1e-12);
  EXPECT_NEAR(h.inertia, 10.0 * (1.0 / 6.0 + 4.0), 1e-12);
}

TEST(World, JointsAreValidatedAndGoWithTheirBodies) {
  World world;
  const BodyId ground = addBox(world, "ground", Vec2(0, 0), 1, 1, BodyType::Static);
  const BodyId wall = addBox(world, "wall", Vec2(5, 0), 1, 1, BodyType::Static);
  const BodyId link = addBox(world, "link", Vec2(1, 0), 1, 0.2, BodyType::Dynamic);
  std::string error;
  JointDef self;
  self.bodyA = self.bodyB = link;
  EXPECT_FALSE(world.createJoint(self, &error).valid());
  EXPECT_NE(error.find("body_b"), std::string::npos) << error;
  JointDef statics;
  statics.bodyA = ground;
  statics.bodyB = wall;
  EXPECT_FALSE(world.createJoint(statics, &error).valid());
  JointDef limits;
  limits.bodyA = ground;
  limits.bodyB = link;
  limits.enableLimit = true;
  limits.lower = 1.0;
  limits.upper = -1.0;
  EXPECT_FALSE(world.createJoint(limits, &error).valid());
  EXPECT_NE(error.find("lower"), std::string::npos) << error;

  JointDef hinge;
  hinge.name = "hinge";
  hinge.bodyA = ground;
  hinge.bodyB = link;
  hinge.anchor = Vec2(0.5, 0.0);
  const JointId id = world.createJoint(hinge, &error);
  ASSERT_TRUE(id.valid()) << error;
  EXPECT_EQ(world.findJoint("hinge"), id);
  EXPECT_EQ(world.jointCount(), 1u);
  world.destroyBody(link);
  EXPECT_FALSE(world.isValid(id));
  EXPECT_EQ(world.jointCount(), 0u);
}

TEST(World, RevoluteLimitHoldsTheLinkWithinItsRange) {
  World world;
  const BodyId ground = addBox(world, "ground", Vec2(0, 0), 0.2, 0.2, BodyType::Static);
  const BodyId link = addBox(world, "link", Vec2(1, 0), 2.0, 0.2, BodyType::Dynamic);
  JointDef hinge;
  hinge.bodyA = ground;
  hinge.bodyB = link;
  hinge.anchor = Vec2::Zero();
  hinge.enableLimit = true;
  hinge.lower = -0.5;
  hinge.upper = 0.5;
  const JointId id = world.createJoint(hinge);
  double lowest = 0.0;
  for (int i = 0; i < 300; ++i) {
    world.step();
    lowest = std::min(lowest, world.jointState(id).position);
  }
  EXPECT_GT(lowest, -0.5 - 0.05);  // falls onto the lower limit, overshoots it by < 0.05 rad
  EXPECT_NEAR(world.jointState(id).position, -0.5, 0.01);
}

TEST(World, RevoluteMotorTurnsAtItsSpeedWithinItsTorque) {
  WorldDef def;
  def.gravity = Vec2::Zero();
  World world(def);
  const BodyId ground = addBox(world, "ground", Vec2(0, 0), 0.2, 0.2, BodyType::Static);
  const BodyId wheel = addCircle(world, "wheel", Vec2(0, 0), 0.5, BodyType::Dynamic);
  JointDef hinge;
  hinge.bodyA = ground;
  hinge.bodyB = wheel;
  hinge.enableMotor = true;
  hinge.motorSpeed = 2.0;
  hinge.maxMotorTorque = 1000.0;
  world.createJoint(hinge);
  for (int i = 0; i < 10; ++i) world.step();
  EXPECT_NEAR(world.body(wheel).angularVelocity, 2.0, 1e-9);

  // A weak motor accelerates at torque / inertia and no faster.
  World slow(def);
  const BodyId g2 = addBox(slow, "ground", Vec2(0, 0), 0.2, 0.2, BodyType::Static);
  const BodyId w2 = addCircle(slow, "wheel", Vec2(0, 0), 0.5, BodyType::Dynamic);
  hinge.bodyA = g2;
  hinge.bodyB = w2;
  hinge.maxMotorTorque = 0.01;
  slow.createJoint(hinge);
  slow.step();
  const double inertia = slow.body(w2).inertia;
  EXPECT_NEAR(slow.body(w2).angularVelocity, 0.01 * 0.01 / inertia, 1e-9);
}

TEST(World, EveryOverlappingPairBecomesAContact) {
  // Random circles: the broad phase plus narrow phase must find exactly the overlapping pairs.
  WorldDef def;
  def.gravity = Vec2::Zero();
  World world(def);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(-10.0, 10.0), radius(0.2, 1.0);
  std::vector<Vec2> centers;
  std::vector<double> radii;
  for (int i = 0; i < 300; ++i) {
    const double x = pos(rng), y = pos(rng);
    centers.emplace_back(x, y);
    radii.push_back(radius(rng));
    addCircle(world, "c" + std::to_string(i), centers[i], radii[i], BodyType::Dynamic);
  }
  world.step();  // contacts found in a step are those at the positions before it moved
  std::set<std::pair<int, int>> expected, found;
  for (int i = 0; i < 300; ++i) {
    for (int j = i + 1; j < 300; ++j) {
      if ((centers[i] - centers[j]).norm() < radii[i] + radii[j] - 1e-9) expected.insert({i, j});
    }
  }
  for (const ContactInfo& c : world.contacts()) {
    if (c.separation < 0.0) found.insert({c.bodyA.index, c.bodyB.index});
  }
  EXPECT_EQ(found, expected);
  EXPECT_FALSE(expected.empty());
}

}  // namespace
}  // namespace impulse2d
