// impulse/particles/gravity.hpp — uniform gravity, an acceleration.
#pragma once

#include "force.hpp"

namespace impulse::particles {

template <class T>
struct gravity {
  static constexpr force_effect effect = force_effect::acceleration;

  /// m/s², the same for every particle whatever its mass.
  vec3<T> acceleration{T(0), T(-9.81), T(0)};

  void validate() const { detail::require_finite(acceleration, "gravity: acceleration is not finite"); }

  template <int W>
  vec3_batch<T, W> evaluate(const vec3_batch<T, W>&, const vec3_batch<T, W>&,
                            const particle_lanes<T, W>&) const noexcept {
    return vec3_batch<T, W>::broadcast(acceleration);
  }
};

}  // namespace impulse::particles
