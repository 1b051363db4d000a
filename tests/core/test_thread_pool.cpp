// impulse::thread_pool, the task hook's own implementation: every item of a
// loop runs exactly once, on a worker index below the pool's count, loops
// can be outstanding together, waits that spin and waits that sleep both
// end, a pool of one runs on the calling thread, and each worker starts on
// its own slice of a loop.
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include <doctest/doctest.h>

#include "impulse/thread_pool.hpp"

namespace core_thread_pool_tests {

namespace {

struct counts {
  std::vector<std::atomic<int>> runs;
  std::vector<std::atomic<int>> worker_used;
  std::atomic<int> bad_worker{0};
  std::uint32_t workers;
  counts(std::size_t items, std::uint32_t w) : runs(items), worker_used(w), workers(w) {}
};

void count_range(std::uint32_t begin, std::uint32_t end, std::uint32_t worker, void* context) {
  counts& c = *static_cast<counts*>(context);
  if (worker >= c.workers) {
    ++c.bad_worker;
    return;
  }
  ++c.worker_used[worker];
  for (std::uint32_t i = begin; i < end; ++i) ++c.runs[i];
}

TEST_CASE("a pool runs every item of a loop exactly once, for any item count and range") {
  for (std::uint32_t workers : {1u, 2u, 3u, 8u}) {
    impulse::thread_pool pool{workers};
    const impulse::task_system tasks = pool.tasks();
    CHECK(tasks.workers == workers);
    for (std::uint32_t items : {1u, 7u, 64u, 1000u, 100003u})
      for (std::uint32_t min_range : {1u, 5u, 4096u}) {
        CAPTURE(workers);
        CAPTURE(items);
        CAPTURE(min_range);
        counts c{items, workers};
        void* handle = tasks.enqueue(&count_range, items, min_range, &c, tasks.user_context);
        tasks.finish(handle, tasks.user_context);
        int wrong = 0;
        for (auto& r : c.runs) wrong += r.load() != 1;
        CHECK(wrong == 0);
        CHECK(c.bad_worker.load() == 0);
      }
  }
}

TEST_CASE("two loops outstanding together both run to completion") {
  impulse::thread_pool pool{3};
  const impulse::task_system tasks = pool.tasks();
  counts a{5000, 3}, b{7000, 3};
  void* ha = tasks.enqueue(&count_range, 5000, 10, &a, tasks.user_context);
  void* hb = tasks.enqueue(&count_range, 7000, 10, &b, tasks.user_context);
  tasks.finish(hb, tasks.user_context);
  tasks.finish(ha, tasks.user_context);
  int wrong = 0;
  for (auto& r : a.runs) wrong += r.load() != 1;
  for (auto& r : b.runs) wrong += r.load() != 1;
  CHECK(wrong == 0);
}

TEST_CASE("loops back to back run every item once, whether the waits spin or sleep") {
  // Most loops follow the last within microseconds, so the workers and the
  // caller find each other while spinning. Every 16th loop starts after a
  // pause longer than the spin (the workers fall asleep), and in every 8th a
  // range outlasts the spin (the caller falls asleep waiting for it).
  for (std::uint32_t workers : {2u, 3u, 8u}) {
    CAPTURE(workers);
    impulse::thread_pool pool{workers};
    const impulse::task_system tasks = pool.tasks();
    std::vector<std::atomic<int>> runs(200);
    int wrong = 0;
    for (int k = 0; k < 400; ++k) {
      if (k % 16 == 15) std::this_thread::sleep_for(std::chrono::microseconds(300));
      const std::uint32_t items = 1 + std::uint32_t(k * 37 % 200);
      for (std::uint32_t i = 0; i < items; ++i) runs[i] = 0;
      auto body = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
        if (k % 8 == 7 && begin == 0) std::this_thread::sleep_for(std::chrono::microseconds(200));
        for (std::uint32_t i = begin; i < end; ++i) ++runs[i];
      };
      impulse::detail::parallel_for(tasks, items, 1, body);
      for (std::uint32_t i = 0; i < items; ++i) wrong += runs[i].load() != 1;
    }
    CHECK(wrong == 0);
  }
}

TEST_CASE("a pool of one worker starts no thread and runs loops on the caller") {
  impulse::thread_pool pool{1};
  const impulse::task_system tasks = pool.tasks();
  CHECK_FALSE(tasks.parallel());
  const std::thread::id caller = std::this_thread::get_id();
  bool elsewhere = false;
  auto body = [&](std::uint32_t, std::uint32_t, std::uint32_t) { elsewhere |= std::this_thread::get_id() != caller; };
  impulse::detail::parallel_for(tasks, 1000, 1, body);
  CHECK_FALSE(elsewhere);
}

TEST_CASE("with two workers, both take ranges of a long loop") {
  impulse::thread_pool pool{2};
  const impulse::task_system tasks = pool.tasks();
  // Each range sleeps, so the caller cannot finish the loop alone before
  // the other worker wakes.
  std::atomic<int> seen[2] = {0, 0};
  auto body = [&](std::uint32_t, std::uint32_t, std::uint32_t worker) {
    ++seen[worker];
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  };
  impulse::detail::parallel_for(tasks, 64, 1, body);
  CHECK(seen[0].load() + seen[1].load() == 32);  // 16 ranges per worker
  CHECK(seen[1].load() > 0);
}

TEST_CASE("with two workers, each starts on its own half of a loop and takes the other's from its far end") {
  // Loops over the same items back to back then give each worker the items
  // it had in the loop before. 32 ranges of 2 items: the caller's half is
  // 0-15, the other worker's 16-31. Whatever the timing, a worker's first range is the
  // front of its own half, and a range taken from the other half is taken
  // from its back.
  impulse::thread_pool pool{2};
  const impulse::task_system tasks = pool.tasks();
  std::vector<std::uint32_t> order[2];
  auto body = [&](std::uint32_t begin, std::uint32_t, std::uint32_t worker) {
    order[worker].push_back(begin / 2);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  };
  impulse::detail::parallel_for(tasks, 64, 1, body);
  REQUIRE(order[0].size() + order[1].size() == 32);
  if (!order[0].empty()) CHECK(order[0].front() == 0);
  if (!order[1].empty()) CHECK(order[1].front() == 16);
  for (std::uint32_t w = 0; w < 2; ++w) {
    CAPTURE(w);
    // Its own half in rising order, then the other's in falling order.
    std::size_t k = 0;
    while (k + 1 < order[w].size() && order[w][k + 1] == order[w][k] + 1 && order[w][k + 1] / 16 == w) ++k;
    for (++k; k < order[w].size(); ++k) {
      CHECK(order[w][k] / 16 != w);
      if (k + 1 < order[w].size()) CHECK(order[w][k + 1] + 1 == order[w][k]);
    }
  }
}

}  // namespace

}  // namespace core_thread_pool_tests
