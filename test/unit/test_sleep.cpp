// Sleeping: still islands stop moving exactly, and anything that disturbs them wakes them.
#include <gtest/gtest.h>
#include <impulse2d/world.hpp>

#include "test_scenes.hpp"

namespace impulse2d {
namespace {

using test::addBox;
using test::addCircle;

void stepSeconds(World& world, double seconds) {
  const double end = world.time() + seconds;
  while (world.time() < end - 1e-9) world.step();
}

// Two boxes stacked on the ground, left three seconds to fall asleep.
struct SleepingStack {
  BodyId bottom, top;
};
SleepingStack addSleepingStack(World& world) {
  test::addGround(world);
  SleepingStack stack;
  stack.bottom = addBox(world, "bottom", Vec2(0, 0.5), 1, 1, BodyType::Dynamic);
  stack.top = addBox(world, "top", Vec2(0, 1.5), 1, 1, BodyType::Dynamic);
  stepSeconds(world, 3.0);
  return stack;
}

TEST(Sleep, ASettledStackFallsAsleepAndStaysBitForBitStill) {
  World world;
  test::addGround(world);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 5; ++i) {
    boxes.push_back(
        addBox(world, "b" + std::to_string(i), Vec2(0, 0.5 + i), 1, 1, BodyType::Dynamic));
  }
  stepSeconds(world, 3.0);
  for (BodyId id : boxes) EXPECT_FALSE(world.body(id).awake);
  const uint64_t asleep = world.hash();
  stepSeconds(world, 1.0);
  EXPECT_EQ(world.hash(), asleep);
  EXPECT_GT(world.contactCount(), 0u) << "sleeping contacts are still reported";
}

TEST(Sleep, AForceWakesTheWholeIsland) {
  World world;
  const auto [bottom, top] = addSleepingStack(world);
  ASSERT_FALSE(world.body(top).awake);
  world.applyForce(bottom, Vec2(200.0, 0.0), world.body(bottom).center);
  world.step();
  EXPECT_TRUE(world.body(bottom).awake);
  EXPECT_TRUE(world.body(top).awake) << "the box on top is in the same island";
  EXPECT_GT(world.body(bottom).linearVelocity.x(), 0.0);
}

TEST(Sleep, AFallingBodyWakesWhatItLandsOn) {
  World world;
  test::addGround(world);
  const BodyId box = addBox(world, "box", Vec2(0, 0.5), 1, 1, BodyType::Dynamic);
  stepSeconds(world, 3.0);
  ASSERT_FALSE(world.body(box).awake);
  const Vec2 before = world.body(box).xf.p;
  addCircle(world, "ball", Vec2(0.4, 4.0), 0.3, BodyType::Dynamic, 50.0);
  bool woke = false;
  for (int i = 0; i < 200 && !woke; ++i) {
    world.step();
    woke = world.body(box).awake;
  }
  EXPECT_TRUE(woke);
  stepSeconds(world, 0.2);
  EXPECT_NE(world.body(box).xf.p, before) << "the heavy ball's impact moves the box";
}

TEST(Sleep, DestroyingABodyWakesWhatItTouchedAndItFalls) {
  World world;
  const BodyId aside = addBox(world, "aside", Vec2(5, 0.5), 1, 1, BodyType::Dynamic);
  const auto [bottom, top] = addSleepingStack(world);
  ASSERT_FALSE(world.body(top).awake);
  ASSERT_FALSE(world.body(aside).awake);
  ASSERT_TRUE(world.destroyBody(bottom));
  EXPECT_TRUE(world.body(top).awake) << "it lay on the destroyed box";
  EXPECT_FALSE(world.body(aside).awake) << "it touched nothing destroyed";
  stepSeconds(world, 1.0);
  // Resting on the ground now: its centre half a box above it, within the 5 mm slop.
  EXPECT_NEAR(world.body(top).center.y(), 0.5, 0.005);
  for (const ContactInfo& contact : world.contacts()) {
    EXPECT_NE(contact.bodyA, bottom);
    EXPECT_NE(contact.bodyB, bottom);
  }
}

TEST(Sleep, TeleportingWakesAndSleepCanBeTurnedOff) {
  WorldDef def;
  def.enableSleep = false;
  World world(def);
  test::addGround(world);
  const BodyId box = addBox(world, "box", Vec2(0, 0.5), 1, 1, BodyType::Dynamic);
  stepSeconds(world, 3.0);
  EXPECT_TRUE(world.body(box).awake);

  World sleepy;
  test::addGround(sleepy);
  const BodyId other = addBox(sleepy, "box", Vec2(0, 0.5), 1, 1, BodyType::Dynamic);
  stepSeconds(sleepy, 3.0);
  ASSERT_FALSE(sleepy.body(other).awake);
  sleepy.setTransform(other, Vec2(0, 3.0), 0.0);
  sleepy.step();
  EXPECT_TRUE(sleepy.body(other).awake);
  EXPECT_LT(sleepy.body(other).xf.p.y(), 3.0) << "it falls again";
}

TEST(Sleep, SwitchingSleepOffWakesSleepersAndTheyStayAwake) {
  World world;
  const auto [bottom, top] = addSleepingStack(world);
  ASSERT_FALSE(world.body(bottom).awake);
  ASSERT_FALSE(world.body(top).awake);
  world.settings().enableSleep = false;
  world.step();
  EXPECT_TRUE(world.body(bottom).awake);
  EXPECT_TRUE(world.body(top).awake);
  stepSeconds(world, 3.0);
  EXPECT_TRUE(world.body(bottom).awake) << "nothing sleeps while sleeping is off";
  EXPECT_TRUE(world.body(top).awake);
  EXPECT_NEAR(world.body(top).center.y(), 1.5, 0.02) << "the stack still rests";
  world.settings().enableSleep = true;
  world.step();
  EXPECT_TRUE(world.body(top).awake) << "stillness counts from zero once sleeping is back on";
  stepSeconds(world, 3.0);
  EXPECT_FALSE(world.body(top).awake);
}

BodyId addSleepingBox(World& world, const std::string& name, const Vec2& position) {
  BodyDef def;
  def.name = name;
  def.position = position;
  def.awake = false;
  def.shapes.push_back(ShapeDef());
  return world.createBody(def);
}

// A body created asleep hangs where it was made (as a settled body would) until something
// touches it; then it falls like any other.
TEST(Sleep, ABodyCreatedAsleepWaitsForATouch) {
  World world;
  test::addGround(world);
  const BodyId sleeper = addSleepingBox(world, "sleeper", Vec2(0.0, 3.0));
  const BodyId faller = addBox(world, "faller", Vec2(5.0, 3.0), 1, 1, BodyType::Dynamic);
  ASSERT_FALSE(world.body(sleeper).awake);
  stepSeconds(world, 0.3);
  EXPECT_EQ(world.body(sleeper).center, Vec2(0.0, 3.0)) << "not even gravity moves it";
  EXPECT_LT(world.body(faller).center.y(), 3.0 - 0.4) << "the same box created awake falls";
  addCircle(world, "ball", Vec2(0.0, 4.0), 0.4, BodyType::Dynamic);
  stepSeconds(world, 3.0);
  EXPECT_NEAR(world.body(sleeper).center.y(), 0.5, 0.01) << "woken by the ball, it fell";
}

TEST(Sleep, AWorldThatDoesNotSleepCreatesEveryBodyAwake) {
  WorldDef def;
  def.enableSleep = false;
  World world(def);
  const BodyId box = addSleepingBox(world, "box", Vec2(0.0, 3.0));
  EXPECT_TRUE(world.body(box).awake);
  world.step();
  EXPECT_LT(world.body(box).center.y(), 3.0);
}

// Islands are the bodies linked by touching contacts and joints, each judged on its own: a pile
// kept busy does not keep another pile awake, and the ground links nothing.
TEST(Sleep, TwoPilesApartSleepEachOnItsOwn) {
  World world;
  test::addGround(world);
  const BodyId quietTop = addBox(world, "quiet_top", Vec2(-5, 1.5), 1, 1, BodyType::Dynamic);
  addBox(world, "quiet_bottom", Vec2(-5, 0.5), 1, 1, BodyType::Dynamic);
  const BodyId busyTop = addBox(world, "busy_top", Vec2(5, 1.5), 1, 1, BodyType::Dynamic);
  const BodyId busyBottom = addBox(world, "busy_bottom", Vec2(5, 0.5), 1, 1, BodyType::Dynamic);
  for (int i = 0; i < 180; ++i) {  // 3 s, the busy pile nudged to and fro
    world.applyForce(busyBottom, Vec2(i % 60 < 30 ? 20.0 : -20.0, 0.0),
                     world.body(busyBottom).center);
    world.step();
  }
  EXPECT_FALSE(world.body(quietTop).awake);
  EXPECT_TRUE(world.body(busyTop).awake) << "it rests on a moving box: same island";
}

// A joint links two bodies that do not touch into one island: pushing one wakes the other.
TEST(Sleep, AJointLinksBodiesThatDoNotTouch) {
  World world;
  test::addGround(world);
  const BodyId left = addBox(world, "left", Vec2(-2, 0.5), 1, 1, BodyType::Dynamic);
  const BodyId right = addBox(world, "right", Vec2(2, 0.5), 1, 1, BodyType::Dynamic);
  ASSERT_TRUE(world.createJoint(test::distanceDef(left, right, world.body(left).center)).valid());
  stepSeconds(world, 3.0);
  ASSERT_FALSE(world.body(left).awake);
  ASSERT_FALSE(world.body(right).awake);
  EXPECT_TRUE(world.applyForce(left, Vec2(-300.0, 0.0), world.body(left).center));
  world.step();
  EXPECT_TRUE(world.body(right).awake);
  EXPECT_TRUE(world.body(left).awake);
  EXPECT_LT(world.body(left).linearVelocity.x(), -1.0);
  stepSeconds(world, 0.2);
  EXPECT_LT(world.body(right).center.x(), 2.0 - 0.01)
      << "pulled along by the joint; left at " << world.body(left).center.x();
}

// A moving kinematic body keeps what it touches awake, however slowly it moves; a kinematic
// body at rest does not.
TEST(Sleep, AMovingKinematicBodyKeepsWhatItTouchesAwake) {
  for (const double speed : {0.0, 0.001}) {
    World world;
    const BodyId belt = addBox(world, "belt", Vec2(0, -0.5), 10, 1, BodyType::Kinematic);
    world.setVelocity(belt, Vec2(speed, 0.0), 0.0);
    const BodyId box = addBox(world, "box", Vec2(0, 0.5), 1, 1, BodyType::Dynamic);
    stepSeconds(world, 3.0);
    EXPECT_EQ(world.body(box).awake, speed > 0.0) << "belt speed " << speed << " m/s";
  }
}

}  // namespace
}  // namespace impulse2d
