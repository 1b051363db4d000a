// The stage runner (core/detail/stage_runner.hpp), which runs the contact
// solver's few hundred loops a step through one call of the task hook:
// every item of every loop runs exactly once, each loop sees everything
// the loops before it wrote, and the program completes on any scheduler,
// including those that run the helpers on the leader's own thread,
// after the program, or hold the leader until the helpers return; and a
// program that throws lets its helpers go.
#include <cstdint>
#include <thread>
#include <vector>

#include <doctest/doctest.h>

#include "schedulers.hpp"
#include "impulse/core/detail/stage_runner.hpp"
#include "impulse/thread_pool.hpp"

namespace core_stage_runner_tests {

namespace {

/// A program of loops in which each item reads its neighbours as the loop
/// before left them: wrong if a loop started before the last one ended, or
/// if an item ran twice or not at all.
struct chain_program {
  impulse::detail::stage_runner& runner;
  std::vector<std::uint64_t> a, b;
  std::vector<int> runs;  ///< per item, in the loop under way
  int missed = 0;         ///< items that ran other than once
  int loops = 0;
  bool shared_seen = false;

  chain_program(impulse::detail::stage_runner& r, std::size_t n) : runner(r), a(n), b(n), runs(n) {
    for (std::size_t i = 0; i < n; ++i) a[i] = i * 2654435761u % 1000003u;
  }

  void operator()() {
    shared_seen = runner.shared();
    const std::uint32_t n = std::uint32_t(a.size());
    for (int loop = 0; loop < 300; ++loop) {
      // Some loops are short (one block, or none), some long.
      const std::uint32_t count = loop % 7 == 3 ? 0 : loop % 5 == 1 ? 3 : n;
      std::vector<std::uint64_t>& from = loop % 2 == 0 ? a : b;
      std::vector<std::uint64_t>& to = loop % 2 == 0 ? b : a;
      auto body = [&](std::uint32_t begin, std::uint32_t end) {
        for (std::uint32_t i = begin; i < end; ++i) {
          to[i] = (from[i] * 31 + from[(i + 1) % n] + from[(i + n - 1) % n] + std::uint64_t(loop)) % 1000000007u;
          ++runs[i];
        }
      };
      runner.loop(count, 4, body);
      for (std::uint32_t i = 0; i < n; ++i) {
        if (i < count) missed += runs[i] != 1;
        else to[i] = from[i];  // the items a short loop leaves
        runs[i] = 0;
      }
      ++loops;
    }
  }
};

std::vector<std::uint64_t> serial_result(std::size_t n) {
  impulse::detail::stage_runner runner;
  chain_program p{runner, n};
  runner.run(impulse::task_system{}, p);
  return p.a;
}

/// Runs every range inside finish, after the program: the helpers find it over.
struct deferred_scheduler {
  struct pending {
    impulse::task_function* task;
    std::uint32_t count;
    void* context;
  };
  static inline std::vector<pending> queue;
  static void* enqueue(impulse::task_function* task, std::uint32_t count, std::uint32_t, void* context, void*) {
    queue.push_back({task, count, context});
    return nullptr;
  }
  static void finish(void*, void*) {
    for (const pending& p : queue)
      for (std::uint32_t i = 0; i < p.count; ++i) p.task(i, i + 1, i % 2, p.context);
    queue.clear();
  }
  static impulse::task_system tasks() { return {2, &enqueue, &finish, nullptr}; }
};

/// Runs the ranges on threads of its own and returns from enqueue only once
/// they have: the helpers wait for a leader that has not started, and must
/// give up.
struct holding_scheduler {
  static void* enqueue(impulse::task_function* task, std::uint32_t count, std::uint32_t, void* context, void*) {
    std::vector<std::thread> threads;
    for (std::uint32_t i = 0; i < count; ++i) threads.emplace_back([=] { task(i, i + 1, i + 1, context); });
    for (std::thread& t : threads) t.join();
    return nullptr;
  }
  static void finish(void*, void*) {}
  static impulse::task_system tasks() { return {3, &enqueue, &finish, nullptr}; }
};

void check_program(const impulse::task_system& tasks, bool expect_shared) {
  constexpr std::size_t n = 1000;
  impulse::detail::stage_runner runner;
  chain_program p{runner, n};
  runner.run(tasks, p);
  CHECK(p.loops == 300);
  CHECK(p.missed == 0);
  CHECK(p.shared_seen == expect_shared);
  CHECK_FALSE(runner.shared());
  CHECK(p.a == serial_result(n));
}

}  // namespace

TEST_CASE("a stage runner's loops each run every item once, after the loop before, on a pool of 2, 3 or 8") {
  for (std::uint32_t workers : {2u, 3u, 8u}) {
    CAPTURE(workers);
    impulse::thread_pool pool{workers};
    check_program(pool.tasks(), true);
  }
}

TEST_CASE("a stage runner completes on schedulers that run the helpers on the leader's thread, after it, or hold it") {
  SUBCASE("no hook: plain calls") { check_program(impulse::task_system{}, false); }
  SUBCASE("ranges run inside enqueue, back to front") {
    check_program(impulse::test::backwards_scheduler::tasks(), true);
  }
  SUBCASE("ranges run inside finish, after the program") { check_program(deferred_scheduler::tasks(), true); }
  SUBCASE("enqueue returns only once the helpers have") { check_program(holding_scheduler::tasks(), true); }
}

TEST_CASE("a stage runner runs one program after another with the same pool") {
  impulse::thread_pool pool{2};
  impulse::detail::stage_runner runner;
  const std::vector<std::uint64_t> expected = serial_result(257);
  for (int run = 0; run < 50; ++run) {
    chain_program p{runner, 257};
    runner.run(pool.tasks(), p);
    CHECK(p.missed == 0);
    CHECK(p.a == expected);
  }
}

TEST_CASE("a program that throws lets its helpers go, and the runner and the pool run the next one") {
  impulse::thread_pool pool{2};
  impulse::detail::stage_runner runner;
  struct failure {};
  std::vector<int> seen(1000);
  auto failing = [&] {
    auto body = [&](std::uint32_t begin, std::uint32_t end) {
      for (std::uint32_t i = begin; i < end; ++i) ++seen[i];
    };
    runner.loop(1000, 4, body);
    throw failure{};
  };
  CHECK_THROWS_AS(runner.run(pool.tasks(), failing), failure);
  CHECK_FALSE(runner.shared());
  int once = 0;
  for (const int n : seen) once += n == 1;
  CHECK(once == 1000);  // the loop before the throw ran whole
  chain_program p{runner, 257};
  runner.run(pool.tasks(), p);
  CHECK(p.missed == 0);
  CHECK(p.a == serial_result(257));
}

}  // namespace core_stage_runner_tests
