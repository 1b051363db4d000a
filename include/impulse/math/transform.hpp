// impulse/math/transform.hpp — rigid transform: a rotation followed by a translation.
//
// apply(t, p) = rotate(t.rotation, p) + t.position maps body space to world
// space. (a * b) applies b first, then a, matching quaternion composition.
#pragma once

#include "quat.hpp"
#include "vec3.hpp"

namespace impulse {

template <scalar_type T>
struct transform {
  using scalar = T;

  vec3<T> position{};
  quat<T> rotation{};

  static constexpr transform identity() noexcept { return {vec3<T>::zero(), quat<T>::identity()}; }

  friend constexpr bool operator==(const transform&, const transform&) = default;
};

/// Body-space point to world space.
template <scalar_type T>
constexpr vec3<T> apply(const transform<T>& t, const vec3<T>& p) noexcept {
  return rotate(t.rotation, p) + t.position;
}

/// Body-space direction to world space (no translation).
template <scalar_type T>
constexpr vec3<T> apply_direction(const transform<T>& t, const vec3<T>& d) noexcept {
  return rotate(t.rotation, d);
}

/// World-space point to body space: the inverse of apply.
template <scalar_type T>
constexpr vec3<T> inverse_apply(const transform<T>& t, const vec3<T>& p) noexcept {
  return inverse_rotate(t.rotation, p - t.position);
}

/// World-space direction to body space.
template <scalar_type T>
constexpr vec3<T> inverse_apply_direction(const transform<T>& t, const vec3<T>& d) noexcept {
  return inverse_rotate(t.rotation, d);
}

template <scalar_type T>
constexpr transform<T> inverse(const transform<T>& t) noexcept {
  const quat<T> r = conjugate(t.rotation);
  return {-rotate(r, t.position), r};
}

/// Composition: apply(a * b, p) == apply(a, apply(b, p)).
template <scalar_type T>
constexpr transform<T> operator*(const transform<T>& a, const transform<T>& b) noexcept {
  return {rotate(a.rotation, b.position) + a.position, a.rotation * b.rotation};
}

/// The relative transform that maps b's body space into a's: inverse(a) * b,
/// computed without forming the inverse.
template <scalar_type T>
constexpr transform<T> inverse_mul(const transform<T>& a, const transform<T>& b) noexcept {
  const quat<T> ra = conjugate(a.rotation);
  return {rotate(ra, b.position - a.position), ra * b.rotation};
}

}  // namespace impulse
