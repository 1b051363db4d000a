// impulse/core/task_system.hpp — the hook through which a program lends
// impulse its worker threads.
//
// impulse never creates a thread. A step that can spread over cores hands
// each parallel loop to two callbacks the program provides: `enqueue` starts
// a loop over items [0, item_count) on the program's own scheduler (a job
// system, TBB, enkiTS, or impulse/thread_pool.hpp), split into ranges of at
// least `min_range` items however it likes, and `finish` returns once every
// range has run. Without callbacks, or with one worker, a loop runs on the
// calling thread as a plain call.
//
// What impulse runs through the hook does not depend on how the items are
// split or which worker runs which range: each range writes only its own
// items, and whatever is gathered across items is gathered in item order
// afterwards. So the results are bit-identical for any worker count and any
// scheduler.
//
//   impulse::thread_pool pool{2};
//   particles.set_task_system(pool.tasks());
#pragma once

#include <cstdint>

namespace impulse {

/// One range of a parallel loop: items [begin, end), run by worker
/// `worker` (0 ≤ worker < task_system::workers), with the loop's context.
using task_function = void(std::uint32_t begin, std::uint32_t end, std::uint32_t worker, void* task_context);

struct task_system {
  /// How many threads may run a loop's ranges at once, the calling thread
  /// included; a worker index is below it.
  std::uint32_t workers = 1;
  /// Starts `task` over [0, item_count) in ranges of at least min_range
  /// items (the last may be shorter) and returns a handle for `finish`.
  /// It may run ranges before it returns, on any thread.
  void* (*enqueue)(task_function* task, std::uint32_t item_count, std::uint32_t min_range,
                   void* task_context, void* user_context) = nullptr;
  /// Returns when every range of the loop `handle` names has run.
  void (*finish)(void* handle, void* user_context) = nullptr;
  /// Passed back to both callbacks.
  void* user_context = nullptr;

  /// Whether loops go through the callbacks at all.
  [[nodiscard]] bool parallel() const noexcept { return workers > 1 && enqueue != nullptr && finish != nullptr; }
};

namespace detail {

/// Runs body(begin, end, worker) over [0, count): through the hook when it
/// has more than one worker and the loop more than one range, else as one
/// call on this thread.
template <class Body>
void parallel_for(const task_system& tasks, std::uint32_t count, std::uint32_t min_range, Body& body) {
  if (count == 0) return;
  if (!tasks.parallel() || count <= min_range) {
    body(std::uint32_t(0), count, std::uint32_t(0));
    return;
  }
  task_function* run = [](std::uint32_t begin, std::uint32_t end, std::uint32_t worker, void* context) {
    (*static_cast<Body*>(context))(begin, end, worker);
  };
  void* handle = tasks.enqueue(run, count, min_range, &body, tasks.user_context);
  tasks.finish(handle, tasks.user_context);
}

}  // namespace detail
}  // namespace impulse
