// impulse/particles/drag.hpp — viscous (linear) drag, F = −k·v.
//
// Linear drag is the low-Reynolds-number law (Stokes): right for snow, dust
// and smoke at the speeds a particle effect has, and it keeps the
// projectile-with-drag problem in closed form for the tests. A heavier
// particle slows less, since the force is divided by its mass.
#pragma once

#include "force.hpp"

namespace impulse::particles {

template <class T>
struct drag {
  static constexpr force_effect effect = force_effect::force;

  /// k in N·s/m (kg/s), ≥ 0. With mass 1 kg a velocity decays as e^(−k·t).
  T coefficient = T(0.1);

  void validate() const {
    detail::require_finite(coefficient, "drag: coefficient is not finite");
    detail::require(coefficient >= T(0), error_code::invalid_parameter,
                    "drag: coefficient is negative (it would feed energy in)");
  }

  template <int W>
  vec3_batch<T, W> evaluate(const vec3_batch<T, W>&, const vec3_batch<T, W>& v,
                            const particle_lanes<T, W>&) const noexcept {
    return v * -coefficient;
  }
};

}  // namespace impulse::particles
