// Poses for the narrow-phase tests: a pose from a position (and a
// rotation), and a random rotation.
#pragma once

#include "impulse/core/random.hpp"
#include "impulse/math/transform.hpp"

namespace test {

template <class T>
impulse::transform<T> at(const impulse::vec3<T>& p, const impulse::quat<T>& q = impulse::quat<T>::identity()) {
  return {p, q};
}

/// A rotation about a random axis by a random angle in (−3.14, 3.14).
template <class T>
impulse::quat<T> random_rotation(impulse::lcg32& random) {
  const impulse::vec3<T> axis = normalize(
      impulse::vec3<T>{random.uniform<T>(-1, 1), random.uniform<T>(-1, 1), random.uniform<T>(T(-1), T(1))} +
      impulse::vec3<T>{T(1e-3), 0, 0});
  return impulse::quat<T>::from_axis_angle(axis, random.uniform<T>(T(-3.14), T(3.14)));
}

}  // namespace test
