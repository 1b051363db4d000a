// impulse/shapes/sphere.hpp — a solid ball centered at the body origin.
#pragma once

#include <cmath>

#include "../core/error.hpp"
#include "../core/policy.hpp"
#include "../math/aabb.hpp"
#include "../math/transform.hpp"
#include "mass_properties.hpp"

namespace impulse {

template <scalar_type T>
struct sphere {
  static constexpr policy_kind kind = policy_kind::shape;

  T radius = T(0.5);  ///< m, > 0

  /// A sphere of the given radius; a zero, negative or non-finite radius is refused.
  static sphere make(T radius) {
    const sphere s{radius};
    s.validate();
    return s;
  }
  void validate() const {
    if (!std::isfinite(radius)) detail::report_error(error_code::non_finite, "sphere: radius is not finite");
    if (!(radius > T(0))) detail::report_error(error_code::degenerate_shape, "sphere: radius must be positive");
  }

  /// The point of the sphere farthest along `direction` (any point of the
  /// surface for a zero direction).
  vec3<T> support(const vec3<T>& direction) const noexcept {
    return normalize_or(direction, vec3<T>::unit_x()) * radius;
  }
  aabb<T> local_aabb() const noexcept { return aabb<T>::from_center_half_extents({}, vec3<T>::splat(radius)); }
  aabb<T> world_aabb(const transform<T>& pose) const noexcept {
    return aabb<T>::from_center_half_extents(pose.position, vec3<T>::splat(radius));
  }
};

/// Solid ball: m = ρ·4/3·πr³, I = 2/5·m·r² about every axis.
template <scalar_type T>
mass_properties<T> mass_properties_of(const sphere<T>& s, T density) {
  s.validate();
  detail::require_density(density);
  const T pi = T(3.14159265358979323846);
  const T m = density * T(4) / T(3) * pi * s.radius * s.radius * s.radius;
  return {m, {}, mat3<T>::diagonal(vec3<T>::splat(T(0.4) * m * s.radius * s.radius))};
}

}  // namespace impulse
