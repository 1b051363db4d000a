// impulse/thread_pool.hpp — a small std::thread pool that implements the task
// hook (core/task_system.hpp), for programs without a scheduler of their own,
// the examples and the benchmarks. Optional: nothing else in impulse includes
// it, so a program that brings its own scheduler never parses <thread>.
//
//   impulse::thread_pool pool{2};            // the calling thread and one more
//   particles.set_task_system(pool.tasks());
//
// A pool of W workers starts W − 1 threads; the thread that calls finish()
// works too, as worker 0. A loop is cut into about sixteen ranges per worker
// (never below its min_range), and its ranges into one slice per worker.
// Each worker claims its own slice's ranges from the front, one at a time,
// then what is left of the others' from their backs, so a worker slowed by
// the machine's other work takes fewer. Workers end a loop up to a range
// apart: on a cloth of springs (two long loops a stage) two workers idled
// for a median 9 % of a step with four ranges per worker, 4 % with
// sixteen. Each slice's counter has a cache line of its own, so claiming
// from one's own slice does not take the line from the other workers. A step's loops over the same items
// back to back (bodies, contacts, particles) so give each worker the items
// it had in the loop before, still in its cache, where one shared counter
// dealt them out in turn: half of what a loop read had just been written
// on the other core.
//
// Waiting spins before it sleeps, on both sides: a worker with nothing to do,
// and the caller waiting for the other workers' last ranges. A game's step
// issues its loops back to back, a few microseconds apart, and waking a
// sleeping thread costs about as long as a small loop takes (tens of
// microseconds on a virtual machine, whose idle cores halt). The spin lasts
// about 50 µs and pauses the core between looks; with more workers than
// hardware threads it yields its core instead, so the worker it waits for
// can run. One thread at a time may drive a pool.
#pragma once

#include <algorithm>
#include <array>
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
  explicit thread_pool(std::uint32_t workers)
      : workers_(workers), oversubscribed_(workers > std::max(std::thread::hardware_concurrency(), 1u)) {
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
      posted_.fetch_add(1);
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

  [[nodiscard]] std::uint32_t workers() const noexcept { return workers_; }

  /// The hook bound to this pool; valid while the pool lives.
  [[nodiscard]] task_system tasks() noexcept { return {workers_, &enqueue, &finish, this}; }

 private:
  /// Slices a loop's items are cut into; with more workers, worker w
  /// starts on slice w mod max_slices.
  static constexpr std::uint32_t max_slices = 16;

  struct loop {
    loop(task_function* t, void* c, std::uint32_t n, std::uint32_t r, std::uint32_t workers)
        : task(t), context(c), count(n), range(r), slices(std::min({workers, max_slices, n / r + (n % r != 0)})) {
      const std::uint64_t ranges = n / r + (n % r != 0);
      for (std::uint32_t s = 0; s < slices; ++s)
        unclaimed[s].word.store(pack(ranges * s / slices, ranges * (s + 1) / slices), std::memory_order_relaxed);
    }
    task_function* const task;
    void* const context;
    const std::uint32_t count, range, slices;
    // Slice s's ranges not yet claimed, [front, back) in units of `range`,
    // packed front << 32 | back: its owner takes the front, others the back.
    // A cache line each: a worker's claims on its own slice do not take
    // the line from the others.
    struct alignas(64) slice_state {
      std::atomic<std::uint64_t> word{0};
    };
    std::array<slice_state, max_slices> unclaimed{};
    std::atomic<std::uint32_t> done{0};      // items whose range has run
    std::atomic<std::uint32_t> visitors{0};  // other workers that may still claim a range

    static std::uint64_t pack(std::uint64_t front, std::uint64_t back) noexcept { return front << 32 | back; }
    [[nodiscard]] bool any_unclaimed() const noexcept {
      for (std::uint32_t s = 0; s < slices; ++s) {
        const std::uint64_t word = unclaimed[s].word.load();
        if (word >> 32 < (word & 0xffffffffu)) return true;
      }
      return false;
    }
    /// Claims a range for `worker`: its own slice's front, else another's
    /// back, in slice order after its own. Returns the range's index, or
    /// no_range when every range is claimed.
    std::uint32_t claim(std::uint32_t worker) noexcept {
      const std::uint32_t home = worker % max_slices % slices;
      for (std::uint32_t k = 0; k < slices; ++k) {
        std::atomic<std::uint64_t>& slice = unclaimed[(home + k) % slices].word;
        std::uint64_t word = slice.load();
        for (;;) {
          const std::uint64_t front = word >> 32, back = word & 0xffffffffu;
          if (front >= back) break;
          const std::uint64_t taken = k == 0 ? pack(front + 1, back) : pack(front, back - 1);
          if (slice.compare_exchange_weak(word, taken)) return std::uint32_t(k == 0 ? front : back - 1);
        }
      }
      return no_range;
    }
    static constexpr std::uint32_t no_range = ~std::uint32_t(0);
  };

  static void* enqueue(task_function* task, std::uint32_t count, std::uint32_t min_range, void* context,
                       void* user) {
    thread_pool& pool = *static_cast<thread_pool*>(user);
    const std::uint32_t pieces = 16 * pool.workers_;
    const std::uint32_t range = std::max({min_range, count / pieces + (count % pieces != 0), std::uint32_t(1)});
    loop* handle;
    {
      const std::lock_guard lock(pool.mutex_);
      handle = &pool.loops_.emplace_back(task, context, count, range, pool.workers_);
      // Under the lock: a worker reads the counter under it before it waits,
      // so it either sees this post or is already waiting for the notify.
      pool.posted_.fetch_add(1);
    }
    pool.wake_.notify_all();
    return handle;
  }

  static void finish(void* handle, void* user) {
    thread_pool& pool = *static_cast<thread_pool*>(user);
    loop& l = *static_cast<loop*>(handle);
    pool.run_ranges(l, 0);
    // Every range is claimed; wait until the other workers have run theirs
    // and let go of the loop. A worker takes a visit under the lock, so the
    // check under the lock is final.
    for (;;) {
      pool.wait(pool.done_, [&] { return l.done.load() == l.count && l.visitors.load() == 0; });
      const std::lock_guard lock(pool.mutex_);
      if (l.visitors.load() != 0) continue;
      pool.loops_.remove_if([&](const loop& other) { return &other == &l; });
      return;
    }
  }

  /// Claims and runs ranges of l as `worker` until none is left to claim.
  void run_ranges(loop& l, std::uint32_t worker) {
    std::uint32_t ran = 0;
    for (std::uint32_t r = l.claim(worker); r != loop::no_range; r = l.claim(worker)) {
      const std::uint32_t begin = r * l.range, end = begin + std::min(l.range, l.count - begin);
      l.task(begin, end, worker, l.context);
      ran += end - begin;
    }
    if (ran != 0 && l.done.fetch_add(ran) + ran == l.count) notify(done_);
  }

  void work(std::uint32_t worker) {
    for (;;) {
      loop* visit = nullptr;
      std::uint64_t seen;
      {
        const std::lock_guard lock(mutex_);
        if (stopping_) return;
        seen = posted_.load();
        for (loop& l : loops_)
          if (l.any_unclaimed()) {
            l.visitors.fetch_add(1);
            visit = &l;
            break;
          }
      }
      if (visit) {
        run_ranges(*visit, worker);
        visit->visitors.fetch_sub(1);  // the last touch: finish() may free it now
        notify(done_);
        continue;
      }
      wait(wake_, [&] { return posted_.load() != seen; });
    }
  }

  /// Returns once ready() holds: spins for a while, then sleeps on `cv`,
  /// which notify(cv) wakes. ready() reads only atomics (sequentially
  /// consistent, as the sleepers_ count is), so a change made before
  /// notify either is seen before sleeping or finds the sleeper counted.
  template <class Ready>
  void wait(std::condition_variable& cv, const Ready& ready) {
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::microseconds(50);
    for (std::uint32_t i = 1; !ready(); ++i) {
      if (i % 64 == 0 && std::chrono::steady_clock::now() > give_up) {
        sleepers_.fetch_add(1);
        {
          std::unique_lock lock(mutex_);
          cv.wait(lock, [&] { return stopping_ || ready(); });
        }
        sleepers_.fetch_sub(1);
        return;
      }
      relax();
    }
  }

  void notify(std::condition_variable& cv) {
    if (sleepers_.load() == 0) return;
    { const std::lock_guard lock(mutex_); }  // a sleeper is either waiting or not yet checking
    cv.notify_all();
  }

  /// One turn of a spin: a pause for the core's sibling and the memory
  /// system, or, with more workers than hardware threads, the core itself.
  void relax() const noexcept {
    if (oversubscribed_) {
      std::this_thread::yield();
      return;
    }
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#elif defined(__aarch64__)
    asm volatile("yield");
#else
    std::this_thread::yield();
#endif
  }

  const std::uint32_t workers_;
  const bool oversubscribed_;
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::list<loop> loops_;                 // under mutex_; a list, so a handle stays valid
  std::atomic<std::uint64_t> posted_{0};  // loops posted (and the stop)
  std::atomic<std::uint32_t> sleepers_{0};
  bool stopping_ = false;  // under mutex_
};

}  // namespace impulse
