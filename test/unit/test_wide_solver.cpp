// The sub-stepping solvers' SIMD kernels and threads (contact_kernels.cpp, step_workers.hpp):
// the same scene gives bit-identical states on every instruction set the processor has (a lane
// at a time on the portable target is the scalar reference) and on any number of threads.
#include <gtest/gtest.h>
#include <impulse2d/scene.hpp>
#include <impulse2d/simd.hpp>
#include <impulse2d/world.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "all_solvers.hpp"
#include "contact_bundles.hpp"

namespace impulse2d {
namespace {

// Scenes that exercise every kernel path: two-point manifolds in piles, one-point circles,
// restitution, joints in the overflow and in lanes (joint_grid: colours of dozens of revolute
// joints, with static, kinematic and welded bodies among them), and bodies a colour cannot hold
// (a box touched by many).
const char* const kScenes[] = {"test/scenes/pyramid20.yaml", "test/scenes/bounce.yaml",
                               "test/scenes/bridge20.yaml", "test/scenes/joint_grid.yaml",
                               "test/determinism/canonical.yaml"};

uint64_t runScene(const std::string& file, SolverType solver, int threads, int steps) {
  Scene scene;
  std::string error;
  EXPECT_TRUE(loadSceneFile(std::string(IMPULSE2D_SOURCE_DIR) + "/" + file, &scene, &error))
      << error;
  scene.world.solver = solver;
  scene.world.threads = threads;
  scene.world.enableSleep = false;  // keep every body in the solver for the whole run
  World world(scene.world);
  EXPECT_TRUE(addScene(scene, world, &error)) << error;
  for (int i = 0; i < steps; ++i) world.step();
  return world.hash();
}

class WideSolver : public ::testing::TestWithParam<test::SolverCase> {};

TEST_P(WideSolver, EveryInstructionSetGivesTheSameState) {
  const std::vector<std::string> targets = simdTargets();
  ASSERT_FALSE(targets.empty());
  for (const char* file : kScenes) {
    std::vector<uint64_t> hashes;
    for (const std::string& target : targets) {
      ASSERT_TRUE(useSimdTarget(target)) << target;
      ASSERT_EQ(simdTarget(), target);
      hashes.push_back(runScene(file, GetParam().type, 1, 150));
    }
    useSimdTarget("");
    for (size_t i = 1; i < hashes.size(); ++i) {
      EXPECT_EQ(hashes[i], hashes[0]) << file << ": " << targets[i] << " against " << targets[0];
    }
    std::printf("wide solver: %s %s: %zu instruction sets (%s ... %s), one state\n",
                GetParam().name, file, targets.size(), targets.front().c_str(),
                targets.back().c_str());
  }
}

TEST_P(WideSolver, AnyNumberOfThreadsGivesTheSameState) {
  for (const char* file : kScenes) {
    const uint64_t one = runScene(file, GetParam().type, 1, 150);
    for (const int threads : {2, 3, 4}) {
      EXPECT_EQ(runScene(file, GetParam().type, threads, 150), one)
          << file << " on " << threads << " threads";
    }
  }
}

// The revolute joints in lanes (joint_lanes.hpp) repeat the scalar rows' operations, so the
// grid gives the state the scalar path gave before there were lanes (hashes from commit 1dcbb19):
// as it settles, and kicked at 800 m/s twice, where the warm start of the joints around the
// kicked bodies breaks the motion limits and goes back to the scalar path.
uint64_t kicked(const std::string& file, const std::vector<std::string>& kickedBodies, bool kick,
                int threads) {
  Scene scene;
  std::string error;
  EXPECT_TRUE(
      loadSceneFile(std::string(IMPULSE2D_SOURCE_DIR) + "/test/scenes/" + file, &scene, &error))
      << error;
  scene.world.solver = SolverType::SubstepNgs;
  scene.world.threads = threads;
  World world(scene.world);
  EXPECT_TRUE(addScene(scene, world, &error)) << error;
  for (int i = 0; i < (kick ? 200 : 300); ++i) {
    if (kick && (i == 60 || i == 130)) {
      for (const BodyId id : world.bodies()) {
        const std::string& name = world.body(id).name;
        if (std::find(kickedBodies.begin(), kickedBodies.end(), name) != kickedBodies.end()) {
          world.setVelocity(id, Vec2(800.0, -500.0), 300.0);
        }
      }
    }
    world.step();
  }
  return world.hash();
}
uint64_t kickedGrid(bool kick, int threads) {
  return kicked("joint_grid.yaml", {"g6_7", "g2_11"}, kick, threads);
}

TEST(WideSolver, JointsInLanesGiveTheScalarPathsState) {
  for (const int threads : {1, 2}) {
    EXPECT_EQ(kickedGrid(false, threads), 0x8e18a9b24c49578bull) << threads << " threads";
    EXPECT_EQ(kickedGrid(true, threads), 0x2d3db45bf1770620ull) << threads << " threads";
  }
}

// A chain's joints are all in the overflow, solved one lane after the other; where a kicked
// body's warm start goes back to the scalar path, that joint's scalar warm start comes before the
// next joint's lane (runJointOverflow stops there). Hashes from commit 455030e, which went back to
// the world after every lane; chain40's re-pinned when a colour's few contacts took lanes instead
// of the overflow, from builds that gave every joint the scalar path and that ran the overflow
// one lane a call, both equal to this one.
TEST(WideSolver, AChainsLanesGiveWayToTheScalarPathInOrder) {
  for (const int threads : {1, 2}) {
    EXPECT_EQ(kicked("bridge20.yaml", {"plank_5", "plank_12"}, true, threads),
              0x31f5aa844608b042ull)
        << threads << " threads";
    EXPECT_EQ(kicked("chain40.yaml", {"link_9", "link_30"}, true, threads), 0x53fdffd97ea871f6ull)
        << threads << " threads";
  }
}

TEST(WideSolver, AnUnknownInstructionSetIsRefused) {
  EXPECT_FALSE(useSimdTarget("NEON_BF16"));
  EXPECT_FALSE(simdTargets().empty());
}

// The choice is an explicit call (programs make it at start-up): IMPULSE2D_SIMD names one of the
// targets, anything else is refused with the choices and changes nothing, unset or empty leaves
// the kernels where they are.
TEST(WideSolver, TheEnvironmentChoosesTheInstructionSetWhenAsked) {
  ASSERT_TRUE(useSimdTarget(""));
  const std::string best = simdTarget();
  ASSERT_EQ(best, simdTargets().front());
  setenv("IMPULSE2D_SIMD", "NEON_BF16", 1);
  const std::string refused = useSimdTargetFromEnvironment();
  EXPECT_EQ(refused.rfind("IMPULSE2D_SIMD=NEON_BF16 is not one of: " + best, 0), 0u) << refused;
  EXPECT_EQ(simdTarget(), best);
  const std::string last = simdTargets().back();
  setenv("IMPULSE2D_SIMD", last.c_str(), 1);
  EXPECT_EQ(useSimdTargetFromEnvironment(), "");
  EXPECT_EQ(simdTarget(), last);
  setenv("IMPULSE2D_SIMD", "", 1);
  EXPECT_EQ(useSimdTargetFromEnvironment(), "");
  EXPECT_EQ(simdTarget(), last);
  unsetenv("IMPULSE2D_SIMD");
  EXPECT_EQ(useSimdTargetFromEnvironment(), "");
  ASSERT_TRUE(useSimdTarget(""));
  EXPECT_EQ(simdTarget(), best);
}

INSTANTIATE_TEST_SUITE_P(AllSolvers, WideSolver, ::testing::ValuesIn(test::allSolvers()),
                         test::SolverCaseName());

}  // namespace
}  // namespace impulse2d
