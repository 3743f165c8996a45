// Bodies lost for good below the static bodies (world_bounds.cpp): reported once, at the step
// their top passes the line one static height below the lowest static point, and removed then
// only with WorldDef::removeLostBodies; never while something can still stop or hold them.
#include <gtest/gtest.h>
#include <impulse2d/world.hpp>

#include <cmath>
#include <string>

#include "test_scenes.hpp"

namespace impulse2d {
namespace {

using test::addBox;

// A 40 x 1 ground whose top is y = 0: the lowest static point is y = -1 and the static bodies
// are 1 m tall, so a body is lost once its top is below y = -2.
constexpr double kLostLine = -2.0;

// A 0.3 m box dropped from rest beside the ground: its corners reach 0.3 / sqrt(2) from its
// centre, so it is lost from the step whose end finds its centre below -2 - 0.212 m. With another
// gravity the whole scene is turned so that its "down" is along it.
struct Drop {
  World world;
  BodyId box;
  double maxExtent = 0.0;

  explicit Drop(const Vec2& gravity = Vec2(0.0, -9.81), bool remove = false) {
    world.settings().gravity = gravity;
    world.settings().removeLostBodies = remove;
    add("ground", Vec2(0.0, -0.5), Vec2(40.0, 1.0), BodyType::Static);
    box = add("box", Vec2(25.0, 3.0), Vec2(0.3, 0.3), BodyType::Dynamic);
    maxExtent = world.body(box).maxExtent;
  }
  // The turn that takes (0, -1) to gravity's direction.
  double turn() const {
    const Vec2 down = world.settings().gravity.normalized();
    return std::atan2(down.x(), -down.y());
  }
  BodyId add(const std::string& name, const Vec2& position, const Vec2& size, BodyType type) {
    BodyDef def;
    def.name = name;
    def.type = type;
    def.position = Rot(turn()).apply(position);
    def.angle = turn();
    def.shapes.resize(1);
    def.shapes[0].size = size;
    return world.createBody(def);
  }
  // The box's top along "up": the scene's y before turning.
  double top() const {
    const Vec2 up = -world.settings().gravity.normalized();
    return up.dot(world.body(box).center) + maxExtent;
  }
};

TEST(LostBodies, ABoxFallingBesideTheGroundIsReportedOnceWhenItPassesTheLine) {
  Drop drop;
  EXPECT_NEAR(drop.maxExtent, 0.3 / std::sqrt(2.0), 1e-12);
  int steps = 0;
  while (drop.top() >= kLostLine && steps < 1000) {
    drop.world.step();
    ++steps;
    if (drop.top() >= kLostLine) {
      ASSERT_TRUE(drop.world.takeLostBodies().empty()) << "step " << steps << " " << drop.top();
    }
  }
  // Free fall from a top at 3.212 m to below -2 m: 5.212 m, sqrt(2 * 5.212 / 9.81) = 1.03 s.
  EXPECT_NEAR(steps * 0.01, std::sqrt(2.0 * (3.0 + drop.maxExtent - kLostLine) / 9.81), 0.02);
  const std::vector<LostBody> lost = drop.world.takeLostBodies();
  ASSERT_EQ(lost.size(), 1u);
  EXPECT_EQ(lost[0].name, "box");
  EXPECT_EQ(lost[0].id, drop.box);
  EXPECT_NEAR(lost[0].depth, -1.0 - drop.top(), 1e-12);
  EXPECT_GT(lost[0].depth, 1.0);
  EXPECT_NE(lost[0].reason.find("lost for good"), std::string::npos) << lost[0].reason;
  EXPECT_NE(lost[0].reason.find("height of 1 m"), std::string::npos) << lost[0].reason;
  EXPECT_TRUE(drop.world.isValid(drop.box)) << "reported, not removed, by default";
  for (int i = 0; i < 100; ++i) drop.world.step();
  EXPECT_TRUE(drop.world.takeLostBodies().empty()) << "reported once";
  EXPECT_EQ(drop.world.lostBodyCount(), 1u);
  EXPECT_EQ(drop.world.removedBodyCount(), 0u);
  EXPECT_TRUE(drop.world.isValid(drop.box));

  // Brought back above the ground and dropped again beside it: lost again, reported again.
  ASSERT_TRUE(drop.world.setTransform(drop.box, Vec2(25.0, 3.0), 0.0));
  ASSERT_TRUE(drop.world.setVelocity(drop.box, Vec2::Zero(), 0.0));
  for (int i = 0; i < steps; ++i) drop.world.step();
  EXPECT_EQ(drop.world.takeLostBodies().size(), 1u);
  EXPECT_EQ(drop.world.lostBodyCount(), 2u);
}

TEST(LostBodies, WithRemoveLostBodiesTheBoxIsRemovedAtTheSameStep) {
  Drop reported;
  Drop removed(Vec2(0.0, -9.81), true);
  for (int step = 1; step <= 200; ++step) {
    reported.world.step();
    removed.world.step();
    const bool lost = !reported.world.takeLostBodies().empty();
    const std::vector<RemovedBody> gone = removed.world.takeRemovedBodies();
    ASSERT_EQ(gone.size(), lost ? 1u : 0u) << "step " << step;
    if (lost) {
      EXPECT_EQ(gone[0].name, "box");
      EXPECT_EQ(gone[0].cause, RemovalCause::LostForGood);
      EXPECT_NE(gone[0].reason.find("lost for good"), std::string::npos) << gone[0].reason;
      EXPECT_FALSE(removed.world.isValid(removed.box));
      EXPECT_TRUE(removed.world.takeLostBodies().empty()) << "removed, so not listed as lost";
      return;
    }
  }
  FAIL() << "never lost";
}

TEST(LostBodies, DownIsAlongGravityWhateverItsDirection) {
  Drop alongY;
  const double g = 9.81;
  int lostAt = 0;
  for (int step = 1; step <= 200 && lostAt == 0; ++step) {
    alongY.world.step();
    if (!alongY.world.takeLostBodies().empty()) lostAt = step;
  }
  ASSERT_GT(lostAt, 0);
  for (const Vec2& gravity :
       {Vec2(g, 0.0), Vec2(0.0, g), Vec2(-g, 0.0), Vec2(Vec2(g, g) / std::sqrt(2.0))}) {
    Drop turned(gravity);
    int turnedAt = 0;
    for (int step = 1; step <= 1000 && turnedAt == 0; ++step) {
      turned.world.step();
      if (!turned.world.takeLostBodies().empty()) turnedAt = step;
    }
    ASSERT_GT(turnedAt, 0) << gravity.transpose();
    if (gravity.x() != 0.0 && gravity.y() != 0.0) {
      // Slanted: the static bounding box's corner reaches deeper than the ground along gravity,
      // so the line is lower and the box is lost later, never sooner.
      EXPECT_GT(turnedAt, lostAt) << gravity.transpose();
    } else {
      EXPECT_EQ(turnedAt, lostAt) << gravity.transpose();
    }
  }
}

TEST(LostBodies, NothingIsLostWithoutGravityOrWithoutStaticBodies) {
  Drop drop;
  drop.world.settings().gravity = Vec2::Zero();
  ASSERT_TRUE(drop.world.setVelocity(drop.box, Vec2(0.0, -100.0), 0.0));
  for (int i = 0; i < 200; ++i) drop.world.step();
  EXPECT_LT(drop.world.body(drop.box).center.y(), -190.0);
  EXPECT_EQ(drop.world.lostBodyCount(), 0u) << "top-down: drifting away is not falling";

  World empty;
  const BodyId box = addBox(empty, "box", Vec2(0.0, 0.0), 1.0, 1.0, BodyType::Dynamic);
  for (int i = 0; i < 200; ++i) empty.step();
  EXPECT_LT(empty.body(box).center.y(), -10.0);
  EXPECT_EQ(empty.lostBodyCount(), 0u) << "no static body to fall off";
}

TEST(LostBodies, ARisingBodyIsNotLostUntilItFallsAgain) {
  Drop drop;
  ASSERT_TRUE(drop.world.setTransform(drop.box, Vec2(25.0, -10.0), 0.0));
  // Thrown up at 10 m/s from 10 m below the ground: it rises for 1.02 s, to y = -4.9 m.
  ASSERT_TRUE(drop.world.setVelocity(drop.box, Vec2(0.0, 10.0), 0.0));
  int lostAt = 0;
  for (int step = 1; step <= 300 && lostAt == 0; ++step) {
    drop.world.step();
    if (!drop.world.takeLostBodies().empty()) lostAt = step;
  }
  EXPECT_NEAR(lostAt * 0.01, 10.0 / 9.81, 0.02) << "lost when it turns, not before";
}

TEST(LostBodies, JointsToAnythingNotLostHoldABody) {
  // A chain of ten 1 m links hanging from a 10 cm static pin: every link hangs farther below
  // the pin than the pin is tall, and none is lost while the chain holds.
  World world;
  addBox(world, "pin", Vec2(0.0, 0.0), 0.1, 0.1, BodyType::Static);
  BodyId above = world.findBody("pin");
  JointId top;
  for (int i = 0; i < 10; ++i) {
    const BodyId link =
        addBox(world, "link" + std::to_string(i), Vec2(0.0, -0.5 - i), 0.1, 1.0, BodyType::Dynamic);
    JointDef hinge;
    hinge.bodyA = above;
    hinge.bodyB = link;
    hinge.anchor = Vec2(0.0, -static_cast<double>(i));
    const JointId id = world.createJoint(hinge);
    ASSERT_TRUE(id.valid());
    if (i == 0) top = id;
    above = link;
  }
  // Nudged so that it swings (and never sleeps) for the whole run.
  ASSERT_TRUE(world.setVelocity(above, Vec2(2.0, 0.0), 0.0));
  for (int i = 0; i < 300; ++i) world.step();
  EXPECT_EQ(world.lostBodyCount(), 0u);

  // Cut at the pin, the whole chain falls and is lost, every link.
  ASSERT_TRUE(world.destroyJoint(top));
  for (int i = 0; i < 300; ++i) world.step();
  EXPECT_EQ(world.lostBodyCount(), 10u);
}

TEST(LostBodies, ABodyThatIsNotLostHoldsEveryChainJointedToIt) {
  // A beam resting across a 2 m static post, a chain of six 1 m links hanging from each end:
  // the lower links are far below the post, the beam is not, and joints join them all (the
  // search finds this from the joints' components, not by walking each chain every step).
  World world;
  addBox(world, "post", Vec2(0.0, -0.5), 2.0, 1.0, BodyType::Static);
  const BodyId beam = addBox(world, "beam", Vec2(0.0, 0.25), 6.0, 0.5, BodyType::Dynamic, 50.0);
  for (const double side : {-1.0, 1.0}) {
    BodyId above = beam;
    for (int i = 0; i < 6; ++i) {
      const std::string name = std::string(side < 0.0 ? "left" : "right") + std::to_string(i);
      const BodyId link =
          addBox(world, name, Vec2(2.8 * side, -0.5 - i), 0.1, 1.0, BodyType::Dynamic, 0.5);
      JointDef hinge;
      hinge.bodyA = above;
      hinge.bodyB = link;
      hinge.anchor = Vec2(2.8 * side, -static_cast<double>(i));
      ASSERT_TRUE(world.createJoint(hinge).valid());
      above = link;
    }
  }
  for (int i = 0; i < 200; ++i) world.step();
  EXPECT_LT(world.body(world.findBody("left5")).center.y(), -4.0) << "the chains hang";
  EXPECT_EQ(world.lostBodyCount(), 0u);

  // Without the beam the two chains fall apart from each other, and each is lost whole.
  ASSERT_TRUE(world.destroyBody(beam));
  for (int i = 0; i < 300; ++i) world.step();
  EXPECT_EQ(world.lostBodyCount(), 12u);
}

TEST(LostBodies, AKinematicPlatformBelowCanStillCatchIt) {
  Drop drop;
  // A platform 20 m below the ground, right under the box.
  const BodyId platform =
      addBox(drop.world, "platform", Vec2(25.0, -20.0), 4.0, 0.5, BodyType::Kinematic);
  for (int i = 0; i < 300; ++i) drop.world.step();
  EXPECT_EQ(drop.world.lostBodyCount(), 0u);
  EXPECT_NEAR(drop.world.body(drop.box).center.y(), -20.0 + 0.25 + 0.15, 0.02) << "it landed";
  // The platform leaves (and the box, asleep on it, is woken): the box falls, and is lost once
  // it is one static height below the platform's lowest point, wherever the platform went.
  ASSERT_TRUE(drop.world.setTransform(platform, Vec2(100.0, -20.0), 0.0));
  ASSERT_TRUE(drop.world.setVelocity(drop.box, Vec2::Zero(), 0.0));
  for (int i = 0; i < 150; ++i) drop.world.step();
  EXPECT_EQ(drop.world.lostBodyCount(), 1u);
}

TEST(LostBodies, TheStaticBoundsFollowStaticBodiesThatChange) {
  Drop drop;
  for (int i = 0; i < 150; ++i) drop.world.step();
  ASSERT_EQ(drop.world.takeLostBodies().size(), 1u);
  const double y = drop.world.body(drop.box).center.y();
  // A static floor appears far below the falling box: it is no longer lost, and lands there.
  const BodyId floor =
      addBox(drop.world, "floor", Vec2(25.0, y - 50.0), 10.0, 1.0, BodyType::Static);
  for (int i = 0; i < 500; ++i) drop.world.step();
  EXPECT_NEAR(drop.world.body(drop.box).center.y(), y - 50.0 + 0.5 + 0.15, 0.02);
  EXPECT_TRUE(drop.world.takeLostBodies().empty());
  // The floor is taken away again: the box falls, and is lost a second time.
  ASSERT_TRUE(drop.world.destroyBody(floor));
  for (int i = 0; i < 200; ++i) drop.world.step();
  EXPECT_EQ(drop.world.takeLostBodies().size(), 1u);
  // The ground moved below the box: not lost any more, so found lost again only once it
  // falls past the ground's new line.
  ASSERT_TRUE(drop.world.setTransform(
      drop.world.findBody("ground"), Vec2(0.0, drop.world.body(drop.box).center.y() - 100.0), 0.0));
  drop.world.step();
  EXPECT_TRUE(drop.world.takeLostBodies().empty());
  for (int i = 0; i < 1500; ++i) drop.world.step();  // 100 m and the ground's height: ~5 s
  EXPECT_EQ(drop.world.takeLostBodies().size(), 1u);
}

}  // namespace
}  // namespace impulse2d
