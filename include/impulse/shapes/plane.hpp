// impulse/shapes/plane.hpp — a static half-space, the ground of most scenes.
//
// Solid where n·x + offset < 0; the surface is n·x + offset = 0 and the free
// side is where n points (the convention of particles::plane_collider). It
// is unbounded, so it has no mass properties and belongs only to static
// bodies: mass_properties_of(plane) does not exist, and asking for it is a
// compile error.
#pragma once

#include <cmath>
#include <limits>

#include "../core/error.hpp"
#include "../core/policy.hpp"
#include "../math/aabb.hpp"
#include "../math/scalar_traits.hpp"
#include "../math/transform.hpp"

namespace impulse {

template <scalar_type T>
struct plane {
  static constexpr policy_kind kind = policy_kind::shape;

  vec3<T> normal{T(0), T(1), T(0)};  ///< unit, pointing out of the solid
  T offset = T(0);                   ///< m: the surface is n·x + offset = 0

  static plane make(const vec3<T>& normal, T offset) {
    const plane p{normal, offset};
    p.validate();
    return p;
  }
  void validate() const {
    if (!is_finite(normal) || !std::isfinite(offset))
      detail::report_error(error_code::non_finite, "plane: normal or offset is not finite");
    if (!(length_squared(normal) > scalar_traits<T>::zero_length_squared))
      detail::report_error(error_code::degenerate_shape, "plane: normal has zero length");
    if (!(std::abs(length(normal) - T(1)) <= scalar_traits<T>::unit_tolerance))
      detail::report_error(error_code::not_normalized, "plane: normal is not a unit vector");
  }

  T distance(const vec3<T>& x) const noexcept { return dot(normal, x) + offset; }

  /// Unbounded in every direction a broad phase cares about.
  aabb<T> local_aabb() const noexcept {
    const T big = std::numeric_limits<T>::max();
    return {vec3<T>::splat(-big), vec3<T>::splat(big)};
  }
  aabb<T> world_aabb(const transform<T>&) const noexcept { return local_aabb(); }
};

}  // namespace impulse
