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

  /// How float lanes compute (|d|² + ε)^(-3/2). `estimate`: from the
  /// hardware's estimate of 1/√ (rsqrt14ps, rsqrtps) and a polynomial
  /// correction, with no square root and no division. `exact`: one square
  /// root and one division, each correctly rounded. The force is within
  /// 5e-7 of the law by the estimate and 4e-7 by the exact form, which
  /// carries the float roundings of d and |d|² + ε as well
  /// (tests/particles/test_forces.cpp). Double lanes and single
  /// particles (W = 1) always take the exact form: x86 has no double estimate
  /// below AVX-512. `automatic`, the default, takes the estimate where it
  /// has 14 bits (AVX-512's rsqrt14ps: a linear correction) and the exact
  /// form where it has 11 (AVX's and SSE's rsqrtps, whose quadratic
  /// correction made the kernel no faster than a square root and a
  /// division: docs/particles_benchmark.md).
  enum class root_method { automatic, estimate, exact };
  root_method root = root_method::automatic;

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
    constexpr int bits = impulse::detail::rsqrt_estimate_bits<T, W>();
    if constexpr (bits > 0)
      if (root == root_method::estimate || (bits >= 14 && root == root_method::automatic))
        return sum<W, root_method::estimate>(x);
    return sum<W, root_method::exact>(x);
  }

  /// The exact form whatever `root` says: the same bits at every width and
  /// on every machine. A particle system with cross_platform_determinism
  /// calls this instead of evaluate.
  template <int W>
  vec3_batch<T, W> evaluate_portable(const vec3_batch<T, W>& x, const vec3_batch<T, W>&,
                                     const particle_lanes<T, W>&) const noexcept {
    return sum<W, root_method::exact>(x);
  }

  /// r2^(-3/2) for r2 > 0 (positive, finite, normal), by `method` where W
  /// lanes of T have an estimate, exactly otherwise. The estimate y of
  /// 1/√r2 gives e = r2·y² = 1 + δ, and r2^(-3/2) = y³·(1 + δ)^(-3/2) =
  /// y³·(1 − 1.5δ + 1.875δ² − …). rsqrt14ps has |δ| ≤ 2^-13, so the linear
  /// term leaves 1.875δ² ≤ 3e-8, below float's rounding; rsqrtps has
  /// |δ| ≤ 2^-10.4 and takes the quadratic term too (2.2|δ|³ ≤ 1e-9). This is
  /// one multiply fewer than a Newton step for 1/√r2 followed by a cube.
  template <int W>
  static batch<T, W> inverse_root_cubed(batch<T, W> r2, root_method method) noexcept {
    constexpr int bits = impulse::detail::rsqrt_estimate_bits<T, W>();
    if constexpr (bits > 0) {
      if (method == root_method::estimate) {
        batch<T, W> y = r2;
        impulse::detail::lane_rsqrt_estimate<T, W>(y.v);
        const batch<T, W> yy = y * y;
        const batch<T, W> e = r2 * yy;
        if constexpr (bits >= 14) return (yy * y) * (T(2.5) - e * T(1.5));  // 1 − 1.5δ
        // δ = e − 1 is exact (e is within 2^-10 of 1), and the small terms
        // are added to 1 last: in powers of e, 4.375 − 5.25e + 1.875e²,
        // they cancelled to 5e-7.
        const batch<T, W> delta = e - T(1);
        return (yy * y) * ((delta * T(1.875) - T(1.5)) * delta + T(1));
      }
    }
    return T(1) / (r2 * sqrt(r2));
  }

 private:
  /// The force of every enabled point, the root taken by `method`.
  template <int W, root_method method>
  vec3_batch<T, W> sum(const vec3_batch<T, W>& x) const noexcept {
    vec3_batch<T, W> f = vec3_batch<T, W>::broadcast({});
    for (std::size_t i = 0; i < count; ++i) {
      if (!points[i].enabled) continue;
      const vec3_batch<T, W> d = vec3_batch<T, W>::broadcast(points[i].position) - x;
      // |d|² + ε as a chain of fused multiply-adds, ε innermost.
      const batch<T, W> r2 = d.x * d.x + (d.y * d.y + (d.z * d.z + softening));
      if constexpr (method == root_method::estimate) {
        f = f + d * (inverse_root_cubed(r2, method) * points[i].strength);
      } else {
        // One square root and one division, as few as the law allows.
        f = f + d * (points[i].strength / (r2 * sqrt(r2)));
      }
    }
    return f;
  }
};

}  // namespace impulse::particles
