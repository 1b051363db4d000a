// impulse/dynamics/material.hpp — what a body's surface and bulk are made of,
// and how two materials combine at a contact.
//
// Combine rules (docs/standard_scenes.md): friction is the geometric mean
// sqrt(a·b), so that ice (0) on anything is ice and equal
// materials keep their value; restitution is the larger of the two, so that
// a rubber ball bounces on concrete as it does on rubber. Box2D v3 uses the
// same two rules; Bullet multiplies both, and ODE takes whatever the contact
// callback sets.
#pragma once

#include <algorithm>
#include <cmath>

#include "../core/error.hpp"
#include "../core/policy.hpp"

namespace impulse {

template <scalar_type T>
struct material {
  T density = T(1);      ///< kg/m³, > 0; used for a dynamic body given no mass of its own
  T friction = T(0.6);   ///< Coulomb coefficient, dimensionless, >= 0
  T restitution = T(0);  ///< ratio of separating to approaching normal speed, in [0, 1]

  void validate() const {
    if (!std::isfinite(density) || !std::isfinite(friction) || !std::isfinite(restitution))
      detail::report_error(error_code::non_finite, "material: density, friction and restitution must be finite");
    if (!(density > T(0))) detail::report_error(error_code::non_positive_mass, "material: density must be positive");
    if (friction < T(0)) detail::report_error(error_code::invalid_parameter, "material: friction must be >= 0");
    if (restitution < T(0) || restitution > T(1))
      detail::report_error(error_code::invalid_parameter, "material: restitution must lie in [0, 1]");
  }
};

/// Friction of a contact between materials of friction a and b: sqrt(a·b).
template <scalar_type T>
[[nodiscard]] T combine_friction(T a, T b) noexcept {
  return std::sqrt(a * b);
}

/// Restitution of a contact between materials of restitution a and b: max(a, b).
template <scalar_type T>
[[nodiscard]] T combine_restitution(T a, T b) noexcept {
  return std::max(a, b);
}

}  // namespace impulse
