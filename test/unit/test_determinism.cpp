// Determinism: test/determinism/canonical.yaml stepped kPinnedSteps times gives the pinned hash
// per solver (World::hash: the exact bits of every body's pose and velocity), in one run, in
// chunks with pauses and read-outs between them, after clearing and reloading, and in a second
// world alongside; and impulse2d_sim --hash prints it too. The node's is compared with the CLI's
// in test/ros/hash.test.
//
// The pinned values change whenever the solver or the collision code changes on purpose: update
// kPinned from the "actual" value the failing test prints (check first that every other
// determinism test still passes: they compare runs with each other, not with the table).
#include <gtest/gtest.h>
#include <impulse2d/scene.hpp>

#include <cinttypes>
#include <cstdio>
#include <map>
#include <string>

#include "all_solvers.hpp"

namespace impulse2d {
namespace {

using test::SolverCase;

constexpr int kPinnedSteps = 300;

// Solver name -> World::hash() after kPinnedSteps steps of the canonical scene.
const std::map<std::string, uint64_t> kPinned = {
    {"baumgarte", 0xfa0c5abe69f5a55aull},
    {"ngs", 0xb78541426ee9698dull},
    {"soft", 0x68c18e6e448bf25dull},
    {"substep", 0x55b58069557fbc41ull},
};

std::string hex(uint64_t h) {
  char text[19];
  std::snprintf(text, sizeof text, "%016" PRIx64, h);
  return text;
}

std::string canonicalPath() {
  return std::string(IMPULSE2D_SOURCE_DIR) + "/test/determinism/canonical.yaml";
}

void load(World& world, SolverType solver) {
  Scene scene;
  std::string error;
  ASSERT_TRUE(loadSceneFile(canonicalPath(), &scene, &error)) << error;
  world.settings() = scene.world;
  world.settings().solver = solver;
  ASSERT_TRUE(addScene(scene, world, &error)) << error;
}

uint64_t run(SolverType solver, int steps) {
  World world;
  load(world, solver);
  for (int i = 0; i < steps; ++i) world.step();
  return world.hash();
}

class Determinism : public ::testing::TestWithParam<SolverCase> {};

TEST_P(Determinism, CanonicalSceneMatchesThePinnedHash) {
  const auto pinned = kPinned.find(GetParam().name);
  ASSERT_NE(pinned, kPinned.end())
      << "no pinned hash for " << GetParam().name << "; add it to kPinned: actual "
      << hex(run(GetParam().type, kPinnedSteps));
  const uint64_t actual = run(GetParam().type, kPinnedSteps);
  EXPECT_EQ(hex(actual), hex(pinned->second))
      << "solver " << GetParam().name << ": actual " << hex(actual) << ", pinned "
      << hex(pinned->second) << " (update kPinned if the solver changed on purpose)";
  std::printf("determinism: %s %s\n", GetParam().name, hex(actual).c_str());
}

TEST_P(Determinism, SameHashWhenSteppedInChunksWithReadOutsBetween) {
  World world;
  load(world, GetParam().type);
  int done = 0;
  for (const int chunk : {1, 49, 100, 7, 143}) {
    for (int i = 0; i < chunk; ++i) world.step();
    done += chunk;
    // A pause: reading everything out must change nothing.
    const uint64_t before = world.hash();
    (void)world.contacts();
    for (const BodyId id : world.bodies()) (void)world.body(id);
    for (const JointId id : world.joints()) (void)world.jointState(id);
    EXPECT_EQ(world.hash(), before);
  }
  ASSERT_EQ(done, kPinnedSteps);
  EXPECT_EQ(hex(world.hash()), hex(run(GetParam().type, kPinnedSteps)));
}

TEST_P(Determinism, SameHashAfterClearingAndReloading) {
  World world;
  load(world, GetParam().type);
  for (int i = 0; i < 123; ++i) world.step();
  world.clear();
  load(world, GetParam().type);
  for (int i = 0; i < kPinnedSteps; ++i) world.step();
  EXPECT_EQ(hex(world.hash()), hex(run(GetParam().type, kPinnedSteps)));
}

TEST_P(Determinism, TwoWorldsSteppedInTurnAgree) {
  World a, b;
  load(a, GetParam().type);
  load(b, GetParam().type);
  for (int i = 0; i < kPinnedSteps; ++i) {
    a.step();
    b.step();
  }
  EXPECT_EQ(hex(a.hash()), hex(b.hash()));
}

TEST_P(Determinism, CliPrintsTheSameHash) {
  const std::string command = std::string(IMPULSE2D_SIM_EXECUTABLE) + " " + canonicalPath() +
                              " --solver " + GetParam().name + " --steps " +
                              std::to_string(kPinnedSteps) + " --hash";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buffer[256];
  while (fgets(buffer, sizeof buffer, pipe) != nullptr) output += buffer;
  ASSERT_EQ(pclose(pipe), 0) << output;
  const std::string expected = "hash: " + hex(run(GetParam().type, kPinnedSteps));
  EXPECT_NE(output.find(expected), std::string::npos) << output << "\nexpected " << expected;
}

INSTANTIATE_TEST_SUITE_P(AllSolvers, Determinism, ::testing::ValuesIn(test::allSolvers()),
                         test::SolverCaseName());

}  // namespace
}  // namespace impulse2d
