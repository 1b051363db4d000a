// impulse/thread_pool.hpp — a small std::thread pool that implements the task
// hook (core/task_system.hpp), for programs without a scheduler of their own,
// the examples and the benchmarks. Optional: nothing else in impulse includes
// it, so a program that brings its own scheduler never parses <thread>.
//
//   impulse::thread_pool pool{2};            // the calling thread and one more
//   particles.set_task_system(pool.tasks());
//
// A pool of W workers starts W − 1 threads; the thread that calls finish()
// works too, as worker 0. A loop is cut into about four ranges per worker
// (never below its min_range), claimed one at a time, so a worker slowed by
// the machine's other work takes fewer. Between loops a worker spins for a
// short while (about 50 µs) before it sleeps: a game's step issues its loops
// back to back, and waking a sleeping thread costs several microseconds, as
// long as a small loop takes. One thread at a time may drive a pool.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <list>
#include <mutex>
#include <thread>
#include <vector>

#include "core/error.hpp"
#include "core/task_system.hpp"

namespace impulse {

class thread_pool {
 public:
  /// The most workers a pool may have.
  static constexpr std::uint32_t max_workers = 256;

  /// A pool of `workers` workers, the calling thread included (1 starts no thread).
  explicit thread_pool(std::uint32_t workers) : workers_(workers) {
    if (workers < 1 || workers > max_workers)
      detail::report_error(error_code::invalid_parameter, "thread_pool: workers must be between 1 and 256");
    threads_.reserve(workers - 1);
    for (std::uint32_t w = 1; w < workers; ++w) threads_.emplace_back([this, w] { work(w); });
  }
  thread_pool(const thread_pool&) = delete;
  thread_pool& operator=(const thread_pool&) = delete;
  ~thread_pool() {
    {
      const std::lock_guard lock(mutex_);
      stopping_ = true;
      posted_.fetch_add(1, std::memory_order_release);
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

  [[nodiscard]] std::uint32_t workers() const noexcept { return workers_; }

  /// The hook bound to this pool; valid while the pool lives.
  [[nodiscard]] task_system tasks() noexcept { return {workers_, &enqueue, &finish, this}; }

 private:
  struct loop {
    task_function* task;
    void* context;
    std::uint32_t count, range;
    std::uint32_t next = 0;     // first item not yet claimed
    std::uint32_t running = 0;  // ranges claimed and not yet done
  };

  static void* enqueue(task_function* task, std::uint32_t count, std::uint32_t min_range, void* context,
                       void* user) {
    thread_pool& pool = *static_cast<thread_pool*>(user);
    const std::uint32_t pieces = 4 * pool.workers_;
    const std::uint32_t range = std::max({min_range, (count + pieces - 1) / pieces, std::uint32_t(1)});
    loop* handle;
    {
      const std::lock_guard lock(pool.mutex_);
      handle = &pool.loops_.emplace_back(loop{task, context, count, range});
      // Under the lock: a worker reads the counter under it before it waits,
      // so it either sees this post or is already waiting for the notify.
      pool.posted_.fetch_add(1, std::memory_order_release);
    }
    pool.wake_.notify_all();
    return handle;
  }

  static void finish(void* handle, void* user) {
    thread_pool& pool = *static_cast<thread_pool*>(user);
    loop& l = *static_cast<loop*>(handle);
    std::unique_lock lock(pool.mutex_);
    while (pool.run_one(l, 0, lock)) {
    }
    pool.done_.wait(lock, [&] { return l.running == 0; });
    pool.loops_.remove_if([&](const loop& other) { return &other == &l; });
  }

  /// Claims and runs the next range of l as `worker`, with the lock held on
  /// entry and on return; false when no range is left to claim.
  bool run_one(loop& l, std::uint32_t worker, std::unique_lock<std::mutex>& lock) {
    if (l.next >= l.count) return false;
    const std::uint32_t begin = l.next, end = begin + std::min(l.range, l.count - begin);
    l.next = end;
    ++l.running;
    lock.unlock();
    l.task(begin, end, worker, l.context);
    lock.lock();
    if (--l.running == 0 && l.next >= l.count) done_.notify_all();
    return true;
  }

  bool claim_any(std::uint32_t worker, std::unique_lock<std::mutex>& lock) {
    for (loop& l : loops_)
      if (run_one(l, worker, lock)) return true;  // the list may have changed: start again
    return false;
  }

  void work(std::uint32_t worker) {
    std::unique_lock lock(mutex_);
    while (!stopping_) {
      if (claim_any(worker, lock)) continue;
      // Nothing to claim: spin on the post counter, unlocked, then sleep.
      const std::uint64_t seen = posted_.load(std::memory_order_acquire);
      lock.unlock();
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::microseconds(50);
      while (posted_.load(std::memory_order_acquire) == seen && std::chrono::steady_clock::now() < give_up)
        std::this_thread::yield();
      lock.lock();
      wake_.wait(lock, [&] { return stopping_ || posted_.load(std::memory_order_acquire) != seen; });
    }
  }

  const std::uint32_t workers_;
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::list<loop> loops_;                // under mutex_; a list, so a handle stays valid
  std::atomic<std::uint64_t> posted_{0};  // loops posted (and the stop), for the spin
  bool stopping_ = false;                 // under mutex_
};

}  // namespace impulse
