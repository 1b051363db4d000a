// impulse/dynamics/detail/solver_parts.hpp — what both shipped solvers do at
// each part (substep) of a step, as solvers that move the bodies themselves
// (contact_solver.hpp, moves_bodies): the joints prepared and warm started
// where the bodies are, and the bodies moved, with each body's angular
// momentum kept in step with the ω its rows change.
//
// A body moves in a straight line and turns torque-free with its L held
// (free_rotation.hpp), so the gyroscopic motion, ω turning as the body
// turns, needs no term of its own; ω and I_w⁻¹ are then those of the pose
// reached.
#pragma once

#include <span>

#include "../../math/mat3.hpp"
#include "../../math/quat.hpp"
#include "../../math/vec3.hpp"
#include "../contact_constraint.hpp"
#include "../free_rotation.hpp"
#include "../joint.hpp"
#include "joint_tree.hpp"

namespace impulse::detail {

/// The joints at the start of a part of h: each prepared where the bodies
/// are now and its impulses applied again (forgotten first, with
/// `forget`), and the tree's loads gathered over h and its rows factored
/// and warm started where it can. True when the tree's rows are solved
/// exactly in this part.
template <scalar_type T>
bool start_joints(joint_tree<T>& tree, std::span<solver_body<T>> bodies, std::span<joint_constraint<T>> joints, T h,
                  bool forget) {
  const std::span<const solver_body<T>> read = bodies;
  tree.clear_loads();
  for (joint_constraint<T>& j : joints) {
    prepare_joint(read, j);
    tree.add_load(read, j, h);
    if (forget) forget_impulses(j);
    warm_start_joint(bodies, j);
  }
  const bool exact = !tree.empty() && tree.factor(read, joints);
  if (exact) tree.warm_start(bodies, joints);
  return exact;
}

/// L changed by I_w times what forces and rows did to ω since it was last
/// in step with it (`synced`). Only that change passes through I_w:
/// converting L to ω and back at every substep drifted |L| in float by
/// 1.4 % in 10⁴ steps of a free body, and with nothing acting on the body
/// its L stays the same to the bit.
template <scalar_type T>
void sync_momentum(solver_body<T>& b, vec3<T>& synced) noexcept {
  if (b.inverse_mass == T(0)) return;
  const principal_inertia<T>& p = b.principal;
  const quat<T> turned = p.own_axes ? b.orientation : b.orientation * p.axes;
  const vec3<T> change = inverse_rotate(turned, b.angular_velocity - synced);
  b.angular_momentum += rotate(turned, vec3<T>{change.x * p.moments.x, change.y * p.moments.y, change.z * p.moments.z});
  synced = b.angular_velocity;
}

/// I_w⁻¹ and ω = I_w⁻¹·L of the pose a body has reached, its L held (in
/// step with ω beforehand).
template <scalar_type T>
void reorient_inertia(solver_body<T>& b, vec3<T>& synced) noexcept {
  const principal_inertia<T>& p = b.principal;
  // I_w⁻¹ = Σ (1/I_i)·r_i·r_iᵀ over the principal axes r_i in the world;
  // 1/I_i is the reference's rate plus axis i's.
  const mat3<T> axes = to_mat3(p.own_axes ? b.orientation : b.orientation * p.axes);
  b.inverse_inertia = outer(axes.col[0], axes.col[0] * (p.rate + p.rates.x)) +
                      outer(axes.col[1], axes.col[1] * (p.rate + p.rates.y)) +
                      outer(axes.col[2], axes.col[2] * (p.rate + p.rates.z));
  b.angular_velocity = b.inverse_inertia * b.angular_momentum;
  synced = b.angular_velocity;
}

/// Moves a body over h: its center in a straight line at its velocity plus
/// `push`, and the torque-free turn with its L held, `spin` turned with the
/// turn about L (`push` and `spin` are a position pass's pseudo-velocities,
/// sequential_impulse.hpp). Fourth order in the turn under a fourth-order
/// integrator policy. Static, kinematic and held bodies (no mass) turn at
/// the ω they have.
template <scalar_type T>
void move_body(solver_body<T>& b, vec3<T>& synced, T h, bool fourth_order, const vec3<T>& push = {},
               const vec3<T>& spin = {}) noexcept {
  b.position += (b.linear_velocity + push) * h;
  const principal_inertia<T>& p = b.principal;
  // A body whose moments are all equal (a sphere, a cube) has the same
  // I_w at every pose: it turns exactly at the ω it has.
  if (b.inverse_mass == T(0) || p.isotropic()) {
    b.orientation = integrate(b.orientation, b.angular_velocity + spin, h);
    return;
  }
  sync_momentum(b, synced);
  b.orientation = free_turn(b.orientation, p, b.angular_momentum, h, fourth_order, spin);
  reorient_inertia(b, synced);
}

}  // namespace impulse::detail
