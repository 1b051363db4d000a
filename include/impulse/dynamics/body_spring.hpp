// impulse/dynamics/body_spring.hpp — a damped spring between points of bodies.
//
// Hooke's law plus a dashpot along the spring: with d = p_b − p_a, u = d/|d|,
//     f_a = (k·(|d| − L0) + c·u·(v_b − v_a))·u,   f_b = −f_a,
// each applied at its end point, so a spring at a corner of a cube turns it
// as well as pulling it. Damping acts along the spring only: it removes the
// stretching motion and leaves the swinging alone, like a real coil spring.
// End b is either a point of a second body or a fixed world anchor.
#pragma once

#include <cmath>

#include "../math/vec3.hpp"
#include "body_motion.hpp"
#include "fwd.hpp"

namespace impulse {

template <scalar_type T>
struct body_spring {
  body_id body_a{};       ///< the body at end a
  vec3<T> point_a{};      ///< end a in body_a's space, relative to its center of mass, m
  body_id body_b{};       ///< the body at end b, or none: point_b is a world anchor
  vec3<T> point_b{};      ///< end b in body_b's space, or the world anchor, m
  T stiffness = T(0);     ///< k, N/m, ≥ 0
  T damping = T(0);       ///< c, N·s/m along the spring, ≥ 0
  T rest_length = T(0);   ///< L0, m, ≥ 0

  /// A spring from a fixed world point to a point of one body.
  static constexpr body_spring to_anchor(body_id body, const vec3<T>& local_point, const vec3<T>& anchor,
                                         T stiffness, T damping, T rest_length = T(0)) noexcept {
    return {body, local_point, body_id{}, anchor, stiffness, damping, rest_length};
  }
  /// A spring between a point of body a and a point of body b.
  static constexpr body_spring between(body_id a, const vec3<T>& local_a, body_id b, const vec3<T>& local_b,
                                       T stiffness, T damping, T rest_length = T(0)) noexcept {
    return {a, local_a, b, local_b, stiffness, damping, rest_length};
  }
};

/// Where a spring's ends are and the force on end a (end b bears −force).
template <scalar_type T>
struct spring_load {
  vec3<T> point_a{}, point_b{};  ///< world, m
  vec3<T> force{};               ///< on end a, N
};

/// The spring's load with end a on a body at kinematics `a` and end b on
/// `b`, or at its world anchor when `b` is null. At zero length the
/// direction is undefined and the force is zero.
template <scalar_type T>
[[nodiscard]] spring_load<T> spring_load_of(const body_spring<T>& s, const body_kinematics<T>& a,
                                            const body_kinematics<T>* b) noexcept {
  spring_load<T> load;
  load.point_a = a.point(s.point_a);
  load.point_b = b ? b->point(s.point_b) : s.point_b;
  const vec3<T> d = load.point_b - load.point_a;
  const T len = length(d);
  if (!(len > T(0))) return load;
  const vec3<T> u = d * (T(1) / len);
  const vec3<T> relative = (b ? b->velocity_at(load.point_b) : vec3<T>{}) - a.velocity_at(load.point_a);
  load.force = u * (s.stiffness * (len - s.rest_length) + s.damping * dot(u, relative));
  return load;
}

/// ½·k·(|d| − L0)², J.
template <scalar_type T>
[[nodiscard]] T spring_energy(const body_spring<T>& s, const vec3<T>& point_a, const vec3<T>& point_b) noexcept {
  const T stretch = length(point_b - point_a) - s.rest_length;
  return T(0.5) * s.stiffness * stretch * stretch;
}

}  // namespace impulse
