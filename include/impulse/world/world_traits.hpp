// impulse/world/world_traits.hpp — a config's world policies, with the
// defaults for those it does not name.
//
// default_config (config.hpp) names only what every module uses, so that a
// particles-only program never parses the world's headers; the world's own
// members are filled in here when a config leaves them out: every shape, a
// dynamic BVH, sequential impulses, sleeping on, CCD off.
#pragma once

#include "../broadphase/dynamic_bvh.hpp"
#include "../core/policy.hpp"
#include "../dynamics/sequential_impulse.hpp"
#include "../dynamics/soft_step.hpp"
#include "../shapes/box.hpp"
#include "../shapes/capsule.hpp"
#include "../shapes/convex_hull.hpp"
#include "../shapes/plane.hpp"
#include "../shapes/sphere.hpp"
#include "../shapes/triangle_mesh.hpp"

namespace impulse::detail {

template <class C>
struct world_shapes {
  using type = shape_list<sphere, box, capsule, convex_hull, plane, triangle_mesh>;
};
template <class C>
  requires has_shapes<C>
struct world_shapes<C> {
  using type = typename C::shapes;
};

template <class C>
struct world_broadphase {
  using type = broadphase::dynamic_bvh;
};
template <class C>
  requires has_broadphase<C>
struct world_broadphase<C> {
  using type = typename C::broadphase;
};

template <class C>
struct world_solver {
  using type = solver::sequential_impulse;
};
template <class C>
  requires has_solver<C>
struct world_solver<C> {
  using type = typename C::solver;
};

template <class C>
consteval bool world_sleeping() {
  if constexpr (has_sleeping<C>) {
    return C::sleeping;
  } else {
    return true;
  }
}

template <class C>
consteval bool world_ccd() {
  if constexpr (has_ccd<C>) {
    return C::ccd;
  } else {
    return false;
  }
}

}  // namespace impulse::detail
