// tests/particles/particle_test.hpp — what the particle tests share: the
// configurations they run under (float and double, the native batch width
// and the scalar fallback), and a copy of a system's state to show that a
// refused call changed nothing.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include <doctest/doctest.h>

#include "impulse/particles.hpp"

namespace particle_test {

template <class T, int W, class I = impulse::integrators::symplectic_euler, bool Lifetime = true,
          bool Masses = true>
struct config : impulse::default_config {
  using scalar = T;
  using integrator = I;
  static constexpr int particle_width = W;
  static constexpr bool particle_lifetime = Lifetime;
  static constexpr bool particle_masses = Masses;
};

template <class T>
inline constexpr int native = impulse::native_width<T>;

// The configurations every particle test runs under: both scalars, each at
// the target's width and at the scalar fallback W = 1 (and float at the SSE
// width 4, which differs from native on AVX targets).
#define PARTICLE_CONFIGS                                                                        \
  particle_test::config<float, particle_test::native<float>>, particle_test::config<float, 1>, \
      particle_test::config<float, 4>, particle_test::config<double, particle_test::native<double>>, \
      particle_test::config<double, 1>

template <class T>
inline constexpr T epsilon = impulse::scalar_traits<T>::epsilon;

/// Everything a system exposes about its particles, to compare before and after.
template <class T>
struct snapshot {
  std::vector<T> values;
  template <class System>
  explicit snapshot(const System& s) {
    const auto p = s.positions(), v = s.velocities();
    for (std::size_t i = 0; i < s.size(); ++i)
      values.insert(values.end(), {p.x[i], p.y[i], p.z[i], v.x[i], v.y[i], v.z[i], s.mass(std::uint32_t(i))});
  }
  bool operator==(const snapshot&) const = default;
};

/// Largest distance any particle is behind any of the system's half-spaces
/// (0 when all are inside), in units of the rounding a projection leaves.
template <class System>
double worst_penetration_in_roundings(const System& s) {
  double worst = 0;
  const auto p = s.positions();
  for (const auto& plane : s.planes()) {
    if (plane.finite) continue;
    for (std::size_t i = 0; i < s.size(); ++i)
      worst = std::fmax(worst, double(-plane.distance(p[i]) / plane.rounding_at(p[i])));
  }
  return worst;
}

}  // namespace particle_test
