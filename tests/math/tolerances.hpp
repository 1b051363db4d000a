// tests/math/tolerances.hpp — what the math tests share: the rounding unit,
// the distances the tolerances are measured in, a deterministic source of
// inputs, and how doctest prints a vector, matrix or quaternion on failure.
//
// Each tolerance is named where it is used, as a multiple of epsilon<T> with
// the reason for the multiple; only the tolerances used by more than one file
// live here.
#pragma once

#include <cmath>
#include <cstdint>

#include <doctest/doctest.h>

#include <impulse/math/mat3.hpp>
#include <impulse/math/quat.hpp>
#include <impulse/math/scalar_traits.hpp>
#include <impulse/math/vec3.hpp>

namespace impulse::test {

/// The spacing of T at 1: every tolerance below is a multiple of it.
template <class T>
inline constexpr T epsilon = scalar_traits<T>::epsilon;

/// | |v| - 1 | of a freshly normalised vector or quaternion: a sum of squares
/// (four roundings), a square root, a reciprocal and a multiply.
template <class T>
inline constexpr T normalized_length = 4 * epsilon<T>;

/// A rotation of an O(1) vector by a unit quaternion or rotation matrix: two
/// cross products and three sums, each entry a handful of roundings of O(1).
template <class T>
inline constexpr T rotation_rounding = 8 * epsilon<T>;

template <class T>
T max_abs_diff(const vec3<T>& a, const vec3<T>& b) {
  return max_component(abs(a - b));
}

template <class T>
T max_abs_diff(const mat3<T>& a, const mat3<T>& b) {
  return std::fmax(max_abs_diff(a.col[0], b.col[0]),
                   std::fmax(max_abs_diff(a.col[1], b.col[1]), max_abs_diff(a.col[2], b.col[2])));
}

template <class T>
T max_abs_diff(const quat<T>& a, const quat<T>& b) {
  return std::fmax(max_abs_diff(a.vector_part(), b.vector_part()), std::abs(a.w - b.w));
}

/// A 64-bit linear congruential generator (Knuth's MMIX constants): the same
/// inputs on every platform and every run, without <random>.
struct lcg {
  std::uint64_t state = 0x9E3779B97F4A7C15u;

  /// Uniform in [0, 1), from the top 53 bits.
  double uniform() {
    state = state * 6364136223846793005u + 1442695040888963407u;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  }

  template <class T>
  T in(double lo, double hi) {
    return static_cast<T>(lo + (hi - lo) * uniform());
  }

  template <class T>
  vec3<T> vector(double lo, double hi) {
    return {in<T>(lo, hi), in<T>(lo, hi), in<T>(lo, hi)};
  }

  /// A direction: a point of the unit ball away from the center, normalised.
  template <class T>
  vec3<T> unit_vector() {
    for (;;) {
      const vec3<double> v{in<double>(-1, 1), in<double>(-1, 1), in<double>(-1, 1)};
      const double l2 = length_squared(v);
      if (l2 > 0.01 && l2 <= 1) {
        const vec3<double> n = v / std::sqrt(l2);
        return {static_cast<T>(n.x), static_cast<T>(n.y), static_cast<T>(n.z)};
      }
    }
  }

  /// An orientation: a rotation by up to π about a random axis.
  template <class T>
  quat<T> rotation() {
    return quat<T>::from_axis_angle(unit_vector<T>(), in<T>(-3.14159, 3.14159));
  }
};

}  // namespace impulse::test

namespace doctest {

template <class T>
struct StringMaker<impulse::vec3<T>> {
  static String convert(const impulse::vec3<T>& v) {
    return String("(") + toString(v.x) + ", " + toString(v.y) + ", " + toString(v.z) + ")";
  }
};

template <class T>
struct StringMaker<impulse::quat<T>> {
  static String convert(const impulse::quat<T>& q) {
    return String("(") + toString(q.x) + ", " + toString(q.y) + ", " + toString(q.z) + "; " +
           toString(q.w) + ")";
  }
};

template <class T>
struct StringMaker<impulse::mat3<T>> {
  static String convert(const impulse::mat3<T>& m) {
    return String("rows [") + StringMaker<impulse::vec3<T>>::convert(m.row(0)) + " " +
           StringMaker<impulse::vec3<T>>::convert(m.row(1)) + " " +
           StringMaker<impulse::vec3<T>>::convert(m.row(2)) + "]";
  }
};

}  // namespace doctest
