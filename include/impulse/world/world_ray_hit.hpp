// impulse/world/world_ray_hit.hpp — what world::ray_cast finds: the
// nearest body a ray meets, where and at what fraction.
#pragma once

#include "../dynamics/fwd.hpp"
#include "../math/vec3.hpp"

namespace impulse {

/// The nearest body a ray, or a cast shape (world::shape_cast), meets.
template <scalar_type T>
struct world_ray_hit {
  body_id body;
  T fraction = T(0);  ///< of the ray's translation
  vec3<T> point{};    ///< world, m
  vec3<T> normal{};   ///< world, unit, out of the body
};

}  // namespace impulse
