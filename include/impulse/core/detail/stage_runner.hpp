// impulse/core/detail/stage_runner.hpp — a sequence of parallel loops,
// hundreds a step, through one call of the task hook.
//
// The contact solver sweeps each color once per iteration: a few hundred
// loops a step, each a few microseconds long. Handed to the hook one at a
// time, each would pay an enqueue, a wake-up and a wait, about as long as
// the loop itself. So the solver enqueues helpers once, on the hook's
// other workers, and runs its program on the calling thread, the leader.
// A helper spins until the leader publishes a loop, claims blocks of it
// with a compare-and-swap and runs them; the leader claims blocks too,
// and goes on when every block of its loop is done (the stages of Box2D
// v3's solver work the same way).
//
// No one waits for a thread that may not be running: a helper waits only
// for the leader, and only a bounded time for it to start; the leader
// waits only for blocks already claimed, which are running. So the
// program completes whatever the scheduler does, also on one that runs
// the helpers inside enqueue or finish on the leader's own thread: they
// find nothing to do, and the leader does all the work.
//
// Which thread runs which block does not change what is computed: each
// block of a loop writes only its own items, as with parallel_for
// (core/task_system.hpp).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
// sched_yield where there is one: <thread> would add 12 000 lines to what
// every world program parses.
#if __has_include(<sched.h>)
#include <sched.h>
#else
#include <thread>
#endif

#include "../task_system.hpp"

namespace impulse::detail {

/// Gives this thread's core to another thread that is ready to run.
inline void yield_core() noexcept {
#if __has_include(<sched.h>)
  sched_yield();
#else
  std::this_thread::yield();
#endif
}

class stage_runner {
 public:
  stage_runner() = default;
  // Copies start idle: the state means something only during run().
  stage_runner(const stage_runner&) noexcept {}
  stage_runner& operator=(const stage_runner&) noexcept { return *this; }

  /// Runs program() on this thread while the hook's other workers help
  /// with its loops; without workers, its loops are plain calls.
  template <class Program>
  void run(const task_system& tasks, Program& program) {
    if (!tasks.parallel()) {
      program();
      return;
    }
    claim_.store(0);
    done_.store(0);
    started_.store(false);
    leader_ = thread_tag();
    workers_ = tasks.workers;
    task_function* helper = [](std::uint32_t, std::uint32_t, std::uint32_t, void* self) {
      static_cast<stage_runner*>(self)->help();
    };
    void* const handle = tasks.enqueue(helper, tasks.workers - 1, 1, this, tasks.user_context);
    // However the program ends, by returning or by an exception (an
    // allocation that failed), the helpers are let go and waited for.
    struct release {
      stage_runner& runner;
      const task_system& tasks;
      void* handle;
      ~release() {
        runner.shared_ = false;
        runner.claim_.store(finished);
        tasks.finish(handle, tasks.user_context);
      }
    } const done{*this, tasks, handle};
    started_.store(true);
    shared_ = true;
    program();
  }

  /// Whether loop() may hand blocks to other threads: inside run(), with workers.
  [[nodiscard]] bool shared() const noexcept { return shared_; }

  /// f(begin, end) over [0, count): when shared(), in one block per worker
  /// (of at least min_block items) that any thread may claim; else in one
  /// call. Returns when every block has run. Only the leader calls it,
  /// and f must not throw: other threads may be running its other blocks.
  /// (The program may throw between loops, run() lets the helpers go.)
  ///
  /// One block per worker: in the solver's sweeps (10 µs a color in
  /// `pile`), four per worker spent more on the claims, each a cache line
  /// passed between the cores, than they saved in balance.
  template <class F>
  void loop(std::uint32_t count, std::uint32_t min_block, F& f) {
    if (count == 0) return;
    const std::uint64_t pieces = std::min(workers_, max_blocks);
    const std::uint32_t block =
        shared_ ? std::max({min_block, std::uint32_t((count + pieces - 1) / pieces), 1u}) : count;
    const std::uint32_t blocks = std::uint32_t((std::uint64_t(count) + block - 1) / block);
    if (blocks == 1) {
      f(std::uint32_t(0), count);
      return;
    }
    task_.store(&call<F>, std::memory_order_relaxed);
    context_.store(&f, std::memory_order_relaxed);
    count_.store(count, std::memory_order_relaxed);
    block_.store(block, std::memory_order_relaxed);
    done_.store(0, std::memory_order_relaxed);
    // Published with block 0 claimed: the leader's, run before it looks
    // for more. done_ counts the blocks the others run.
    const std::uint64_t stage = (claim_.load(std::memory_order_relaxed) >> 32) + 1;
    claim_.store(stage << 32 | std::uint64_t(blocks) << 16 | 1u, std::memory_order_release);
    f(std::uint32_t(0), std::min(count, block));
    const std::uint32_t mine = 1 + run_blocks(claim_.load(std::memory_order_acquire), false);
    for (std::uint32_t spins = 0; done_.load(std::memory_order_acquire) != blocks - mine; ++spins) relax(spins);
  }

 private:
  using block_function = void(std::uint32_t begin, std::uint32_t end, void* context);
  template <class F>
  static void call(std::uint32_t begin, std::uint32_t end, void* context) {
    (*static_cast<F*>(context))(begin, end);
  }

  /// The claim word: the published loop's stage (a count of loops, the
  /// high 32 bits), its blocks (16 bits) and its next block to claim (the
  /// low 16).
  static constexpr std::uint64_t finished = ~std::uint64_t(0);  ///< the program is over
  static constexpr std::uint32_t max_blocks = 0xffffu;
  static std::uint32_t blocks_of(std::uint64_t c) noexcept { return std::uint32_t(c >> 16) & 0xffffu; }
  static std::uint32_t next_of(std::uint64_t c) noexcept { return std::uint32_t(c) & 0xffffu; }
  static bool open(std::uint64_t c) noexcept { return c != finished && next_of(c) < blocks_of(c); }

  /// Claims and runs blocks of the loop `c` names until none is left, and
  /// returns how many; a helper (`counted`) adds each to done_. A
  /// successful claim proves that loop is still the published one, and
  /// its description with it: the leader publishes the next only once
  /// every block of this one is done.
  std::uint32_t run_blocks(std::uint64_t c, bool counted = true) {
    std::uint32_t ran = 0;
    while (open(c)) {
      if (!claim_.compare_exchange_weak(c, c + 1, std::memory_order_acq_rel, std::memory_order_acquire)) continue;
      const std::uint32_t b = next_of(c), block = block_.load(std::memory_order_relaxed);
      const std::uint32_t count = count_.load(std::memory_order_relaxed);
      task_.load(std::memory_order_relaxed)(b * block, std::min(count, (b + 1) * block),
                                            context_.load(std::memory_order_relaxed));
      if (counted) done_.fetch_add(1, std::memory_order_release);
      ++ran;
      c = claim_.load(std::memory_order_acquire);
    }
    return ran;
  }

  /// A helper's life: whatever loop is published, claim from it, until
  /// the leader says the program is over. On the leader's own thread (a
  /// scheduler may run ranges inside enqueue or finish) it cannot help:
  /// the program has not started there, or is over. On another thread it
  /// waits a while for the leader to start, then gives up: a scheduler may
  /// also hold the leader in enqueue until the helpers return.
  void help() {
    if (thread_tag() == leader_) return;
    for (std::uint32_t spins = 0; !started_.load(std::memory_order_acquire); ++spins) {
      if (spins == patience) return;
      relax(spins);
    }
    std::uint32_t spins = 0;
    for (std::uint64_t c = claim_.load(std::memory_order_acquire); c != finished;
         c = claim_.load(std::memory_order_acquire)) {
      if (open(c)) {
        run_blocks(c);
        spins = 0;
      } else {
        relax(spins++);
      }
    }
  }

  /// Turns of relax() a helper waits for the leader to start.
  static constexpr std::uint32_t patience = 4096;

  /// An address that differs from thread to thread.
  static const void* thread_tag() noexcept {
    static thread_local const char tag = 0;
    return &tag;
  }

  /// One turn of a wait: a pause for the core's sibling, and past a few
  /// hundred turns the core itself, for a thread the machine has not
  /// given a core of its own (more workers than cores).
  static void relax(std::uint32_t spins) noexcept {
    if (spins > 256 && spins % 16 == 0) {
      yield_core();
      return;
    }
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#elif defined(__aarch64__)
    asm volatile("yield");
#endif
  }

  // The claim word and the loop it names share a cache line: a helper
  // reads both in one miss.
  alignas(64) std::atomic<std::uint64_t> claim_{0};  ///< the published loop's stage and next block
  std::atomic<block_function*> task_{nullptr};
  std::atomic<void*> context_{nullptr};
  std::atomic<std::uint32_t> count_{0}, block_{0};
  alignas(64) std::atomic<std::uint32_t> done_{0};  ///< the loop's blocks the helpers have run
  alignas(64) std::atomic<bool> started_{false};  ///< the leader is past enqueue
  const void* leader_ = nullptr;      ///< the leader's thread_tag()
  std::uint32_t workers_ = 1;
  bool shared_ = false;
};

}  // namespace impulse::detail
