// World::profile(): each stage's time of the last step, only while profiling is on, and never a
// change of the result.
#include <impulse2d/world.hpp>

#include <gtest/gtest.h>

#include "all_solvers.hpp"
#include "test_scenes.hpp"

namespace impulse2d {
namespace {

using test::allSolvers;
using test::SolverCase;
using test::SolverCaseName;

class Profile : public ::testing::TestWithParam<SolverCase> {
 protected:
  // A 10-row pyramid with a pendulum beside it: contacts, a joint, every stage some work.
  static void build(World& world) {
    test::addGround(world);
    test::addPyramid(world, 10, 0.5);
    const BodyId anchor = test::addBox(world, "anchor", Vec2(8, 6), 0.2, 0.2, BodyType::Static);
    const BodyId bob = test::addBox(world, "bob", Vec2(9, 6), 0.3, 0.3, BodyType::Dynamic);
    JointDef pin;
    pin.name = "pin";
    pin.type = JointType::Revolute;
    pin.bodyA = anchor;
    pin.bodyB = bob;
    pin.anchor = Vec2(8, 6);
    world.createJoint(pin);
  }
  WorldDef settings() const {
    WorldDef def;
    def.solver = GetParam().type;
    return def;
  }
};

TEST_P(Profile, OffByDefaultAndZero) {
  World world(settings());
  build(world);
  EXPECT_FALSE(world.profiling());
  for (int i = 0; i < 10; ++i) world.step();
  EXPECT_EQ(world.profile().total, 0.0);
  for (const auto& [name, ms] : world.profile().stages()) EXPECT_EQ(ms, 0.0) << name;
}

// Each stage takes its part of the step: none negative, together no more than the whole. The
// stages every solver has take some time.
TEST_P(Profile, StagesArePartsOfTheStep) {
  World world(settings());
  build(world);
  world.setProfiling(true);
  for (int i = 0; i < 30; ++i) {
    world.step();
    const StepProfile& p = world.profile();
    double sum = 0.0;
    for (const auto& [name, ms] : p.stages()) {
      EXPECT_GE(ms, 0.0) << name;
      sum += ms;
    }
    EXPECT_GT(p.total, 0.0);
    EXPECT_LE(sum, p.total * (1.0 + 1e-9)) << "step " << i;
    EXPECT_GT(p.narrowPhase, 0.0);
    EXPECT_GT(p.prepare, 0.0);
    EXPECT_GT(p.solve, 0.0);
    EXPECT_GT(p.integrate, 0.0);
  }
}

TEST_P(Profile, TimingChangesNoResult) {
  World plain(settings()), timed(settings());
  build(plain);
  build(timed);
  timed.setProfiling(true);
  for (int i = 0; i < 120; ++i) {
    plain.step();
    timed.step();
  }
  EXPECT_EQ(plain.hash(), timed.hash());
}

INSTANTIATE_TEST_SUITE_P(AllSolvers, Profile, ::testing::ValuesIn(allSolvers()), SolverCaseName());

}  // namespace
}  // namespace impulse2d
