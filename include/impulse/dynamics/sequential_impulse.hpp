// impulse/dynamics/sequential_impulse.hpp — the contact solver by sequential
// impulses: projected Gauss–Seidel over the velocity rows of every contact,
// warm started, with a restitution pass before it and a split-impulse
// position pass after it, in parts of the step.
//
// One step (Catto, "Iterative Dynamics with Temporal Coherence", GDC 2005;
// "Fast and Simple Physics using Sequential Impulses", GDC 2006), taken in
// `substeps` equal parts (4 by default; solver_settings.hpp):
//
// 1. Forces: each body's velocity takes a part's share of this step's
//    change from gravity and loads, at the start of each part.
// 2. Restitution, once, before the first part: contacts approaching faster
//    than the threshold are made to separate at e times their approach
//    speed, pairwise and in sequence (contact_rows.hpp, restitution_pass,
//    says why not inside the iterations).
// 3. Warm start, each part: each point's impulses from the last part (or
//    step, matched by feature id) are applied again.
// 4. Velocity iterations, each part: per manifold, friction at the patch
//    (two tangent rows within the Coulomb disc of the patch's normal
//    impulse and a twist row), then a few passes over the points' normal
//    rows, clamped to push only (solver_settings.hpp, manifold_sweeps,
//    says why more than one). A row that is apart (a speculative contact,
//    depth < 0) or shallower than the rest depth may sink to that depth
//    within the part but no further (solver_settings.hpp, rest_depth, says
//    why not to zero); each part re-measures the depth from how far the
//    bodies have moved (contact_batch.hpp, retarget_batch). The manifolds
//    are visited color by color, W that share no moving body at a time in
//    SIMD lanes (constraint_graph.hpp, contact_batch.hpp); a manifold no
//    color could take is solved alone after them.
//    Each part's sweeps end with the support sweep (support_sweep.hpp):
//    the normal rows once more from the ground up, each manifold solved as
//    if its lower body could not move, which stops a stack in one pass
//    whatever its masses (settings.support_sweep).
// 5. Position pass, in the last part (split impulses; Catto's "Box2D: the
//    position problem", Bullet's split impulse): the normal rows once more
//    on separate pseudo-velocities, pushing penetration beyond the slop out
//    at a fraction per step. Those velocities move the bodies this part and
//    are dropped, so correcting a penetration adds no kinetic energy: a
//    Baumgarte term in the velocity rows would turn every correction into
//    a bounce, and a box landing in a stack would pop the one beneath.
//    Non-linear Gauss–Seidel on positions (Box2D v2) does the same at the
//    cost of a contact re-evaluation per iteration. It too ends with a
//    support sweep.
// 6. Motion, each part: the bodies move with the solved velocities plus
//    the pseudo-velocities, each turned with its L held (free_rotation.hpp,
//    solver_parts.hpp).
// Joints (joint.hpp) take part in steps 3 and 4, before the contacts of
// each iteration, rigid, prepared where the bodies are at each part; those
// that form trees have their rows solved all at once, exactly
// (joint_tree.hpp). Their drift is removed once the bodies have moved
// (project_joints: non-linear Gauss–Seidel on the poses, which sees the
// drift that a pass planned from the start of the part cannot, and a Newton
// step on the trees): by one pass between parts, and position_iterations
// passes once the step is done.
//
// The rows, their colors and their SIMD batches are worked out once a step,
// from where the step found the contacts: the parts cost their sweeps, a
// warm start and a re-aim of the rows, not a new preparation. Why parts at
// all: a step's length, not its number of sweeps, sets how tall a tower of
// boxes stands (docs/stacks.md).
#pragma once

#include <algorithm>
#include <span>
#include <utility>
#include <vector>

#include "../core/policy.hpp"
#include "../core/task_system.hpp"
#include "detail/constraint_graph.hpp"
#include "detail/contact_groups.hpp"
#include "detail/contact_batch.hpp"
#include "contact_constraint.hpp"
#include "detail/contact_rows.hpp"
#include "joint.hpp"
#include "detail/joint_tree.hpp"
#include "detail/solver_stages.hpp"
#include "detail/solver_parts.hpp"
#include "detail/support_sweep.hpp"
#include "solver_settings.hpp"

namespace impulse {

template <scalar_type T>
class basic_sequential_impulse {
 public:
  /// Its numbers: the shared ones and its own (solver_settings.hpp).
  using settings_type = sequential_impulse_settings<T>;
  /// It moves the bodies itself, part by part (contact_solver.hpp).
  static constexpr bool moves_bodies = true;
  /// Its impulses act over a part of the step (substeps; the whole step
  /// by default).
  static T impulse_step(const settings_type& settings, T dt) noexcept { return dt / T(settings.substeps); }

  /// Whether the turns are fourth order (the world asks for them under a
  /// fourth-order integrator policy; contact_solver.hpp).
  void set_fourth_order_turns(bool fourth) noexcept { fourth_order_ = fourth; }

  /// Spreads the solve across the hook's workers (core/task_system.hpp):
  /// groups of islands, each solved whole by one worker, when the contacts
  /// share out evenly that way (detail/contact_groups.hpp); else each
  /// color's batches, and the loops over bodies and batches. Islands share
  /// no moving body, nor do the batches of one color, so the bodies come
  /// out the same, bit for bit, whichever worker solves which; the rest
  /// stays on this thread.
  void set_task_system(const task_system& tasks) noexcept { stages_.set_task_system(tasks); }

  /// How many groups of islands the last solve shared among the workers,
  /// each solved whole on one (detail/contact_groups.hpp); 0 when its
  /// colors were shared instead, or it ran on one thread.
  [[nodiscard]] std::uint32_t solved_groups() const noexcept { return solved_groups_; }
  /// The colors of the last solve's contacts: the most any group of
  /// islands took, when it went by groups.
  [[nodiscard]] std::size_t color_count() const noexcept {
    std::size_t most = 0;
    const std::size_t used = std::min<std::size_t>(sets_.size(), std::max<std::size_t>(solved_groups_, 1));
    for (std::size_t g = 0; g < used; ++g) most = std::max(most, sets_[g].graph.color_count());
    return most;
  }

  void prepare(std::span<const solver_body<T>> bodies, std::span<contact_constraint<T>> contacts) const noexcept;

  /// Steps 1–5 above, and the bodies moved: once, or in `substeps` equal
  /// parts. Steps 4 and 5 run on batches of contacts that share no moving
  /// body (constraint_graph.hpp), W at a time in SIMD lanes
  /// (contact_batch.hpp).
  ///
  /// In parts, the contacts, their rows and the batches are worked out
  /// once; each part applies its share of the forces, warm starts, asks of
  /// each row what the point's depth now asks (re-measured from how far
  /// the bodies have moved, contact_batch.hpp, retarget_batch), sweeps,
  /// and moves the bodies. Restitution is applied once, before the first.
  ///
  /// Joints (joint.hpp) are solved rigidly in the same iterations, before
  /// the contacts of each, from where the bodies are at each part; one
  /// pass of project_joints removes their drift between parts, and
  /// project_joints once the step is done.
  ///
  /// With a task hook the whole solve is one call of it: its loops are the
  /// stages of a stage_runner (core/detail/stage_runner.hpp).
  void solve(std::span<solver_body<T>> bodies, std::span<contact_constraint<T>> contacts,
             std::span<joint_constraint<T>> joints, const settings_type& settings, T dt);

  /// What the caller does with a solve's results, handed over by the worker
  /// that solved a group of islands as soon as the group is done, while its
  /// contacts and bodies are in that worker's cache: run(context, contacts,
  /// bodies) names each contact and body of the solve once, over all the
  /// calls (the bodies that no impulse moves last, on the calling thread).
  /// Only when the solve went by groups (solved_groups() > 0); otherwise
  /// the caller takes the results after solve returns.
  struct group_results {
    void (*run)(void* context, std::span<const std::uint32_t> contacts, std::span<const std::uint32_t> bodies);
    void* context;
  };
  /// solve, handing each group's results to `results` (above).
  void solve(std::span<solver_body<T>> bodies, std::span<contact_constraint<T>> contacts,
             std::span<joint_constraint<T>> joints, const settings_type& settings, T dt,
             const group_results& results);

  /// Non-linear Gauss–Seidel on the joints, position_iterations passes
  /// over the bodies' poses after they have moved (joint.hpp,
  /// project_joint), each with a Newton step on the joint trees
  /// (joint_tree.hpp).
  void project_joints(std::span<solver_body<T>> bodies, std::span<joint_constraint<T>> joints,
                      const settings_type& settings);

 private:
  static constexpr int width = detail::contact_lanes<T>;
  using batch_type = detail::contact_batch<T, width>;
  using row_type = detail::batch_row<T, width>;

  using displacement = detail::body_displacement<T>;
  /// Contacts that one program solves: their colors and SIMD batches, the
  /// batches' rows, and their order of support. The step's, or one group
  /// of islands' (contact_groups.hpp).
  struct contact_set {
    detail::constraint_graph graph;
    detail::support_order support;
    std::vector<batch_type> batches;
    std::vector<row_type> rows;
    std::vector<std::uint32_t> first_rows;        // each batch's first row in rows
    std::vector<std::pair<T, T>> leftover_slips;  // the leftover manifolds' slip targets at the start, in parts
  };

  /// What one program solves: a contact set, and which contacts and bodies
  /// are its own (a group's), or all of them, across the workers (`whole`).
  struct scope {
    contact_set& set;
    std::span<const std::uint32_t> contacts, bodies;
    bool whole;
  };

  void solve_stages(std::span<solver_body<T>> bodies, std::span<contact_constraint<T>> contacts,
                    std::span<joint_constraint<T>> joints, const settings_type& settings, T dt,
                    const group_results* results) {
    const int parts = settings.substeps;
    const T share = T(1) / T(parts);
    synced_.resize(bodies.size());
    moved_.assign(parts > 1 ? bodies.size() : 0, {});
    auto start_bodies = [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        solver_body<T>& b = bodies[i];
        if (!moved_.empty()) moved_[i].spin = b.angular_velocity;
        synced_[i] = b.angular_velocity;
        b.linear_velocity += b.force_linear * share;
        b.angular_velocity += b.force_angular * share;
        b.bias_linear = {};
        b.bias_angular = {};
      }
    };
    stages_.each_index(bodies.size(), min_bodies, start_bodies);
    // Restitution sees the velocities with one part's forces added: ½ +
    // 1/(2·parts) of the step's change, measured from its start
    // (contact_rows.hpp, restitution_pass).
    detail::restitution_pass(bodies, contacts, settings.restitution_threshold, settings.velocity_iterations,
                             T(0.5) + T(0.5) * share, dt);
    if (!settings.warm_starting)
      for (contact_constraint<T>& c : contacts) detail::forget_impulses(c);
    const std::span<const solver_body<T>> read = bodies;
    tree_.build(read, joints, settings.exact_joint_trees);
    // Islands shared out among the workers, each group solved whole on
    // one (contact_groups.hpp); else each color's batches split among
    // them. Joints, solved one by one across the islands, keep the colors.
    const std::uint32_t workers = stages_.tasks().workers;
    solved_groups_ = 0;
    if (stages_.shared() && joints.empty() &&
        groups_.split(read, std::span<const contact_constraint<T>>(contacts), workers)) {
      sets_.resize(std::max<std::size_t>(sets_.size(), groups_.size()));
      auto solve_groups = [&](std::size_t begin, std::size_t end) {
        for (std::size_t g = begin; g < end; ++g) {
          const std::span<const std::uint32_t> own_contacts = groups_.contacts(std::uint32_t(g));
          const std::span<const std::uint32_t> own_bodies = groups_.bodies(std::uint32_t(g));
          solve_set({sets_[g], own_contacts, own_bodies, false}, bodies, contacts, joints, settings, dt);
          if (results) results->run(results->context, own_contacts, own_bodies);
        }
      };
      stages_.each_index(groups_.size(), 1, solve_groups);
      solved_groups_ = groups_.size();
      // The bodies at rest that nothing moves, moved as the parts would
      // have: no group read anything their moves change.
      for (int part = 0; part < parts; ++part)
        for (const std::uint32_t i : groups_.fixed_bodies()) move_part(bodies, i, part, parts, true, dt);
      if (results) results->run(results->context, {}, groups_.fixed_bodies());
      return;
    }
    solve_set({sets_.empty() ? sets_.emplace_back() : sets_[0], {}, {}, true}, bodies, contacts, joints, settings,
              dt);
  }

  /// f(i) for each of the scope's bodies.
  template <class F>
  void each_body(const scope& s, std::size_t count, F& f) {
    if (!s.whole) {
      for (const std::uint32_t i : s.bodies) f(i);
      return;
    }
    auto range = [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) f(i);
    };
    stages_.each_index(count, min_bodies, range);
  }

  /// f(written, batches, backward) over the scope's batches color by
  /// color (solver_stages.hpp, by_color); a group's, on this thread,
  /// writes only the bodies that move (the others are read by every group).
  template <class F>
  void by_color(const scope& s, bool backward, F& f) {
    if (s.whole)
      stages_.by_color(s.set.graph, std::span<batch_type>(s.set.batches), backward, f);
    else
      f(std::integral_constant<detail::lanes_written, detail::lanes_written::moving>{},
        std::span<batch_type>(s.set.batches), backward);
  }

  /// f(begin, end) over the scope's batches.
  template <class F>
  void each_batch(const scope& s, F& f) {
    if (s.whole)
      stages_.each_index(s.set.batches.size(), min_batches, f);
    else
      f(std::size_t(0), s.set.batches.size());
  }

  /// Body i moved through part `part` of `parts` with the solved velocities
  /// plus the position pass's pseudo-velocities, turned with its L held;
  /// then, unless it was the last, the next part's share of the forces
  /// added when `next` (the move before stands in for a loop of its own
  /// when no projection of the joints comes between the parts), or its L
  /// brought in step after the last.
  void move_part(std::span<solver_body<T>> bodies, std::size_t i, int part, int parts, bool next, T dt) {
    const T h = dt / T(parts);
    solver_body<T>& b = bodies[i];
    if (!moved_.empty()) {
      moved_[i].linear += (b.linear_velocity + b.bias_linear) * h;
      moved_[i].angular += (b.angular_velocity + b.bias_angular) * h;
    }
    detail::move_body(b, synced_[i], h, fourth_order_, b.bias_linear, b.bias_angular);
    if (part + 1 == parts)
      detail::sync_momentum(b, synced_[i]);
    else if (next)
      next_part(b, T(1) / T(parts));
  }

  /// A part's share of the forces, and its bias reset.
  static void next_part(solver_body<T>& b, T share) noexcept {
    b.linear_velocity += b.force_linear * share;
    b.angular_velocity += b.force_angular * share;
    b.bias_linear = {};
    b.bias_angular = {};
  }

  /// Steps 3 to 6 for the scope's contacts and bodies, from their colors
  /// and batches to the impulses stored back.
  void solve_set(const scope& s, std::span<solver_body<T>> bodies, std::span<contact_constraint<T>> contacts,
                 std::span<joint_constraint<T>> joints, const settings_type& settings, T dt) {
    contact_set& set = s.set;
    const int parts = settings.substeps;
    const T h = dt / T(parts), share = T(1) / T(parts);
    const detail::row_target_rule<T> rule{settings.rest_depth, settings.linear_slop, settings.position_correction,
                                          settings.max_correction_speed, T(1) / h};
    const std::span<const solver_body<T>> read = bodies;
    const std::span<const contact_constraint<T>> all = contacts;
    if (s.whole)
      set.graph.build(read, all, width);
    else
      set.graph.build(read, all, s.contacts, width);
    for (const std::uint32_t i : set.graph.leftover()) row_targets(contacts[i], rule, {});
    set.leftover_slips.clear();
    if (parts > 1)
      for (const std::uint32_t i : set.graph.leftover())
        set.leftover_slips.push_back({contacts[i].slip_target1, contacts[i].slip_target2});
    // Each batch's rows placed first, then the batches loaded side by
    // side, each with its contacts' row targets.
    set.batches.resize(set.graph.batch_count());
    set.rows.resize(detail::place_batch_rows(set.graph, all, set.first_rows));
    auto load = [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        for (const std::uint32_t i : set.graph.batch(k)) row_targets(contacts[i], rule, {});
        detail::load_batch(read, all, set.graph.batch(k), set.batches[k], std::span<row_type>(set.rows),
                           set.first_rows[k]);
      }
    };
    each_batch(s, load);
    const std::span<const batch_type> batches = set.batches;
    if (settings.support_sweep) set.support.build(read, batches);
    const joint_pass<T> rigid_pass{softness<T>::rigid(), h};
    constexpr auto real = detail::velocity_kind::real, pseudo = detail::velocity_kind::pseudo;
    int sweeps = 0;  // over all parts so far
    const bool projected = !joints.empty();  // project_between_parts
    for (int part = 0; part < parts; ++part) {
      if (part > 0) {
        if (projected) {
          auto next_parts = [&](std::size_t i) { next_part(bodies[i], share); };
          each_body(s, bodies.size(), next_parts);
        }
        for (const std::uint32_t i : set.graph.leftover()) row_targets(contacts[i], rule, moved_);
        for (std::size_t k = 0; k < set.graph.leftover().size(); ++k)
          detail::turn_slip_targets(contacts[set.graph.leftover()[k]], std::span<const displacement>(moved_),
                                    set.leftover_slips[k]);
      }
      const bool exact = projected && detail::start_joints(tree_, bodies, joints, h, part == 0 && !settings.warm_starting);
      // After the first part, each batch's targets turned with the moves
      // so far, then its warm start: one loop over the batches, not two.
      auto warm_start = [&](auto written, std::span<batch_type> range, bool) {
        for (batch_type& b : range) {
          if (part > 0) detail::retarget_batch(b, rows_of(set, b), std::span<const displacement>(moved_), rule);
          detail::batch_velocities<T, width> v = detail::gather(read, b, real);
          detail::warm_start_batch(v, b, rows_of(set, b));
          detail::scatter(bodies, b, v, real, written);
        }
      };
      by_color(s, false, warm_start);
      for (const std::uint32_t i : set.graph.leftover()) detail::warm_start(bodies, contacts[i]);
      for (int iteration = 0; iteration < settings.velocity_iterations; ++iteration) {
        for (joint_constraint<T>& j : joints) detail::solve_joint(bodies, j, rigid_pass);
        if (exact) tree_.solve_velocities(bodies, joints);
        // Forward through the colors, then back (symmetric Gauss–Seidel):
        // always forward, support climbed a 100-row pyramid one color at a
        // time and its boxes moved 12 cm in 200 steps; alternating, 6 mm.
        // The alternation runs on across parts: started forward in every
        // part, an odd number of sweeps a part (4 × 5, 8 × 3) let the
        // pyramid's top wander 15 to 22 cm.
        auto sweep = [&](auto written, std::span<batch_type> range, bool backward) {
          for (std::size_t k = 0; k < range.size(); ++k) {
            batch_type& b = range[backward ? range.size() - 1 - k : k];
            detail::batch_velocities<T, width> v = detail::gather(read, b, real);
            // Friction first: it is bounded by the normal impulses, and the
            // normal rows, solved last, are the ones that must hold (no
            // sinking).
            detail::solve_batch_friction(v, b, rows_of(set, b));
            detail::solve_batch_normals<detail::normal_pass::velocity>(v, b, rows_of(set, b),
                                                                       settings.manifold_sweeps);
            detail::scatter(bodies, b, v, real, written);
          }
        };
        by_color(s, (sweeps + iteration) % 2 != 0, sweep);
        for (const std::uint32_t i : set.graph.leftover()) solve_velocity(bodies, contacts[i], settings);
      }
      if (settings.support_sweep)
        set.support.template sweep<detail::support_kind::velocity>(bodies, batches, std::span<const row_type>(set.rows),
                                                                   settings.manifold_sweeps);
      sweeps += settings.velocity_iterations;
      // The position pass, in the last part: it pushes the step's fraction
      // of each penetration out within it, for the cost of one part's.
      // Shared among the parts, one sweep each, it stalled a heap of 30
      // boxes pushed apart without gravity; four sweeps in each part cost
      // pile 14 % more and held no taller a tower.
      auto push = [&](auto written, std::span<batch_type> range, bool) {
        for (batch_type& b : range) {
          detail::batch_velocities<T, width> v = detail::gather(read, b, pseudo);
          detail::solve_batch_normals<detail::normal_pass::position>(v, b, rows_of(set, b), settings.manifold_sweeps);
          detail::scatter(bodies, b, v, pseudo, written);
        }
      };
      for (int iteration = 0; part + 1 == parts && iteration < settings.position_iterations; ++iteration) {
        by_color(s, false, push);
        for (const std::uint32_t i : set.graph.leftover()) solve_position(bodies, contacts[i], settings);
      }
      if (part + 1 == parts && settings.support_sweep)
        set.support.template sweep<detail::support_kind::position>(bodies, batches, std::span<const row_type>(set.rows),
                                                                   settings.manifold_sweeps);
      auto move = [&](std::size_t i) { move_part(bodies, i, part, parts, !projected, dt); };
      each_body(s, bodies.size(), move);
      if (part + 1 < parts && projected) project_between_parts(bodies, joints, settings);
    }
    auto store = [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) detail::store_batch(set.batches[k], rows_of(set, set.batches[k]), contacts);
    };
    each_batch(s, store);
  }

  struct pose {
    vec3<T> position;
    quat<T> orientation;
  };

  static constexpr std::uint32_t min_batches = detail::solver_stages::min_batches;
  static constexpr std::uint32_t min_bodies = detail::solver_stages::min_bodies;

  detail::solver_stages stages_;
  detail::contact_groups groups_;
  std::vector<contact_set> sets_;  // the step's, or one per group
  detail::joint_tree<T> tree_;
  std::vector<pose> poses_;  // each body's pose before a projection between parts
  std::vector<displacement> moved_;  // each body's displacement since the start of the step, in parts
  std::vector<vec3<T>> synced_;      // each body's ω when its L was last brought in step (solver_parts.hpp)
  bool fourth_order_ = false;
  std::uint32_t solved_groups_ = 0;

  /// Between two parts, the joints' drift removed by one pass of
  /// project_joints (with its Newton steps on the trees), the bodies'
  /// displacements kept up with what it moved. Without it a chain of 100
  /// links tapering from 1 kg at the pivot to 1000 kg, let go from
  /// horizontal, opened 8.6 cm in 4 parts (0.013 mm with it); four passes
  /// held it no better and cost the ragdoll pile of bench/joints 13 % more.
  void project_between_parts(std::span<solver_body<T>> bodies, std::span<joint_constraint<T>> joints,
                             const settings_type& settings) {
    poses_.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      detail::sync_momentum(bodies[i], synced_[i]);
      poses_[i] = {bodies[i].position, bodies[i].orientation};
    }
    tree_.project_joints(bodies, joints, 1, settings.joint_correction, true);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      solver_body<T>& b = bodies[i];
      if (b.orientation == poses_[i].orientation && b.position == poses_[i].position) continue;
      b.orientation = normalize(b.orientation);
      moved_[i].linear += b.position - poses_[i].position;
      moved_[i].angular += rotation_between(poses_[i].orientation, b.orientation);
      // Turned, an anisotropic body keeps L and takes the ω of its new pose.
      if (b.inverse_mass > T(0) && !b.principal.isotropic()) detail::reorient_inertia(b, synced_[i]);
    }
  }

  static std::span<row_type> rows_of(contact_set& set, const batch_type& b) noexcept {
    return std::span<row_type>(set.rows).subspan(b.first_row, std::size_t(b.rows_used));
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

  /// What the rows ask of each point, as deep as it now lies: the depth
  /// found, less how far the bodies have moved apart along the normal
  /// since (`moved`, empty before they have moved; to first order in their
  /// turns, as retarget_batch). The velocity row: vn ≥ −gap_speed, a point
  /// shallower than the rest depth (or apart by a gap) may sink to it
  /// within the part but no further. The position pass: to separate at a
  /// fraction of the penetration beyond the slop per step; < 0 when the
  /// point lies within the slop and takes no part.
  static void row_targets(contact_constraint<T>& c, const detail::row_target_rule<T>& rule,
                          std::span<const displacement> moved) noexcept {
    for (int i = 0; i < c.count; ++i) {
      contact_constraint_point<T>& p = c.points[i];
      const T depth = moved.empty() ? p.depth : detail::depth_now(c, p, moved);
      p.gap_speed = depth < rule.rest_depth ? (rule.rest_depth - depth) * rule.inverse_substep : T(0);
      p.push_speed = depth > rule.linear_slop
                         ? std::min(rule.position_correction * (depth - rule.linear_slop) * rule.inverse_substep,
                                    rule.max_correction_speed)
                         : T(-1);
      p.bias_impulse = T(0);
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

// The entry points out of the class, not inline: where a program declares
// the solver extern (IMPULSE_EXTERN_TEMPLATES, core/extern_templates.hpp),
// its files then compile none of it, not even to inline it.

template <scalar_type T>
void basic_sequential_impulse<T>::prepare(std::span<const solver_body<T>> bodies,
                                          std::span<contact_constraint<T>> contacts) const noexcept {
  stages_.prepare(bodies, contacts);
}

template <scalar_type T>
void basic_sequential_impulse<T>::solve(std::span<solver_body<T>> bodies, std::span<contact_constraint<T>> contacts,
                                        std::span<joint_constraint<T>> joints, const settings_type& settings, T dt) {
  auto program = [&] { solve_stages(bodies, contacts, joints, settings, dt, nullptr); };
  stages_.run(program);
}

template <scalar_type T>
void basic_sequential_impulse<T>::solve(std::span<solver_body<T>> bodies, std::span<contact_constraint<T>> contacts,
                                        std::span<joint_constraint<T>> joints, const settings_type& settings, T dt,
                                        const group_results& results) {
  auto program = [&] { solve_stages(bodies, contacts, joints, settings, dt, &results); };
  stages_.run(program);
}

template <scalar_type T>
void basic_sequential_impulse<T>::project_joints(std::span<solver_body<T>> bodies,
                                                 std::span<joint_constraint<T>> joints,
                                                 const settings_type& settings) {
  tree_.project_joints(bodies, joints, settings.position_iterations, settings.joint_correction, true);
}

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
