// impulse/shapes/capsule.hpp — a cylinder with hemispherical caps, along y.
//
// The set of points within `radius` of the segment from (0, −h, 0) to
// (0, h, 0): a swept sphere, the cheapest shape that rolls on its side and
// stands on its end.
#pragma once

#include <cmath>

#include "../core/error.hpp"
#include "../core/policy.hpp"
#include "../math/aabb.hpp"
#include "../math/transform.hpp"
#include "mass_properties.hpp"

namespace impulse {

template <scalar_type T>
struct capsule {
  static constexpr policy_kind kind = policy_kind::shape;

  T radius = T(0.25);       ///< m, > 0
  T half_height = T(0.5);   ///< h, m, ≥ 0: half the length of the core segment

  static capsule make(T radius, T half_height) {
    const capsule c{radius, half_height};
    c.validate();
    return c;
  }
  void validate() const {
    if (!std::isfinite(radius) || !std::isfinite(half_height))
      detail::report_error(error_code::non_finite, "capsule: radius or half height is not finite");
    if (!(radius > T(0)) || !(half_height >= T(0)))
      detail::report_error(error_code::degenerate_shape,
                           "capsule: radius must be positive and half height non-negative");
  }

  vec3<T> support(const vec3<T>& d) const noexcept {
    const vec3<T> end{T(0), d.y < T(0) ? -half_height : half_height, T(0)};
    return end + normalize_or(d, vec3<T>::unit_y()) * radius;
  }
  aabb<T> local_aabb() const noexcept {
    return aabb<T>::from_center_half_extents({}, {radius, half_height + radius, radius});
  }
  /// Exact: the box around the two transformed cap centers, grown by the radius.
  aabb<T> world_aabb(const transform<T>& pose) const noexcept {
    const vec3<T> axis = rotate(pose.rotation, vec3<T>{T(0), half_height, T(0)});
    const vec3<T> reach = abs(axis) + vec3<T>::splat(radius);
    return aabb<T>::from_center_half_extents(pose.position, reach);
  }
};

/// Cylinder (mass m_c, radius r, height 2h) plus two hemispheres (together a
/// ball of mass m_s). About the axis: m_c·r²/2 + 2/5·m_s·r². Across it: the
/// cylinder's m_c·(r²/4 + h²/3), and each hemisphere's own 83/320·(m_s/2)·r²
/// about its center of mass, 3r/8 beyond the cylinder's end, carried to the
/// middle: together m_s·(2r²/5 + h² + 3hr/4).
template <scalar_type T>
mass_properties<T> mass_properties_of(const capsule<T>& c, T density) {
  c.validate();
  detail::require_density(density);
  const T pi = T(3.14159265358979323846), r = c.radius, h = c.half_height, r2 = r * r;
  const T m_cylinder = density * pi * r2 * T(2) * h;
  const T m_sphere = density * T(4) / T(3) * pi * r2 * r;
  const T axial = m_cylinder * r2 / T(2) + T(0.4) * m_sphere * r2;
  const T across = m_cylinder * (r2 / T(4) + h * h / T(3)) + m_sphere * (T(0.4) * r2 + h * h + T(0.75) * h * r);
  return {m_cylinder + m_sphere, {}, mat3<T>::diagonal({across, axial, across})};
}

}  // namespace impulse
