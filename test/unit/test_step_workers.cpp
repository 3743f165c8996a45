// StepWorkers (src/core/step_workers.hpp): every block of a stage runs exactly once, on one
// thread or several, with the callable taken by reference (FunctionRef), not copied; a stage too
// small to share runs on the stepping thread.
#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "step_workers.hpp"

namespace impulse2d {
namespace {

TEST(StepWorkers, EveryRangeOfAStageRunsOnceOnAnyNumberOfThreads) {
  for (const int threads : {1, 2}) {
    StepWorkers workers;
    workers.setThreads(threads);
    constexpr int kCount = 10007, kPerBlock = 64;  // a last block shorter than the others
    std::vector<std::atomic<int>> runs(kCount);
    int stages = 0, sessions = 0;
    // A lambda of more than two references: what std::function copied to the heap.
    const int offset = 3, scale = 2;
    workers.session([&] {
      ++sessions;
      for (int stage = 0; stage < 5; ++stage, ++stages) {
        workers.forRanges(kCount, kPerBlock, [&](int begin, int end, int worker) {
          EXPECT_GE(worker, 0);
          EXPECT_LT(worker, workers.threads());
          for (int i = begin; i < end; ++i) runs[i] += scale * (offset - 2);
        });
      }
    });
    EXPECT_EQ(sessions, 1);
    EXPECT_EQ(stages, 5);
    for (int i = 0; i < kCount; ++i) ASSERT_EQ(runs[i].load(), 5 * 2) << "item " << i;
  }
}

TEST(StepWorkers, AStageNotSharedRunsInOrderOnTheSteppingThread) {
  StepWorkers workers;
  workers.setThreads(2);
  std::vector<int> order;  // no atomics: only the stepping thread may touch it
  std::vector<int> workersSeen;
  workers.session([&] {
    workers.forRanges(
        100, 10,
        [&](int begin, int, int worker) {
          order.push_back(begin);
          workersSeen.push_back(worker);
        },
        /*shared=*/false);
  });
  ASSERT_EQ(order.size(), 10u);
  for (int block = 0; block < 10; ++block) {
    EXPECT_EQ(order[block], 10 * block);
    EXPECT_EQ(workersSeen[block], 0);
  }
}

TEST(StepWorkers, FunctionRefCallsTheCallableItRefersTo) {
  int calls = 0;
  auto count = [&calls](int by) {
    calls += by;
    return calls;
  };
  const FunctionRef<int(int)> ref(count);
  EXPECT_EQ(ref(2), 2);
  EXPECT_EQ(ref(3), 5);
  EXPECT_EQ(calls, 5);  // the lambda itself, not a copy
}

}  // namespace
}  // namespace impulse2d
