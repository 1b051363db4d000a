// impulse/world/detail/world_traits.hpp — a config's world policies, with the
// defaults for those it does not name.
//
// default_config (config.hpp) names only what every module uses, so that a
// particles-only program never parses the world's headers; the world's own
// members are filled in here when a config leaves them out: every shape, a
// dynamic BVH, sequential impulses, sleeping on, CCD off.
#pragma once

#include "../../broadphase/broad_phase.hpp"
#include "../../broadphase/dynamic_bvh.hpp"
#include "../../core/policy.hpp"
#include "../../dynamics/body_motion.hpp"
#include "../../dynamics/contact_solver.hpp"
#include "../../dynamics/sequential_impulse.hpp"
#include "../../dynamics/soft_step.hpp"
#include "../../shapes/box.hpp"
#include "../../shapes/capsule.hpp"
#include "../../shapes/compound.hpp"
#include "../../shapes/convex_hull.hpp"
#include "../../shapes/plane.hpp"
#include "../../shapes/sphere.hpp"
#include "../../shapes/heightfield.hpp"
#include "../../shapes/triangle_mesh.hpp"
#include "../world_settings.hpp"

namespace impulse::detail {

template <class C>
struct world_shapes {
  using type = shape_list<sphere, box, capsule, convex_hull, plane, triangle_mesh, heightfield, compound>;
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

/// Whether bodies collide. A world without collision (`collision =
/// false`) has no broad phase, contacts, joints or solver: forces move its
/// bodies, evaluated at every stage of the integrator (force_motion.hpp).
template <class C>
consteval bool world_collides() {
  if constexpr (has_collision<C>) {
    return C::collision;
  } else {
    return true;
  }
}

/// Sleeping is on unless the config turns it off; a world without
/// collision never sleeps.
template <class C>
consteval bool world_sleeping() {
  if constexpr (has_sleeping<C>) {
    return C::sleeping;
  } else {
    return world_collides<C>();
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

/// The settings a world holds: world_settings with its solver's
/// settings_type (solver_settings<T> while the config check reports a
/// solver without one, so that only its message is shown).
template <class C>
struct world_solver_settings {
  using T = typename C::scalar;
  using solver = typename world_solver<C>::type::template type<T>;
  using type = world_settings<T, solver_settings<T>>;
};
template <class C>
  requires requires { typename world_solver<C>::type::template type<typename C::scalar>::settings_type; }
struct world_solver_settings<C> {
  using T = typename C::scalar;
  using type = world_settings<T, typename world_solver<C>::type::template type<T>::settings_type>;
};

/// A body standing still: the system a world's integrator is checked on.
template <scalar_type T>
struct still_body {
  body_pose<T> position_rate(const body_pose<T>&, const body_momentum<T>&) const { return {}; }
  body_momentum<T> momentum_rate(const body_pose<T>&, const body_momentum<T>&) const { return {}; }
};

template <class I, class T>
concept world_integrator = requires(body_pose<T>& x, body_momentum<T>& p, T h) { I::advance(x, p, h, still_body<T>{}); };
template <class C, class T>
consteval bool integrator_advances() {
  if constexpr (has_integrator<C>) {
    return world_integrator<typename C::integrator, T>;
  } else {
    return false;
  }
}
template <class P, class T>
concept makes_type = requires { typename P::template type<T>; };

/// What the world calls of its config's policies, beyond check_config's
/// kinds: `static_assert(check_world_config<C>());` fails with a message
/// naming the policy and the member it lacks. The world calls the
/// integrator's advance (body_motion.hpp), its broad phase's operations
/// (broadphase/broad_phase.hpp) and its solver's (contact_solver.hpp).
template <class C>
consteval bool check_world_config() {
  if constexpr (!check_config<C>()) {
    return false;
  } else {
    using T = typename C::scalar;
    using broadphase_policy = typename world_broadphase<C>::type;
    using solver_policy = typename world_solver<C>::type;
    static_assert(has_integrator<C>, "impulse world: the config names no `integrator`; inherit impulse::default_config");
    static_assert(world_collides<C>() || (!world_sleeping<C>() && !world_ccd<C>()),
                  "impulse world: a world without collision neither sleeps nor sweeps; drop `sleeping` and `ccd` "
                  "or set them false");
    constexpr bool integrates = integrator_advances<C, T>();
    static_assert(!has_integrator<C> || integrates,
                  "impulse world: the config's integrator has no static `advance(body_pose<T>&, "
                  "body_momentum<T>&, T h, system)` (integrators/ode_state.hpp)");
    static_assert(makes_type<broadphase_policy, T>,
                  "impulse world: the config's broadphase has no member template `type<T>`");
    static_assert(makes_type<solver_policy, T>, "impulse world: the config's solver has no member template `type<T>`");
    if constexpr (makes_type<broadphase_policy, T> && makes_type<solver_policy, T>) {
      static_assert(broadphase::check_broad_phase<typename broadphase_policy::template type<T>, T>());
      static_assert(check_contact_solver<typename solver_policy::template type<T>, T>());
      return integrates;
    } else {
      return false;
    }
  }
}

}  // namespace impulse::detail
