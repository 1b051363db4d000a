// impulse/particles/point_forces.hpp — attractors and repellers with softened
// inverse-square fall-off.
//
// Each point pulls a particle at x with F = s·d / (|d|² + ε)^(3/2), d = p − x:
// inverse-square at distances well beyond √ε, and bounded (|F| ≤ 0.385·s/ε) at
// the point itself, where the bare law is infinite and a particle passing
// through would be flung out at whatever speed the step happened to sample.
// s > 0 attracts, s < 0 repels. Points can be moved, re-signed and switched
// off between steps; the kernel loops over the active ones only.
#pragma once

#include <array>
#include <cstddef>

#include "force.hpp"

namespace impulse::particles {

template <class T>
struct point_force {
  vec3<T> position{};
  /// s in N·m²: the force at distance r ≫ √ε is s/r². Negative repels.
  T strength = T(1);
  bool enabled = true;
};

template <class T>
struct point_forces {
  static constexpr force_effect effect = force_effect::force;
  /// Points held inline, so the kernel's loop bound is small and known.
  static constexpr std::size_t max_points = 8;

  std::array<point_force<T>, max_points> points{};
  /// How many of `points` exist (enabled or not).
  std::size_t count = 0;
  /// ε in m²: the softening length squared. Must be > 0.
  T softening = T(0.05);

  /// Adds a point and returns its index; a ninth point is refused.
  std::size_t add(const vec3<T>& position, T strength) {
    detail::require(count < max_points, error_code::capacity_exceeded,
                    "point_forces: all 8 points are in use");
    detail::require_finite(position, "point_forces: position is not finite");
    detail::require_finite(strength, "point_forces: strength is not finite");
    points[count] = {position, strength, true};
    return count++;
  }

  void validate() const {
    detail::require(count <= max_points, error_code::capacity_exceeded, "point_forces: count exceeds 8");
    detail::require_finite(softening, "point_forces: softening is not finite");
    detail::require(softening > T(0), error_code::invalid_parameter,
                    "point_forces: softening must be positive (the force is infinite at the point without it)");
    for (std::size_t i = 0; i < count; ++i) {
      detail::require_finite(points[i].position, "point_forces: a position is not finite", std::uint32_t(i));
      detail::require_finite(points[i].strength, "point_forces: a strength is not finite", std::uint32_t(i));
    }
  }

  template <int W>
  vec3_batch<T, W> evaluate(const vec3_batch<T, W>& x, const vec3_batch<T, W>&,
                            const particle_lanes<T, W>&) const noexcept {
    vec3_batch<T, W> f = vec3_batch<T, W>::broadcast({});
    for (std::size_t i = 0; i < count; ++i) {
      if (!points[i].enabled) continue;
      const vec3_batch<T, W> d = vec3_batch<T, W>::broadcast(points[i].position) - x;
      const batch<T, W> r2 = length_squared(d) + softening;
      if constexpr (impulse::detail::has_rsqrt_estimate<T, W>()) {
        // (|d|² + ε)^(-3/2) as the cube of rsqrt: no square root and no
        // division, which bound this kernel's speed (core/batch.hpp, rsqrt).
        const batch<T, W> inverse_r = rsqrt(r2);
        f = f + d * (inverse_r * inverse_r * inverse_r * points[i].strength);
      } else {
        // Without an estimate, one square root and one division, as few as
        // the law allows: 1/√ cubed took a division and three products.
        f = f + d * (points[i].strength / (r2 * sqrt(r2)));
      }
    }
    return f;
  }
};

}  // namespace impulse::particles
