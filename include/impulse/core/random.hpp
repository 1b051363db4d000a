// impulse/core/random.hpp — the small deterministic generators the library uses.
//
// Emitters and per-particle variations must give the same particles on every
// machine and every run, so they use these fixed generators instead of
// <random>, whose distributions are implementation-defined (and whose header
// costs compile time). lcg32 is the generator docs/standard_scenes.md
// prescribes for the standard scenes, so a peer engine can reproduce them
// draw for draw.
#pragma once

#include <cstdint>

namespace impulse {

/// x <- 1664525·x + 1013904223 (mod 2^32) (Numerical Recipes' LCG).
struct lcg32 {
  std::uint32_t state = 12345;

  constexpr std::uint32_t next() noexcept {
    state = state * 1664525u + 1013904223u;
    return state;
  }
  /// Uniform in [0, 1) from the top 24 bits, exact in float and double.
  template <class T>
  constexpr T uniform() noexcept {
    return T(next() >> 8) / T(16777216);
  }
  /// Uniform in [lo, hi).
  template <class T>
  constexpr T uniform(T lo, T hi) noexcept {
    return lo + (hi - lo) * uniform<T>();
  }
};

/// A 32-bit integer hash with full avalanche (the "lowbias32" finalizer of
/// Chris Wellons' hash-prospector): consecutive inputs give unrelated outputs,
/// so a particle's serial number can seed its own fixed random offsets.
constexpr std::uint32_t hash32(std::uint32_t x) noexcept {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

/// hash32 mapped to [-1, 1), from the top 24 bits.
template <class T>
constexpr T hash_signed_unit(std::uint32_t x) noexcept {
  return T(hash32(x) >> 8) / T(8388608) - T(1);
}

}  // namespace impulse
