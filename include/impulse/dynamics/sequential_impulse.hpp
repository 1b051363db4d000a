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
// 2. Restitution: contacts approaching faster than the threshold are made
//    to separate at e times their approach speed, pairwise and in sequence
//    (contact_rows.hpp, restitution_pass, says why not inside the
//    iterations).
// 3. Warm start: each point's impulses from the last step, matched by
//    feature id, are applied again.
// 4. Velocity iterations: per manifold, friction at the patch (two tangent
//    rows within the Coulomb disc of the patch's normal impulse and a
//    twist row), then a few passes over the points' normal rows, clamped
//    to push only (solver_settings.hpp, manifold_sweeps, says why more
//    than one). A row that starts apart (a speculative contact, depth < 0)
//    or shallower than the rest depth may sink to that depth within the
//    step but no further (solver_settings.hpp, rest_depth, says why not to
//    zero). The manifolds are
//    visited color by color, W that share no moving body at a time in
//    SIMD lanes (constraint_graph.hpp, contact_batch.hpp); a manifold no
//    color could take is solved alone after them.
// 5. Position pass (split impulses; Catto's "Box2D: the position problem",
//    Bullet's split impulse): the normal rows once more on separate
//    pseudo-velocities, pushing penetration beyond the slop out at a
//    fraction per step. Those velocities move the bodies this step and are
//    dropped, so correcting a penetration adds no kinetic energy: a
//    Baumgarte term in the velocity rows would turn every correction into
//    a bounce, and a box landing in a stack would pop the one beneath.
//    Non-linear Gauss–Seidel on positions (Box2D v2) does the same at the
//    cost of a contact re-evaluation per iteration.
// Joints (joint.hpp) take part in steps 3 and 4, before the contacts of
// each iteration, rigid; those that form trees have their rows solved all
// at once, exactly (joint_tree.hpp). Their drift is removed once the bodies
// have moved (project_joints: non-linear Gauss–Seidel on the poses, which
// sees the drift that a pass planned from the start of the step cannot,
// and a Newton step on the trees).
// The world then moves the bodies with the solved velocities plus the
// pseudo-velocities, turning each with its L held (free_rotation.hpp).
#pragma once

#include <algorithm>
#include <span>
#include <vector>

#include "../core/policy.hpp"
#include "detail/constraint_graph.hpp"
#include "detail/contact_batch.hpp"
#include "contact_constraint.hpp"
#include "detail/contact_rows.hpp"
#include "joint.hpp"
#include "detail/joint_tree.hpp"
#include "solver_settings.hpp"

namespace impulse {

template <scalar_type T>
class basic_sequential_impulse {
 public:
  /// Its numbers: the shared ones and its own (solver_settings.hpp).
  using settings_type = sequential_impulse_settings<T>;
  /// The world moves the bodies after the solve (contact_solver.hpp).
  static constexpr bool moves_bodies = false;
  /// Its impulses act over the whole step.
  static T impulse_step(const settings_type&, T dt) noexcept { return dt; }

  void prepare(std::span<const solver_body<T>> bodies, std::span<contact_constraint<T>> contacts) const noexcept {
    detail::prepare_contacts(bodies, contacts);
  }

  /// Steps 1–5 above: the velocities and pseudo-velocities of the step.
  /// Steps 4 and 5 run on batches of contacts that share no moving body
  /// (constraint_graph.hpp), W at a time in SIMD lanes (contact_batch.hpp).
  ///
  /// Joints (joint.hpp) are solved rigidly in the same iterations, before
  /// the contacts of each; project_joints removes their drift once the
  /// bodies have moved.
  void solve(std::span<solver_body<T>> bodies, std::span<contact_constraint<T>> contacts,
             std::span<joint_constraint<T>> joints, const settings_type& settings, T dt) {
    const T inverse_dt = T(1) / dt;
    for (solver_body<T>& b : bodies) {
      b.linear_velocity += b.force_linear;
      b.angular_velocity += b.force_angular;
      b.bias_linear = {};
      b.bias_angular = {};
    }
    detail::restitution_pass(bodies, contacts, settings.restitution_threshold, settings.velocity_iterations, T(1),
                             dt);
    for (contact_constraint<T>& c : contacts) {
      if (settings.warm_starting) {
        detail::warm_start(bodies, c);
      } else {
        detail::forget_impulses(c);
      }
    }
    const std::span<const solver_body<T>> read = bodies;
    tree_.build(read, joints, settings.exact_joint_trees);
    for (joint_constraint<T>& j : joints) {
      detail::prepare_joint(read, j);
      tree_.add_load(read, j, dt);
      if (settings.warm_starting) {
        detail::warm_start_joint(bodies, j);
      } else {
        detail::forget_impulses(j);
      }
    }
    const joint_pass<T> rigid_pass{softness<T>::rigid(), dt};
    for (contact_constraint<T>& c : contacts) row_targets(c, settings, inverse_dt);
    if (!tree_.empty() && tree_.factor(read, joints)) tree_.warm_start(bodies, joints);
    graph_.build(read, std::span<const contact_constraint<T>>(contacts), width);
    batches_.resize(graph_.batch_count());
    rows_.clear();
    for (std::size_t k = 0; k < batches_.size(); ++k)
      detail::load_batch(read, std::span<const contact_constraint<T>>(contacts), graph_.batch(k), batches_[k],
                         rows_);
    constexpr auto real = detail::velocity_kind::real, pseudo = detail::velocity_kind::pseudo;
    for (int iteration = 0; iteration < settings.velocity_iterations; ++iteration) {
      for (joint_constraint<T>& j : joints) detail::solve_joint(bodies, j, rigid_pass);
      if (!tree_.empty()) tree_.solve_velocities(bodies, joints);
      // Forward through the colors, then back (symmetric Gauss–Seidel):
      // always forward, support climbed a 100-row pyramid one color at a
      // time and its boxes moved 12 cm in 200 steps; alternating, 6 mm.
      for (std::size_t k = 0; k < batches_.size(); ++k) {
        batch_type& b = batches_[iteration % 2 == 0 ? k : batches_.size() - 1 - k];
        detail::batch_velocities<T, width> v = detail::gather(read, b, real);
        // Friction first: it is bounded by the normal impulses, and the
        // normal rows, solved last, are the ones that must hold (no sinking).
        detail::solve_batch_friction(v, b, rows_of(b));
        detail::solve_batch_normals(v, b, rows_of(b), settings.manifold_sweeps, false);
        detail::scatter(bodies, b, v, real);
      }
      for (const std::uint32_t i : graph_.leftover()) solve_velocity(bodies, contacts[i], settings);
    }
    for (int iteration = 0; iteration < settings.position_iterations; ++iteration) {
      for (batch_type& b : batches_) {
        detail::batch_velocities<T, width> v = detail::gather(read, b, pseudo);
        detail::solve_batch_normals(v, b, rows_of(b), settings.manifold_sweeps, true);
        detail::scatter(bodies, b, v, pseudo);
      }
      for (const std::uint32_t i : graph_.leftover()) solve_position(bodies, contacts[i], settings);
    }
    for (const batch_type& b : batches_) detail::store_batch(b, rows_of(b), contacts);
  }

  /// Non-linear Gauss–Seidel on the joints, position_iterations passes
  /// over the bodies' poses after they have moved (joint.hpp,
  /// project_joint), each with a Newton step on the joint trees
  /// (joint_tree.hpp).
  void project_joints(std::span<solver_body<T>> bodies, std::span<joint_constraint<T>> joints,
                      const settings_type& settings) {
    tree_.project_joints(bodies, joints, settings.position_iterations, settings.joint_correction, true);
  }

 private:
  static constexpr int width = detail::contact_lanes<T>;
  using batch_type = detail::contact_batch<T, width>;
  using row_type = detail::batch_row<T, width>;

  detail::constraint_graph graph_;
  detail::joint_tree<T> tree_;
  std::vector<batch_type> batches_;
  std::vector<row_type> rows_;

  std::span<row_type> rows_of(const batch_type& b) noexcept {
    return std::span<row_type>(rows_).subspan(b.first_row, std::size_t(b.rows_used));
  }

  /// One manifold's rows, one after another: the manifolds the coloring
  /// left over.
  static void solve_velocity(std::span<solver_body<T>> bodies, contact_constraint<T>& c,
                             const settings_type& settings) noexcept {
    solver_body<T>& a = bodies[c.body_a];
    solver_body<T>& b = bodies[c.body_b];
    // Friction first, as in the batches (solve above).
    detail::solve_friction(a, b, c);
    for (int sweep = 0; sweep < settings.manifold_sweeps; ++sweep)
      for (int i = 0; i < c.count; ++i) {
        contact_constraint_point<T>& p = c.points[i];
        detail::solve_normal(a.linear_velocity, a.angular_velocity, b.linear_velocity, b.angular_velocity, a, b,
                             c.normal, p, p.normal_impulse, p.gap_speed);
      }
  }

  /// What the rows ask of each point. The velocity row: vn ≥ −gap_speed,
  /// a point shallower than the rest depth (or apart by a gap) may sink to
  /// it within the step but no further. The position pass: to separate at
  /// a fraction of the penetration beyond the slop per step; < 0 when the
  /// point lies within the slop and takes no part.
  static void row_targets(contact_constraint<T>& c, const settings_type& settings, T inverse_dt) noexcept {
    for (int i = 0; i < c.count; ++i) {
      contact_constraint_point<T>& p = c.points[i];
      p.gap_speed = p.depth < settings.rest_depth ? (settings.rest_depth - p.depth) * inverse_dt : T(0);
      p.push_speed = p.depth > settings.linear_slop
                         ? std::min(settings.position_correction * (p.depth - settings.linear_slop) * inverse_dt,
                                    settings.max_correction_speed)
                         : T(-1);
    }
  }

  static void solve_position(std::span<solver_body<T>> bodies, contact_constraint<T>& c,
                             const settings_type& settings) noexcept {
    solver_body<T>& a = bodies[c.body_a];
    solver_body<T>& b = bodies[c.body_b];
    for (int sweep = 0; sweep < settings.manifold_sweeps; ++sweep)
      for (int i = 0; i < c.count; ++i) {
        contact_constraint_point<T>& p = c.points[i];
        if (p.push_speed < T(0)) continue;
        detail::solve_normal(a.bias_linear, a.bias_angular, b.bias_linear, b.bias_angular, a, b, c.normal, p,
                             p.bias_impulse, -p.push_speed);
      }
  }
};

namespace solver {
/// Projected Gauss–Seidel with warm starting, a restitution pass and split
/// impulses (dynamics/sequential_impulse.hpp).
struct sequential_impulse {
  static constexpr policy_kind kind = policy_kind::solver;
  template <scalar_type T>
  using type = basic_sequential_impulse<T>;
};
}  // namespace solver

}  // namespace impulse
