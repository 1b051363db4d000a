// impulse/dynamics/detail/constraint_parts.hpp — the pieces every joint is built
// from: a point held to a point, a rotation held to a rotation, and a single
// row along a line or about an axis.
//
// Jolt assembles its constraints from such parts (PointConstraintPart,
// RotationEulerConstraintPart, AxisConstraintPart, AngleConstraintPart);
// each part here knows its Jacobian, its effective mass and how to apply
// an impulse, and a joint (joint.hpp) says which parts it has and what
// each one is asked to do. A part solves one Gauss–Seidel update:
//
//   λ = −m_eff·s_m·(J·v + bias) − s_i·Λ,   Λ ← clamp(Λ + λ)
//
// with Λ the impulse accumulated this step, bias the velocity that corrects
// the error (0 for a rigid row whose error is removed from the positions
// once the bodies have moved), and
// s_m, s_i the scales of a soft row (softness.hpp): 1 and 0 for a rigid one.
// The three-row parts are solved as blocks (the 3×3 effective mass
// inverted once per step), not row by row: the rows of a point share the
// bodies' rotation, and Gauss–Seidel over them would need many sweeps to
// agree on a hanging chain's pivots.
#pragma once

#include <algorithm>
#include <optional>

#include "../../core/policy.hpp"
#include "../../math/mat3.hpp"
#include "../../math/vec3.hpp"
#include "../contact_constraint.hpp"
#include "../softness.hpp"

namespace impulse::detail {

/// The velocities a pass works on: the bodies' own, or the displacements
/// of a pass on the positions (joint.hpp, project_joint).
template <scalar_type T>
struct velocity_pair {
  vec3<T>& va;
  vec3<T>& wa;
  vec3<T>& vb;
  vec3<T>& wb;
};
template <scalar_type T>
velocity_pair<T> real_velocities(solver_body<T>& a, solver_body<T>& b) noexcept {
  return {a.linear_velocity, a.angular_velocity, b.linear_velocity, b.angular_velocity};
}

/// K⁻¹ of a 3×3 effective mass, or zero when K is singular (neither body
/// can move along some direction: two static bodies never get here).
template <scalar_type T>
mat3<T> inverse_or_zero(const mat3<T>& k) noexcept {
  const std::optional<mat3<T>> inverse = try_inverse(k);
  return inverse ? *inverse : mat3<T>::zero();
}

/// One row, J = [−u, −arm_a, u, arm_b] on (v_A, ω_A, v_B, ω_B): along u
/// between a point of A at r_a and one of B at r_b (arm = r × u), or, with
/// u = 0 and both arms w, of the relative spin about w.
template <scalar_type T>
struct row_part {
  vec3<T> linear{}, arm_a{}, arm_b{};
  vec3<T> turn_a{}, turn_b{};  ///< I⁻¹·arm: what a unit impulse does to each spin
  T mass = T(0);               ///< 1 / (J M⁻¹ Jᵀ), kg (or kg·m²)

  void prepare_linear(const solver_body<T>& a, const solver_body<T>& b, const vec3<T>& ra, const vec3<T>& rb,
                      const vec3<T>& u) noexcept {
    linear = u;
    arm_a = cross(ra, u), arm_b = cross(rb, u);
    finish(a, b, a.inverse_mass + b.inverse_mass);
  }
  void prepare_angular(const solver_body<T>& a, const solver_body<T>& b, const vec3<T>& w) noexcept {
    linear = {};
    arm_a = arm_b = w;
    finish(a, b, T(0));
  }

  [[nodiscard]] T speed(const velocity_pair<T>& v) const noexcept {
    return dot(linear, v.vb - v.va) + dot(arm_b, v.wb) - dot(arm_a, v.wa);
  }
  void apply(const velocity_pair<T>& v, const solver_body<T>& a, const solver_body<T>& b, T lambda) const noexcept {
    v.va -= linear * (lambda * a.inverse_mass);
    v.wa -= turn_a * lambda;
    v.vb += linear * (lambda * b.inverse_mass);
    v.wb += turn_b * lambda;
  }
  /// One update towards sign·J·v = −bias, the accumulated impulse kept
  /// within [lower, upper] (sign −1: the row reversed, as an upper limit
  /// is).
  void solve(const velocity_pair<T>& v, const solver_body<T>& a, const solver_body<T>& b, T& total, T bias,
             const softness<T>& soft, T lower, T upper, T sign = T(1)) const noexcept {
    const T next = std::clamp(
        total - mass * soft.mass_scale * (sign * speed(v) + bias) - soft.impulse_scale * total, lower, upper);
    apply(v, a, b, sign * (next - total));
    total = next;
  }

 private:
  void finish(const solver_body<T>& a, const solver_body<T>& b, T linear_part) noexcept {
    turn_a = a.inverse_inertia * arm_a;
    turn_b = b.inverse_inertia * arm_b;
    const T k = linear_part + dot(arm_a, turn_a) + dot(arm_b, turn_b);
    mass = k > T(0) ? T(1) / k : T(0);
  }
};

/// A point of A held to a point of B: v_B + ω_B × r_b − v_A − ω_A × r_a = 0,
/// three rows solved as one block. K = (m_A⁻¹ + m_B⁻¹)·1 − [r_a]× I_A⁻¹ [r_a]×
/// − [r_b]× I_B⁻¹ [r_b]× (Catto, "Modeling and Solving Constraints", GDC 2009).
template <scalar_type T>
struct point_part {
  vec3<T> ra{}, rb{};
  mat3<T> mass = mat3<T>::zero();  ///< K⁻¹

  void prepare(const solver_body<T>& a, const solver_body<T>& b, const vec3<T>& offset_a,
               const vec3<T>& offset_b) noexcept {
    ra = offset_a, rb = offset_b;
    const mat3<T> sa = skew(ra), sb = skew(rb);
    mat3<T> k = mat3<T>::identity() * (a.inverse_mass + b.inverse_mass);
    k -= sa * a.inverse_inertia * sa;
    k -= sb * b.inverse_inertia * sb;
    mass = inverse_or_zero(k);
  }
  [[nodiscard]] vec3<T> speed(const velocity_pair<T>& v) const noexcept {
    return v.vb + cross(v.wb, rb) - v.va - cross(v.wa, ra);
  }
  void apply(const velocity_pair<T>& v, const solver_body<T>& a, const solver_body<T>& b,
             const vec3<T>& lambda) const noexcept {
    v.va -= lambda * a.inverse_mass;
    v.wa -= a.inverse_inertia * cross(ra, lambda);
    v.vb += lambda * b.inverse_mass;
    v.wb += b.inverse_inertia * cross(rb, lambda);
  }
  void solve(const velocity_pair<T>& v, const solver_body<T>& a, const solver_body<T>& b, vec3<T>& total,
             const vec3<T>& bias, const softness<T>& soft) const noexcept {
    const vec3<T> lambda = (mass * (speed(v) + bias)) * (-soft.mass_scale) - total * soft.impulse_scale;
    apply(v, a, b, lambda);
    total += lambda;
  }
};

/// B's orientation held to A's: ω_B − ω_A = 0, three rows as one block,
/// K = I_A⁻¹ + I_B⁻¹.
template <scalar_type T>
struct rotation_part {
  mat3<T> mass = mat3<T>::zero();  ///< K⁻¹

  void prepare(const solver_body<T>& a, const solver_body<T>& b) noexcept {
    mass = inverse_or_zero(a.inverse_inertia + b.inverse_inertia);
  }
  void apply(const velocity_pair<T>& v, const solver_body<T>& a, const solver_body<T>& b,
             const vec3<T>& lambda) const noexcept {
    v.wa -= a.inverse_inertia * lambda;
    v.wb += b.inverse_inertia * lambda;
  }
  void solve(const velocity_pair<T>& v, const solver_body<T>& a, const solver_body<T>& b, vec3<T>& total,
             const vec3<T>& bias, const softness<T>& soft) const noexcept {
    const vec3<T> lambda = (mass * (v.wb - v.wa + bias)) * (-soft.mass_scale) - total * soft.impulse_scale;
    apply(v, a, b, lambda);
    total += lambda;
  }
};

}  // namespace impulse::detail
