// impulse/dynamics/soft_step.hpp — the contact solver of Box2D v3: soft
// contact rows on substeps, each followed by a rigid relax pass.
//
// Catto, "Solver2D" (2024) and Box2D v3's solver.c/contact_solver.c. The
// step is cut into n substeps (4). In each: the substep's share of the
// forces, the carried-over impulses once more (warm start), a sweep of
// soft rows, the bodies moved (a straight line, and the torque-free turn
// with L held: free_rotation.hpp), and a sweep of rigid rows without push
// (relax). A soft row treats a penetration as a stiff, heavily damped
// spring (30 Hz, damping ratio 10): it pushes out at a rate set by the
// spring rather than by a Baumgarte fraction, and its mass and impulse
// scales keep the push implicit, so it neither overshoots nor adds energy
// the relax pass does not take out again. The separation is re-measured
// before every sweep from how far the bodies have moved and turned since
// the contact was found, so substeps see the contact close as it closes.
//
// Where the sequential-impulse solver spends iterations, this one spends
// substeps: four substeps of one sweep converge a stack better than ten
// sweeps of one step, because each substep starts from the last one's
// positions. The restitution pass and the friction rows are the same as
// sequential_impulse's (contact_rows.hpp); restitution is applied once,
// before the first substep.
#pragma once

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "../core/policy.hpp"
#include "../math/quat.hpp"
#include "contact_constraint.hpp"
#include "detail/contact_rows.hpp"
#include "joint.hpp"
#include "detail/joint_tree.hpp"
#include "detail/solver_parts.hpp"
#include "softness.hpp"
#include "solver_settings.hpp"

namespace impulse {

template <scalar_type T>
class basic_soft_step {
 public:
  /// Its numbers: the shared ones and its own (solver_settings.hpp).
  using settings_type = soft_step_settings<T>;
  /// It moves the bodies itself, substep by substep (contact_solver.hpp).
  static constexpr bool moves_bodies = true;
  /// Its impulses are per substep.
  static T impulse_step(const settings_type& settings, T dt) noexcept { return dt / T(settings.substeps); }

  /// Whether the turns are fourth order (the world asks for them under a
  /// fourth-order integrator policy; contact_solver.hpp).
  void set_fourth_order_turns(bool fourth) noexcept { fourth_order_ = fourth; }

  void prepare(std::span<const solver_body<T>> bodies, std::span<contact_constraint<T>> contacts) const noexcept {
    detail::prepare_contacts(bodies, contacts);
    for (contact_constraint<T>& c : contacts)
      for (int i = 0; i < c.count; ++i) {
        contact_constraint_point<T>& p = c.points[i];
        p.local_a = inverse_rotate(bodies[c.body_a].orientation, p.offset_a);
        p.local_b = inverse_rotate(bodies[c.body_b].orientation, p.offset_b);
      }
  }

  /// The whole step: velocities solved and bodies moved.
  ///
  /// Joints (joint.hpp) are solved before the contacts in each sweep: stiff
  /// springs (joint_hertz) measured from where the bodies are at each
  /// substep, then rigid in the relax pass. The rows of joint trees are
  /// solved exactly (joint_tree.hpp) and rigidly, asked to close the
  /// springs' bias rate of their error: as springs, the hanging 10:1 chain's
  /// light links sagged 7.6 mm under their load.
  ///
  /// Velocities are left as solved; world::project_joints then calls
  /// project_joints below.
  void solve(std::span<solver_body<T>> bodies, std::span<contact_constraint<T>> contacts,
             std::span<joint_constraint<T>> joints, const settings_type& settings, T dt) {
    const int n = settings.substeps;
    const T h = dt / T(n), inverse_h = T(1) / h, share = T(1) / T(n);
    const T hertz = std::min(settings.contact_hertz, T(0.25) * inverse_h);
    const softness<T> moving = soften(hertz, settings.contact_damping_ratio, h);
    const softness<T> fixed = soften(T(2) * hertz, settings.contact_damping_ratio, h);
    const joint_pass<T> joint_solve{soften(std::min(settings.joint_hertz, T(0.25) * inverse_h),
                                           settings.joint_damping_ratio, h),
                                    h};
    const joint_pass<T> joint_relax{softness<T>::rigid(), h};
    start_.resize(bodies.size());
    synced_.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) start_[i] = bodies[i].position, synced_[i] = bodies[i].angular_velocity;

    detail::restitution_pass(bodies, contacts, settings.restitution_threshold, settings.velocity_iterations,
                             T(0.5) - T(0.5) * share, dt);
    if (!settings.warm_starting)
      for (contact_constraint<T>& c : contacts) detail::forget_impulses(c);
    const std::span<const solver_body<T>> read = bodies;
    tree_.build(read, joints, settings.exact_joint_trees);
    for (int substep = 0; substep < n; ++substep) {
      for (solver_body<T>& b : bodies) {
        b.linear_velocity += b.force_linear * share;
        b.angular_velocity += b.force_angular * share;
      }
      const bool exact = detail::start_joints(tree_, bodies, joints, h, substep == 0 && !settings.warm_starting);
      for (contact_constraint<T>& c : contacts) detail::warm_start(bodies, c);
      for (int i = 0; i < settings.substep_iterations; ++i) {
        for (joint_constraint<T>& j : joints) detail::solve_joint(bodies, j, joint_solve);
        if (exact) tree_.solve_velocities(bodies, joints, joint_solve.hold.bias_rate);
        for (contact_constraint<T>& c : contacts) solve_contact(bodies, c, settings, moving, fixed, inverse_h, true);
      }
      for (std::size_t i = 0; i < bodies.size(); ++i) detail::move_body(bodies[i], synced_[i], h, fourth_order_);
      for (int i = 0; i < settings.relax_iterations; ++i) {
        for (joint_constraint<T>& j : joints) detail::solve_joint(bodies, j, joint_relax);
        if (exact) tree_.solve_velocities(bodies, joints);
        for (contact_constraint<T>& c : contacts) solve_contact(bodies, c, settings, moving, fixed, inverse_h, false);
      }
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) detail::sync_momentum(bodies[i], synced_[i]);
  }

  /// The joints' drift removed once the step is done, as
  /// sequential_impulse does (joint_tree.hpp, project_joints): without it,
  /// the whip of the 10:1 chain's tail, let go from horizontal, opened a
  /// joint 44 mm; with it, 0.004 mm. Limits are left to their soft rows,
  /// as contacts are: pushed back here too, a hinge resting on its limit
  /// bounced on it every step and its torque read 1.1 % high.
  void project_joints(std::span<solver_body<T>> bodies, std::span<joint_constraint<T>> joints,
                      const settings_type& settings) {
    tree_.project_joints(bodies, joints, settings.position_iterations, settings.joint_correction, false);
  }

 private:
  void solve_contact(std::span<solver_body<T>> bodies, contact_constraint<T>& c, const settings_type& settings,
                     const softness<T>& moving, const softness<T>& fixed, T inverse_h, bool push_out) const noexcept {
    solver_body<T>& a = bodies[c.body_a];
    solver_body<T>& b = bodies[c.body_b];
    const softness<T>& soft = a.inverse_mass == T(0) || b.inverse_mass == T(0) ? fixed : moving;
    const vec3<T> moved = (b.position - start_[c.body_b]) - (a.position - start_[c.body_a]);
    for (int sweep = 0; sweep < settings.manifold_sweeps; ++sweep)
      for (int i = 0; i < c.count; ++i) {
        contact_constraint_point<T>& p = c.points[i];
        // The separation now: as found, plus how far the two points have
        // moved apart along the normal since.
        const vec3<T> turned = (rotate(b.orientation, p.local_b) - p.offset_b) -
                               (rotate(a.orientation, p.local_a) - p.offset_a);
        const T separation = dot(c.normal, moved + turned) - p.depth;
        T bias = T(0), mass_scale = T(1), impulse_scale = T(0);
        if (separation > T(0)) {
          bias = separation * inverse_h;  // speculative: close the gap, no more
        } else if (push_out) {
          bias = std::max(soft.bias_rate * std::min(separation + settings.linear_slop, T(0)),
                          -settings.max_correction_speed);
          mass_scale = soft.mass_scale;
          impulse_scale = soft.impulse_scale;
        }
        detail::solve_normal(a.linear_velocity, a.angular_velocity, b.linear_velocity, b.angular_velocity, a, b,
                             c.normal, p, p.normal_impulse, bias, mass_scale, impulse_scale);
      }
    detail::solve_friction(a, b, c);
  }

  std::vector<vec3<T>> start_;   // each body's position at the start of the step
  std::vector<vec3<T>> synced_;  // each body's ω when its L was last brought in step (sync_momentum)
  bool fourth_order_ = false;
  detail::joint_tree<T> tree_;
};

namespace solver {
/// Soft contact rows on substeps with a relax pass, as Box2D v3
/// (dynamics/soft_step.hpp).
struct soft_step {
  static constexpr policy_kind kind = policy_kind::solver;
  template <scalar_type T>
  using type = basic_soft_step<T>;
};
}  // namespace solver

}  // namespace impulse
