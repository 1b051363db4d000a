// impulse/core/floating_point.hpp — what lockstep determinism asks of the
// compiler, and the checks that it got it.
//
// A config with `static constexpr bool cross_platform_determinism = true`
// promises the same bits from every build of a program: g++ or clang, -O2 or
// -O3, SSE2, AVX2 or AVX-512 (docs/world.md, "Lockstep determinism"). IEEE
// 754 rounds +, −, ×, ÷ and √ correctly on every such machine, so the same
// operations in the same order give the same bits. Three things break that,
// and this header checks for each:
//   - fusing a multiply and an add into one FMA instruction rounds once
//     where the code asked for two. GCC fuses across statements by default
//     wherever the target has FMA (-march=haswell and later), clang within
//     an expression; GCC 12's SLP vectoriser fuses a quaternion product's
//     terms (fmsubadd) even with contraction off. impulse's code must be
//     compiled with -ffp-contract=off, and with g++ -fno-tree-slp-vectorize
//     (the CMake target impulse::deterministic and Meson's
//     impulse-deterministic dependency add them), or, with the single
//     header, with IMPULSE_CROSS_PLATFORM_DETERMINISM defined before
//     including it, which turns both off for the header's own code alone. A
//     world or particle system checks this when it is made
//     (contraction_in_effect, quat_product_fused).
//   - -ffast-math lets the compiler reorder sums and drop NaN checks; it is
//     refused at compile time.
//   - x87 arithmetic (32-bit x86 without SSE2) keeps 80-bit intermediates:
//     refused at compile time (FLT_EVAL_METHOD must be 0).
// The C library's transcendental functions differ by library; the
// simulation path uses impulse's own (math/trigonometry.hpp) in every build.
#pragma once

#include <cfloat>

#include "policy.hpp"

namespace impulse::detail {

/// Config::cross_platform_determinism, false when absent.
template <class C>
consteval bool cross_platform_determinism() {
  if constexpr (has_cross_platform_determinism<C>) {
    return C::cross_platform_determinism;
  } else {
    return false;
  }
}

/// Whether the compiler fused the multiply and the add below into one FMA:
/// a·b + c with a = b = 1 + 2^-30 and c = −(1 + 2^-29) is 2^-60 exactly,
/// which one rounding keeps and two lose (a·b rounds to 1 + 2^-29). The
/// operands are volatile so that the compiler cannot fold the sum; inline,
/// so that it is compiled with the flags of the code that calls it.
inline bool contraction_in_effect() noexcept {
  volatile double a = 1.0 + 0x1p-30, b = 1.0 + 0x1p-30, c = -(1.0 + 0x1p-29);
  const double x = a, y = b, z = c;
  return x * y + z != 0.0;
}

/// What a world or particle system with cross_platform_determinism states
/// at compile time about the build it is in.
template <class C>
consteval bool check_determinism_build() {
  if constexpr (cross_platform_determinism<C>()) {
#if defined(__FAST_MATH__)
    static_assert(!cross_platform_determinism<C>(),
                  "impulse config: cross_platform_determinism cannot hold under -ffast-math, which lets the "
                  "compiler reorder floating-point sums");
#endif
#if defined(FLT_EVAL_METHOD)
    static_assert(FLT_EVAL_METHOD == 0,
                  "impulse config: cross_platform_determinism needs each operation rounded to its type "
                  "(FLT_EVAL_METHOD 0: SSE2 on x86, not the x87 unit)");
#endif
  }
  return true;
}

/// The message of the error a world with cross_platform_determinism gives
/// when its code was compiled with contraction on.
inline constexpr const char* contraction_message =
    "cross_platform_determinism: this program's impulse code fuses multiplies and adds (FMA "
    "contraction), which rounds differently from a build that does not; compile it with "
    "-ffp-contract=off, and with g++ -fno-tree-slp-vectorize too (CMake: link impulse::deterministic), "
    "or define IMPULSE_CROSS_PLATFORM_DETERMINISM before including the single header";

}  // namespace impulse::detail
