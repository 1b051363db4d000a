// world_fuzz — libFuzzer target for the world's interface: the fault
// suite's driver (tests/faults/api_driver.hpp) with its choices read from
// the fuzzer's bytes instead of a generator. Every promise the driver checks
// (refused calls change nothing, no body becomes non-finite, a step that
// holds a body names it) aborts here when broken, and the sanitizers catch
// the rest. Build with -DIMPULSE_BUILD_FUZZERS=ON and clang:
//
//   build/fuzz/tests/impulse_world_fuzz -max_total_time=600 -max_len=4096 corpus
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "../faults/api_driver.hpp"

namespace {

struct fuzz_config : impulse::default_config {};

/// The fuzzer's bytes, four at a time; zeros once they run out.
struct byte_stream {
  const std::uint8_t* data;
  std::size_t size, at = 0;
  std::uint32_t operator()() noexcept {
    std::uint32_t value = 0;
    const std::size_t n = size - at < 4 ? size - at : 4;
    std::memcpy(&value, data + at, n);
    at += n;
    return value;
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  impulse::test::api_driver<impulse::world<fuzz_config>> driver;
  byte_stream bytes{data, size};
  // About one call per 16 bytes (a call reads 2 to 20 numbers), at most 2 000.
  const std::uint64_t calls = size / 16 < 2000 ? size / 16 : 2000;
  driver.run(calls, bytes, [](std::uint64_t n, const char* call, const char* what) {
    std::fprintf(stderr, "world_fuzz: call %llu (%s): %s\n", static_cast<unsigned long long>(n), call, what);
    std::abort();
  });
  return 0;
}
