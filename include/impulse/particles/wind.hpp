// impulse/particles/wind.hpp — wind as drag toward a moving air velocity.
//
// F = k·(w_i − v): a particle is dragged toward the local air velocity w_i,
// so a flake at rest is pushed along and a flake moving with the air feels
// nothing (Stokes drag in the air's frame). Each particle sees its own steady
// gust, w_i = w·(1 + σ·r_i), with r_i ∈ [−1, 1) fixed per particle (hashed
// from its serial number when it was added): the same particle always feels
// the same wind, on every run and every batch width, and neighbouring flakes
// drift apart instead of moving as a sheet.
#pragma once

#include "force.hpp"

namespace impulse::particles {

template <class T>
struct wind {
  static constexpr force_effect effect = force_effect::force;
  static constexpr bool uses_variation = true;

  /// Air velocity w, m/s.
  vec3<T> velocity{T(1), T(0), T(0)};
  /// k in N·s/m (kg/s), ≥ 0: how strongly a particle is carried along.
  T coefficient = T(0.5);
  /// σ, dimensionless in [0, 1]: the spread of the per-particle gust; 0 gives
  /// every particle the same wind.
  T variation = T(0.3);

  void validate() const {
    detail::require_finite(velocity, "wind: velocity is not finite");
    detail::require_finite(coefficient, "wind: coefficient is not finite");
    detail::require_finite(variation, "wind: variation is not finite");
    detail::require(coefficient >= T(0), error_code::invalid_parameter, "wind: coefficient is negative");
    detail::require(variation >= T(0) && variation <= T(1), error_code::invalid_parameter,
                    "wind: variation is outside [0, 1]");
  }

  template <int W>
  vec3_batch<T, W> evaluate(const vec3_batch<T, W>&, const vec3_batch<T, W>& v,
                            const particle_lanes<T, W>& p) const noexcept {
    const batch<T, W> gust = (p.variation * variation + T(1)) * coefficient;
    return vec3_batch<T, W>::broadcast(velocity) * gust - v * coefficient;
  }
};

}  // namespace impulse::particles
