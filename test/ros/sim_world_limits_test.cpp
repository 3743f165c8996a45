// The node's request path (SimWorld, which WorldNode serialises its services onto) refuses what
// breaks limits.hpp with a message and an unchanged world, and reports bodies the world removed.
// Regression of fuzz_node_requests
// (test/fuzz/corpus/node_requests/regress_huge_wrench_nan_on_ground): a wrench of 4e233 N at a
// point 4e233 m away made NaN impulses that reached the static ground.
#include "../../src/ros/conversions.hpp"
#include "../../src/ros/sim_world.hpp"

#include <gtest/gtest.h>
#include <impulse2d/limits.hpp>

#include <cmath>
#include <limits>

namespace impulse2d {
namespace bridge {
namespace {

const char* const kScene = R"(
bodies:
  - {name: ground, type: static, position: [0, -0.5], shapes: [{size: [20, 1]}]}
  - {name: a, position: [0, 0.5], shapes: [{size: [1, 1]}]}
)";

class SimWorldLimits : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string error;
    ASSERT_TRUE(sim.loadStartScene(kScene, &error)) << error;
  }
  SimWorld sim;
  std::string error;
};

TEST_F(SimWorldLimits, AbsurdWrenchesAreRefused) {
  EXPECT_FALSE(sim.applyWrench("a", Vec2(4e233, 4e233), 0.0, Vec2(0.0, 4e233), 0.0, &error));
  EXPECT_NE(error.find("force"), std::string::npos) << error;
  EXPECT_FALSE(sim.applyWrench("a", Vec2(1.0, 0.0), 0.0, Vec2(0.0, 4e233), 0.0, &error));
  EXPECT_NE(error.find("point"), std::string::npos) << error;
  EXPECT_FALSE(sim.applyWrench("a", Vec2(1.0, 0.0), 2e12, Vec2::Zero(), 0.0, &error));
  EXPECT_FALSE(sim.applyWrench("a", Vec2(1.0, 0.0), 0.0, Vec2::Zero(),
                               std::numeric_limits<double>::quiet_NaN(), &error));
  // A huge duration is accepted (held "forever") without overflowing the step count.
  EXPECT_TRUE(sim.applyWrench("a", Vec2(0.0, 1.0), 0.0, Vec2::Zero(), 1e300, &error)) << error;
  for (int i = 0; i < 10; ++i) sim.step();
  for (const BodySnapshot& body : sim.bodies(false)) {
    EXPECT_TRUE(isFinite(body.position) && isFinite(body.linearVelocity)) << body.name;
  }
}

TEST_F(SimWorldLimits, PendingWrenchesAreCapped) {
  for (size_t i = 0; i < kMaxPendingWrenches; ++i) {
    ASSERT_TRUE(sim.applyWrench("a", Vec2(0.0, 0.001), 0.0, Vec2::Zero(), 10.0, &error)) << i;
  }
  EXPECT_FALSE(sim.applyWrench("a", Vec2(0.0, 0.001), 0.0, Vec2::Zero(), 10.0, &error));
  EXPECT_NE(error.find("4096 pending wrenches"), std::string::npos) << error;
}

TEST_F(SimWorldLimits, SetBodyStateStaysWithinTheLimits) {
  EXPECT_FALSE(sim.setBodyState("a", Vec2(0.0, 2e6), 0.0, Vec2::Zero(), 0.0, &error));
  EXPECT_NE(error.find("pose"), std::string::npos) << error;
  EXPECT_FALSE(sim.setBodyState("a", Vec2(0.0, 1.0), 0.0, Vec2(2e6, 0.0), 0.0, &error));
  EXPECT_NE(error.find("twist"), std::string::npos) << error;
  BodySnapshot a;
  ASSERT_TRUE(sim.getBodyState("a", &a, &error));
  EXPECT_EQ(a.position, Vec2(0.0, 0.5));
}

TEST_F(SimWorldLimits, BodiesThatLeaveTheWorldAreReportedOnce) {
  // The default speed limit (400 m/s) never gets a body out of 1e7 m; a world may raise it to
  // the fastest a body may be set moving, 1e6 m/s, which passes x = 1e7 m in step 1000.
  SimWorld fast;
  ASSERT_TRUE(fast.loadStartScene(R"(
world: {gravity: [0, 0], max_linear_speed: 1000000}
bodies:
  - {name: stay, position: [0, 0], shapes: [{size: [1, 1]}]}
  - {name: away, position: [5, 0], linear_velocity: [1000000, 0], shapes: [{size: [1, 1]}]}
)",
                                  &error))
      << error;
  for (int i = 0; i < 999; ++i) fast.step();
  EXPECT_TRUE(fast.takeBodyLosses().empty());
  fast.step();
  const std::vector<BodyLoss> removed = fast.takeBodyLosses();
  ASSERT_EQ(removed.size(), 1u);
  EXPECT_EQ(removed[0].describe(), "removed body 'away': it left the world extent of 1e7 m");
  EXPECT_TRUE(removed[0].removed);
  EXPECT_EQ(removed[0].cause, RemovalCause::LeftWorldExtent);
  EXPECT_GT(removed[0].position.x(), kWorldExtent);
  EXPECT_EQ(removed[0].simTimeNs, fast.simTimeNs());
  EXPECT_TRUE(fast.takeBodyLosses().empty());
  EXPECT_EQ(fast.bodyCount(), 1u);
  EXPECT_EQ(fast.removedBodyCount(), 1u);
}

TEST_F(SimWorldLimits, BodiesLostForGoodAreReportedAndRemovedOnlyWhenTheWorldSaysSo) {
  const char* const kDrop = R"(
bodies:
  - {name: ground, type: static, position: [0, -0.5], shapes: [{size: [20, 1]}]}
  - {name: off, position: [15, 0], shapes: [{size: [1, 1]}]}
)";
  for (const bool remove : {false, true}) {
    SimWorld drop;
    const std::string world = remove ? "world: {remove_lost_bodies: true}\n" : "";
    ASSERT_TRUE(drop.loadStartScene(world + kDrop, &error)) << error;
    // Its top at 0.707 m passes -2 m once it fell 2.71 m: after sqrt(2 x 2.71 / 9.81) = 0.74 s.
    for (int i = 0; i < 100; ++i) drop.step();
    const std::vector<BodyLoss> lost = drop.takeBodyLosses();
    ASSERT_EQ(lost.size(), 1u) << remove;
    EXPECT_EQ(lost[0].cause, RemovalCause::LostForGood);
    EXPECT_EQ(lost[0].removed, remove);
    EXPECT_EQ(drop.bodyCount(), remove ? 1u : 2u);
    EXPECT_EQ(drop.removedBodyCount(), remove ? 1u : 0u);
    EXPECT_EQ(drop.lostBodyCount(), remove ? 0u : 1u);
    const std::string line = lost[0].describe();
    EXPECT_EQ(line.rfind(remove ? "removed body 'off': lost for good: it fell "
                                : "body 'off' is lost for good: it fell ",
                         0),
              0u)
        << line;
    EXPECT_NE(line.find("below every static body, more than their height of 1 m"),
              std::string::npos)
        << line;
    // The counts run on across a reset, which brings the body back.
    drop.reset();
    for (int i = 0; i < 100; ++i) drop.step();
    EXPECT_EQ(drop.takeBodyLosses().size(), 1u);
    EXPECT_EQ(drop.removedBodyCount() + drop.lostBodyCount(), 2u);
  }
}

TEST_F(SimWorldLimits, AForceAtTheWorldOriginFarFromTheBodyIsPointedOut) {
  std::vector<std::string> notes;
  BodyDef far;
  far.name = "far";
  far.position = Vec2(3.0, 4.0);
  far.shapes.resize(1);
  ASSERT_TRUE(sim.spawnBody(far, &error)) << error;
  ASSERT_TRUE(sim.applyWrench("far", Vec2(1.0, 0.0), 0.0, Vec2::Zero(), 0.0, &error, &notes));
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_EQ(notes[0],
            "point: (0, 0), the world origin, 5 m from the centre of mass: the force also turns "
            "the body");
  notes.clear();
  // At the body, or a torque alone: nothing to point out.
  ASSERT_TRUE(sim.applyWrench("far", Vec2(1.0, 0.0), 0.0, Vec2(3.0, 4.0), 0.0, &error, &notes));
  ASSERT_TRUE(sim.applyWrench("far", Vec2::Zero(), 1.0, Vec2::Zero(), 0.0, &error, &notes));
  EXPECT_TRUE(notes.empty());
}

TEST(ConversionsLimits, OversizedMessagesAreRefusedBeforeConversion) {
  impulse2d::Body msg;
  msg.name = "many";
  msg.type = impulse2d::Body::DYNAMIC;
  impulse2d::Shape box;
  box.type = impulse2d::Shape::BOX;
  box.width = box.height = 1.0;
  msg.shapes.assign(kMaxShapesPerBody + 1, box);
  BodyDef def;
  EXPECT_NE(toBodyDef(msg, &def).find("at most 64 shapes"), std::string::npos);
  impulse2d::Shape polygon;
  polygon.type = impulse2d::Shape::POLYGON;
  polygon.vertices.resize(kMaxPolygonVertices + 1);
  msg.shapes.assign(1, polygon);
  EXPECT_NE(toBodyDef(msg, &def).find("at most 16 vertices"), std::string::npos);
}

}  // namespace
}  // namespace bridge
}  // namespace impulse2d
