// impulse/math/scalar_traits.hpp — tolerances per scalar type, in one place.
//
// Every tolerance the math layer uses lives here, with its unit and the reason
// for its value, so that float and double builds differ in exactly these
// numbers and nowhere else. Later layers (contacts, sleeping) add their own
// struct of the same shape next to their code.
#pragma once

#include <limits>

#include "../core/policy.hpp"

namespace impulse {

template <scalar_type T>
struct scalar_traits;

template <>
struct scalar_traits<float> {
  /// Machine epsilon (dimensionless): the spacing of floats at 1.
  static constexpr float epsilon = std::numeric_limits<float>::epsilon();

  /// Squared length (m², or the square of whatever unit the vector has) below
  /// which a vector is treated as zero and refuses to be normalised. Chosen
  /// far above the smallest normal float (1.2e-38) so that 1/sqrt of it is
  /// finite, and far below any length a physics scene uses (1e-12 m).
  static constexpr float zero_length_squared = 1e-24f;

  /// Largest allowed | |v| - 1 | for a vector or quaternion that must be unit
  /// (a plane normal, an orientation). Loose enough for a value written in
  /// source with seven digits; tight enough that the rotation it describes is
  /// off by less than 1e-5 rad.
  static constexpr float unit_tolerance = 1e-5f;

  /// Below this argument the exponential map uses the series
  /// sin(h)/h = 1 − h²/6 + h⁴/120 − h⁶/5040 and cos h to h⁸/8!, in h² alone,
  /// instead of a square root, sin and cos: the first term left out,
  /// h⁸/9!, is then under epsilon, and the series stays finite as
  /// |ω| -> 0 where the quotient is 0/0. Solves h⁸/362880 = epsilon:
  /// (362880 · 1.19e-7)^(1/8) = 0.675.
  static constexpr float series_threshold = 0.67f;

  /// Relative tolerance for a determinant or pivot to count as singular.
  static constexpr float singular_tolerance = 1e-6f;
};

template <>
struct scalar_traits<double> {
  static constexpr double epsilon = std::numeric_limits<double>::epsilon();
  /// As for float; 1e-60 keeps 1/sqrt finite with room to spare (min 2.2e-308).
  static constexpr double zero_length_squared = 1e-60;
  /// 1e-10: a unit vector given with ten digits passes, rotations are off by < 1e-10 rad.
  static constexpr double unit_tolerance = 1e-10;
  /// (362880 · 2.22e-16)^(1/8) = 0.0548.
  static constexpr double series_threshold = 0.054;
  static constexpr double singular_tolerance = 1e-12;
};

}  // namespace impulse
