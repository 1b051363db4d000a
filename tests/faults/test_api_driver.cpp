// The fault suite's randomized driver (api_driver.hpp): 10⁵ calls of the
// whole world interface, with sensible and hostile arguments, on a running
// world; after each, a refused call must have left the world as it was,
// and no body may have become non-finite. Its libFuzzer entry is
// tests/fuzz/world_fuzz.cpp.
#include <doctest/doctest.h>

#include <cstdint>
#include <string>

#include "api_driver.hpp"

namespace faults_api_driver_tests {

namespace {

/// The soft step in double, sleeping off (tests/world/scenes.hpp).
using soft_step_double_config = impulse::test::soft_double_config;

/// Runs `calls` calls from `seed` and checks the driver found nothing.
template <class Config>
typename impulse::test::api_driver<impulse::world<Config>>::counts drive(std::uint32_t seed, std::uint64_t calls) {
  impulse::test::api_driver<impulse::world<Config>> driver;
  impulse::test::splitmix random{seed};
  int failures = 0;
  driver.run(calls, random,
             [&](std::uint64_t n, const char* call, const char* what) {
               if (++failures <= 5) FAIL_CHECK("call " << n << " (" << call << "): " << what);
             });
  CHECK(failures == 0);
  return driver.tally();
}

}  // namespace

TEST_CASE("10^5 random calls with hostile arguments: refused calls change nothing, nothing becomes non-finite") {
  const auto counts = drive<impulse::default_config>(20261126u, 100000);
  // The driver reached what it is there to reach: refusals, steps, and
  // steps that held a body.
  CHECK(counts.calls == 100000);
  CHECK(counts.refused > 10000);
  CHECK(counts.steps > 5000);
  MESSAGE("refused " << counts.refused << ", steps " << counts.steps << ", steps holding a body "
                     << counts.held_steps);
}

TEST_CASE("2.5·10^4 random calls on soft_step in double, sleeping off: the same promises") {
  const auto counts = drive<soft_step_double_config>(7u, 25000);
  CHECK(counts.refused > 2500);
  CHECK(counts.steps > 1250);
}

}  // namespace faults_api_driver_tests
