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
#include <memory>
#include <type_traits>
#include <utility>

namespace impulse2d {

/// A callable taken by reference, for calls that return before it goes away (a stage, a
/// session). std::function copied each lambda of more than two pointers to the heap, on one
/// thread too: with the colouring's table, 17 allocations a step on bridge20 (now none).
template <class Signature>
class FunctionRef;
template <class Result, class... Args>
class FunctionRef<Result(Args...)> {
 public:
  template <class Fn, class = std::enable_if_t<!std::is_same_v<std::decay_t<Fn>, FunctionRef>>>
  FunctionRef(Fn&& fn)  // NOLINT: implicit, as std::function
      : object_(const_cast<void*>(static_cast<const void*>(std::addressof(fn)))),
        call_([](void* object, Args... args) -> Result {
          return (*static_cast<std::remove_reference_t<Fn>*>(object))(std::forward<Args>(args)...);
        }) {}
  Result operator()(Args... args) const { return call_(object_, std::forward<Args>(args)...); }

 private:
  void* object_;
  Result (*call_)(void*, Args...);
};

class StepWorkers {
 public:
  using Block = FunctionRef<void(int block, int worker)>;

  StepWorkers();
  ~StepWorkers();
  StepWorkers(const StepWorkers&) = delete;
  StepWorkers& operator=(const StepWorkers&) = delete;

  /// 1 (the default) runs everything on the stepping thread; more creates the arena (at most
  /// as many threads as the processor runs at once).
  void setThreads(int threads);
  int threads() const { return threads_; }

  /// Runs `body` with the helpers at hand: stage() calls inside it run in parallel.
  void session(FunctionRef<void()> body);
  /// Runs fn(block, worker) for every block in [0, blocks) and returns when all are done; worker
  /// is in [0, threads()). Outside a session, on one thread, or not `shared` (work too small to
  /// pay for handing it over), the blocks run in order on this thread as worker 0.
  void stage(int blocks, Block fn, bool shared = true);
  /// A stage over [0, count) cut into blocks of `perBlock`: fn(begin, end, worker) for each.
  template <class Fn>
  void forRanges(int count, int perBlock, const Fn& fn, bool shared = true) {
    stage((count + perBlock - 1) / perBlock,
          [&](int block, int worker) {
            const int begin = block * perBlock;
            fn(begin, std::min(count, begin + perBlock), worker);
          },
          shared);
  }

 private:
  struct Shared;  // the arena and the stage hand-over (step_workers.cpp)
  int threads_ = 1;
  bool inSession_ = false;
  std::unique_ptr<Shared> shared_;
};

}  // namespace impulse2d
