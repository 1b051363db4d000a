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
// the contact was found (to first order in the turns, as
// sequential_impulse's parts: contact_batch.hpp, depths_now), so substeps
// see the contact close as it closes.
//
// The rows, their colors and their SIMD batches are those of
// sequential_impulse, worked out once a step: each sweep takes the colors
// in order, the W manifolds of a batch in SIMD lanes (constraint_graph.hpp,
// contact_batch.hpp), as Box2D v3's solver does. One manifold after
// another, the same sweeps cost 4.9 times as much on `pyramid`.
//
// Where the sequential-impulse solver spends iterations, this one spends
// substeps: four substeps of one sweep converge a stack better than ten
// sweeps of one step, because each substep starts from the last one's
// positions. The restitution pass and the friction rows are the same as
// sequential_impulse's (contact_rows.hpp); restitution is applied once,
// before the first substep.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "../core/policy.hpp"
#include "../core/task_system.hpp"
#include "contact_constraint.hpp"
#include "detail/constraint_graph.hpp"
#include "detail/contact_batch.hpp"
#include "detail/contact_rows.hpp"
#include "joint.hpp"
#include "detail/joint_tree.hpp"
#include "detail/solver_parts.hpp"
#include "detail/solver_stages.hpp"
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

  /// Spreads the solve's loops across the hook's workers, as
  /// sequential_impulse does (solver_stages.hpp): the bodies come out the
  /// same, bit for bit, for any worker count.
  void set_task_system(const task_system& tasks) noexcept { stages_.set_task_system(tasks); }

  void prepare(std::span<const solver_body<T>> bodies, std::span<contact_constraint<T>> contacts) const noexcept;

  /// The whole step: velocities solved and bodies moved.
  ///
  /// The contacts, their rows, their colors and their SIMD batches are
  /// worked out once a step (constraint_graph.hpp, contact_batch.hpp), as
  /// sequential_impulse's are; each sweep takes the colors in turn, the
  /// W manifolds of a batch at once in SIMD lanes.
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
             std::span<joint_constraint<T>> joints, const settings_type& settings, T dt);

  /// The joints' drift removed once the step is done, as
  /// sequential_impulse does (joint_tree.hpp, project_joints): without it,
  /// the whip of the 10:1 chain's tail, let go from horizontal, opened a
  /// joint 44 mm; with it, 0.004 mm. Limits are left to their soft rows,
  /// as contacts are: pushed back here too, a hinge resting on its limit
  /// bounced on it every step and its torque read 1.1 % high.
  void project_joints(std::span<solver_body<T>> bodies, std::span<joint_constraint<T>> joints,
                      const settings_type& settings);
  /// The colors of the last solve's contacts.
  [[nodiscard]] std::size_t color_count() const noexcept { return graph_.color_count(); }

 private:
  static constexpr int width = detail::contact_lanes<T>;
  using batch_type = detail::contact_batch<T, width>;
  using row_type = detail::batch_row<T, width>;
  using displacement = detail::body_displacement<T>;
  static constexpr std::uint32_t min_batches = detail::solver_stages::min_batches;
  static constexpr std::uint32_t min_bodies = detail::solver_stages::min_bodies;

  void solve_stages(std::span<solver_body<T>> bodies, std::span<contact_constraint<T>> contacts,
                    std::span<joint_constraint<T>> joints, const settings_type& settings, T dt) {
    const int n = settings.substeps;
    const T h = dt / T(n), inverse_h = T(1) / h, share = T(1) / T(n);
    const T hertz = std::min(settings.contact_hertz, T(0.25) * inverse_h);
    moving_ = soften(hertz, settings.contact_damping_ratio, h);
    fixed_ = soften(T(2) * hertz, settings.contact_damping_ratio, h);
    const joint_pass<T> joint_solve{soften(std::min(settings.joint_hertz, T(0.25) * inverse_h),
                                           settings.joint_damping_ratio, h),
                                    h};
    const joint_pass<T> joint_relax{softness<T>::rigid(), h};
    synced_.resize(bodies.size());
    moved_.assign(bodies.size(), {});
    auto start_bodies = [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) synced_[i] = moved_[i].spin = bodies[i].angular_velocity;
    };
    stages_.each_index(bodies.size(), min_bodies, start_bodies);

    detail::restitution_pass(bodies, contacts, settings.restitution_threshold, settings.velocity_iterations,
                             T(0.5) - T(0.5) * share, dt);
    if (!settings.warm_starting)
      for (contact_constraint<T>& c : contacts) detail::forget_impulses(c);
    const std::span<const solver_body<T>> read = bodies;
    tree_.build(read, joints, settings.exact_joint_trees);
    graph_.build(read, std::span<const contact_constraint<T>>(contacts), width);
    leftover_slips_.clear();
    for (const std::uint32_t i : graph_.leftover())
      leftover_slips_.push_back({contacts[i].slip_target1, contacts[i].slip_target2});
    // Each batch's rows placed first, then the batches loaded side by side.
    batches_.resize(graph_.batch_count());
    rows_.resize(detail::place_batch_rows(graph_, std::span<const contact_constraint<T>>(contacts), first_rows_));
    auto load = [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        detail::load_batch(read, std::span<const contact_constraint<T>>(contacts), graph_.batch(k), batches_[k],
                           std::span<row_type>(rows_), first_rows_[k]);
        detail::soften_batch(batches_[k], moving_, fixed_);
      }
    };
    stages_.each_index(batches_.size(), min_batches, load);
    retarget(read, contacts, settings, inverse_h);
    constexpr auto real = detail::velocity_kind::real;
    auto forces = [&](std::size_t begin, std::size_t end) {
      for (solver_body<T>& b : bodies.subspan(begin, end - begin)) {
        b.linear_velocity += b.force_linear * share;
        b.angular_velocity += b.force_angular * share;
      }
    };
    auto warm_start = [&](auto written, std::span<batch_type> range, bool) {
      for (batch_type& b : range) {
        detail::batch_velocities<T, width> v = detail::gather(read, b, real);
        detail::warm_start_batch(v, b, rows_of(b));
        detail::scatter(bodies, b, v, real, written);
      }
    };
    auto move = [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        solver_body<T>& b = bodies[i];
        moved_[i].linear += b.linear_velocity * h;
        moved_[i].angular += b.angular_velocity * h;
        detail::move_body(b, synced_[i], h, fourth_order_);
      }
    };
    for (int substep = 0; substep < n; ++substep) {
      stages_.each_index(bodies.size(), min_bodies, forces);
      const bool exact = detail::start_joints(tree_, bodies, joints, h, substep == 0 && !settings.warm_starting);
      stages_.by_color(graph_, std::span<batch_type>(batches_), false, warm_start);
      for (const std::uint32_t i : graph_.leftover()) detail::warm_start(bodies, contacts[i]);
      for (int i = 0; i < settings.substep_iterations; ++i) {
        for (joint_constraint<T>& j : joints) detail::solve_joint(bodies, j, joint_solve);
        if (exact) tree_.solve_velocities(bodies, joints, joint_solve.hold.bias_rate);
        sweep<detail::normal_pass::soft>(bodies, contacts, settings);
      }
      stages_.each_index(bodies.size(), min_bodies, move);
      retarget(read, contacts, settings, inverse_h);
      for (int i = 0; i < settings.relax_iterations; ++i) {
        for (joint_constraint<T>& j : joints) detail::solve_joint(bodies, j, joint_relax);
        if (exact) tree_.solve_velocities(bodies, joints);
        sweep<detail::normal_pass::relax>(bodies, contacts, settings);
      }
    }
    auto store = [&](std::span<batch_type> range) {
      for (const batch_type& b : range) detail::store_batch(b, rows_of(b), contacts);
    };
    stages_.each_batch(std::span<batch_type>(batches_), store);
    auto sync = [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) detail::sync_momentum(bodies[i], synced_[i]);
    };
    stages_.each_index(bodies.size(), min_bodies, sync);
  }

  std::span<row_type> rows_of(const batch_type& b) noexcept {
    return std::span<row_type>(rows_).subspan(b.first_row, std::size_t(b.rows_used));
  }

  /// Every row's targets where the bodies are now, from how far they have
  /// moved since the contacts were found: those of the relax sweep that
  /// follows and of the next substep's soft sweep (soft_targets_batch).
  void retarget(std::span<const solver_body<T>> bodies, std::span<contact_constraint<T>> contacts,
                const settings_type& settings, T inverse_h) {
    const std::span<const displacement> moved = moved_;
    const T slop = settings.linear_slop, fastest = settings.max_correction_speed;
    auto aim = [&](std::span<batch_type> range) {
      for (batch_type& b : range) detail::soft_targets_batch(b, rows_of(b), moved, slop, fastest, inverse_h);
    };
    stages_.each_batch(std::span<batch_type>(batches_), aim);
    for (std::size_t k = 0; k < graph_.leftover().size(); ++k) {
      contact_constraint<T>& c = contacts[graph_.leftover()[k]];
      detail::turn_slip_targets(c, moved, leftover_slips_[k]);
      const T rate = softness_of(bodies, c).bias_rate;
      for (int i = 0; i < c.count; ++i) {
        contact_constraint_point<T>& p = c.points[i];
        const T depth = detail::depth_now(c, p, moved);
        p.gap_speed = std::max(-depth, T(0)) * inverse_h;
        p.push_speed = std::min(rate * std::max(depth - slop, T(0)), fastest);
      }
    }
  }

  /// A contact's softness: stiffer where a body cannot move.
  const softness<T>& softness_of(std::span<const solver_body<T>> bodies, const contact_constraint<T>& c) const {
    return bodies[c.body_a].inverse_mass == T(0) || bodies[c.body_b].inverse_mass == T(0) ? fixed_ : moving_;
  }

  /// One sweep over the contacts: the colors in turn, each batch's normal
  /// rows and then its friction; then the manifolds left over, one by one.
  template <detail::normal_pass Pass>
  void sweep(std::span<solver_body<T>> bodies, std::span<contact_constraint<T>> contacts,
             const settings_type& settings) {
    constexpr auto real = detail::velocity_kind::real;
    const std::span<const solver_body<T>> read = bodies;
    auto pass = [&](auto written, std::span<batch_type> range, bool) {
      for (batch_type& b : range) {
        detail::batch_velocities<T, width> v = detail::gather(read, b, real);
        detail::solve_batch_normals<Pass>(v, b, rows_of(b), settings.manifold_sweeps);
        detail::solve_batch_friction(v, b, rows_of(b));
        detail::scatter(bodies, b, v, real, written);
      }
    };
    stages_.by_color(graph_, std::span<batch_type>(batches_), false, pass);
    for (const std::uint32_t i : graph_.leftover()) {
      contact_constraint<T>& c = contacts[i];
      solver_body<T>& a = bodies[c.body_a];
      solver_body<T>& b = bodies[c.body_b];
      const softness<T>& soft = softness_of(read, c);
      for (int s = 0; s < settings.manifold_sweeps; ++s)
        for (int k = 0; k < c.count; ++k) {
          contact_constraint_point<T>& p = c.points[k];
          const bool pushing = Pass == detail::normal_pass::soft && p.gap_speed <= T(0);
          detail::solve_normal(a.linear_velocity, a.angular_velocity, b.linear_velocity, b.angular_velocity, a, b,
                               c.normal, p, p.normal_impulse, pushing ? -p.push_speed : p.gap_speed,
                               pushing ? soft.mass_scale : T(1), pushing ? soft.impulse_scale : T(0));
        }
      detail::solve_friction(a, b, c);
    }
  }

  detail::solver_stages stages_;
  detail::constraint_graph graph_;
  detail::joint_tree<T> tree_;
  std::vector<batch_type> batches_;
  std::vector<row_type> rows_;
  std::vector<std::uint32_t> first_rows_;  ///< each batch's first row in rows_
  std::vector<std::pair<T, T>> leftover_slips_;  // the leftover manifolds' slip targets at the start
  std::vector<displacement> moved_;  // each body's displacement since the start of the step
  std::vector<vec3<T>> synced_;      // each body's ω when its L was last brought in step (solver_parts.hpp)
  softness<T> moving_, fixed_;       // of contacts between moving bodies, and with one that cannot move
  bool fourth_order_ = false;
};

// The entry points out of the class, as sequential_impulse's are: a
// program's extern declaration (core/extern_templates.hpp) then keeps the
// solver out of its files.

template <scalar_type T>
void basic_soft_step<T>::prepare(std::span<const solver_body<T>> bodies,
                                 std::span<contact_constraint<T>> contacts) const noexcept {
  stages_.prepare(bodies, contacts);
}

template <scalar_type T>
void basic_soft_step<T>::solve(std::span<solver_body<T>> bodies, std::span<contact_constraint<T>> contacts,
                               std::span<joint_constraint<T>> joints, const settings_type& settings, T dt) {
  auto program = [&] { solve_stages(bodies, contacts, joints, settings, dt); };
  stages_.run(program);
}

template <scalar_type T>
void basic_soft_step<T>::project_joints(std::span<solver_body<T>> bodies, std::span<joint_constraint<T>> joints,
                                        const settings_type& settings) {
  tree_.project_joints(bodies, joints, settings.position_iterations, settings.joint_correction, false);
}

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
