// The step's results, bit for bit, pinned for the builds that record them:
// `pile` and `large_pyramid` (docs/standard_scenes.md) after 600 steps,
// hashed (scenes.hpp, transform_hash) and compared with the hashes below.
// Rearranging the world's code (a stage moved to its own file, a record
// to another container) must not change a bit of what it computes; a
// change that means to must say so and record the new hashes here.
//
// The file is compiled with floating-point contraction and automatic
// vectorisation off (tests/CMakeLists.txt says why), so that the hash
// depends only on the arithmetic the code asks for: g++ and clang then
// agree. It still depends on the contact batches' width, which follows
// the instruction set, so each hash belongs to one width (build_key). A
// build with no hash recorded checks that two runs of each scene hash
// alike. Only optimised builds run the scenes: 600 steps of large_pyramid
// take about 5 s at -O3 and would take minutes at -O0 under the
// sanitizers, where 60 steps of pile run twice and must hash alike.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

#include "../world/scenes.hpp"

using namespace impulse;

namespace {

std::uint64_t pile_hash(int steps) {
  world<> w;
  impulse::test::add_ground(w);
  impulse::test::add_pile(w);
  impulse::test::run(w, steps);
  return impulse::test::transform_hash(w);
}

}  // namespace

#ifdef NDEBUG
namespace {

/// What changes the arithmetic the code asks for: the widest instruction
/// set, which sets the contact batches' width (contact_batch.hpp).
std::string build_key() {
#if defined(__AVX512F__)
  return "avx512f";
#elif defined(__AVX2__)
  return "avx2";
#else
  return "sse2";
#endif
}

struct recorded {
  std::string_view build;
  std::uint64_t pile, large_pyramid;
};

/// Recorded on 2026-11-27 (AMD EPYC, Debian 12): g++ 12.2 and clang 14,
/// -O3 -march=native, agree.
constexpr recorded hashes[] = {
    {"avx512f", 0x650e63302a177d4dull, 0x965b57ce39d0a348ull},
};


/// `large_pyramid`: a 100-box base (5050 boxes of 100 kg), ground
/// half-extents (400, 1, 400), sleeping off.
std::uint64_t large_pyramid_hash() {
  world<impulse::test::awake_config> w;
  impulse::test::add_ground(w, 0.6f, {}, 400.0f);
  for (int k = 0; k < 100; ++k) {
    const int n = 100 - k;
    for (int i = 0; i < n; ++i) impulse::test::add_cube(w, {float(i) - float(n - 1) / 2, 0.5f + float(k), 0}, 100.0f);
  }
  impulse::test::run(w, 600);
  return impulse::test::transform_hash(w);
}

}  // namespace

TEST_CASE("600 steps of pile and of large_pyramid hash as recorded for this build") {
  const std::string key = build_key();
  const std::uint64_t pile = pile_hash(600), pyramid = large_pyramid_hash();
  char line[160];
  std::snprintf(line, sizeof line, "{\"%s\", 0x%016llxull, 0x%016llxull}", key.c_str(),
                static_cast<unsigned long long>(pile), static_cast<unsigned long long>(pyramid));
  INFO("this build's entry: ", std::string(line));
  for (const recorded& r : hashes)
    if (r.build == key) {
      CHECK(pile == r.pile);
      CHECK(pyramid == r.large_pyramid);
      return;
    }
  MESSAGE("no hashes recorded for ", key, ": checking that a second run hashes alike");
  CHECK(pile_hash(600) == pile);
  CHECK(large_pyramid_hash() == pyramid);
}
#else
TEST_CASE("60 steps of pile, the first landings, hash alike twice in a debug build") {
  // The recorded hashes are the optimised builds'; here, determinism alone.
  CHECK(pile_hash(60) == pile_hash(60));
}
#endif
