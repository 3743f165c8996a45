#include "step_workers.hpp"

#include <oneapi/tbb/info.h>
#include <oneapi/tbb/task_arena.h>
#include <oneapi/tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <deque>
#include <thread>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace impulse2d {
namespace {

// Waits a moment: a pause while the wait is short, then the processor goes to others (a machine
// running more threads than cores would otherwise spin away the time of the thread waited for).
void backOff(int& spins) {
  if (++spins < 2000) {
#if defined(__x86_64__) || defined(__i386__)
    _mm_pause();
#endif
  } else {
    std::this_thread::yield();
  }
}

}  // namespace

struct StepWorkers::Shared {
  // A stage's blocks are cut into one run per worker: a worker claims the blocks of its own run
  // first, so that in every pass over the same data (the colours of each sub-step) each thread
  // takes the same part and finds it in its own cache; then it helps with the others' runs.
  struct alignas(64) Run {
    std::atomic<int> next{0};  // the next block to claim
    int end = 0;
  };
  struct Stage {
    explicit Stage(int threads) : runs(static_cast<size_t>(threads)) {}
    std::deque<Run> runs;  // one per thread; the first runCount are this stage's
    int runCount = 0;
    alignas(64) std::atomic<int> done{0};
    int blocks = 0;
    const Block* fn = nullptr;
  };

  explicit Shared(int threads) : arena(threads) {}

  // Claims and runs blocks of `stage`, its own run first, until none is left; then counts them
  // done at once. Counted block by block, each count took the line of `done` from the thread
  // spinning on it (on a VM whose cores hand a line over in about 250 ns, pyramid20 on two
  // threads took 0.89-0.91 ms a step counting each block, 0.81-0.83 counting once).
  static void work(Stage& stage, int worker) {
    const size_t runs = static_cast<size_t>(stage.runCount);
    int ran = 0;
    for (size_t k = 0; k < runs; ++k) {
      Run& run = stage.runs[(static_cast<size_t>(worker) + k) % runs];
      for (int block = run.next.fetch_add(1, std::memory_order_relaxed); block < run.end;
           block = run.next.fetch_add(1, std::memory_order_relaxed)) {
        (*stage.fn)(block, worker);
        ++ran;
      }
    }
    if (ran > 0) stage.done.fetch_add(ran, std::memory_order_release);
  }

  void helper(int worker) {
    const Stage* seen = nullptr;
    int spins = 0;
    for (;;) {
      Stage* stage = current.load(std::memory_order_acquire);
      if (stage != nullptr && stage != seen) {
        seen = stage;
        work(*stage, worker);
        spins = 0;
        continue;
      }
      if (ending.load(std::memory_order_acquire)) return;
      backOff(spins);
    }
  }

  tbb::task_arena arena;
  // The stages, by number in the session: a deque keeps them in place as it grows, so a helper
  // that still holds a finished stage only finds no block left in it. They are kept from session
  // to session (the first `used` are this one's): a step of 24 colours and 8 sub-steps has
  // hundreds, and making each anew took two allocations.
  std::deque<Stage> stages;
  size_t used = 0;
  std::atomic<Stage*> current{nullptr};
  std::atomic<bool> ending{false};
};

StepWorkers::StepWorkers() = default;
StepWorkers::~StepWorkers() = default;

void StepWorkers::setThreads(int threads) {
  // More threads than the processor runs at once would only wait for each other (and TBB warns
  // that it has no workers for them): the result is the same on any number.
  threads = std::max(1, std::min(threads, tbb::info::default_concurrency()));
  if (threads == threads_) return;
  threads_ = threads;
  shared_.reset(threads > 1 ? new Shared(threads) : nullptr);
}

void StepWorkers::session(FunctionRef<void()> body) {
  if (threads_ == 1) {
    body();
    return;
  }
  Shared& s = *shared_;
  s.used = 0;
  s.current.store(nullptr, std::memory_order_relaxed);
  s.ending.store(false, std::memory_order_relaxed);
  s.arena.execute([&] {
    tbb::task_group helpers;
    for (int worker = 1; worker < threads_; ++worker) {
      helpers.run([&s, worker] { s.helper(worker); });
    }
    inSession_ = true;
    body();
    inSession_ = false;
    s.ending.store(true, std::memory_order_release);
    helpers.wait();
  });
}

void StepWorkers::stage(int blocks, Block fn, bool shared) {
  if (!inSession_ || blocks <= 1 || !shared) {
    for (int block = 0; block < blocks; ++block) fn(block, 0);
    return;
  }
  const int runs = std::min(threads_, blocks);
  Shared& s = *shared_;
  if (s.used == s.stages.size()) s.stages.emplace_back(threads_);
  Shared::Stage& stage = s.stages[s.used++];
  stage.runCount = runs;
  stage.done.store(0, std::memory_order_relaxed);
  stage.blocks = blocks;
  stage.fn = &fn;
  for (int r = 0; r < runs; ++r) {  // run r: blocks [r blocks / runs, (r + 1) blocks / runs)
    stage.runs[r].next.store(static_cast<int>(int64_t(r) * blocks / runs),
                             std::memory_order_relaxed);
    stage.runs[r].end = static_cast<int>(int64_t(r + 1) * blocks / runs);
  }
  shared_->current.store(&stage, std::memory_order_release);
  Shared::work(stage, 0);
  int spins = 0;
  while (stage.done.load(std::memory_order_acquire) < blocks) backOff(spins);
}

}  // namespace impulse2d
