// impulse/shapes/detail/thinnest_half_extent.hpp — how thin a shape is: the
// distance a body of it may cross in one step before continuous collision
// sweeps it (world/detail/continuous.hpp), and the scale of a compound's
// welding of its children's contact points (narrowphase/compound.hpp).
#pragma once

#include <algorithm>
#include <limits>

#include "../../core/policy.hpp"
#include "../../math/aabb.hpp"

namespace impulse::detail {

/// A shape's thinnest half-extent, m: a ball's or a capsule's radius, the
/// smallest half-extent of a box's or a hull's local box, a compound's
/// thinnest child's; infinite for planes, meshes and heightfields, which
/// are static or kinematic and never swept.
template <scalar_type T, class Shape>
[[nodiscard]] T thinnest_half_extent(const Shape& shape) noexcept {
  if constexpr (requires { shape.thinnest_half_extent(); }) {
    return shape.thinnest_half_extent();
  } else if constexpr (requires { shape.radius; }) {
    return shape.radius;
  } else if constexpr (requires { shape.local_aabb(); }) {
    const aabb<T> box = shape.local_aabb();
    const vec3<T> half = (box.upper - box.lower) * T(0.5);
    return std::min({half.x, half.y, half.z});
  } else {
    return std::numeric_limits<T>::infinity();
  }
}

}  // namespace impulse::detail
