// impulse/math/trigonometry.hpp — sin, cos, atan2, acos and cbrt that give the
// same bits on every machine.
//
// The C library's sin, cos and atan2 differ between glibc, musl, Apple's libm
// and Microsoft's CRT in the last bit, and a last bit is enough for two
// lockstep peers to drift apart (world.md, "Lockstep determinism"). These are
// built from +, −, ×, ÷, √, floor and fmod alone, which IEEE 754 rounds
// correctly everywhere, in double whatever the scalar, and rounded once to
// the scalar at the end. The simulation path (quaternion integration,
// rotation_between, joint angles, the character controller) calls only these.
//
// The method is the textbook one (Muller, "Elementary Functions", chapters 6
// and 11): sin and cos reduce the argument by the nearest multiple of π/2 with
// π/2 split in three (Cody and Waite), the first two parts 33 bits long so that
// k·part is exact for |k| < 2^20, then evaluate their Taylor series on
// [−π/4, π/4] through x^17 and x^18 (the next terms are below 1e-19 there;
// for float results, through x^11 and x^12).
// atan reduces |y/x| ≤ 1 to u = (t − c)/(1 + t·c) about the nearest c = k/8,
// |u| ≤ 1/16, and adds atan(c) from a table to the series through u^13 (the
// next term is 1e-18 of u). Each is within 2 ulp of the true value in double
// (tests/math/test_trigonometry.cpp checks against the C library's to 4 ulp).
// The constants are hexadecimal literals, exact as written.
//
// These are only portable when the compiler does not fuse their multiplies
// and adds: a world with cross_platform_determinism checks that it does not.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "../core/policy.hpp"

namespace impulse {

/// sin x and cos x from one reduction.
template <scalar_type T>
struct sine_cosine {
  T sin;
  T cos;
};

namespace detail {

/// Terms: through x^17 and x^18 for a double result, x^11 and x^12 for a
/// float one (the next terms are below 1e-19, and 7e-12 of float's 6e-8).
template <bool for_float = false>
sine_cosine<double> portable_sin_cos(double x) noexcept {
  if (!std::isfinite(x)) return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  if (x == 0.0) return {x, 1.0};  // keeps the sign of −0, as std::sin does
  // Past 2^19 rad the quotient k would outgrow the split's 20 spare bits:
  // fmod is exact, so the argument is first brought within one turn of the
  // rounded 2π. Angles this large have lost their fraction long before.
  constexpr double two_pi = 0x1.921fb54442d18p+2;
  if (std::abs(x) > 0x1p19) x = std::fmod(x, two_pi);
  constexpr double two_over_pi = 0x1.45f306dc9c883p-1;
  constexpr double half_pi_1 = 0x1.921fb544p+0, half_pi_2 = 0x1.0b4611a6p-34, half_pi_3 = 0x1.3198a2e037073p-69;
  const double k = std::floor(x * two_over_pi + 0.5);
  const double r = ((x - k * half_pi_1) - k * half_pi_2) - k * half_pi_3;
  const double r2 = r * r;
  // Horner's form, the coefficients 1/n! exact to their rounding.
  double s, c;
  if constexpr (for_float) {
    s = r + r * r2 * (-1.0 / 6.0 + r2 * (1.0 / 120.0 + r2 * (-1.0 / 5040.0 + r2 * (1.0 / 362880.0
        + r2 * (-1.0 / 39916800.0)))));
    c = 1.0 + r2 * (-0.5 + r2 * (1.0 / 24.0 + r2 * (-1.0 / 720.0 + r2 * (1.0 / 40320.0
        + r2 * (-1.0 / 3628800.0 + r2 * (1.0 / 479001600.0))))));
  } else {
    s = r + r * r2 * (-1.0 / 6.0 + r2 * (1.0 / 120.0 + r2 * (-1.0 / 5040.0 + r2 * (1.0 / 362880.0
        + r2 * (-1.0 / 39916800.0 + r2 * (1.0 / 6227020800.0 + r2 * (-1.0 / 1307674368000.0
        + r2 * (1.0 / 355687428096000.0))))))));
    c = 1.0 + r2 * (-0.5 + r2 * (1.0 / 24.0 + r2 * (-1.0 / 720.0 + r2 * (1.0 / 40320.0
        + r2 * (-1.0 / 3628800.0 + r2 * (1.0 / 479001600.0 + r2 * (-1.0 / 87178291200.0
        + r2 * (1.0 / 20922789888000.0 + r2 * (-1.0 / 6402373705728000.0)))))))));
  }
  switch (static_cast<std::int64_t>(k) & 3) {
    case 0: return {s, c};
    case 1: return {c, -s};
    case 2: return {-s, -c};
    default: return {-c, s};
  }
}

/// atan t for t in [0, 1].
inline double portable_atan_unit(double t) noexcept {
  // atan(k/8), k = 0 … 8, each the double nearest the true value.
  static constexpr double table[9] = {0.0,
                                      0x1.fd5ba9aac2f6ep-4,
                                      0x1.f5b75f92c80ddp-3,
                                      0x1.6f61941e4def1p-2,
                                      0x1.dac670561bb4fp-2,
                                      0x1.1e00babdefeb4p-1,
                                      0x1.4978fa3269ee1p-1,
                                      0x1.700a7c5784634p-1,
                                      0x1.921fb54442d18p-1};
  const int k = static_cast<int>(t * 8.0 + 0.5);
  const double c = double(k) / 8.0;
  const double u = (t - c) / (1.0 + t * c);
  const double u2 = u * u;
  const double series = u + u * u2 * (-1.0 / 3.0 + u2 * (1.0 / 5.0 + u2 * (-1.0 / 7.0 + u2 * (1.0 / 9.0
                        + u2 * (-1.0 / 11.0 + u2 * (1.0 / 13.0))))));
  return table[k] + series;
}

inline double portable_atan2(double y, double x) noexcept {
  constexpr double pi = 0x1.921fb54442d18p+1, half_pi = 0x1.921fb54442d18p+0, quarter_pi = 0x1.921fb54442d18p-1;
  if (std::isnan(x) || std::isnan(y)) return std::numeric_limits<double>::quiet_NaN();
  const double ax = std::abs(x), ay = std::abs(y);
  double a;
  if (std::isinf(ax) || std::isinf(ay)) {
    // The C standard's limits: toward the infinite one's axis, or the diagonal.
    if (std::isinf(ax) && std::isinf(ay)) a = quarter_pi;
    else a = std::isinf(ay) ? half_pi : 0.0;
  } else if (ay <= ax) {
    a = ax > 0.0 ? portable_atan_unit(ay / ax) : 0.0;  // atan2(±0, ±0): ±0 or ±π below
  } else {
    a = half_pi - portable_atan_unit(ax / ay);
  }
  if (std::signbit(x)) a = pi - a;
  return std::signbit(y) ? -a : a;
}

inline double portable_cbrt(double x) noexcept {
  if (!std::isfinite(x) || x == 0.0) return x;
  const double a = std::abs(x);
  // A start within a factor of 2 from the exponent, then Newton's steps on
  // y³ = a, which double the correct digits: eight reach double's 53 bits
  // from the worst start. Written y − (y − a/y²)/3, the correction is a
  // small difference of two close numbers, so its rounding stays small.
  int e = 0;
  (void)std::frexp(a, &e);
  double y = std::ldexp(1.0, e / 3);
  for (int i = 0; i < 8; ++i) y -= (y - a / (y * y)) / 3.0;
  return std::signbit(x) ? -y : y;
}

}  // namespace detail

/// sin x and cos x (x in radians), within 2 ulp in double and 1 in float
/// (computed in double, rounded once); NaN for an infinite or NaN x. The
/// same bits on every IEEE-754 machine, where std::sin and std::cos differ
/// by library.
template <scalar_type T>
sine_cosine<T> portable_sin_cos(T x) noexcept {
  const sine_cosine<double> r = detail::portable_sin_cos<std::is_same_v<T, float>>(double(x));
  return {T(r.sin), T(r.cos)};
}

template <scalar_type T>
T portable_sin(T x) noexcept {
  return portable_sin_cos(x).sin;
}

template <scalar_type T>
T portable_cos(T x) noexcept {
  return portable_sin_cos(x).cos;
}

/// The angle of (x, y) in [−π, π], as std::atan2, including its signed zeros
/// and infinities; portable as portable_sin_cos.
template <scalar_type T>
T portable_atan2(T y, T x) noexcept {
  return T(detail::portable_atan2(double(y), double(x)));
}

/// acos x in [0, π] for x in [−1, 1]; NaN outside. From atan2 of √(1 − x²)
/// computed as √((1 − x)(1 + x)), exact to rounding near ±1 where acos is
/// steep.
template <scalar_type T>
T portable_acos(T x) noexcept {
  const double d = double(x);
  if (!(std::abs(d) <= 1.0)) return std::numeric_limits<T>::quiet_NaN();
  return T(detail::portable_atan2(std::sqrt((1.0 - d) * (1.0 + d)), d));
}

/// The real cube root, by Newton's steps from the exponent; portable as
/// portable_sin_cos.
template <scalar_type T>
T portable_cbrt(T x) noexcept {
  return T(detail::portable_cbrt(double(x)));
}

}  // namespace impulse
