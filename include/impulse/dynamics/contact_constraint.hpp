// impulse/dynamics/contact_constraint.hpp — a contact manifold as the solver
// sees it: rows of the velocity constraint at each point, their effective
// masses and the impulses they have accumulated.
//
// A manifold with normal n (from A into B) has a normal row at each point,
// n·(v_B(p) − v_A(p)) ≥ bias with a non-negative impulse (Catto, "Fast and
// Simple Physics using Sequential Impulses", GDC 2006), and friction for
// the patch as a whole: two tangent rows at its middle whose impulses lie
// within the Coulomb disc μ·Σλn, and a twist row about the normal (the
// comment on contact_constraint says why not per point). The tangents are
// a fixed function of the normal while the contact is at rest, so the
// impulses carried over from the last step (warm starting) point the same
// way; once it slips, the first tangent follows the slip.
//
// Bodies are referred to by their place in the solver's body array; static
// and kinematic bodies are there too, with zero inverse mass, so every row
// has two ends and no branch.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "../math/mat3.hpp"
#include "../math/quat.hpp"
#include "../math/vec3.hpp"
#include "../narrowphase/manifold.hpp"
#include "free_rotation.hpp"

namespace impulse {

/// A body during one solve: its velocities and what moves them.
template <scalar_type T>
struct solver_body {
  vec3<T> position{};                         ///< center of mass, m
  quat<T> orientation = quat<T>::identity();  ///< unit
  vec3<T> linear_velocity{};   ///< m/s
  vec3<T> angular_velocity{};  ///< rad/s, world
  /// Change of velocity this step from forces (gravity, loads), added by
  /// the solver: all at once (sequential_impulse) or a substep's share at
  /// a time (soft_step).
  vec3<T> force_linear{};
  vec3<T> force_angular{};
  /// Split-impulse pseudo-velocities: they move the body this step and are
  /// then dropped, so position correction adds no kinetic energy.
  vec3<T> bias_linear{};
  vec3<T> bias_angular{};
  mat3<T> inverse_inertia = mat3<T>::zero();  ///< world, 1/(kg·m²); zero for static and kinematic
  T inverse_mass = T(0);                     ///< 1/kg
  /// For a solver that moves the bodies itself (contact_solver.hpp): the
  /// body's angular momentum L (world, kg·m²/s), which it turns the body
  /// with and keeps in step with ω, and its principal moments and axes
  /// (free_rotation.hpp). Meaningful when inverse_mass > 0.
  vec3<T> angular_momentum{};
  principal_inertia<T> principal{};
};

/// What a contact has accumulated, kept between steps: the normal impulse
/// of each point (matched by feature id) and the friction of the whole
/// manifold. Friction is kept as a world vector: the tangents follow the
/// slip and change from step to step, and the vector is projected onto the
/// new ones.
template <scalar_type T>
struct manifold_impulse {
  std::array<T, contact_manifold<T>::capacity> normal{};  ///< N·s, per point
  vec3<T> friction{};  ///< N·s, across the normal, at the middle of the patch
  T twist = T(0);      ///< N·m·s, about the normal
};

/// One point's normal row.
template <scalar_type T>
struct contact_constraint_point {
  vec3<T> offset_a{};  ///< from A's center of mass to the point, m
  vec3<T> offset_b{};
  // The normal row's angular Jacobians, r × n, and what they do to each
  // body's spin, I⁻¹·(r × n): worked out once per step, so that an
  // iteration is dot products and additions.
  vec3<T> arm_a{}, arm_b{};
  vec3<T> turn_a{}, turn_b{};
  T normal_mass = T(0);     ///< 1 / (J M⁻¹ Jᵀ) of the normal row, kg
  T depth = T(0);           ///< at the start of the step, m (< 0: a gap, up to max_speculative_distance)
  T force_delta = T(0);     ///< change of the normal velocity this step from forces alone, m/s
  T normal_impulse = T(0);  ///< N·s
  T bias_impulse = T(0);    ///< accumulated by the position pass
  /// How fast the velocity row lets the point approach, m/s: enough to
  /// close a gap, or to sink to the rest depth, within the step
  /// (sequential_impulse.hpp, row_targets).
  T gap_speed = T(0);
  /// The position pass's target separation speed, m/s; < 0 where the
  /// point takes no part in it (sequential_impulse.hpp, row_targets).
  T push_speed = T(-1);
};

/// A manifold's rows: a normal row per point, and friction for the patch
/// as a whole, at its middle (the anchor): two tangent rows within the
/// Coulomb disc μ·Σλn and a twist row about the normal within μ·Σλn·r.
///
/// Friction per point, solved point after point, makes a sliding box spin:
/// each point's friction, applied alone, turns the box a little about the
/// normal, the next point then slips a little sideways, and the sum leans
/// off the slip (a box sliding along an axis slows 6 % too little and
/// drifts sideways; along a diagonal, where the order is symmetric, it is
/// exact). At the middle of the patch the tangent rows exert no torque
/// about the normal, and the twist row has its own bound. (PhysX's patch
/// friction works the same way.)
template <scalar_type T>
struct contact_constraint {
  std::uint32_t body_a = 0, body_b = 0;  ///< places in the solver's body array
  vec3<T> normal{};                      ///< unit, from A into B
  vec3<T> tangent1{}, tangent2{};
  T friction = T(0);
  T restitution = T(0);
  int count = 0;
  contact_constraint_point<T> points[contact_manifold<T>::capacity];
  vec3<T> anchor_a{};  ///< from A's center of mass to the middle of the patch, m
  vec3<T> anchor_b{};
  /// The inverse of the 2×2 effective mass of the tangent rows, kg: the
  /// rows share the bodies' rotation, and solved one by one they would
  /// turn the friction impulse away from the slip it opposes.
  T tangent_mass11 = T(0), tangent_mass12 = T(0), tangent_mass22 = T(0);
  T twist_mass = T(0);    ///< kg·m²
  T twist_radius = T(0);  ///< m: the lever of the patch's friction about its middle
  /// The relative velocity along each tangent the friction rows hold the
  /// patch at, m/s: not 0 but what cancels the bodies' curving over the
  /// step (world/detail/solve.hpp says why), so that a box stuck to a turning
  /// platform stays where it is on it.
  T slip_target1 = T(0), slip_target2 = T(0);
  T tangent_impulse1 = T(0), tangent_impulse2 = T(0);  ///< N·s
  T twist_impulse = T(0);                              ///< N·m·s
};

/// Two unit tangents making a right-handed frame (t1, t2, n) with n, a
/// fixed function of n (Duff et al., "Building an Orthonormal Basis,
/// Revisited", 2017): no cancellation near any axis, and the same tangents
/// for the same normal on every step. For a contact at rest.
template <scalar_type T>
void tangents_of(const vec3<T>& n, vec3<T>& t1, vec3<T>& t2) noexcept {
  const T sign = std::copysign(T(1), n.z);
  const T a = T(-1) / (sign + n.z);
  const T b = n.x * n.y * a;
  t1 = {T(1) + sign * n.x * n.x * a, sign * b, -sign * n.x};
  t2 = {b, sign + n.y * n.y * a, -n.y};
}

/// The tangents of a contact slipping at relative velocity v: t1 along the
/// slip, so that a sliding contact's friction, which saturates the Coulomb
/// disc, opposes the slip exactly; the fixed frame of tangents_of when the
/// slip is below `rest_speed` (its direction is noise there).
template <scalar_type T>
void slip_tangents(const vec3<T>& n, const vec3<T>& v, T rest_speed, vec3<T>& t1, vec3<T>& t2) noexcept {
  const vec3<T> slip = v - n * dot(n, v);
  const T speed_squared = length_squared(slip);
  if (!(speed_squared > rest_speed * rest_speed)) {
    tangents_of(n, t1, t2);
    return;
  }
  t1 = slip * (T(1) / std::sqrt(speed_squared));
  t2 = cross(n, t1);
}

/// The inverse of the 2×2 matrix J M⁻¹ Jᵀ of the rows along d1 and d2, as
/// (m11, m12, m22); zeros when neither body can move.
template <scalar_type T>
void tangent_block(const solver_body<T>& a, const solver_body<T>& b, const vec3<T>& ra, const vec3<T>& rb,
                   const vec3<T>& d1, const vec3<T>& d2, T& m11, T& m12, T& m22) noexcept {
  const vec3<T> ra1 = cross(ra, d1), ra2 = cross(ra, d2), rb1 = cross(rb, d1), rb2 = cross(rb, d2);
  const vec3<T> ia1 = a.inverse_inertia * ra1, ib1 = b.inverse_inertia * rb1;
  const T linear = a.inverse_mass + b.inverse_mass;  // d1 ⟂ d2, so no linear cross term
  const T k11 = linear + dot(ra1, ia1) + dot(rb1, ib1);
  const T k12 = dot(ra2, ia1) + dot(rb2, ib1);
  const T k22 = linear + dot(ra2, a.inverse_inertia * ra2) + dot(rb2, b.inverse_inertia * rb2);
  const T det = k11 * k22 - k12 * k12;
  if (!(det > T(0))) {
    m11 = m12 = m22 = T(0);
    return;
  }
  const T inverse = T(1) / det;
  m11 = k22 * inverse, m12 = -k12 * inverse, m22 = k11 * inverse;
}

/// Velocity of B relative to A at offsets ra, rb.
template <scalar_type T>
[[nodiscard]] vec3<T> relative_velocity(const solver_body<T>& a, const solver_body<T>& b, const vec3<T>& ra,
                                        const vec3<T>& rb) noexcept {
  return b.linear_velocity + cross(b.angular_velocity, rb) - a.linear_velocity - cross(a.angular_velocity, ra);
}

/// Applies impulse j to B at rb and −j to A at ra.
template <scalar_type T>
void apply_impulse(solver_body<T>& a, solver_body<T>& b, const vec3<T>& ra, const vec3<T>& rb,
                   const vec3<T>& j) noexcept {
  a.linear_velocity -= j * a.inverse_mass;
  a.angular_velocity -= a.inverse_inertia * cross(ra, j);
  b.linear_velocity += j * b.inverse_mass;
  b.angular_velocity += b.inverse_inertia * cross(rb, j);
}

}  // namespace impulse
