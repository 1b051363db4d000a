// Task schedulers for the tests of what runs across workers
// (core/task_system.hpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "impulse/core/task_system.hpp"

namespace impulse::test {

/// A scheduler on one thread that runs a loop's ranges back to front, in
/// ranges of odd sizes, as workers 0, 1 and 2 in turn: what a real one may
/// do, made repeatable.
struct backwards_scheduler {
  static void* enqueue(impulse::task_function* task, std::uint32_t count, std::uint32_t min_range,
                       void* context, void*) {
    std::vector<std::uint32_t> cuts{count};
    for (std::uint32_t end = count, k = 0; end > 0; ++k) {
      const std::uint32_t size = std::min(end, min_range + (k * 37) % 101);
      end -= size;
      cuts.push_back(end);
    }
    for (std::size_t c = 0; c + 1 < cuts.size(); ++c) task(cuts[c + 1], cuts[c], std::uint32_t(c % 3), context);
    return nullptr;
  }
  static void finish(void*, void*) {}
  static impulse::task_system tasks() { return {3, &enqueue, &finish, nullptr}; }
};

}  // namespace impulse::test
