// Closed-form test problems for the integrators: each integrates to t_end
// with step h and returns the distance to the exact solution there.
#pragma once

#include <cmath>

#include "impulse/math/vec3.hpp"

namespace impulse_test {

using impulse::vec3;

/// x'' = -ω² x, x(0) = 1, v(0) = 0: x(t) = cos ωt. A scalar state.
template <class I, class T>
T oscillator_error(T h, T t_end) {
  const T omega = 2;
  T x = 1, v = 0;
  const long steps = std::lround(t_end / h);
  for (long i = 0; i < steps; ++i)
    I::step(x, v, h, [&](const T& position, const T&) { return -omega * omega * position; });
  return std::abs(x - std::cos(omega * t_end));
}

/// v' = g - k v (projectile with linear drag), a vec3 state:
/// v(t) = v∞ + (v0 - v∞) e^{-kt}, x(t) = x0 + v∞ t + (v0 - v∞)(1 - e^{-kt})/k, v∞ = g/k.
template <class I, class T>
T projectile_with_drag_error(T h, T t_end) {
  const vec3<T> g{0, T(-9.81), 0}, x0{0, 1, 0}, v0{3, 5, -2};
  const T k = T(0.7);
  vec3<T> x = x0, v = v0;
  const long steps = std::lround(t_end / h);
  for (long i = 0; i < steps; ++i)
    I::step(x, v, h, [&](const vec3<T>&, const vec3<T>& velocity) { return g - velocity * k; });
  const vec3<T> v_inf = g / k;
  const vec3<T> exact = x0 + v_inf * t_end + (v0 - v_inf) * ((T(1) - std::exp(-k * t_end)) / k);
  return impulse::length(x - exact);
}

/// Circular orbit of radius r about an attractor of strength μ at the origin:
/// a = -μ x / |x|³, speed √(μ/r), angular rate √(μ/r³).
template <class I, class T>
T circular_orbit_error(T h, T t_end) {
  const T mu = 4, r = 2;
  vec3<T> x{r, 0, 0}, v{0, std::sqrt(mu / r), 0};
  const long steps = std::lround(t_end / h);
  for (long i = 0; i < steps; ++i)
    I::step(x, v, h, [&](const vec3<T>& position, const vec3<T>&) {
      const T d = impulse::length(position);
      return position * (-mu / (d * d * d));
    });
  const T angle = std::sqrt(mu / (r * r * r)) * t_end;
  return impulse::length(x - vec3<T>{r * std::cos(angle), r * std::sin(angle), 0});
}

}  // namespace impulse_test
