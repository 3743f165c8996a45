// The position guard's bookkeeping (position_guard.hpp) on hand-made joints and errors: which
// groups it judges, which it restores, and when it arms and rests.
#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "position_guard.hpp"

namespace impulse2d {
namespace {

struct Link {
  int a, b;      // entries, -1 for a body the step does not move
  double error;  // squared (m^2)
};

// Visits `links` as a solver path would.
auto visitOf(const std::vector<Link>& links) {
  return [&links](const auto& note) {
    for (const Link& l : links) note(l.a, l.b, l.error);
  };
}

struct Verdict {
  std::set<int> restored, forgotten;
};

Verdict judge(PositionGuard& guard, int entries, const std::vector<Link>& before,
              const std::vector<Link>& after) {
  guard.measureBefore(entries, visitOf(before));
  Verdict v;
  guard.keepOrRestore(
      visitOf(after), [&](int e) { v.restored.insert(e); },
      [&](size_t j) { v.forgotten.insert(static_cast<int>(j)); });
  return v;
}

constexpr double kFar = PositionGuard::kJudgedError * PositionGuard::kJudgedError;

// Two groups: {0, 1, 2} joined by joints 0 and 1 (joint 2 pins entry 2 to a static body), and
// {3, 4} by joint 3. Only the first opened wider; only it is restored, whole, and its joints
// forgotten.
TEST(PositionGuard, RestoresOnlyTheGroupThePassOpenedWider) {
  PositionGuard guard;
  const std::vector<Link> before = {
      {0, 1, 2 * kFar}, {1, 2, 2 * kFar}, {2, -1, 2 * kFar}, {3, 4, 2 * kFar}};
  std::vector<Link> after = before;
  after[0].error = 1.0 * kFar;  // one joint closed,
  after[2].error = 4.0 * kFar;  // another opened more: the group's sum grew
  after[3].error = 1.5 * kFar;  // the other group closed
  const Verdict v = judge(guard, 5, before, after);
  EXPECT_EQ(v.restored, (std::set<int>{0, 1, 2}));
  EXPECT_EQ(v.forgotten, (std::set<int>{0, 1, 2}));
}

// A group open by less than kJudgedError rms is left to the passes even when they widen it; the
// same sum spread over fewer joints is judged.
TEST(PositionGuard, JudgesAGroupOnlyWhenItsJointsAreFarOpenOnAverage) {
  PositionGuard guard;
  // Four joints, 1.5 kFar in all: 0.375 kFar each on average, under the level.
  std::vector<Link> before = {{0, 1, 1.5 * kFar}, {1, 2, 0.0}, {2, 3, 0.0}, {3, 4, 0.0}};
  std::vector<Link> after = before;
  after[0].error = 3.0 * kFar;
  EXPECT_TRUE(judge(guard, 5, before, after).restored.empty());
  // One joint, the same sum: over the level.
  before = {{0, 1, 1.5 * kFar}};
  after = {{0, 1, 3.0 * kFar}};
  EXPECT_EQ(judge(guard, 2, before, after).restored, (std::set<int>{0, 1}));
}

// Armed by a joint wider than kJudgedError; a guarded step that found nothing worse rests the
// guard for 1, then 3 steps; one that found a group worse keeps it armed.
TEST(PositionGuard, ArmsOnWideJointsAndRestsAfterStepsWithNothingWorse) {
  PositionGuard guard;
  const double wide = 2.0 * PositionGuard::kJudgedError;
  guard.settle(0.5 * PositionGuard::kJudgedError);
  EXPECT_FALSE(guard.armed()) << "no joint that wide";
  guard.settle(wide);
  ASSERT_TRUE(guard.armed());
  const std::vector<Link> open = {{0, 1, 4 * kFar}}, closed = {{0, 1, 1.5 * kFar}};
  judge(guard, 2, open, closed);  // nothing worse
  guard.settle(wide);
  EXPECT_FALSE(guard.armed()) << "rests one step";
  guard.settle(wide);
  ASSERT_TRUE(guard.armed());
  judge(guard, 2, open, closed);
  for (int step = 0; step < 3; ++step) {
    guard.settle(wide);
    EXPECT_FALSE(guard.armed()) << "rests three steps, step " << step;
  }
  guard.settle(wide);
  ASSERT_TRUE(guard.armed());
  EXPECT_EQ(judge(guard, 2, closed, open).restored.size(), 2u);  // worse
  guard.settle(wide);
  EXPECT_TRUE(guard.armed()) << "a step that found a group worse does not rest";
}

// Baumgarte's step start: the joints of groups far open on average are judged, whole; without
// rests the guard sweeps every step, however quiet the last ones were.
TEST(PositionGuard, JudgesWholeGroupsAtTheStepStartAndSweepsEveryStepWithoutRests) {
  PositionGuard guard;
  // Group {0, 1, 2}: 1.5 kFar + 0 over two joints, 0.75 kFar each, not judged; group {3, 4, 5}:
  // 4 kFar + 0 + 0.5 kFar over three joints, 1.5 kFar each, judged with all three joints.
  const std::vector<Link> links = {
      {0, 1, 1.5 * kFar}, {1, 2, 0.0}, {3, 4, 4 * kFar}, {4, 5, 0.0}, {5, -1, 0.5 * kFar}};
  const auto judged = [&](bool rests) {
    guard.measureStepStart(6, visitOf(links), rests);
    std::set<int> joints;
    if (guard.armed()) guard.forEachJudgedJoint([&](size_t j) { joints.insert(int(j)); });
    return joints;
  };
  EXPECT_EQ(judged(false), (std::set<int>{2, 3, 4}));
  const std::vector<Link> quiet = {{0, 1, 0.0}};
  for (int step = 0; step < 3; ++step) {
    guard.measureStepStart(2, visitOf(quiet), false);
    EXPECT_FALSE(guard.armed()) << "no joint wide, step " << step;
  }
  EXPECT_EQ(judged(false), (std::set<int>{2, 3, 4})) << "swept at once after quiet steps";
  // With rests (soft), a quiet step rests the sweep: the wide joints are not seen the next step.
  guard = PositionGuard();
  guard.measureStepStart(2, visitOf(quiet), true);
  EXPECT_TRUE(judged(true).empty()) << "resting";
  EXPECT_EQ(judged(true), (std::set<int>{2, 3, 4})) << "rested one step";
}

}  // namespace
}  // namespace impulse2d
