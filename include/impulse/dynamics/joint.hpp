// impulse/dynamics/joint.hpp — joints between two bodies: ball-and-socket,
// hinge, slider, fixed (weld) and distance (rigid or a spring), each made of
// the parts of constraint_parts.hpp and solved in the same solver as the
// contacts, warm started like them.
//
//   ball      the anchor of A held to the anchor of B (a point part).
//   hinge     a point part, and B's copy of the axis held to A's (two
//             angular rows across it); the angle about the axis may be
//             limited and driven by a motor (one angular row along it).
//   slider    the orientation held (a rotation part) and B's anchor held to
//             the line through A's along the axis (two linear rows across
//             it); the translation may be limited and driven.
//   fixed     a point part and a rotation part.
//   distance  one row along the line between the anchors: rigid, or a
//             spring of given frequency and damping ratio (softness.hpp),
//             implicit, so stable at any stiffness.
//
// Each solver asks the rows for something different (joint_pass):
// sequential_impulse solves them rigidly, and once the bodies have moved
// the world removes the drift by moving them back onto the joints
// (project_joint, non-linear Gauss–Seidel on the positions); soft_step makes
// them stiff springs on each substep, re-measuring the error from where
// the bodies are (Box2D v3's joint softness), then relaxes them rigidly.
//
// Limits are one-sided rows with their own impulses (Box2D's lower and
// upper impulses), speculative like contacts: a joint short of its limit
// may approach it within the step but not pass it.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <span>

#include "../core/error.hpp"
#include "../core/policy.hpp"
#include "../math/quat.hpp"
#include "../math/vec3.hpp"
#include "detail/constraint_parts.hpp"
#include "contact_constraint.hpp"
#include "fwd.hpp"
#include "softness.hpp"

namespace impulse {

enum class joint_type : std::uint8_t { ball, hinge, slider, fixed, distance };

/// What a joint is, as world::create_joint takes it. Anchors and axis are
/// world values at creation; the joint keeps them in the bodies' frames.
/// The factories fill in what each type needs.
template <scalar_type T>
struct joint_def {
  joint_type type = joint_type::ball;
  body_id body_a{}, body_b{};
  /// World point, m: where the joint holds A and B together (a distance
  /// joint's end on A).
  vec3<T> anchor_a{};
  /// World point, m: a distance joint's end on B (the others use anchor_a).
  vec3<T> anchor_b{};
  /// World direction (any length > 0): the hinge's axis of rotation, the
  /// slider's line of travel. The hinge angle is positive about it.
  vec3<T> axis{T(1), T(0), T(0)};
  /// Whether B's angle about the axis (hinge, rad, 0 at creation) or
  /// translation along it (slider, m, 0 at creation) is kept within
  /// [lower, upper].
  bool enable_limit = false;
  T lower = T(0), upper = T(0);
  /// Whether a motor drives B relative to A about (hinge) or along
  /// (slider) the axis at motor_speed (rad/s or m/s), applying at most
  /// max_motor_force (N·m for a hinge, N for a slider).
  bool enable_motor = false;
  T motor_speed = T(0);
  T max_motor_force = T(0);
  /// Distance joint: the anchors' distance it keeps, m.
  T length = T(0);
  /// Distance joint: 0 for a rigid rod; else a spring of this frequency,
  /// Hz (ω = 2πf, stiffness k = m·ω² for an effective mass m), with
  /// damping ratio spring_damping_ratio (1: critically damped).
  T spring_hertz = T(0);
  T spring_damping_ratio = T(0);
  /// The joint breaks, at the end of the first step in which the impulse
  /// it applied exceeds this force (N) or torque (N·m) times the step (a
  /// substep for soft_step). Infinite: unbreakable.
  T break_force = std::numeric_limits<T>::infinity();
  T break_torque = std::numeric_limits<T>::infinity();
  /// Whether the two bodies still collide with each other.
  bool collide_connected = false;
  std::uint64_t user_data = 0;

  static joint_def ball(body_id a, body_id b, const vec3<T>& anchor) noexcept {
    return make(joint_type::ball, a, b, anchor);
  }
  static joint_def hinge(body_id a, body_id b, const vec3<T>& anchor, const vec3<T>& axis) noexcept {
    joint_def d = make(joint_type::hinge, a, b, anchor);
    d.axis = axis;
    return d;
  }
  static joint_def slider(body_id a, body_id b, const vec3<T>& anchor, const vec3<T>& axis) noexcept {
    joint_def d = make(joint_type::slider, a, b, anchor);
    d.axis = axis;
    return d;
  }
  static joint_def fixed(body_id a, body_id b, const vec3<T>& anchor) noexcept {
    return make(joint_type::fixed, a, b, anchor);
  }
  /// A rod (or, with spring_hertz set, a spring) from anchor_a on A to
  /// anchor_b on B, of their present distance.
  static joint_def distance(body_id a, body_id b, const vec3<T>& anchor_a, const vec3<T>& anchor_b) noexcept {
    joint_def d = make(joint_type::distance, a, b, anchor_a);
    d.anchor_b = anchor_b;
    d.length = impulse::length(anchor_b - anchor_a);
    return d;
  }

  /// Refuses what no world could take: non-finite anchors or axis, a zero
  /// axis, limits out of order, negative forces, lengths or rates.
  void validate() const {
    if (!is_finite(anchor_a) || !is_finite(anchor_b) || !is_finite(axis))
      detail::report_error(error_code::non_finite, "joint_def: anchors and axis must be finite");
    if ((type == joint_type::hinge || type == joint_type::slider) && !(length_squared(axis) > T(0)))
      detail::report_error(error_code::invalid_parameter, "joint_def: a hinge or slider needs a non-zero axis");
    if (!std::isfinite(lower) || !std::isfinite(upper) || lower > upper)
      detail::report_error(error_code::invalid_parameter, "joint_def: limits must be finite with lower <= upper");
    const T values[] = {max_motor_force, length, spring_hertz, spring_damping_ratio};
    for (const T v : values)
      if (!std::isfinite(v) || v < T(0))
        detail::report_error(error_code::invalid_parameter,
                             "joint_def: motor force, length and spring rates must be finite and >= 0");
    if (!std::isfinite(motor_speed))
      detail::report_error(error_code::non_finite, "joint_def: motor_speed must be finite");
    if (!(break_force > T(0)) || !(break_torque > T(0)))
      detail::report_error(error_code::invalid_parameter,
                           "joint_def: break_force and break_torque must be > 0 (infinity: unbreakable)");
  }

 private:
  static joint_def make(joint_type type, body_id a, body_id b, const vec3<T>& anchor) noexcept {
    joint_def d;
    d.type = type;
    d.body_a = a, d.body_b = b;
    d.anchor_a = d.anchor_b = anchor;
    return d;
  }
};

/// A joint as the solver sees it: what it holds, in the bodies' frames;
/// the impulses it has accumulated, kept between steps; and its parts and
/// errors, worked out again each step (each substep in soft_step).
template <scalar_type T>
struct joint_constraint {
  joint_type type = joint_type::ball;
  std::uint32_t body_a = 0, body_b = 0;  ///< places in the solver's body array

  // ---- the joint, fixed at creation ----
  vec3<T> local_anchor_a{}, local_anchor_b{};  ///< from each center of mass, body frame, m
  vec3<T> local_axis_a{T(1), T(0), T(0)};      ///< unit, A's frame
  quat<T> reference = quat<T>::identity();      ///< B's orientation in A's frame at creation
  bool enable_limit = false, enable_motor = false;
  T lower = T(0), upper = T(0);
  T motor_speed = T(0), max_motor_force = T(0);
  T length = T(0), spring_hertz = T(0), spring_damping_ratio = T(0);
  /// A spring of absolute stiffness (N/m) and damping (N·s/m) rather than
  /// of a frequency: the world's springs (world::create_spring), whose
  /// stiffness must not change with the masses they pull.
  T spring_stiffness = T(0), spring_damping = T(0);

  /// Whether the distance row is a spring (soft) rather than a rod.
  [[nodiscard]] bool is_spring() const noexcept {
    return spring_hertz > T(0) || spring_stiffness > T(0) || spring_damping > T(0);
  }

  // ---- accumulated, carried to the next step ----
  vec3<T> point_impulse{};     ///< N·s on B, world (ball, hinge, fixed)
  vec3<T> rotation_impulse{};  ///< N·m·s on B, world (fixed, slider)
  T across_impulse[2] = {};    ///< across the axis: N·m·s (hinge), N·s (slider)
  T axial_impulse = T(0);      ///< distance: N·s along the line
  T motor_impulse = T(0), lower_impulse = T(0), upper_impulse = T(0);

  // ---- this step ----
  detail::point_part<T> point;
  detail::rotation_part<T> rotation;
  detail::row_part<T> across[2];
  detail::row_part<T> axial;
  vec3<T> axis{};              ///< world: A's axis (hinge, slider), the line (distance)
  vec3<T> across_axis[2]{};    ///< world, unit, perpendicular to axis
  vec3<T> separation{};        ///< B's anchor less A's, m
  vec3<T> rotation_error{};    ///< rotation vector from where A holds B to where B is, rad
  T across_error[2] = {};      ///< m (slider) or rad (hinge)
  T position = T(0);           ///< hinge angle (rad), slider translation (m), distance (m)
  /// Whether its holding rows are solved exactly with its tree's
  /// (joint_tree.hpp), not here; its limit and motor still are.
  bool in_tree = false;
};

/// What one velocity pass asks of a joint's rows.
template <scalar_type T>
struct joint_pass {
  /// Of the rows that hold (point, rotation, across, a rigid distance):
  /// rigid in sequential_impulse, a stiff spring in soft_step's solve,
  /// rigid again in its relax.
  softness<T> hold = softness<T>::rigid();
  T h = T(1);  ///< the step or substep, s
};

namespace detail {

/// B's angle about A's axis since creation, in (−π, π].
template <scalar_type T>
[[nodiscard]] T twist_angle(const quat<T>& qa, const quat<T>& qb, const joint_constraint<T>& j) noexcept {
  quat<T> d = conjugate(qa) * qb * conjugate(j.reference);
  if (d.w < T(0)) d = d * T(-1);
  return T(2) * portable_atan2(dot(d.vector_part(), j.local_axis_a), d.w);
}

/// The parts, their masses and the joint's errors, from where the bodies
/// are now.
template <scalar_type T>
void prepare_joint(std::span<const solver_body<T>> bodies, joint_constraint<T>& j) noexcept {
  const solver_body<T>& a = bodies[j.body_a];
  const solver_body<T>& b = bodies[j.body_b];
  const vec3<T> ra = rotate(a.orientation, j.local_anchor_a), rb = rotate(b.orientation, j.local_anchor_b);
  j.separation = (b.position + rb) - (a.position + ra);
  const bool holds_point = j.type == joint_type::ball || j.type == joint_type::hinge || j.type == joint_type::fixed;
  const bool holds_rotation = j.type == joint_type::fixed || j.type == joint_type::slider;
  if (holds_point) j.point.prepare(a, b, ra, rb);
  if (holds_rotation) {
    j.rotation.prepare(a, b);
    // E·(q_A·reference) = q_B; for a small E its rotation vector is 2·vec(E).
    quat<T> e = b.orientation * conjugate(j.reference) * conjugate(a.orientation);
    if (e.w < T(0)) e = e * T(-1);
    j.rotation_error = e.vector_part() * T(2);
  }
  switch (j.type) {
    case joint_type::hinge: {
      j.axis = rotate(a.orientation, j.local_axis_a);
      tangents_of(j.axis, j.across_axis[0], j.across_axis[1]);
      // B's copy of the axis, turned from A's by the rotation e (small).
      const vec3<T> axis_b = rotate(b.orientation, inverse_rotate(j.reference, j.local_axis_a));
      const vec3<T> e = cross(j.axis, axis_b);
      for (int i = 0; i < 2; ++i) {
        j.across[i].prepare_angular(a, b, j.across_axis[i]);
        j.across_error[i] = dot(j.across_axis[i], e);
      }
      j.axial.prepare_angular(a, b, j.axis);
      j.position = twist_angle(a.orientation, b.orientation, j);
      break;
    }
    case joint_type::slider: {
      j.axis = rotate(a.orientation, j.local_axis_a);
      tangents_of(j.axis, j.across_axis[0], j.across_axis[1]);
      // A's end of each row is where B's anchor is: the line turns with A
      // about A's center, so A's lever reaches B's anchor.
      const vec3<T> reach = ra + j.separation;
      for (int i = 0; i < 2; ++i) {
        j.across[i].prepare_linear(a, b, reach, rb, j.across_axis[i]);
        j.across_error[i] = dot(j.across_axis[i], j.separation);
      }
      j.axial.prepare_linear(a, b, reach, rb, j.axis);
      j.position = dot(j.axis, j.separation);
      break;
    }
    case joint_type::distance: {
      const T d = impulse::length(j.separation);
      // Anchors that meet give no line: keep the creation direction.
      j.axis = d > T(1e-6) ? j.separation * (T(1) / d) : rotate(a.orientation, j.local_axis_a);
      j.axial.prepare_linear(a, b, ra, rb, j.axis);
      j.position = d;
      break;
    }
    default:
      break;
  }
}

/// The impulse along the axis the motor and limits apply, on B.
template <scalar_type T>
[[nodiscard]] T axis_impulse(const joint_constraint<T>& j) noexcept {
  return j.motor_impulse + j.lower_impulse - j.upper_impulse;
}

/// The last step's impulses applied again. A joint in a tree
/// (joint_tree.hpp) has its limit and motor rows applied here, and its
/// tree applies the rest (joint_tree::warm_start).
template <scalar_type T>
void warm_start_joint(std::span<solver_body<T>> bodies, const joint_constraint<T>& j) noexcept {
  solver_body<T>& a = bodies[j.body_a];
  solver_body<T>& b = bodies[j.body_b];
  const velocity_pair<T> v = real_velocities(a, b);
  if (j.in_tree) {
    if (j.type == joint_type::hinge || j.type == joint_type::slider) j.axial.apply(v, a, b, axis_impulse(j));
    return;
  }
  switch (j.type) {
    case joint_type::ball:
      j.point.apply(v, a, b, j.point_impulse);
      break;
    case joint_type::fixed:
      j.point.apply(v, a, b, j.point_impulse);
      j.rotation.apply(v, a, b, j.rotation_impulse);
      break;
    case joint_type::hinge:
      j.point.apply(v, a, b, j.point_impulse);
      [[fallthrough]];
    case joint_type::slider:
      if (j.type == joint_type::slider) j.rotation.apply(v, a, b, j.rotation_impulse);
      for (int i = 0; i < 2; ++i) j.across[i].apply(v, a, b, j.across_impulse[i]);
      j.axial.apply(v, a, b, axis_impulse(j));
      break;
    case joint_type::distance:
      j.axial.apply(v, a, b, j.axial_impulse);
      break;
  }
}

template <scalar_type T>
void forget_impulses(joint_constraint<T>& j) noexcept {
  j.point_impulse = j.rotation_impulse = {};
  j.across_impulse[0] = j.across_impulse[1] = T(0);
  j.axial_impulse = j.motor_impulse = j.lower_impulse = j.upper_impulse = T(0);
}

/// One velocity pass over a joint's rows: the motor, then the limits, then
/// the rows that hold, which are solved last so that they hold best.
template <scalar_type T>
void solve_joint(std::span<solver_body<T>> bodies, joint_constraint<T>& j, const joint_pass<T>& pass) noexcept {
  solver_body<T>& a = bodies[j.body_a];
  solver_body<T>& b = bodies[j.body_b];
  const velocity_pair<T> v = real_velocities(a, b);
  constexpr T unbounded = std::numeric_limits<T>::infinity();
  const softness<T>& hold = pass.hold;
  if (j.type == joint_type::hinge || j.type == joint_type::slider) {
    if (j.enable_motor) {
      const T most = j.max_motor_force * pass.h;
      j.axial.solve(v, a, b, j.motor_impulse, -j.motor_speed, softness<T>::rigid(), -most, most);
    }
    if (j.enable_limit) {
      // Short of a limit, the joint may reach it within the step
      // (speculative); past it, the hold's softness pushes it back.
      const T to_lower = j.position - j.lower, to_upper = j.upper - j.position;
      const bool lower_apart = to_lower > T(0), upper_apart = to_upper > T(0);
      j.axial.solve(v, a, b, j.lower_impulse, lower_apart ? to_lower / pass.h : hold.bias_rate * to_lower,
                    lower_apart ? softness<T>::rigid() : hold, T(0), unbounded);
      j.axial.solve(v, a, b, j.upper_impulse, upper_apart ? to_upper / pass.h : hold.bias_rate * to_upper,
                    upper_apart ? softness<T>::rigid() : hold, T(0), unbounded, T(-1));
    }
  }
  if (j.in_tree) return;
  if (j.type == joint_type::hinge || j.type == joint_type::slider)
    for (int i = 0; i < 2; ++i)
      j.across[i].solve(v, a, b, j.across_impulse[i], hold.bias_rate * j.across_error[i], hold, -unbounded,
                        unbounded);
  switch (j.type) {
    case joint_type::ball:
    case joint_type::hinge:
      j.point.solve(v, a, b, j.point_impulse, j.separation * hold.bias_rate, hold);
      break;
    case joint_type::fixed:
      j.rotation.solve(v, a, b, j.rotation_impulse, j.rotation_error * hold.bias_rate, hold);
      j.point.solve(v, a, b, j.point_impulse, j.separation * hold.bias_rate, hold);
      break;
    case joint_type::slider:
      j.rotation.solve(v, a, b, j.rotation_impulse, j.rotation_error * hold.bias_rate, hold);
      break;
    case joint_type::distance: {
      const T stretch = j.position - j.length;
      const softness<T> row = j.spring_hertz > T(0) ? soften(j.spring_hertz, j.spring_damping_ratio, pass.h)
                              : j.is_spring()     ? soften_absolute(j.spring_stiffness, j.spring_damping, j.axial.mass, pass.h)
                                                  : hold;
      j.axial.solve(v, a, b, j.axial_impulse, row.bias_rate * stretch, row, -unbounded, unbounded);
      break;
    }
  }
}

/// Moves the two bodies by a position impulse: as apply() would change
/// their velocities over a unit of time.
template <scalar_type T>
struct position_nudge {
  vec3<T> va{}, wa{}, vb{}, wb{};
  velocity_pair<T> pair() noexcept { return {va, wa, vb, wb}; }
  void move(solver_body<T>& a, solver_body<T>& b) const noexcept {
    a.position += va;
    a.orientation = integrate(a.orientation, wa, T(1));
    b.position += vb;
    b.orientation = integrate(b.orientation, wb, T(1));
  }
};

/// One non-linear Gauss–Seidel pass on the positions (Box2D v2's
/// SolvePositionConstraints; Jolt's position steps): the joint's errors
/// measured where the bodies are now, after they moved, and `fraction` of
/// each removed by moving the bodies directly, their velocities untouched.
///
/// Measured after the move, it sees what a correction planned from the
/// start of the step cannot: a body swinging about a pivot leaves it along
/// the tangent by v²·dt²/(2r) a step (2.7 mm at 4.4 m/s on a 1 m
/// pendulum at 60 Hz; a split-impulse pass at 0.2 left it 11.7 mm apart).
///
/// A tree joint's rows that hold are its tree's Newton step's
/// (joint_tree.hpp, project_joints), as they are its exact solve's in
/// solve_joint: only its limit is pushed back here. Once these passes moved
/// a tree's ball joints too, each by `fraction` of its error as if alone,
/// between the Newton steps, undoing part of each: the 100-link chain
/// tapering from 1000 kg at the pivot to 1 kg (tests/faults/test_chains.cpp;
/// sequential_impulse, float) had its projection cut off at the step limit
/// in 9 steps rather than 1, and opened 113 mm rather than 0.09 mm.
template <scalar_type T>
void project_joint(std::span<solver_body<T>> bodies, joint_constraint<T>& j, T fraction, bool limits = true) noexcept {
  const bool limited = (j.type == joint_type::hinge || j.type == joint_type::slider) && j.enable_limit && limits;
  if (j.in_tree && !limited) return;
  solver_body<T>& a = bodies[j.body_a];
  solver_body<T>& b = bodies[j.body_b];
  prepare_joint(std::span<const solver_body<T>>(bodies), j);
  position_nudge<T> n;
  const velocity_pair<T> v = n.pair();
  const softness<T> rigid = softness<T>::rigid();
  constexpr T unbounded = std::numeric_limits<T>::infinity();
  // Each row is solved from no motion (v = 0 in the nudge) for an impulse
  // that removes `fraction` of its error.
  if (limited) {
    const T to_lower = j.position - j.lower, to_upper = j.upper - j.position;
    T pushed = T(0);
    if (to_lower < T(0)) j.axial.solve(v, a, b, pushed, fraction * to_lower, rigid, T(0), unbounded);
    pushed = T(0);
    if (to_upper < T(0)) j.axial.solve(v, a, b, pushed, fraction * to_upper, rigid, T(0), unbounded, T(-1));
  }
  if (j.in_tree) {
    n.move(a, b);
    return;
  }
  if (j.type == joint_type::hinge || j.type == joint_type::slider)
    for (int i = 0; i < 2; ++i) {
      T pushed = T(0);
      j.across[i].solve(v, a, b, pushed, fraction * j.across_error[i], rigid, -unbounded, unbounded);
    }
  vec3<T> pushed{};
  switch (j.type) {
    case joint_type::ball:
    case joint_type::hinge:
      j.point.solve(v, a, b, pushed, j.separation * fraction, rigid);
      break;
    case joint_type::fixed:
      j.rotation.solve(v, a, b, pushed, j.rotation_error * fraction, rigid);
      j.point.solve(v, a, b, pushed, j.separation * fraction, rigid);
      break;
    case joint_type::slider:
      j.rotation.solve(v, a, b, pushed, j.rotation_error * fraction, rigid);
      break;
    case joint_type::distance:
      // A spring has no error to remove: stretching is what it does.
      if (!j.is_spring()) {
        T along = T(0);
        j.axial.solve(v, a, b, along, fraction * (j.position - j.length), rigid, -unbounded, unbounded);
      }
      break;
  }
  n.move(a, b);
}

/// The impulses the joint applied to B this step (A took the opposite):
/// linear, N·s, and angular about B's anchor, N·m·s, both world.
template <scalar_type T>
struct joint_reaction {
  vec3<T> linear{};
  vec3<T> angular{};
};

template <scalar_type T>
[[nodiscard]] joint_reaction<T> reaction_of(const joint_constraint<T>& j) noexcept {
  joint_reaction<T> r;
  const vec3<T> across = j.across_axis[0] * j.across_impulse[0] + j.across_axis[1] * j.across_impulse[1];
  switch (j.type) {
    case joint_type::ball:
      r.linear = j.point_impulse;
      break;
    case joint_type::fixed:
      r.linear = j.point_impulse;
      r.angular = j.rotation_impulse;
      break;
    case joint_type::hinge:
      r.linear = j.point_impulse;
      r.angular = across + j.axis * axis_impulse(j);
      break;
    case joint_type::slider:
      r.linear = across + j.axis * axis_impulse(j);
      r.angular = j.rotation_impulse;
      break;
    case joint_type::distance:
      r.linear = j.axis * j.axial_impulse;
      break;
  }
  return r;
}

}  // namespace detail
}  // namespace impulse
