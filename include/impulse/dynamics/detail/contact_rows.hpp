// impulse/dynamics/detail/contact_rows.hpp — what both contact solvers do with a
// contact constraint's rows: work out their masses, carry impulses over,
// bounce, and solve friction at the patch.
//
// sequential_impulse.hpp and soft_step.hpp differ in how they treat
// penetration and time (one rigid solve per step and a split-impulse
// position pass, or soft rows on substeps); the rows themselves, the
// restitution pass and the friction are the same code.
#pragma once

#include <algorithm>
#include <cmath>
#include <span>

#include "../../core/policy.hpp"
#include "../contact_constraint.hpp"

namespace impulse::detail {

/// Each row's effective mass, the normal rows' Jacobians, and how much this
/// step's forces change each point's normal velocity, from the bodies'
/// mass properties and force changes and each constraint's offsets and
/// tangents.
template <scalar_type T>
void prepare_contacts(std::span<const solver_body<T>> bodies, std::span<contact_constraint<T>> contacts) noexcept {
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
      // The change of the normal velocity this step's forces alone make.
      p.force_delta = dot(c.normal, b.force_linear + cross(b.force_angular, p.offset_b) - a.force_linear -
                                        cross(a.force_angular, p.offset_a));
      p.bias_impulse = T(0);
    }
    tangent_block(a, b, c.anchor_a, c.anchor_b, c.tangent1, c.tangent2, c.tangent_mass11, c.tangent_mass12,
                  c.tangent_mass22);
    const T k = dot(c.normal, a.inverse_inertia * c.normal) + dot(c.normal, b.inverse_inertia * c.normal);
    c.twist_mass = k > T(0) ? T(1) / k : T(0);
  }
}

/// The normal row's velocity, n·(v_B − v_A) + ω_B·(r_B × n) − ω_A·(r_A × n),
/// of the real velocities or of a position pass's pseudo-velocities.
template <scalar_type T>
[[nodiscard]] T normal_speed(const vec3<T>& va, const vec3<T>& wa, const vec3<T>& vb, const vec3<T>& wb,
                             const vec3<T>& n, const contact_constraint_point<T>& p) noexcept {
  return dot(n, vb - va) + dot(wb, p.arm_b) - dot(wa, p.arm_a);
}

/// The normal row's impulse λ: B pushed along n, A against it.
template <scalar_type T>
void push(vec3<T>& va, vec3<T>& wa, vec3<T>& vb, vec3<T>& wb, const solver_body<T>& a, const solver_body<T>& b,
          const vec3<T>& n, const contact_constraint_point<T>& p, T lambda) noexcept {
  va -= n * (lambda * a.inverse_mass);
  wa -= p.turn_a * lambda;
  vb += n * (lambda * b.inverse_mass);
  wb += p.turn_b * lambda;
}

/// One normal row solved on the velocities (va, wa, vb, wb): the impulse
/// that brings n·Δv to −bias (bias > 0 closes a gap, < 0 pushes apart),
/// accumulated in `total` and kept ≥ 0. A soft row scales the row's mass
/// and leaks part of what it has accumulated (soft_step.hpp); a rigid one
/// passes 1 and 0.
template <scalar_type T>
void solve_normal(vec3<T>& va, vec3<T>& wa, vec3<T>& vb, vec3<T>& wb, const solver_body<T>& a,
                  const solver_body<T>& b, const vec3<T>& n, const contact_constraint_point<T>& p, T& total, T bias,
                  T mass_scale = T(1), T impulse_scale = T(0)) noexcept {
  const T vn = normal_speed(va, wa, vb, wb, n, p);
  const T next = std::max(total - p.normal_mass * mass_scale * (vn + bias) - impulse_scale * total, T(0));
  const T delta = next - total;
  total = next;
  push(va, wa, vb, wb, a, b, n, p, delta);
}

template <scalar_type T>
void apply_twist(solver_body<T>& a, solver_body<T>& b, const vec3<T>& n, T impulse) noexcept {
  a.angular_velocity -= a.inverse_inertia * (n * impulse);
  b.angular_velocity += b.inverse_inertia * (n * impulse);
}

/// Scales (j1, j2) back onto the disc of the given radius.
template <scalar_type T>
void clamp_to_disc(T& j1, T& j2, T radius) noexcept {
  const T squared = j1 * j1 + j2 * j2;
  if (squared > radius * radius) {
    const T scale = radius / std::sqrt(squared);
    j1 *= scale, j2 *= scale;
  }
}

/// Restitution, pairwise and in sequence (Guendelman, Bridson and Fedkiw,
/// "Nonconvex rigid bodies with stacking", SIGGRAPH 2003): every contact
/// approaching faster than the threshold is made to separate at e times
/// its approach speed, one contact at a time, sweeping until none
/// approaches. Inside the Gauss–Seidel iterations a bounce is smeared over
/// every touching contact at once, and a Newton's cradle hands the first
/// ball's speed to the other four together (40 % to the last); pairwise it
/// travels down the row as in the real toy.
///
/// The approach speed is the one at the start of the step: the mean of the
/// normal velocity before and after this step's forces, which for a
/// constant force under symplectic Euler is the exact speed at that
/// instant. Taken after the forces (as most engines do), a ball dropped
/// from 10 m at 60 Hz rebounds 2.5 % too high. The velocities hold that
/// speed plus (applied − ½) of the change this step's forces make: 1 when
/// they were added at once; ½ − 1/(2n) for a solver that adds 1/n of them
/// at each of n substeps and has added none yet, whose bodies move by
/// symplectic Euler at the substep (at 0, soft_step's ball gained 1.8 %
/// of its height at each elastic bounce).
template <scalar_type T>
void restitution_pass(std::span<solver_body<T>> bodies, std::span<contact_constraint<T>> contacts, T threshold,
                      int sweeps, T applied, T dt) noexcept {
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    bool any = false;
    for (contact_constraint<T>& c : contacts) {
      if (c.restitution == T(0)) continue;
      solver_body<T>& a = bodies[c.body_a];
      solver_body<T>& b = bodies[c.body_b];
      T total = T(0);
      for (int i = 0; i < c.count; ++i) {
        contact_constraint_point<T>& p = c.points[i];
        const T vn = dot(c.normal, relative_velocity(a, b, p.offset_a, p.offset_b));
        const T shift = (applied - T(0.5)) * p.force_delta;
        const T at_start = vn - shift;
        // A gap that this step's motion does not close is left to the
        // speculative row: the bodies do not meet this step.
        if (p.depth < T(0) && (at_start + T(0.5) * p.force_delta) * dt >= p.depth) continue;
        if (at_start >= -threshold) continue;
        // Met apart by a gap g, the bodies part from where the step began,
        // g short of where they meet. Parting there at e times the approach
        // speed, they would climb (1 − e²)·g too high against the forces
        // that press them together (a ball's second rebound from 10 m, met
        // 22 cm ahead of the ground, rose 1 % too high); they part at the
        // speed that e times the speed of the impact has left at g.
        T part = -c.restitution * at_start;
        if (p.depth < T(0)) {
          const T pressing = -p.force_delta / dt;  // m/s², closing them
          const T loss = T(1) - c.restitution * c.restitution;
          part = std::sqrt(std::max(part * part + T(2) * pressing * p.depth * loss, T(0)));
        }
        const T lambda = p.normal_mass * (part + shift - vn);
        if (!(lambda > T(0))) continue;
        apply_impulse(a, b, p.offset_a, p.offset_b, c.normal * lambda);
        total += lambda;
      }
      if (total == T(0)) continue;
      any = true;
      // Friction in the impact, within the Coulomb disc of its impulse.
      const vec3<T> v = relative_velocity(a, b, c.anchor_a, c.anchor_b);
      const T v1 = dot(c.tangent1, v) - c.slip_target1, v2 = dot(c.tangent2, v) - c.slip_target2;
      T j1 = -(c.tangent_mass11 * v1 + c.tangent_mass12 * v2), j2 = -(c.tangent_mass12 * v1 + c.tangent_mass22 * v2);
      clamp_to_disc(j1, j2, c.friction * total);
      apply_impulse(a, b, c.anchor_a, c.anchor_b, c.tangent1 * j1 + c.tangent2 * j2);
    }
    if (!any) break;
  }
}

/// Applies a constraint's carried-over impulses again.
template <scalar_type T>
void warm_start(std::span<solver_body<T>> bodies, const contact_constraint<T>& c) noexcept {
  solver_body<T>& a = bodies[c.body_a];
  solver_body<T>& b = bodies[c.body_b];
  for (int i = 0; i < c.count; ++i) {
    const contact_constraint_point<T>& p = c.points[i];
    push(a.linear_velocity, a.angular_velocity, b.linear_velocity, b.angular_velocity, a, b, c.normal, p,
         p.normal_impulse);
  }
  apply_impulse(a, b, c.anchor_a, c.anchor_b, c.tangent1 * c.tangent_impulse1 + c.tangent2 * c.tangent_impulse2);
  apply_twist(a, b, c.normal, c.twist_impulse);
}

template <scalar_type T>
void forget_impulses(contact_constraint<T>& c) noexcept {
  for (int i = 0; i < c.count; ++i) c.points[i].normal_impulse = T(0);
  c.tangent_impulse1 = c.tangent_impulse2 = c.twist_impulse = T(0);
}

/// Friction at the patch: the two tangent rows as one 2×2 block within the
/// Coulomb disc of the patch's normal impulse, then the twist row within
/// that times the patch's lever (contact_constraint.hpp says why at the
/// patch and not per point).
template <scalar_type T>
void solve_friction(solver_body<T>& a, solver_body<T>& b, contact_constraint<T>& c) noexcept {
  T pressed = T(0);
  for (int i = 0; i < c.count; ++i) pressed += c.points[i].normal_impulse;
  const T limit = c.friction * pressed;
  const vec3<T> v = relative_velocity(a, b, c.anchor_a, c.anchor_b);
  const T v1 = dot(c.tangent1, v) - c.slip_target1, v2 = dot(c.tangent2, v) - c.slip_target2;
  T j1 = c.tangent_impulse1 - (c.tangent_mass11 * v1 + c.tangent_mass12 * v2);
  T j2 = c.tangent_impulse2 - (c.tangent_mass12 * v1 + c.tangent_mass22 * v2);
  clamp_to_disc(j1, j2, limit);
  const T d1 = j1 - c.tangent_impulse1, d2 = j2 - c.tangent_impulse2;
  c.tangent_impulse1 = j1, c.tangent_impulse2 = j2;
  apply_impulse(a, b, c.anchor_a, c.anchor_b, c.tangent1 * d1 + c.tangent2 * d2);

  const T spin = dot(c.normal, b.angular_velocity - a.angular_velocity);
  const T bound = limit * c.twist_radius;
  const T total = std::clamp(c.twist_impulse - c.twist_mass * spin, -bound, bound);
  apply_twist(a, b, c.normal, total - c.twist_impulse);
  c.twist_impulse = total;
}

}  // namespace impulse::detail
