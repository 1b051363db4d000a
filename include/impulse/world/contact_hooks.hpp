// impulse/world/contact_hooks.hpp — the user's say in the solve: a hook
// before it that can switch a contact off or change its friction,
// restitution and surface speed (one-way platforms, conveyor belts), and a
// hook after it that reports the impulses each contact applied.
#pragma once

#include <cmath>
#include <exception>

#include "../dynamics/contact_constraint.hpp"
#include "../dynamics/fwd.hpp"
#include "../math/vec3.hpp"
#include "../narrowphase/manifold.hpp"

namespace impulse {

/// What a pre-solve hook may change of one touching manifold, for this
/// step. It starts as the pair's own: enabled, the materials' combined
/// friction and restitution, no surface velocity.
template <scalar_type T>
struct contact_settings {
  /// false: the manifold is left out of this step's solve, and its
  /// impulses are dropped (a body passing up through a one-way platform).
  bool enabled = true;
  T friction = T(0);     ///< ≥ 0, finite
  T restitution = T(0);  ///< in [0, 1]
  /// m/s, world: the velocity friction holds B's surface at, relative to
  /// A's, at the contact (only its part across the normal counts): a
  /// conveyor belt as body A gives its belt speed, as body B the opposite.
  vec3<T> surface_velocity{};
};

/// Called on the thread that steps, before the solve, for each touching
/// manifold the solve would take (one of its bodies awake and dynamic), in
/// a fixed order: the pair's bodies (the manifold's normal points from a
/// into b), the manifold, and the settings to change. It may read the
/// world; a change to it from inside is refused, as inside any callback.
/// Settings out of range are replaced by the pair's own. What a hook
/// throws, or the settings it got wrong, the step reports once it has
/// finished, the world whole: no hook is called again in that step.
template <scalar_type T>
struct pre_solve_hook {
  void (*call)(body_id a, body_id b, const contact_manifold<T>& manifold, contact_settings<T>& settings,
               void* context) = nullptr;
  void* context = nullptr;
};

/// Called on the thread that steps, after the solve, for each manifold it
/// solved, in the same order, with the impulses the manifold applied over
/// the step: normal per point (N·s), friction at the patch, twist (N·m·s).
/// A solver that takes the step in parts reports its last part's scaled
/// to the whole step, a force held over it, as world::joint_force does.
template <scalar_type T>
struct post_solve_hook {
  void (*call)(body_id a, body_id b, const contact_manifold<T>& manifold, const manifold_impulse<T>& impulse,
               void* context) = nullptr;
  void* context = nullptr;
};

namespace detail {

/// Calls a hook, f(), so that what it throws waits for the end of the step
/// (a refusal of a change from inside it, say): the first exception is
/// kept in `caught`, and no hook is called again in the step.
template <class F>
void call_hook(std::exception_ptr& caught, F&& f) {
  if (caught) return;
#if defined(__cpp_exceptions) || defined(__EXCEPTIONS)
  try {
    f();
  } catch (...) {
    caught = std::current_exception();
  }
#else
  f();
#endif
}

}  // namespace detail

/// Whether a hook's settings are ones the solver can take.
template <scalar_type T>
[[nodiscard]] bool valid_settings(const contact_settings<T>& s) noexcept {
  return std::isfinite(s.friction) && s.friction >= T(0) && s.restitution >= T(0) && s.restitution <= T(1) &&
         is_finite(s.surface_velocity);
}

}  // namespace impulse
