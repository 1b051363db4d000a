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
// 2. Restitution (Guendelman, Bridson and Fedkiw, "Nonconvex rigid bodies
//    with stacking", SIGGRAPH 2003): contacts that approach faster than the
//    threshold are made to separate at e times their approach speed, one
//    contact at a time, sweeping until none is left approaching. Done
//    inside the Gauss–Seidel iterations, a bounce is smeared over every
//    touching contact at once, and a Newton's cradle hands the first ball's
//    speed to the other four together (40 % to the last); done pairwise
//    and in sequence, it travels down the row as in the real toy. The
//    approach speed is taken at the start of the step: the mean of the
//    normal velocity before and after this step's forces, which for a
//    constant force under symplectic Euler is the exact speed at that
//    instant. Taken after the forces (as most engines do), a ball dropped
//    from 10 m at 60 Hz rebounds 2.5 % too high.
// 3. Warm start: each point's impulses from the last step, matched by
//    feature id, are applied again.
// 4. Velocity iterations: per point, the two friction rows clamped to the
//    Coulomb disc of the current normal impulse, then the normal row
//    clamped to push only. A row that starts apart (a speculative contact,
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
#include <cmath>
#include <span>

#include "../core/policy.hpp"
#include "../math/quat.hpp"
#include "contact_constraint.hpp"
#include "solver_settings.hpp"

namespace impulse {

template <scalar_type T>
class basic_sequential_impulse {
 public:
  /// Works out each row's effective mass and each point's normal velocity
  /// before this step's forces. The world has set the bodies' velocities,
  /// mass properties and force changes, and each constraint's offsets,
  /// depths, tangents and carried-over impulses.
  void prepare(std::span<const solver_body<T>> bodies, std::span<contact_constraint<T>> contacts) const noexcept {
    for (contact_constraint<T>& c : contacts) {
      const solver_body<T>& a = bodies[c.body_a];
      const solver_body<T>& b = bodies[c.body_b];
      for (int i = 0; i < c.count; ++i) {
        contact_constraint_point<T>& p = c.points[i];
        p.arm_a = cross(p.offset_a, c.normal);
        p.arm_b = cross(p.offset_b, c.normal);
        p.turn_a = a.inverse_inertia * p.arm_a;
        p.turn_b = b.inverse_inertia * p.arm_b;
        const T k = a.inverse_mass + b.inverse_mass + dot(p.arm_a, p.turn_a) + dot(p.arm_b, p.turn_b);
        p.normal_mass = k > T(0) ? T(1) / k : T(0);
        p.approach_speed = dot(c.normal, relative_velocity(a, b, p.offset_a, p.offset_b));
        p.bias_impulse = T(0);
        p.restitution_impulse = T(0);
      }
      tangent_block(a, b, c.anchor_a, c.anchor_b, c.tangent1, c.tangent2, c.tangent_mass11, c.tangent_mass12,
                    c.tangent_mass22);
      const T k = dot(c.normal, a.inverse_inertia * c.normal) + dot(c.normal, b.inverse_inertia * c.normal);
      c.twist_mass = k > T(0) ? T(1) / k : T(0);
    }
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
    for (contact_constraint<T>& c : contacts)
      for (int i = 0; i < c.count; ++i) {
        contact_constraint_point<T>& p = c.points[i];
        p.force_delta = dot(c.normal, relative_velocity(bodies[c.body_a], bodies[c.body_b], p.offset_a, p.offset_b)) -
                        p.approach_speed;
      }
    restitution_pass(bodies, contacts, settings, dt);
    for (contact_constraint<T>& c : contacts) {
      if (settings.warm_starting) {
        warm_start(bodies, c);
      } else {
        for (int i = 0; i < c.count; ++i) c.points[i].normal_impulse = T(0);
        c.tangent_impulse1 = c.tangent_impulse2 = c.twist_impulse = T(0);
      }
    }
    for (int iteration = 0; iteration < settings.velocity_iterations; ++iteration)
      for (contact_constraint<T>& c : contacts) solve_velocity(bodies, c, settings, inverse_dt);
    for (int iteration = 0; iteration < settings.position_iterations; ++iteration)
      for (contact_constraint<T>& c : contacts) solve_position(bodies, c, settings, inverse_dt);
  }

 private:
  static void restitution_pass(std::span<solver_body<T>> bodies, std::span<contact_constraint<T>> contacts,
                               const solver_settings<T>& settings, T dt) noexcept {
    // Each sweep hands an impact one contact further down a chain; a chain
    // of n touching bodies needs n − 1 sweeps when its contacts come in the
    // worst order. The velocity iterations bound the work as they do for
    // the contact rows.
    for (int sweep = 0; sweep < settings.velocity_iterations; ++sweep) {
      bool applied = false;
      for (contact_constraint<T>& c : contacts) {
        if (c.restitution == T(0)) continue;
        solver_body<T>& a = bodies[c.body_a];
        solver_body<T>& b = bodies[c.body_b];
        T total = T(0);
        for (int i = 0; i < c.count; ++i) {
          contact_constraint_point<T>& p = c.points[i];
          const T vn = dot(c.normal, relative_velocity(a, b, p.offset_a, p.offset_b));
          // A gap that this step's motion does not close is left to the
          // speculative row: the bodies do not meet this step.
          if (p.depth < T(0) && vn * dt >= p.depth) continue;
          const T at_start = vn - T(0.5) * p.force_delta;
          if (at_start >= -settings.restitution_threshold) continue;
          const T target = -c.restitution * at_start + T(0.5) * p.force_delta;
          const T lambda = p.normal_mass * (target - vn);
          if (!(lambda > T(0))) continue;
          apply_impulse(a, b, p.offset_a, p.offset_b, c.normal * lambda);
          p.restitution_impulse += lambda;
          total += lambda;
        }
        if (total == T(0)) continue;
        applied = true;
        // Friction in the impact, within the Coulomb disc of its impulse.
        const vec3<T> v = relative_velocity(a, b, c.anchor_a, c.anchor_b);
        const T v1 = dot(c.tangent1, v), v2 = dot(c.tangent2, v);
        T j1 = -(c.tangent_mass11 * v1 + c.tangent_mass12 * v2), j2 = -(c.tangent_mass12 * v1 + c.tangent_mass22 * v2);
        clamp_to_disc(j1, j2, c.friction * total);
        apply_impulse(a, b, c.anchor_a, c.anchor_b, c.tangent1 * j1 + c.tangent2 * j2);
      }
      if (!applied) break;
    }
  }

  static void warm_start(std::span<solver_body<T>> bodies, const contact_constraint<T>& c) noexcept {
    solver_body<T>& a = bodies[c.body_a];
    solver_body<T>& b = bodies[c.body_b];
    for (int i = 0; i < c.count; ++i) {
      const contact_constraint_point<T>& p = c.points[i];
      apply_impulse(a, b, p.offset_a, p.offset_b, c.normal * p.normal_impulse);
    }
    apply_impulse(a, b, c.anchor_a, c.anchor_b, c.tangent1 * c.tangent_impulse1 + c.tangent2 * c.tangent_impulse2);
    apply_twist(a, b, c.normal, c.twist_impulse);
  }

  static void solve_velocity(std::span<solver_body<T>> bodies, contact_constraint<T>& c,
                             const solver_settings<T>& settings, T inverse_dt) noexcept {
    solver_body<T>& a = bodies[c.body_a];
    solver_body<T>& b = bodies[c.body_b];
    // Friction first: it is bounded by the normal impulses, and the normal
    // rows, solved last, are the ones that must hold (no sinking).
    T pressed = T(0);
    for (int i = 0; i < c.count; ++i) pressed += c.points[i].normal_impulse;
    const T limit = c.friction * pressed;
    {
      const vec3<T> v = relative_velocity(a, b, c.anchor_a, c.anchor_b);
      const T v1 = dot(c.tangent1, v), v2 = dot(c.tangent2, v);
      T j1 = c.tangent_impulse1 - (c.tangent_mass11 * v1 + c.tangent_mass12 * v2);
      T j2 = c.tangent_impulse2 - (c.tangent_mass12 * v1 + c.tangent_mass22 * v2);
      clamp_to_disc(j1, j2, limit);
      const T d1 = j1 - c.tangent_impulse1, d2 = j2 - c.tangent_impulse2;
      c.tangent_impulse1 = j1, c.tangent_impulse2 = j2;
      apply_impulse(a, b, c.anchor_a, c.anchor_b, c.tangent1 * d1 + c.tangent2 * d2);
    }
    {
      const T spin = dot(c.normal, b.angular_velocity - a.angular_velocity);
      const T bound = limit * c.twist_radius;
      const T total = std::clamp(c.twist_impulse - c.twist_mass * spin, -bound, bound);
      apply_twist(a, b, c.normal, total - c.twist_impulse);
      c.twist_impulse = total;
    }
    // The normal rows of one patch are coupled strongly through the
    // bodies' rotation (a corner's impulse lifts the opposite corner), far
    // more than patches are coupled to each other; one pass over them
    // leaves a residual spin that tips a tall stack over within seconds.
    // A few passes within the patch settle it at little cost: a 10-box
    // tower that falls in 4 s with one pass stands with four.
    for (int sweep = 0; sweep < settings.manifold_sweeps; ++sweep)
      for (int i = 0; i < c.count; ++i) {
        contact_constraint_point<T>& p = c.points[i];
        const T vn = normal_speed(a.linear_velocity, a.angular_velocity, b.linear_velocity, b.angular_velocity, c.normal, p);
        // Apart by a gap g: the row allows closing it this step, vn ≥ −g/dt.
        const T bias = p.depth < T(0) ? p.depth * inverse_dt : T(0);
        const T total = std::max(p.normal_impulse - p.normal_mass * (vn - bias), T(0));
        const T delta = total - p.normal_impulse;
        p.normal_impulse = total;
        push(a.linear_velocity, a.angular_velocity, b.linear_velocity, b.angular_velocity, a, b, c.normal, p, delta);
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
        const T target = std::min(settings.position_correction * (p.depth - settings.linear_slop) * inverse_dt,
                                  settings.max_correction_speed);
        const T vn = normal_speed(a.bias_linear, a.bias_angular, b.bias_linear, b.bias_angular, c.normal, p);
        const T total = std::max(p.bias_impulse - p.normal_mass * (vn - target), T(0));
        const T delta = total - p.bias_impulse;
        p.bias_impulse = total;
        push(a.bias_linear, a.bias_angular, b.bias_linear, b.bias_angular, a, b, c.normal, p, delta);
      }
  }

  /// The normal row's velocity, n·(v_B − v_A) + ω_B·(r_B × n) − ω_A·(r_A × n),
  /// of the real velocities or of the position pass's pseudo-velocities.
  static T normal_speed(const vec3<T>& va, const vec3<T>& wa, const vec3<T>& vb, const vec3<T>& wb, const vec3<T>& n,
                        const contact_constraint_point<T>& p) noexcept {
    return dot(n, vb - va) + dot(wb, p.arm_b) - dot(wa, p.arm_a);
  }
  /// The normal row's impulse λ: B pushed along n, A against it.
  static void push(vec3<T>& va, vec3<T>& wa, vec3<T>& vb, vec3<T>& wb, const solver_body<T>& a,
                   const solver_body<T>& b, const vec3<T>& n, const contact_constraint_point<T>& p, T lambda) noexcept {
    va -= n * (lambda * a.inverse_mass);
    wa -= p.turn_a * lambda;
    vb += n * (lambda * b.inverse_mass);
    wb += p.turn_b * lambda;
  }

  static void apply_twist(solver_body<T>& a, solver_body<T>& b, const vec3<T>& n, T impulse) noexcept {
    a.angular_velocity -= a.inverse_inertia * (n * impulse);
    b.angular_velocity += b.inverse_inertia * (n * impulse);
  }

  /// Scales (j1, j2) back onto the disc of the given radius.
  static void clamp_to_disc(T& j1, T& j2, T radius) noexcept {
    const T squared = j1 * j1 + j2 * j2;
    if (squared > radius * radius) {
      const T scale = radius / std::sqrt(squared);
      j1 *= scale, j2 *= scale;
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
