// tests/dynamics/motion_test.hpp — configs and bodies shared by the rigid
// motion tests.
#pragma once

#include <cmath>
#include <limits>

#include "impulse/config.hpp"
#include "impulse/dynamics.hpp"
#include "impulse/integrators.hpp"

namespace impulse::test {

template <class T, class I>
struct motion_config : default_config {
  using scalar = T;
  using integrator = I;
};

template <class T, class I>
using body_system = rigid_body_system<motion_config<T, I>>;

template <class T>
constexpr double epsilon_of = double(std::numeric_limits<T>::epsilon());

/// Mass 1 with principal moments (i1, i2, i3) along the body axes.
template <class T>
mass_properties<T> principal(T i1, T i2, T i3) {
  mass_properties<T> p{T(1), {}, mat3<T>::zero()};
  p.inertia(0, 0) = i1, p.inertia(1, 1) = i2, p.inertia(2, 2) = i3;
  return p;
}

/// Angular velocity in body axes: Rᵀ·ω.
template <class T>
vec3<T> body_angular_velocity(const rigid_body<T>& b) {
  return inverse_rotate(b.orientation, b.angular_velocity());
}

}  // namespace impulse::test
