// impulse/core/detail/stopwatch.hpp — the time between laps, for the
// world's step profile (world_events.hpp, step_profile).
//
// The monotonic clock through <ctime>, where the system has one; else
// timespec_get's calendar time. <chrono> would add 13 500 lines to what
// every world program parses.
#pragma once

#include <ctime>

namespace impulse::detail {

class stopwatch {
 public:
  stopwatch() noexcept { read(last_); }

  /// Milliseconds since construction or the last lap.
  double lap_ms() noexcept {
    std::timespec now{};
    read(now);
    const double ms = double(now.tv_sec - last_.tv_sec) * 1e3 + double(now.tv_nsec - last_.tv_nsec) * 1e-6;
    last_ = now;
    return ms;
  }

 private:
  static void read(std::timespec& t) noexcept {
#if defined(CLOCK_MONOTONIC)
    clock_gettime(CLOCK_MONOTONIC, &t);
#else
    std::timespec_get(&t, TIME_UTC);
#endif
  }
  std::timespec last_{};
};

}  // namespace impulse::detail
