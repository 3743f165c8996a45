// The threads of a step. The solver runs as a list of stages (integrate the bodies, solve colour
// 3, ...), each cut into blocks; a stage starts when every block of the one before is done. The
// thread that steps the world runs blocks itself, and threads - 1 helpers join it: oneTBB tasks
// in the world's own arena, which stay for a whole session (the sub-steps of one step) and claim
// blocks through an atomic counter, spinning between stages instead of going back to TBB.
//
// A block always computes the same thing and the blocks of a stage touch disjoint bodies, so
// which thread runs a block never changes the result: a world steps bit-identically on any number
// of threads. A helper TBB never starts only leaves its blocks to the others.
#pragma once

#include <algorithm>
#include <functional>
#include <memory>

namespace impulse2d {

class StepWorkers {
 public:
  using Block = std::function<void(int block, int worker)>;

  StepWorkers();
  ~StepWorkers();
  StepWorkers(const StepWorkers&) = delete;
  StepWorkers& operator=(const StepWorkers&) = delete;

  /// 1 (the default) runs everything on the stepping thread; more creates the arena (at most
  /// as many threads as the processor runs at once).
  void setThreads(int threads);
  int threads() const { return threads_; }

  /// Runs `body` with the helpers at hand: stage() calls inside it run in parallel.
  void session(const std::function<void()>& body);
  /// Runs fn(block, worker) for every block in [0, blocks) and returns when all are done; worker
  /// is in [0, threads()). Outside a session, or on one thread, the blocks run in order.
  void stage(int blocks, const Block& fn);
  /// A stage over [0, count) cut into blocks of `perBlock`: fn(begin, end, worker) for each.
  template <class Fn>
  void forRanges(int count, int perBlock, const Fn& fn) {
    stage((count + perBlock - 1) / perBlock, [&](int block, int worker) {
      const int begin = block * perBlock;
      fn(begin, std::min(count, begin + perBlock), worker);
    });
  }

 private:
  struct Shared;  // the arena and the stage hand-over (step_workers.cpp)
  int threads_ = 1;
  bool inSession_ = false;
  std::unique_ptr<Shared> shared_;
};

}  // namespace impulse2d
