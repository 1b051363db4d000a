// impulse/dynamics/sequential_impulse.hpp — the contact solver by sequential
// impulses: projected Gauss–Seidel over the velocity rows of every contact,
// warm started, with a restitution pass before it and a split-impulse
// position pass after it.
//
// One step (Catto, "Iterative Dynamics with Temporal Coherence", GDC 2005;
// "Fast and Simple Physics using Sequential Impulses", GDC 2006):
//
// 1. Forces: each body's velocity takes this step's change from gravity and
//    loads.
// 2. Restitution: contacts approaching faster than the threshold are made
//    to separate at e times their approach speed, pairwise and in sequence
//    (contact_rows.hpp, restitution_pass, says why not inside the
//    iterations).
// 3. Warm start: each point's impulses from the last step, matched by
//    feature id, are applied again.
// 4. Velocity iterations: per manifold, friction at the patch (two tangent
//    rows within the Coulomb disc of the patch's normal impulse and a
//    twist row), then each point's normal row, clamped to push only. A row that starts apart (a speculative contact,
//    depth < 0) may close its gap within the step but no more.
// 5. Position pass (split impulses; Catto's "Box2D: the position problem",
//    Bullet's split impulse): the normal rows once more on separate
//    pseudo-velocities, pushing penetration beyond the slop out at a
//    fraction per step. Those velocities move the bodies this step and are
//    dropped, so correcting a penetration adds no kinetic energy: a
//    Baumgarte term in the velocity rows would turn every correction into
//    a bounce, and a box landing in a stack would pop the one beneath.
//    Non-linear Gauss–Seidel on positions (Box2D v2) does the same at the
//    cost of a contact re-evaluation per iteration.
// The world then moves the bodies with the solved velocities plus the
// pseudo-velocities, by its integrator policy.
#pragma once

#include <algorithm>
#include <span>

#include "../core/policy.hpp"
#include "contact_constraint.hpp"
#include "contact_rows.hpp"
#include "solver_settings.hpp"

namespace impulse {

template <scalar_type T>
class basic_sequential_impulse {
 public:
  void prepare(std::span<const solver_body<T>> bodies, std::span<contact_constraint<T>> contacts) const noexcept {
    detail::prepare_contacts(bodies, contacts);
  }

  /// Steps 1–5 above: the velocities and pseudo-velocities of the step.
  void solve(std::span<solver_body<T>> bodies, std::span<contact_constraint<T>> contacts,
             const solver_settings<T>& settings, T dt) const noexcept {
    const T inverse_dt = T(1) / dt;
    for (solver_body<T>& b : bodies) {
      b.linear_velocity += b.force_linear;
      b.angular_velocity += b.force_angular;
      b.bias_linear = {};
      b.bias_angular = {};
    }
    detail::restitution_pass(bodies, contacts, settings.restitution_threshold, settings.velocity_iterations, T(1),
                             dt);
    for (contact_constraint<T>& c : contacts) {
      if (settings.warm_starting) {
        detail::warm_start(bodies, c);
      } else {
        detail::forget_impulses(c);
      }
    }
    for (int iteration = 0; iteration < settings.velocity_iterations; ++iteration)
      for (contact_constraint<T>& c : contacts) solve_velocity(bodies, c, settings, inverse_dt);
    for (int iteration = 0; iteration < settings.position_iterations; ++iteration)
      for (contact_constraint<T>& c : contacts) solve_position(bodies, c, settings, inverse_dt);
  }

 private:
  static void solve_velocity(std::span<solver_body<T>> bodies, contact_constraint<T>& c,
                             const solver_settings<T>& settings, T inverse_dt) noexcept {
    solver_body<T>& a = bodies[c.body_a];
    solver_body<T>& b = bodies[c.body_b];
    // Friction first: it is bounded by the normal impulses, and the normal
    // rows, solved last, are the ones that must hold (no sinking).
    detail::solve_friction(a, b, c);
    // The normal rows of one patch are coupled strongly through the
    // bodies' rotation (a corner's impulse lifts the opposite corner), far
    // more than patches are coupled to each other; one pass over them
    // leaves a residual spin that tips a tall stack over within seconds.
    // A few passes within the patch settle it at little cost: a 10-box
    // tower that falls in 4 s with one pass stands with four.
    for (int sweep = 0; sweep < settings.manifold_sweeps; ++sweep)
      for (int i = 0; i < c.count; ++i) {
        contact_constraint_point<T>& p = c.points[i];
        // Apart by a gap g: the row allows closing it this step, vn ≥ −g/dt.
        const T gap_speed = p.depth < T(0) ? -p.depth * inverse_dt : T(0);
        detail::solve_normal(a.linear_velocity, a.angular_velocity, b.linear_velocity, b.angular_velocity, a, b,
                             c.normal, p, p.normal_impulse, gap_speed);
      }
  }

  static void solve_position(std::span<solver_body<T>> bodies, contact_constraint<T>& c,
                             const solver_settings<T>& settings, T inverse_dt) noexcept {
    solver_body<T>& a = bodies[c.body_a];
    solver_body<T>& b = bodies[c.body_b];
    for (int sweep = 0; sweep < settings.manifold_sweeps; ++sweep)
      for (int i = 0; i < c.count; ++i) {
        contact_constraint_point<T>& p = c.points[i];
        if (p.depth <= settings.linear_slop) continue;
        const T push_speed = std::min(settings.position_correction * (p.depth - settings.linear_slop) * inverse_dt,
                                      settings.max_correction_speed);
        detail::solve_normal(a.bias_linear, a.bias_angular, b.bias_linear, b.bias_angular, a, b, c.normal, p,
                             p.bias_impulse, -push_speed);
      }
  }
};

namespace solver {
/// Projected Gauss–Seidel with warm starting, a restitution pass and split
/// impulses (dynamics/sequential_impulse.hpp).
struct sequential_impulse {
  static constexpr policy_kind kind = policy_kind::solver;
  /// The world moves the bodies after the solve.
  static constexpr bool moves_bodies = false;
  template <scalar_type T>
  using type = basic_sequential_impulse<T>;
};
}  // namespace solver

}  // namespace impulse
