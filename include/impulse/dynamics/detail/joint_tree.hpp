// impulse/dynamics/detail/joint_tree.hpp — the joints that form trees, solved
// exactly, in time linear in their number (Baraff, "Linear-Time Dynamics
// using Lagrange Multipliers", SIGGRAPH 1996).
//
// Gauss–Seidel visits one joint at a time, so a load is passed along a
// chain one joint per iteration, and a heavy link between light ones is
// held by joints that each see only their own pair: a hanging chain of
// twenty links alternating 10 kg and 1 kg opened 13 mm in its first steps
// at 20 iterations (still 1.2 mm at 200). Solving all the rows of a tree of
// joints at once means solving
//
//   [ M  Jᵀ ] [ Δv ]   [    0     ]        λ = −y: the joints' impulses,
//   [ J  0  ] [ y  ] = [ −(J·v + b) ]       Δv = M⁻¹·Jᵀ·λ: what they do,
//
// whose graph (a node per moving body, a node per joint, an edge where a
// joint holds a body) is the joints' own. When that is a tree, a node
// eliminated after its children changes only its parent, so H = L·D·Lᵀ has
// no fill-in and both the factorisation and each solve are one pass over
// the nodes, with blocks of at most 6×6: a body's mass matrix, a joint's
// rows. Bodies are symmetric positive definite blocks and joints negative
// definite ones (the matrix is quasi-definite), so each pivot block is
// factored by Cholesky, of D or of −D. Each tree is rooted at its joint to
// the world if it has one, else at a body, so that every joint has a body
// below it: a joint eliminated with none would have a zero pivot.
//
// Which joints: the rows that hold (point, rotation, across, a rigid
// distance) of the joints of each group of bodies they join that forms a
// tree, tied to the world (static and kinematic bodies, which are not
// nodes: they cannot move) by one joint at most. A group with a loop, or
// tied to the world twice, stays with Gauss–Seidel, as do limits, motors
// and springs everywhere, which are inequalities or soft: only equalities
// have an exact solve.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "../../core/policy.hpp"
#include "../../math/mat3.hpp"
#include "../../math/quat.hpp"
#include "../../math/vec3.hpp"
#include "../contact_constraint.hpp"
#include "../joint.hpp"

namespace impulse::detail {

template <scalar_type T>
using block6 = std::array<std::array<T, 6>, 6>;  // [row][column]

/// The number of a joint's rows that hold: point 3, rotation 3, across 2,
/// a rigid distance 1.
template <scalar_type T>
[[nodiscard]] int holding_row_count(const joint_constraint<T>& j) noexcept {
  switch (j.type) {
    case joint_type::ball:
      return 3;
    case joint_type::hinge:
    case joint_type::slider:
      return 5;
    case joint_type::fixed:
      return 6;
    case joint_type::distance:
      return j.is_spring() ? 0 : 1;
  }
  return 0;
}

/// The Jacobian of a joint's holding rows on (v, ω) of A and of B, in the
/// order ball: point; hinge: point, across; slider: rotation, across;
/// fixed: point, rotation; distance: the line. From prepare_joint's parts.
template <scalar_type T>
struct holding_rows {
  block6<T> side[2]{};  ///< A, B
  int count = 0;

  holding_rows() = default;
  explicit holding_rows(const joint_constraint<T>& j) noexcept { assign(j); }

  void assign(const joint_constraint<T>& j) noexcept {
    side[0] = side[1] = block6<T>{};
    count = 0;
    switch (j.type) {
      case joint_type::ball:
        add_point(j.point);
        break;
      case joint_type::hinge:
        add_point(j.point);
        add_row(j.across[0]);
        add_row(j.across[1]);
        break;
      case joint_type::slider:
        add_rotation();
        add_row(j.across[0]);
        add_row(j.across[1]);
        break;
      case joint_type::fixed:
        add_point(j.point);
        add_rotation();
        break;
      case joint_type::distance:
        if (!j.is_spring()) add_row(j.axial);
        break;
    }
  }

  /// What the rows would have to remove, in their order: the joint's
  /// errors (prepare_joint).
  static void errors(const joint_constraint<T>& j, T* out) noexcept {
    int n = 0;
    const auto put = [&](const vec3<T>& e) { out[n] = e.x, out[n + 1] = e.y, out[n + 2] = e.z, n += 3; };
    switch (j.type) {
      case joint_type::ball:
        put(j.separation);
        break;
      case joint_type::hinge:
        put(j.separation);
        out[3] = j.across_error[0], out[4] = j.across_error[1];
        break;
      case joint_type::slider:
        put(j.rotation_error);
        out[3] = j.across_error[0], out[4] = j.across_error[1];
        break;
      case joint_type::fixed:
        put(j.separation);
        put(j.rotation_error);
        break;
      case joint_type::distance:
        out[0] = j.position - j.length;
        break;
    }
  }

  /// What the joint has accumulated on the rows, in their order.
  static void impulses(const joint_constraint<T>& j, T* out) noexcept {
    const auto put = [&](int at, const vec3<T>& v) { out[at] = v.x, out[at + 1] = v.y, out[at + 2] = v.z; };
    switch (j.type) {
      case joint_type::ball:
        put(0, j.point_impulse);
        break;
      case joint_type::hinge:
        put(0, j.point_impulse);
        out[3] = j.across_impulse[0], out[4] = j.across_impulse[1];
        break;
      case joint_type::slider:
        put(0, j.rotation_impulse);
        out[3] = j.across_impulse[0], out[4] = j.across_impulse[1];
        break;
      case joint_type::fixed:
        put(0, j.point_impulse);
        put(3, j.rotation_impulse);
        break;
      case joint_type::distance:
        out[0] = j.axial_impulse;
        break;
    }
  }

  /// The impulses λ of the rows added to what the joint has accumulated.
  static void accumulate(joint_constraint<T>& j, const T* lambda) noexcept {
    const auto take = [&](int at) { return vec3<T>{lambda[at], lambda[at + 1], lambda[at + 2]}; };
    switch (j.type) {
      case joint_type::ball:
        j.point_impulse += take(0);
        break;
      case joint_type::hinge:
        j.point_impulse += take(0);
        j.across_impulse[0] += lambda[3], j.across_impulse[1] += lambda[4];
        break;
      case joint_type::slider:
        j.rotation_impulse += take(0);
        j.across_impulse[0] += lambda[3], j.across_impulse[1] += lambda[4];
        break;
      case joint_type::fixed:
        j.point_impulse += take(0);
        j.rotation_impulse += take(3);
        break;
      case joint_type::distance:
        j.axial_impulse += lambda[0];
        break;
    }
  }

 private:
  // v_B + ω_B × r_b − v_A − ω_A × r_a: A [−1, [r_a]×], B [1, −[r_b]×].
  void add_point(const point_part<T>& p) noexcept {
    const mat3<T> sa = skew(p.ra), sb = skew(p.rb);
    for (int i = 0; i < 3; ++i, ++count) {
      side[0][count][i] = T(-1);
      side[1][count][i] = T(1);
      for (int c = 0; c < 3; ++c) {
        side[0][count][3 + c] = sa(i, c);
        side[1][count][3 + c] = -sb(i, c);
      }
    }
  }
  // ω_B − ω_A.
  void add_rotation() noexcept {
    for (int i = 0; i < 3; ++i, ++count) {
      side[0][count][3 + i] = T(-1);
      side[1][count][3 + i] = T(1);
    }
  }
  // u·(v_B − v_A) + arm_b·ω_B − arm_a·ω_A.
  void add_row(const row_part<T>& r) noexcept {
    for (int c = 0; c < 3; ++c) {
      side[0][count][c] = -r.linear[c];
      side[0][count][3 + c] = -r.arm_a[c];
      side[1][count][c] = r.linear[c];
      side[1][count][3 + c] = r.arm_b[c];
    }
    ++count;
  }
};

/// The forest of joints and its factors; reused step to step.
template <scalar_type T>
class joint_tree {
 public:
  [[nodiscard]] bool empty() const noexcept { return nodes_.empty(); }

  /// Chooses the joints the trees take (joint_constraint::in_tree; none
  /// unless `enabled`) and orders the nodes, children before parents.
  void build(std::span<const solver_body<T>> bodies, std::span<joint_constraint<T>> joints, bool enabled = true) {
    nodes_.clear();
    load_.assign(bodies.size(), vec3<T>{});
    if (!enabled) {
      for (joint_constraint<T>& j : joints) j.in_tree = false;
      return;
    }
    const std::size_t body_count = bodies.size();
    const auto moving = [&](std::uint32_t b) { return bodies[b].inverse_mass > T(0); };
    // Union–find over the bodies, with whether each tree is tied to the world.
    leader_.resize(body_count);
    tied_.assign(body_count, 0);
    for (std::size_t b = 0; b < body_count; ++b) leader_[b] = std::uint32_t(b);
    const auto find = [&](std::uint32_t b) {
      while (leader_[b] != b) b = leader_[b] = leader_[leader_[b]];
      return b;
    };
    // tied_: bit 1, the tree is tied to the world; bit 2, one of its joints
    // closed a loop.
    constexpr std::uint8_t to_world = 1, looped = 2;
    for (joint_constraint<T>& j : joints) {
      j.in_tree = false;
      if (holding_row_count(j) == 0) continue;
      const bool ma = moving(j.body_a), mb = moving(j.body_b);
      if (ma && mb) {
        const std::uint32_t ra = find(j.body_a), rb = find(j.body_b);
        if (ra == rb || (tied_[ra] & tied_[rb] & to_world)) {
          tied_[rb] |= std::uint8_t(tied_[ra] | looped);
          if (ra != rb) leader_[ra] = rb;
          continue;
        }
        leader_[ra] = rb;
        tied_[rb] |= tied_[ra];
      } else if (ma || mb) {
        const std::uint32_t r = find(ma ? j.body_a : j.body_b);
        tied_[r] |= (tied_[r] & to_world) ? looped : to_world;
        if (tied_[r] & looped) continue;
      } else {
        continue;
      }
      j.in_tree = true;
    }
    // A component with a loop stays wholly with Gauss–Seidel: its spanning
    // tree solved exactly and the joints that close its loops by
    // Gauss–Seidel pulled against each other, and bench/joints' grid tore
    // 17 m open (0.56 m all by Gauss–Seidel).
    std::size_t taken = 0;
    for (joint_constraint<T>& j : joints) {
      if (!j.in_tree) continue;
      j.in_tree = !(tied_[find(moving(j.body_a) ? j.body_a : j.body_b)] & looped);
      taken += j.in_tree ? 1 : 0;
    }
    if (taken == 0) return;

    // Each moving body's tree joints (compressed rows).
    first_.assign(body_count + 1, 0);
    for (const joint_constraint<T>& j : joints)
      if (j.in_tree) {
        if (moving(j.body_a)) ++first_[j.body_a + 1];
        if (moving(j.body_b)) ++first_[j.body_b + 1];
      }
    for (std::size_t b = 0; b < body_count; ++b) first_[b + 1] += first_[b];
    links_.resize(first_[body_count]);
    fill_ = first_;
    for (std::size_t k = 0; k < joints.size(); ++k)
      if (joints[k].in_tree) {
        if (moving(joints[k].body_a)) links_[fill_[joints[k].body_a]++] = std::uint32_t(k);
        if (moving(joints[k].body_b)) links_[fill_[joints[k].body_b]++] = std::uint32_t(k);
      }

    // Breadth first from each root: a joint that ties its tree to the
    // world, else any body. Parents come before children, so the reverse is
    // the elimination order.
    placed_.assign(body_count, 0);
    order_.clear();
    const auto grow = [&](std::size_t from) {
      for (std::size_t at = from; at < order_.size(); ++at) {
        const place here = order_[at];
        const std::uint32_t parent = std::uint32_t(at);
        if (here.body) {
          for (std::uint32_t l = first_[here.item]; l < first_[here.item + 1]; ++l) {
            const std::uint32_t k = links_[l];
            if (here.parent != none && order_[here.parent].item == k) continue;
            order_.push_back(joint_node(k, parent, joints[k].body_a == here.item ? 0 : 1, joints[k]));
          }
        } else {
          const joint_constraint<T>& j = joints[here.item];
          for (int s = 0; s < 2; ++s) {
            const std::uint32_t b = s == 0 ? j.body_a : j.body_b;
            if (!moving(b) || placed_[b]) continue;
            placed_[b] = 1;
            order_.push_back(body_node(b, parent, s));
          }
        }
      }
    };
    for (std::size_t k = 0; k < joints.size(); ++k) {
      const joint_constraint<T>& j = joints[k];
      if (j.in_tree && moving(j.body_a) != moving(j.body_b)) {
        order_.push_back(joint_node(std::uint32_t(k), none, 0, j));
        grow(order_.size() - 1);
      }
    }
    for (std::uint32_t b = 0; b < body_count; ++b)
      if (first_[b + 1] > first_[b] && !placed_[b]) {
        placed_[b] = 1;
        order_.push_back(body_node(b, none, 0));
        grow(order_.size() - 1);
      }
    const std::uint32_t n = std::uint32_t(order_.size());
    nodes_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) {
      place& m = nodes_[i];
      m = order_[n - 1 - i];
      if (m.parent != none) m.parent = n - 1 - m.parent;
    }
    rows_.resize(joints.size());
  }

  /// Forgets the loads add_load read (build does too): before a
  /// substep's.
  void clear_loads() noexcept { std::fill(load_.begin(), load_.end(), vec3<T>{}); }

  /// Reads what a tree joint, prepared where the bodies are, held in the
  /// last step or substep of length `h`: its geometric stiffness, which
  /// factor adds to its bodies' inertia.
  ///
  /// A joint that pulls with force f at a lever r (from a body's center of
  /// mass) turns with the body: rotating it by δθ changes its torque by
  /// [f]×[r]×·δθ, a stiffness the step does not see. Under a heavy load a
  /// light link swings across it as a stiff spring, at about
  /// ω = √(|f|·|r|/I) — 500 rad/s for the 1 kg links next to the pivot of a
  /// chain holding 1000 kg — 8 rad in a step of 1/60 s, where the step's
  /// linearisation follows about one; both solvers tore such chains tens of
  /// metres open. Here h²·K, from h·λ = h²·f, is measured as Andrews,
  /// Teichmann and Kry do ("Geometric Stiffness for Real-time Constrained
  /// Multibody Dynamics", 2017): per axis, the length of K's column.
  void add_load(std::span<const solver_body<T>> bodies, const joint_constraint<T>& j, T h) noexcept {
    if (!j.in_tree) return;
    if (j.type != joint_type::ball && j.type != joint_type::hinge && j.type != joint_type::fixed) return;
    const mat3<T> pull = skew(j.point_impulse);
    for (int s = 0; s < 2; ++s) {
      const std::uint32_t b = s == 0 ? j.body_a : j.body_b;
      if (!(bodies[b].inverse_mass > T(0))) continue;
      const mat3<T> k = pull * skew(s == 0 ? j.point.ra : j.point.rb);
      for (int c = 0; c < 3; ++c) load_[b][c] += h * length(k.col[c]);
    }
  }

  /// The tree joints' last impulses applied again, after factor, through
  /// the inertia the tree is solved with: the exact solve then lands where
  /// it would from no start at all, as it does with the bodies' own
  /// inertia. Applied through that, a chain tapering to 1000 kg tore as
  /// before, each step's start undone by a solve that weighs the light
  /// links as heavier (warm_start_joint applies their limits and motors).
  void warm_start(std::span<solver_body<T>> bodies, std::span<const joint_constraint<T>> joints) const noexcept {
    for (const node& m : nodes_) {
      if (m.body) continue;
      const joint_constraint<T>& j = joints[m.item];
      T lambda[6] = {};
      holding_rows<T>::impulses(j, lambda);
      const holding_rows<T>& rows = rows_[m.item];
      for (int s = 0; s < 2; ++s) {
        solver_body<T>& b = bodies[s == 0 ? j.body_a : j.body_b];
        if (!(b.inverse_mass > T(0))) continue;
        vec3<T> linear{}, angular{};
        for (int r = 0; r < m.size; ++r)
          for (int c = 0; c < 3; ++c) {
            linear[c] += rows.side[s][r][c] * lambda[r];
            angular[c] += rows.side[s][r][3 + c] * lambda[r];
          }
        b.linear_velocity += linear * b.inverse_mass;
        b.angular_velocity += solved_inverse_inertia(b, s == 0 ? j.body_a : j.body_b) * angular;
      }
    }
  }

  /// The factors of H from the joints as prepare_joint left them. False,
  /// with every joint handed back to Gauss–Seidel, if a pivot block was not
  /// definite (rows that depend on each other; not met in a tree of the
  /// joints above, whose rows each bind the child body fully).
  bool factor(std::span<const solver_body<T>> bodies, std::span<joint_constraint<T>> joints) {
    for (node& m : nodes_) {
      m.pivot = {};
      if (m.body) {
        const solver_body<T>& b = bodies[m.item];
        const mat3<T> inertia = solved_inertia(b, m.item);
        for (int i = 0; i < 3; ++i) {
          m.pivot[i][i] = T(1) / b.inverse_mass;
          for (int c = 0; c < 3; ++c) m.pivot[3 + i][3 + c] = inertia(i, c);
        }
      } else {
        rows_[m.item].assign(joints[m.item]);
        // Rows past the joint's own are padding, −1 on the diagonal and
        // coupled to nothing, so every block is 6×6 and every loop has
        // fixed bounds the compiler unrolls.
        for (int r = m.size; r < 6; ++r) m.pivot[r][r] = T(-1);
      }
    }
    for (node& m : nodes_) {
      if (!cholesky(m)) {
        abandon(joints);
        return false;
      }
      if (m.parent == none) continue;
      node& p = nodes_[m.parent];
      // W = D⁻¹·H(m, p), then D_p −= H(m, p)ᵀ·W.
      const block6<T> h = link(m, p);
      m.coupling = h;
      solve_pivot(m, m.coupling);
      for (int q = 0; q < 6; ++q)
        for (int r = 0; r < 6; ++r)
          for (int c = 0; c < 6; ++c) p.pivot[r][c] -= h[q][r] * m.coupling[q][c];
    }
    return true;
  }

  /// One exact solve of the tree joints' rows against the velocities the
  /// bodies have now, their impulses accumulated: J·v = −bias_rate·error
  /// after it (rigid, bias_rate 0: J·v = 0).
  void solve_velocities(std::span<solver_body<T>> bodies, std::span<joint_constraint<T>> joints,
                        T bias_rate = T(0)) noexcept {
    for (node& m : nodes_) {
      m.value = {};
      if (m.body) continue;
      const joint_constraint<T>& j = joints[m.item];
      const holding_rows<T>& rows = rows_[m.item];
      const solver_body<T>* ends[2] = {&bodies[j.body_a], &bodies[j.body_b]};
      T error[6] = {};
      if (bias_rate > T(0)) holding_rows<T>::errors(j, error);
      for (int r = 0; r < m.size; ++r) {
        T target = bias_rate * error[r];
        for (int s = 0; s < 2; ++s)
          for (int c = 0; c < 3; ++c)
            target += rows.side[s][r][c] * ends[s]->linear_velocity[c] +
                      rows.side[s][r][3 + c] * ends[s]->angular_velocity[c];
        m.value[r] = -target;
      }
    }
    solve();
    for (const node& m : nodes_) {
      if (m.body) {
        solver_body<T>& b = bodies[m.item];
        b.linear_velocity += vec3<T>{m.value[0], m.value[1], m.value[2]};
        b.angular_velocity += vec3<T>{m.value[3], m.value[4], m.value[5]};
      } else {
        accumulate(joints[m.item], m);
      }
    }
  }

  /// Non-linear Gauss–Seidel on the joints' poses (joint.hpp,
  /// project_joint: `fraction` of each error), `passes` times, each
  /// followed by a Newton step on the trees' rows, measured where the
  /// bodies are then; then Newton steps alone while the trees have not
  /// settled, newton_steps_per_pass·passes steps in all at most. The
  /// passes leave a tree's rows that hold to its Newton steps, and push
  /// back limits passed unless `limits` is false.
  ///
  /// The Newton step takes the whole linearised error: the factor is
  /// exact, so no joint overshoots for its neighbours, as each does under
  /// Gauss–Seidel at 1 (joint_correction). On the 10:1 chain let go from
  /// horizontal, its tail's whip opened 1.9 mm at 0.5 and 0.004 mm at 1.
  ///
  /// Each step is checked (newton_step) because unchecked ones tore chains
  /// apart: with the first pass's factor serving the later ones and every
  /// step taken whole, a chain of 20 equal links let go from horizontal
  /// (1 kg, 0.5 m, 60 Hz) opened 13 m from its 264th step, as its whip
  /// reached the middle links, whose first Newton step turned them by up
  /// to 0.16 rad and left the factor behind; the velocity solve was exact
  /// throughout (J·v within 1e-6 m/s of 0). A fresh factor each pass held
  /// it within 0.01 mm, but not 100 links (0.28–0.65 m): across a taut run
  /// a full step overshoots back and forth, and at the whip a step starts
  /// up to 0.2 m off, which takes up to 21 Newton steps, not four
  /// (docs/joints.md, "Drift").
  void project_joints(std::span<solver_body<T>> bodies, std::span<joint_constraint<T>> joints, int passes,
                      T fraction, bool limits) {
    // The velocity solve's factor is of the poses at the start of the step:
    // a prototype that kept it diverged on the whip.
    reusable_ = false;
    newton_outcome outcome = newton_outcome::moved;
    for (int pass = 0; pass < passes; ++pass) {
      for (joint_constraint<T>& j : joints) project_joint(bodies, j, fraction, limits);
      if (!empty()) outcome = newton_step(bodies, joints);
    }
    for (int step = passes; step < newton_steps_per_pass * passes && outcome == newton_outcome::moved && !empty();
         ++step)
      outcome = newton_step(bodies, joints);
  }

  /// One Newton step on the positions: the bodies moved so as to remove
  /// each tree joint's error, linearised where they are (the joints
  /// prepared and the tree factored there), whole and unchecked.
  void project(std::span<solver_body<T>> bodies, std::span<const joint_constraint<T>> joints) noexcept {
    solve_for_errors(joints);
    move(bodies, T(1));
  }

 private:
  static constexpr std::uint32_t none = ~std::uint32_t(0);

  /// A tree body's inertia (world frame) as the tree solves it: its own,
  /// with the geometric stiffness add_load measured added where that
  /// passes it, so that no body turns faster under its joints' pull than
  /// about a radian a step, and one that does not come near it is left as
  /// it is. (All of it added, the chains held too, but a pendulum's period
  /// would have moved; with three times the body's inertia left out, the
  /// chain of 100 links tapering to 1000 kg tore 42 m open under
  /// soft_step, and held with twice.)
  [[nodiscard]] mat3<T> solved_inertia(const solver_body<T>& b, std::uint32_t index) const noexcept {
    mat3<T> inertia = inverse_or_zero(b.inverse_inertia);
    for (int i = 0; i < 3; ++i) inertia(i, i) += std::max(T(0), load_[index][i] - inertia(i, i));
    return inertia;
  }
  /// Its inverse: the body's own where nothing was added.
  [[nodiscard]] mat3<T> solved_inverse_inertia(const solver_body<T>& b, std::uint32_t index) const noexcept {
    const mat3<T> own = inverse_or_zero(b.inverse_inertia);
    for (int i = 0; i < 3; ++i)
      if (load_[index][i] > own(i, i)) return inverse_or_zero(solved_inertia(b, index));
    return b.inverse_inertia;
  }

  /// Errors below this (m or rad) are not worth a factorisation: Newton's
  /// method has converged to rounding after two steps on the chain, and the
  /// factor is most of the cost of a ragdoll pile's joints.
  static constexpr T settled = T(1e-5);
  /// The projection's Newton steps at most, per pass (project_joints): the
  /// 100-link chains of tests/faults/test_chains.cpp settle within 21 at
  /// the worst step of their whip (3.4 a step on average). Where a step
  /// cannot follow the motion (the tail of a chain tapering 1000:1 at
  /// 450 rad/s) the limit bounds the cost.
  static constexpr int newton_steps_per_pass = 8;
  /// The smallest fraction of a Newton step tried (six halvings) before
  /// the step is given up as no descent.
  static constexpr T smallest_share = T(1) / T(64);

  enum class newton_outcome { settled, moved, stuck };

  /// How far the tree joints are from holding, where the bodies are.
  struct tree_error {
    T worst = T(0);    ///< largest row error, m or rad
    T squares = T(0);  ///< sum of the rows' errors squared: what a Newton step must lower
  };

  /// A body's pose, kept to undo a step.
  struct pose {
    vec3<T> position{};
    quat<T> orientation{};
  };

  /// One Newton step on the trees' rows, kept only if it lowers their
  /// squared error (project_joints says why it must be checked). A factor
  /// from an earlier step is reused (a chord method) only if that step at
  /// least halved the error; when its step fails, the tree is factored
  /// where the bodies are and the step taken again. A fresh factor's step
  /// that fails is halved until it does not (a backtracking line search),
  /// and given up, the bodies where they were, below smallest_share.
  newton_outcome newton_step(std::span<solver_body<T>> bodies, std::span<joint_constraint<T>> joints) {
    const std::span<const solver_body<T>> read = bodies;
    const tree_error before = measure(read, joints);
    if (before.worst <= settled) return newton_outcome::settled;
    bool fresh = !reusable_;
    if (fresh && !factor(read, joints)) return newton_outcome::stuck;
    solve_for_errors(joints);
    keep_poses(bodies);
    T share = T(1);
    for (;;) {
      move(bodies, share);
      const tree_error after = measure(read, joints);
      if (after.squares < before.squares) {
        reusable_ = after.squares <= T(0.25) * before.squares;
        return newton_outcome::moved;
      }
      restore_poses(bodies);
      (void)measure(read, joints);  // the joints prepared where the bodies are again
      if (!fresh) {
        fresh = true;
        if (!factor(read, joints)) return newton_outcome::stuck;
        solve_for_errors(joints);
        continue;
      }
      share *= T(0.5);
      if (share < smallest_share) {
        reusable_ = false;
        return newton_outcome::stuck;
      }
    }
  }

  /// The tree joints prepared where the bodies are, and their errors.
  static tree_error measure(std::span<const solver_body<T>> bodies, std::span<joint_constraint<T>> joints) noexcept {
    tree_error e;
    for (joint_constraint<T>& j : joints) {
      if (!j.in_tree) continue;
      prepare_joint(bodies, j);
      T error[6] = {};
      holding_rows<T>::errors(j, error);
      for (const T row : error) {
        e.worst = std::max(e.worst, std::abs(row));
        e.squares += row * row;
      }
    }
    return e;
  }

  /// The Newton step that removes each tree joint's error as prepared,
  /// from the factor: the bodies' displacements in their nodes' values.
  void solve_for_errors(std::span<const joint_constraint<T>> joints) noexcept {
    for (node& m : nodes_) {
      m.value = {};
      if (m.body) continue;
      T error[6];
      holding_rows<T>::errors(joints[m.item], error);
      for (int r = 0; r < m.size; ++r) m.value[r] = -error[r];
    }
    solve();
  }

  /// The tree's bodies moved by `share` of the solved step.
  void move(std::span<solver_body<T>> bodies, T share) const noexcept {
    for (const node& m : nodes_) {
      if (!m.body) continue;
      solver_body<T>& b = bodies[m.item];
      b.position += vec3<T>{m.value[0], m.value[1], m.value[2]} * share;
      b.orientation = integrate(b.orientation, vec3<T>{m.value[3], m.value[4], m.value[5]}, share);
    }
  }

  void keep_poses(std::span<const solver_body<T>> bodies) {
    kept_.clear();
    for (const node& m : nodes_)
      if (m.body) kept_.push_back({bodies[m.item].position, bodies[m.item].orientation});
  }
  void restore_poses(std::span<solver_body<T>> bodies) const noexcept {
    std::size_t k = 0;
    for (const node& m : nodes_)
      if (m.body) {
        bodies[m.item].position = kept_[k].position;
        bodies[m.item].orientation = kept_[k].orientation;
        ++k;
      }
  }

  /// Where a node sits in its tree.
  struct place {
    std::uint32_t item = 0;  ///< body or joint index
    std::uint32_t parent = none;
    std::uint8_t size = 0;   ///< rows: 6 for a body
    std::uint8_t side = 0;   ///< which side of the joint on the edge to the parent the body is: 0 A, 1 B
    bool body = false;
  };
  struct node : place {
    block6<T> pivot{};         ///< D, then the Cholesky factor L of D (body) or −D (joint), 1/L_ii on its diagonal
    block6<T> coupling{};      ///< W = D⁻¹·H(node, parent): size × parent's size
    std::array<T, 6> value{};  ///< right side, then solution
  };

  static place body_node(std::uint32_t b, std::uint32_t parent, int side) noexcept {
    return {b, parent, 6, std::uint8_t(side), true};
  }
  static place joint_node(std::uint32_t k, std::uint32_t parent, int side, const joint_constraint<T>& j) noexcept {
    return {k, parent, std::uint8_t(holding_row_count(j)), std::uint8_t(side), false};
  }

  /// H(m, p), the block of H coupling a node to its parent: the parent
  /// joint's rows on the body (transposed), or the joint's rows on the
  /// parent body.
  block6<T> link(const node& m, const node& p) const noexcept {
    if (!m.body) return rows_[m.item].side[m.side];
    const block6<T>& jac = rows_[p.item].side[m.side];
    block6<T> h;
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) h[r][c] = jac[c][r];
    return h;
  }

  /// Solves H·x = value in place: forward, children before parents, then
  /// back.
  void solve() noexcept {
    for (node& m : nodes_) {
      if (m.parent != none) {
        node& p = nodes_[m.parent];
        for (int r = 0; r < 6; ++r)
          for (int c = 0; c < 6; ++c) p.value[c] -= m.coupling[r][c] * m.value[r];
      }
      solve_pivot(m, m.value);
    }
    for (std::size_t i = nodes_.size(); i-- > 0;) {
      node& m = nodes_[i];
      if (m.parent == none) continue;
      const node& p = nodes_[m.parent];
      for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c) m.value[r] -= m.coupling[r][c] * p.value[c];
    }
  }

  static void accumulate(joint_constraint<T>& j, const node& m) noexcept {
    T lambda[6];
    for (int r = 0; r < 6; ++r) lambda[r] = -m.value[r];
    holding_rows<T>::accumulate(j, lambda);
  }

  /// L·Lᵀ = the node's pivot (a body) or its negation (a joint), in place,
  /// with the reciprocals of L's diagonal kept on the diagonal: the solves
  /// then multiply, and a division's latency was a quarter of the factor's
  /// time.
  static bool cholesky(node& m) noexcept {
    block6<T>& a = m.pivot;
    const T sign = m.body ? T(1) : T(-1);
    for (int c = 0; c < 6; ++c) {
      T diagonal = sign * a[c][c];
      for (int q = 0; q < c; ++q) diagonal -= a[c][q] * a[c][q];
      if (!(diagonal > T(0)) || !std::isfinite(diagonal)) return false;
      const T reciprocal = T(1) / std::sqrt(diagonal);
      a[c][c] = reciprocal;
      for (int r = c + 1; r < 6; ++r) {
        T sum = sign * a[r][c];
        for (int q = 0; q < c; ++q) sum -= a[r][q] * a[c][q];
        a[r][c] = sum * reciprocal;
      }
    }
    return true;
  }
  /// x ← D⁻¹·x from the node's factor, for x a vector (std::array<T, 6>)
  /// or a block of six columns (block6, row by row).
  template <class Rows>
  static void solve_pivot(const node& m, Rows& x) noexcept {
    const block6<T>& l = m.pivot;
    for (int r = 0; r < 6; ++r) {
      for (int q = 0; q < r; ++q) subtract(x[r], l[r][q], x[q]);
      scale(x[r], l[r][r]);
    }
    for (int r = 5; r >= 0; --r) {
      for (int q = r + 1; q < 6; ++q) subtract(x[r], l[q][r], x[q]);
      scale(x[r], l[r][r]);
    }
    if (!m.body)
      for (int r = 0; r < 6; ++r) scale(x[r], T(-1));
  }
  static void subtract(T& x, T f, const T& y) noexcept { x -= f * y; }
  static void subtract(std::array<T, 6>& x, T f, const std::array<T, 6>& y) noexcept {
    for (int c = 0; c < 6; ++c) x[c] -= f * y[c];
  }
  static void scale(T& x, T f) noexcept { x *= f; }
  static void scale(std::array<T, 6>& x, T f) noexcept {
    for (int c = 0; c < 6; ++c) x[c] *= f;
  }

  /// Hands every joint back to Gauss–Seidel, its rows' impulses forgotten:
  /// warm_start_joint left them to the tree, so they were not applied.
  void abandon(std::span<joint_constraint<T>> joints) noexcept {
    for (joint_constraint<T>& j : joints)
      if (std::exchange(j.in_tree, false)) {
        j.point_impulse = j.rotation_impulse = {};
        j.across_impulse[0] = j.across_impulse[1] = T(0);
        if (j.type == joint_type::distance) j.axial_impulse = T(0);
      }
    nodes_.clear();
  }

  std::vector<node> nodes_;  ///< children before parents
  std::vector<holding_rows<T>> rows_;  ///< per joint; filled for the tree joints
  std::vector<vec3<T>> load_;          ///< per body: h²·K's columns' lengths (take_load), kg·m²
  std::vector<pose> kept_;             ///< the tree's bodies before a Newton step, node order
  bool reusable_ = false;              ///< whether the factor may serve the projection's next step
  // Scratch for build, kept to reuse its memory.
  std::vector<std::uint32_t> leader_, first_, fill_, links_;
  std::vector<std::uint8_t> tied_, placed_;
  std::vector<place> order_;
};

}  // namespace impulse::detail
