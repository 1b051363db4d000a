// impulse/math/vec3.hpp — three-component vector of float or double.
//
// A plain aggregate: `vec3<float>{1, 2, 3}`. Arithmetic is constexpr; the
// functions that need a square root (length, normalize) are not, because
// std::sqrt is not constexpr in C++20.
#pragma once

#include <cmath>
#include <limits>

#include "../core/detail/assert.hpp"
#include "scalar_traits.hpp"

namespace impulse {

template <scalar_type T>
struct vec3 {
  using scalar = T;

  T x{};
  T y{};
  T z{};

  static constexpr vec3 zero() noexcept { return {T(0), T(0), T(0)}; }
  static constexpr vec3 unit_x() noexcept { return {T(1), T(0), T(0)}; }
  static constexpr vec3 unit_y() noexcept { return {T(0), T(1), T(0)}; }
  static constexpr vec3 unit_z() noexcept { return {T(0), T(0), T(1)}; }
  static constexpr vec3 splat(T s) noexcept { return {s, s, s}; }

  constexpr T& operator[](int i) noexcept {
    IMPULSE_ASSERT(i >= 0 && i < 3);
    return i == 0 ? x : (i == 1 ? y : z);
  }
  constexpr const T& operator[](int i) const noexcept {
    IMPULSE_ASSERT(i >= 0 && i < 3);
    return i == 0 ? x : (i == 1 ? y : z);
  }

  constexpr vec3& operator+=(const vec3& b) noexcept { x += b.x; y += b.y; z += b.z; return *this; }
  constexpr vec3& operator-=(const vec3& b) noexcept { x -= b.x; y -= b.y; z -= b.z; return *this; }
  constexpr vec3& operator*=(T s) noexcept { x *= s; y *= s; z *= s; return *this; }
  constexpr vec3& operator/=(T s) noexcept { x /= s; y /= s; z /= s; return *this; }

  friend constexpr bool operator==(const vec3&, const vec3&) = default;
};

template <scalar_type T> constexpr vec3<T> operator-(const vec3<T>& a) noexcept { return {-a.x, -a.y, -a.z}; }
template <scalar_type T> constexpr vec3<T> operator+(const vec3<T>& a, const vec3<T>& b) noexcept { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
template <scalar_type T> constexpr vec3<T> operator-(const vec3<T>& a, const vec3<T>& b) noexcept { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <scalar_type T> constexpr vec3<T> operator*(const vec3<T>& a, T s) noexcept { return {a.x * s, a.y * s, a.z * s}; }
template <scalar_type T> constexpr vec3<T> operator*(T s, const vec3<T>& a) noexcept { return {a.x * s, a.y * s, a.z * s}; }
template <scalar_type T> constexpr vec3<T> operator/(const vec3<T>& a, T s) noexcept { return {a.x / s, a.y / s, a.z / s}; }

/// Componentwise (Hadamard) product and quotient.
template <scalar_type T> constexpr vec3<T> mul(const vec3<T>& a, const vec3<T>& b) noexcept { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
template <scalar_type T> constexpr vec3<T> div(const vec3<T>& a, const vec3<T>& b) noexcept { return {a.x / b.x, a.y / b.y, a.z / b.z}; }

template <scalar_type T>
constexpr T dot(const vec3<T>& a, const vec3<T>& b) noexcept {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

template <scalar_type T>
constexpr vec3<T> cross(const vec3<T>& a, const vec3<T>& b) noexcept {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

template <scalar_type T> constexpr T length_squared(const vec3<T>& a) noexcept { return dot(a, a); }
template <scalar_type T> T length(const vec3<T>& a) noexcept { return std::sqrt(dot(a, a)); }
template <scalar_type T> T distance(const vec3<T>& a, const vec3<T>& b) noexcept { return length(a - b); }

/// Unit vector along a. Precondition: a is not (nearly) zero; use
/// normalize_or when it may be. NaN in gives NaN out, as for quaternions
/// (quat.hpp, normalize): the world finds it.
template <scalar_type T>
vec3<T> normalize(const vec3<T>& a) noexcept {
  const T l2 = length_squared(a);
  IMPULSE_ASSERT(!(l2 <= scalar_traits<T>::zero_length_squared));
  return a * (T(1) / std::sqrt(l2));
}

/// True when | |a| - 1 | is within scalar_traits<T>::unit_tolerance.
template <scalar_type T>
bool is_normalized(const vec3<T>& a) noexcept {
  return std::abs(length_squared(a) - T(1)) <= T(2) * scalar_traits<T>::unit_tolerance;
}

template <scalar_type T>
bool is_finite(const vec3<T>& a) noexcept {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

template <scalar_type T>
constexpr vec3<T> min(const vec3<T>& a, const vec3<T>& b) noexcept {
  return {a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z};
}
template <scalar_type T>
constexpr vec3<T> max(const vec3<T>& a, const vec3<T>& b) noexcept {
  return {a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z};
}
template <scalar_type T>
constexpr vec3<T> abs(const vec3<T>& a) noexcept {
  return {a.x < T(0) ? -a.x : a.x, a.y < T(0) ? -a.y : a.y, a.z < T(0) ? -a.z : a.z};
}
template <scalar_type T> constexpr T min_component(const vec3<T>& a) noexcept { return a.x < a.y ? (a.x < a.z ? a.x : a.z) : (a.y < a.z ? a.y : a.z); }
template <scalar_type T> constexpr T max_component(const vec3<T>& a) noexcept { return a.x > a.y ? (a.x > a.z ? a.x : a.z) : (a.y > a.z ? a.y : a.z); }

/// Unit vector along a, or `fallback` when a has no direction: too short,
/// or with a NaN or infinite component. A finite vector so long that its
/// squared length overflows (beyond 1.8e19 in float) is scaled down first.
template <scalar_type T>
vec3<T> normalize_or(const vec3<T>& a, const vec3<T>& fallback) noexcept {
  if (!is_finite(a)) return fallback;
  const T l2 = length_squared(a);
  if (!(l2 <= std::numeric_limits<T>::max())) return normalize_or(a / max_component(abs(a)), fallback);
  if (!(l2 > scalar_traits<T>::zero_length_squared)) return fallback;
  return a * (T(1) / std::sqrt(l2));
}

/// a + (b - a)·t; t = 0 gives a, t = 1 gives b exactly.
template <scalar_type T>
constexpr vec3<T> lerp(const vec3<T>& a, const vec3<T>& b, T t) noexcept {
  return a * (T(1) - t) + b * t;
}

/// A unit vector perpendicular to the unit vector n (for building bases).
/// Crossing with the axis of the smaller of |n.x| and |n.z| keeps the
/// product's length sqrt(1 - min(n.x², n.z²)) at least 1/√2, so the
/// normalisation never divides by a small number.
template <scalar_type T>
vec3<T> any_perpendicular(const vec3<T>& n) noexcept {
  const vec3<T> other = std::abs(n.x) < std::abs(n.z) ? vec3<T>::unit_x() : vec3<T>::unit_z();
  return normalize(cross(n, other));
}

}  // namespace impulse
