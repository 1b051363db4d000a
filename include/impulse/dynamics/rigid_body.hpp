// impulse/dynamics/rigid_body.hpp — Baraff's rigid body state and the loads on it.
//
// The state is Baraff's ("Physically Based Modeling: Rigid Body Dynamics",
// SIGGRAPH 2001 course notes): the position x of the center of mass, the
// orientation quaternion q, the linear momentum P and the angular momentum
// L, all in world space. Velocities are derived, v = P/m and ω = I_w⁻¹·L
// with I_w⁻¹ = R·I_body⁻¹·Rᵀ. Keeping L rather than ω is what makes free
// rotation right without special care: with no torque L is constant exactly,
// and the gyroscopic precession of ω follows from the turning of I_w.
//
// A body is static (never moves, infinite mass), kinematic (moves as told,
// infinite mass: contacts do not push it) or dynamic. Loads accumulate in
// `force` and `torque` (about the center of mass) until the step consumes
// them; impulses change the momenta at once.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "../core/error.hpp"
#include "../math/mat3.hpp"
#include "../math/quat.hpp"
#include "../math/scalar_traits.hpp"
#include "../math/transform.hpp"
#include "../shapes/mass_properties.hpp"
#include "free_rotation.hpp"

namespace impulse {

enum class body_type : std::uint8_t { static_body, kinematic, dynamic };

template <scalar_type T>
struct rigid_body {
  body_type type = body_type::dynamic;

  // ---- state (world space) ----
  vec3<T> position{};                          ///< center of mass, m
  quat<T> orientation = quat<T>::identity();   ///< body to world, unit
  vec3<T> linear_momentum{};                   ///< P, kg·m/s
  vec3<T> angular_momentum{};                  ///< L about the center of mass, kg·m²/s

  // ---- constants (body space) ----
  T mass = T(1);                                        ///< kg; infinite for static and kinematic
  T inverse_mass = T(1);                                ///< 1/kg; 0 for static and kinematic
  mat3<T> inertia = mat3<T>::identity();                ///< I_body about the center of mass, kg·m²
  mat3<T> inverse_inertia = mat3<T>::identity();        ///< I_body⁻¹; zero for static and kinematic
  principal_inertia<T> principal{};                     ///< I_body's moments and axes (free_rotation.hpp)

  // ---- kinematic bodies move at a set velocity (they have no momentum) ----
  vec3<T> kinematic_velocity{};          ///< m/s
  vec3<T> kinematic_angular_velocity{};  ///< rad/s, world

  // ---- accumulated loads, cleared by each step ----
  vec3<T> force{};   ///< N, through the center of mass
  vec3<T> torque{};  ///< N·m, about the center of mass

  /// A dynamic body with the given mass properties (from a shape's
  /// mass_properties_of, or the user's own) placed with its center of mass
  /// at `pose`. Refuses a non-positive or non-finite mass and an inertia
  /// that is not symmetric positive definite.
  static rigid_body dynamic(const mass_properties<T>& p, const transform<T>& pose = transform<T>::identity()) {
    rigid_body b;
    b.type = body_type::dynamic;
    b.set_pose(pose);
    b.set_mass_properties(p);
    return b;
  }
  /// A static (immovable) or kinematic body at `pose`.
  static rigid_body fixed(body_type type, const transform<T>& pose = transform<T>::identity()) {
    if (type == body_type::dynamic)
      detail::report_error(error_code::invalid_parameter, "rigid_body::fixed: a dynamic body needs mass properties");
    rigid_body b;
    b.type = type;
    b.set_pose(pose);
    b.mass = std::numeric_limits<T>::infinity();
    b.inverse_mass = T(0);
    b.inverse_inertia = mat3<T>::zero();
    return b;
  }

  void set_pose(const transform<T>& pose) {
    if (!is_finite(pose.position) || !std::isfinite(pose.rotation.x) || !std::isfinite(pose.rotation.y) ||
        !std::isfinite(pose.rotation.z) || !std::isfinite(pose.rotation.w))
      detail::report_error(error_code::non_finite, "rigid_body: pose is not finite");
    if (!is_normalized(pose.rotation))
      detail::report_error(error_code::not_normalized, "rigid_body: orientation is not a unit quaternion");
    position = pose.position;
    orientation = pose.rotation;
  }

  /// Mass and body-space inertia about the center of mass. The center of
  /// mass in `p` is where the shape's origin sits relative to it; the body
  /// keeps positions of its center of mass, so a shape whose center is off
  /// its origin (a hull) is offset by the caller.
  void set_mass_properties(const mass_properties<T>& p) {
    if (!std::isfinite(p.mass)) detail::report_error(error_code::non_finite, "rigid_body: mass is not finite");
    if (!(p.mass > T(0))) detail::report_error(error_code::non_positive_mass, "rigid_body: mass must be positive");
    const mat3<T>& i = p.inertia;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        if (!std::isfinite(i(r, c))) detail::report_error(error_code::non_finite, "rigid_body: inertia is not finite");
    // Symmetric, and positive definite by Sylvester's criterion; the
    // principal moments of a real solid also obey the triangle inequality
    // (I_a + I_b ≥ I_c), which a hand-made tensor can break.
    const T scale = trace(i), tolerance = T(64) * scalar_traits<T>::epsilon * scale;
    const bool symmetric = std::abs(i(0, 1) - i(1, 0)) <= tolerance && std::abs(i(0, 2) - i(2, 0)) <= tolerance &&
                           std::abs(i(1, 2) - i(2, 1)) <= tolerance;
    const T minor2 = i(0, 0) * i(1, 1) - i(0, 1) * i(1, 0);
    const bool positive = i(0, 0) > T(0) && minor2 > T(0) && determinant(i) > T(0);
    const bool physical = i(0, 0) + i(1, 1) >= i(2, 2) - tolerance && i(1, 1) + i(2, 2) >= i(0, 0) - tolerance &&
                          i(2, 2) + i(0, 0) >= i(1, 1) - tolerance;
    const std::optional<mat3<T>> inverse = try_inverse(i);
    if (!symmetric || !positive || !physical || !inverse)
      detail::report_error(error_code::degenerate_shape,
                           "rigid_body: inertia must be symmetric positive definite (a real solid's)");
    // A mass or moment so small (a denormal) that its inverse overflows
    // would make the first push infinite.
    bool invertible = std::isfinite(T(1) / p.mass);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) invertible = invertible && std::isfinite((*inverse)(r, c));
    if (!invertible)
      detail::report_error(error_code::non_positive_mass,
                           "rigid_body: mass or inertia too small: its inverse is not finite");
    type = body_type::dynamic;
    mass = p.mass;
    inverse_mass = T(1) / p.mass;
    inertia = i;
    inverse_inertia = *inverse;
    principal = principal_inertia_of(i);
  }

  // ---- derived quantities ----

  [[nodiscard]] transform<T> pose() const noexcept { return {position, orientation}; }
  [[nodiscard]] mat3<T> rotation() const noexcept { return to_mat3(orientation); }
  /// I_w⁻¹ = R·I_body⁻¹·Rᵀ.
  [[nodiscard]] mat3<T> inverse_inertia_world() const noexcept {
    const mat3<T> r = rotation();
    return r * inverse_inertia * transpose(r);
  }
  [[nodiscard]] mat3<T> inertia_world() const noexcept {
    const mat3<T> r = rotation();
    return r * inertia * transpose(r);
  }
  [[nodiscard]] vec3<T> linear_velocity() const noexcept {
    if (type == body_type::kinematic) return kinematic_velocity;
    return linear_momentum * inverse_mass;
  }
  [[nodiscard]] vec3<T> angular_velocity() const noexcept {
    if (type == body_type::kinematic) return kinematic_angular_velocity;
    return inverse_inertia_world() * angular_momentum;
  }
  /// Velocity of the material point now at world point p: v + ω × (p − x).
  [[nodiscard]] vec3<T> velocity_at(const vec3<T>& p) const noexcept {
    return linear_velocity() + cross(angular_velocity(), p - position);
  }
  /// ½·m·v² + ½·ω·L, J (0 for static and kinematic bodies, whose mass is infinite).
  [[nodiscard]] T kinetic_energy() const noexcept {
    if (type != body_type::dynamic) return T(0);
    return T(0.5) * (dot(linear_momentum, linear_velocity()) + dot(angular_velocity(), angular_momentum));
  }

  /// Sets the velocities: the momenta P = m·v, L = I_w·ω of a dynamic body,
  /// the velocities of a kinematic one. A static body refuses.
  void set_velocity(const vec3<T>& v, const vec3<T>& omega) {
    if (!is_finite(v) || !is_finite(omega)) detail::report_error(error_code::non_finite, "rigid_body: velocity is not finite");
    if (type == body_type::static_body)
      detail::report_error(error_code::invalid_parameter, "rigid_body: a static body cannot be given a velocity");
    if (type == body_type::kinematic) {
      kinematic_velocity = v;
      kinematic_angular_velocity = omega;
      return;
    }
    const vec3<T> linear = v * mass, angular = inertia_world() * omega;
    // Finite velocities can still give infinite momenta (1e35 m/s on
    // 8 000 kg, in float): refused here, where the caller can be told.
    if (!is_finite(linear) || !is_finite(angular))
      detail::report_error(error_code::non_finite, "rigid_body: the velocity overflows the body's momentum");
    linear_momentum = linear;
    angular_momentum = angular;
  }

  // ---- loads ----
  // Each load is checked, then added only if the sums stay finite: two
  // finite forces of 3e38 N add to infinity in float, which the next step
  // would find too late to say which call caused it.

  void apply_force(const vec3<T>& f) {
    require_finite(f, "rigid_body: force is not finite");
    const vec3<T> total = force + f;
    require_finite(total, "rigid_body: the force overflows the forces already applied this step");
    force = total;
  }
  void apply_torque(const vec3<T>& t) {
    require_finite(t, "rigid_body: torque is not finite");
    const vec3<T> total = torque + t;
    require_finite(total, "rigid_body: the torque overflows the torques already applied this step");
    torque = total;
  }
  /// A force at world point p: the force, and its moment (p − x) × f.
  void apply_force_at(const vec3<T>& f, const vec3<T>& p) {
    require_finite(f, "rigid_body: force is not finite");
    require_finite(p, "rigid_body: point is not finite");
    const vec3<T> total_force = force + f, total_torque = torque + cross(p - position, f);
    require_finite(total_force, "rigid_body: the force overflows the forces already applied this step");
    require_finite(total_torque, "rigid_body: the force's moment about the center of mass overflows");
    force = total_force;
    torque = total_torque;
  }
  /// An impulse j at world point p changes the momenta at once: ΔP = j,
  /// ΔL = (p − x) × j. Static and kinematic bodies are not moved by it.
  void apply_impulse_at(const vec3<T>& j, const vec3<T>& p) {
    require_finite(j, "rigid_body: impulse is not finite");
    require_finite(p, "rigid_body: point is not finite");
    if (type != body_type::dynamic) return;
    const vec3<T> linear = linear_momentum + j, angular = angular_momentum + cross(p - position, j);
    require_finite(linear, "rigid_body: the impulse overflows the body's momentum");
    require_finite(angular, "rigid_body: the impulse's moment overflows the body's angular momentum");
    linear_momentum = linear;
    angular_momentum = angular;
  }
  void clear_loads() noexcept { force = {}, torque = {}; }

 private:
  static void require_finite(const vec3<T>& v, const char* message) {
    if (!is_finite(v)) detail::report_error(error_code::non_finite, message);
  }
};

}  // namespace impulse
