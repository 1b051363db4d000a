// impulse/shapes/box.hpp — a solid rectangular box centered at the body origin.
#pragma once

#include <cmath>

#include "../core/error.hpp"
#include "../core/policy.hpp"
#include "../math/aabb.hpp"
#include "../math/transform.hpp"
#include "mass_properties.hpp"

namespace impulse {

template <scalar_type T>
struct box {
  static constexpr policy_kind kind = policy_kind::shape;

  vec3<T> half_extents{T(0.5), T(0.5), T(0.5)};  ///< m, each > 0

  static box make(const vec3<T>& half_extents) {
    const box b{half_extents};
    b.validate();
    return b;
  }
  void validate() const {
    if (!is_finite(half_extents)) detail::report_error(error_code::non_finite, "box: half extents are not finite");
    if (!(min_component(half_extents) > T(0)))
      detail::report_error(error_code::degenerate_shape, "box: every half extent must be positive");
  }

  /// The corner farthest along `direction`; on a tie (a zero component) the
  /// positive side, so the result is always a vertex.
  vec3<T> support(const vec3<T>& d) const noexcept {
    return {d.x < T(0) ? -half_extents.x : half_extents.x, d.y < T(0) ? -half_extents.y : half_extents.y,
            d.z < T(0) ? -half_extents.z : half_extents.z};
  }
  aabb<T> local_aabb() const noexcept { return aabb<T>::from_center_half_extents({}, half_extents); }
  /// Exact: the rotated box's extent along each axis is |R|·h.
  aabb<T> world_aabb(const transform<T>& pose) const noexcept { return transform_aabb(local_aabb(), pose); }
};

/// Solid box of sides 2a, 2b, 2c: m = 8ρabc, I = m/3·diag(b² + c², c² + a², a² + b²).
template <scalar_type T>
mass_properties<T> mass_properties_of(const box<T>& b, T density) {
  b.validate();
  detail::require_density(density);
  const vec3<T> h = b.half_extents, h2 = mul(h, h);
  const T m = T(8) * density * h.x * h.y * h.z;
  return {m, {}, mat3<T>::diagonal(vec3<T>{h2.y + h2.z, h2.z + h2.x, h2.x + h2.y} * (m / T(3)))};
}

}  // namespace impulse
