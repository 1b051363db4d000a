// impulse/dynamics/body_motion.hpp — a rigid body's motion as an ODE.
//
// Baraff's state (SIGGRAPH 2001 course notes, "Rigid Body Simulation") split
// for the partitioned integrators (integrators/ode_state.hpp): the pose
// x = (position, orientation q) and the momenta p = (P, L), with
//     x' = (v, ½ ω⊗q),   p' = (F, τ),   v = P/m,   ω = R·I_body⁻¹·Rᵀ·L.
// Between steps q is a unit quaternion; inside a step the integrators combine
// stage orientations linearly, so q is treated as a point of R⁴. The flow of
// q' = ½ ω⊗q keeps |q| constant (left multiplication by a pure quaternion is
// skew-symmetric), so a method of order k leaves |q| off by O(h^(k+1)) per
// step; R is taken from q/|q| at every stage, and q is renormalised at the
// end of the step. Integrating L rather than ω is what makes free rotation
// right: with no torque L is constant, and the gyroscopic precession of ω
// comes from the turning of R.
#pragma once

#include <cmath>
#include <type_traits>

#include "../math/mat3.hpp"
#include "../math/quat.hpp"
#include "../math/vec3.hpp"
#include "fwd.hpp"
#include "rigid_body.hpp"

namespace impulse {

/// The position part of a body's state: where its center of mass is and how
/// it is turned. Adds and scales as an element of R³ × R⁴.
template <scalar_type T>
struct body_pose {
  vec3<T> position{};
  quat<T> orientation = quat<T>::identity();

  friend constexpr body_pose operator+(const body_pose& a, const body_pose& b) noexcept {
    return {a.position + b.position, a.orientation + b.orientation};
  }
  friend constexpr body_pose operator*(const body_pose& a, T h) noexcept {
    return {a.position * h, a.orientation * h};
  }
};

/// The momentum part: linear momentum P (kg·m/s) and angular momentum L
/// about the center of mass (kg·m²/s), world space. Its rate is the wrench.
template <scalar_type T>
struct body_momentum {
  vec3<T> linear{};
  vec3<T> angular{};

  friend constexpr body_momentum operator+(const body_momentum& a, const body_momentum& b) noexcept {
    return {a.linear + b.linear, a.angular + b.angular};
  }
  friend constexpr body_momentum operator*(const body_momentum& a, T h) noexcept {
    return {a.linear * h, a.angular * h};
  }
};

/// A force (N) through the center of mass and a torque (N·m) about it.
template <scalar_type T>
struct wrench {
  vec3<T> force{};
  vec3<T> torque{};

  constexpr wrench& operator+=(const wrench& w) noexcept {
    force += w.force;
    torque += w.torque;
    return *this;
  }
};

/// Everything a force model may ask of a body at one (possibly speculative)
/// state: where it is, how it is turned, how it moves.
template <scalar_type T>
struct body_kinematics {
  vec3<T> position{};
  quat<T> orientation = quat<T>::identity();  ///< unit
  mat3<T> rotation = mat3<T>::identity();     ///< of `orientation`
  vec3<T> linear_velocity{};
  vec3<T> angular_velocity{};  ///< world, rad/s

  /// World position of a body-space point (relative to the center of mass).
  [[nodiscard]] constexpr vec3<T> point(const vec3<T>& local) const noexcept { return position + rotation * local; }
  /// Velocity of the material point at world position p: v + ω × (p − x).
  [[nodiscard]] constexpr vec3<T> velocity_at(const vec3<T>& p) const noexcept {
    return linear_velocity + cross(angular_velocity, p - position);
  }
};

/// The pose and momenta stored in a body.
template <scalar_type T>
[[nodiscard]] constexpr body_pose<T> pose_of(const rigid_body<T>& b) noexcept {
  return {b.position, b.orientation};
}
template <scalar_type T>
[[nodiscard]] constexpr body_momentum<T> momentum_of(const rigid_body<T>& b) noexcept {
  return {b.linear_momentum, b.angular_momentum};
}

/// Kinematics of body b (its type and mass properties) at state (x, p).
/// Static bodies do not move; kinematic bodies move at their set velocity.
template <scalar_type T>
[[nodiscard]] body_kinematics<T> kinematics_of(const rigid_body<T>& b, const body_pose<T>& x,
                                               const body_momentum<T>& p) noexcept {
  body_kinematics<T> k;
  k.position = x.position;
  k.orientation = x.orientation * (T(1) / length(x.orientation));
  k.rotation = to_mat3(k.orientation);
  if (b.type == body_type::dynamic) {
    k.linear_velocity = p.linear * b.inverse_mass;
    k.angular_velocity = k.rotation * (b.inverse_inertia * (transpose(k.rotation) * p.angular));
  } else if (b.type == body_type::kinematic) {
    k.linear_velocity = b.kinematic_velocity;
    k.angular_velocity = b.kinematic_angular_velocity;
  }
  return k;
}

/// x' = (v, ½ ω⊗q), with q as it stands in x (not renormalised, so that the
/// flow keeps |q| exactly).
template <scalar_type T>
[[nodiscard]] constexpr body_pose<T> pose_rate(const body_kinematics<T>& k, const quat<T>& q) noexcept {
  const vec3<T>& w = k.angular_velocity;
  return {k.linear_velocity, quat<T>{w.x, w.y, w.z, T(0)} * q * T(0.5)};
}

namespace detail {
/// The field used when a step is given none.
struct no_force_field {};
}  // namespace detail

/// A force model evaluated per body: field(id, kinematics) -> wrench (force
/// through the center of mass and torque about it). world::step(dt, field)
/// takes one; it must not change the world.
template <class F, class T>
concept body_force_field = std::is_same_v<std::remove_cvref_t<F>, detail::no_force_field> ||
                           std::is_invocable_r_v<wrench<T>, F&, body_id, const body_kinematics<T>&>;

}  // namespace impulse
