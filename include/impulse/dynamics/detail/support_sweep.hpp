// impulse/dynamics/detail/support_sweep.hpp — a last sweep over the normal
// rows from the ground up, each manifold solved with its lower body held.
//
// Gauss–Seidel hands a load down a stack one row at a time, and a row
// between a heavy body and a light one moves the heavy body as the light
// one's effective mass allows: each sweep takes about m/M of the heavy
// body's velocity out, so a 10 000 kg box on a 1 kg box needs thousands of
// sweeps to stop. Shock propagation (Guendelman, Bridson and Fedkiw,
// "Nonconvex rigid bodies with stacking", SIGGRAPH 2003; Erleben,
// "Velocity-based shock propagation for multibody dynamics animation",
// 2007) ends the sweeps with one more, taken in order of support. Each
// body has a level: the fewest contacts between it and a body that cannot
// move (static and kinematic bodies are level 0). Each manifold that joins
// two levels is solved, the lowest first, as if its lower body could not
// move, so the sweep stops a whole stack in one pass whatever its masses.
//
// Which manifolds: one whose upper body is `heavier` times its lower one
// or more, and every manifold beneath it that bears its load down to the
// ground. A stack of like masses needs none (the sweeps in parts stop it:
// docs/stacks.md), and taking every manifold cost `pile` 85 % more.
// Manifolds between bodies of one level (boxes side by side), manifolds
// the coloring left over, and bodies with no path to one that cannot move
// take no part.
//
// The sweep only pushes, from zero, and its impulses are not kept: the
// rows' accumulated impulses, which the next warm start applies, stay
// those of the other sweeps. Kept, they held the same stacks as well, but
// handed to the warm start a patch whose points had taken the heavy
// body's weight unevenly: with one pass over a manifold's rows instead of
// four, or the sweep in the last part only, the 1:1000 stack spun its
// light boxes out. Only the normal rows, too: friction solved this way
// followed the lower body's spin, and the light boxes of a 1:1000 stack,
// spinning at 0.1 to 0.8 rad/s under the heavy ones' loads, carried the
// heavy ones off with them.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "../contact_constraint.hpp"
#include "contact_batch.hpp"

namespace impulse::detail {

/// Which velocities a support sweep changes: the real ones (each row closes
/// at most its gap) or the position pass's pseudo-velocities (each row
/// pushed apart at its push speed).
enum class support_kind { velocity, position };

/// The manifolds of a step's batches in order of support, and the sweep.
class support_order {
 public:
  /// A manifold takes part when its upper body is at least this many
  /// times as heavy as its lower one (or bears the load of one that is).
  static constexpr int heavier = 4;

  /// The bodies' levels from the batches' manifolds (breadth first from
  /// the bodies that cannot move), and the manifolds that take part,
  /// lowest first (within a level, in a fixed order). Nothing when no
  /// manifold has an upper body `heavier` times its lower one.
  template <scalar_type T, int W>
  void build(std::span<const solver_body<T>> bodies, std::span<const contact_batch<T, W>> batches) {
    constexpr std::uint32_t unreached = std::numeric_limits<std::uint32_t>::max();
    const std::size_t n = bodies.size();
    entries_.clear();
    const auto uneven = [&](const contact_batch<T, W>& b, int l) {
      const T ia = bodies[b.body_a[l]].inverse_mass, ib = bodies[b.body_b[l]].inverse_mass;
      return ia > T(0) && ib > T(0) && (ia >= heavier * ib || ib >= heavier * ia);
    };
    bool any = false;
    for (const contact_batch<T, W>& b : batches)
      for (int l = 0; l < b.size && !any; ++l) any = uneven(b, l);
    if (!any) return;
    // Each body's neighbours through the manifolds, as one array cut by
    // `first_`.
    first_.assign(n + 1, 0);
    for (const contact_batch<T, W>& b : batches)
      for (int l = 0; l < b.size; ++l) ++first_[b.body_a[l]], ++first_[b.body_b[l]];
    std::uint32_t sum = 0;
    for (std::size_t i = 0; i <= n; ++i) sum += std::exchange(first_[i], sum);
    next_.assign(first_.begin(), first_.end() - 1);
    neighbor_.resize(sum);
    for (const contact_batch<T, W>& b : batches)
      for (int l = 0; l < b.size; ++l) {
        neighbor_[next_[b.body_a[l]]++] = b.body_b[l];
        neighbor_[next_[b.body_b[l]]++] = b.body_a[l];
      }
    level_.assign(n, unreached);
    queue_.clear();
    for (std::size_t i = 0; i < n; ++i)
      if (bodies[i].inverse_mass == T(0)) level_[i] = 0, queue_.push_back(std::uint32_t(i));
    for (std::size_t head = 0; head < queue_.size(); ++head) {
      const std::uint32_t i = queue_[head];
      for (std::uint32_t k = first_[i]; k < first_[i + 1]; ++k) {
        const std::uint32_t j = neighbor_[k];
        if (level_[j] != unreached) continue;
        level_[j] = level_[i] + 1;
        queue_.push_back(j);
      }
    }
    for (std::size_t k = 0; k < batches.size(); ++k) {
      const contact_batch<T, W>& b = batches[k];
      for (int l = 0; l < b.size; ++l) {
        const std::uint32_t la = level_[b.body_a[l]], lb = level_[b.body_b[l]];
        if (la == lb || la == unreached || lb == unreached) continue;
        entries_.push_back({std::min(la, lb), std::uint32_t(k), std::uint16_t(l), lb > la});
      }
    }
    // From the top down: a manifold takes part when its upper body is
    // `heavier` times its lower one or more, or bears on it a load that
    // such a manifold hands down.
    std::stable_sort(entries_.begin(), entries_.end(),
                     [](const entry& x, const entry& y) { return x.level > y.level; });
    loaded_.assign(n, 0);
    std::size_t kept = 0;
    for (const entry& e : entries_) {
      const contact_batch<T, W>& b = batches[e.batch];
      const std::uint32_t u = e.upper_is_b ? b.body_b[e.lane] : b.body_a[e.lane];
      const std::uint32_t d = e.upper_is_b ? b.body_a[e.lane] : b.body_b[e.lane];
      const T upper = bodies[u].inverse_mass, lower = bodies[d].inverse_mass;
      if (!loaded_[u] && (lower == T(0) || lower < heavier * upper)) continue;
      loaded_[d] = 1;
      entries_[kept++] = e;
    }
    entries_.resize(kept);
    std::reverse(entries_.begin(), entries_.end());
  }

  /// The sweep: each manifold, lowest first, `sweeps` passes over its
  /// normal rows, each row's impulse, from zero and only pushing, on the
  /// upper body alone.
  template <support_kind Kind, scalar_type T, int W>
  void sweep(std::span<solver_body<T>> bodies, std::span<const contact_batch<T, W>> batches,
             std::span<const batch_row<T, W>> rows, int sweeps) const noexcept {
    constexpr bool position = Kind == support_kind::position;
    for (const entry& e : entries_) {
      const contact_batch<T, W>& in = batches[e.batch];
      const int l = e.lane;
      solver_body<T>& a = bodies[in.body_a[l]];
      solver_body<T>& b = bodies[in.body_b[l]];
      const vec3<T> n = in.normal.lane(l);
      vec3<T>& va = position ? a.bias_linear : a.linear_velocity;
      vec3<T>& wa = position ? a.bias_angular : a.angular_velocity;
      vec3<T>& vb = position ? b.bias_linear : b.linear_velocity;
      vec3<T>& wb = position ? b.bias_angular : b.angular_velocity;
      const std::span<const batch_row<T, W>> own = rows.subspan(in.first_row, std::size_t(in.rows_used));
      T pushed[contact_manifold<T>::capacity] = {};
      for (int s = 0; s < sweeps; ++s)
        for (std::size_t ri = 0; ri < own.size(); ++ri) {
          const batch_row<T, W>& r = own[ri];
          // Rows past the lane's points, and in the position pass points
          // within the slop, have no mass.
          if ((position ? r.position_mass[l] : r.mass[l]) == T(0)) continue;
          const vec3<T> arm_a = r.arm_a.lane(l), arm_b = r.arm_b.lane(l);
          const vec3<T> turn_a = r.turn_a.lane(l), turn_b = r.turn_b.lane(l);
          const T speed = dot(n, vb - va) + dot(wb, arm_b) - dot(wa, arm_a);
          const T target = position ? -r.push_speed[l] : r.gap_speed[l];
          // 1/kg: how the row's speed answers an impulse on the upper body.
          const T answer = e.upper_is_b ? b.inverse_mass + dot(arm_b, turn_b) : a.inverse_mass + dot(arm_a, turn_a);
          const T next = std::max(pushed[ri] - (speed + target) / answer, T(0));
          const T delta = next - pushed[ri];
          pushed[ri] = next;
          if (e.upper_is_b) {
            vb += n * (delta * b.inverse_mass);
            wb += turn_b * delta;
          } else {
            va -= n * (delta * a.inverse_mass);
            wa -= turn_a * delta;
          }
        }
    }
  }

 private:
  struct entry {
    std::uint32_t level;  // the lower body's
    std::uint32_t batch;
    std::uint16_t lane;
    bool upper_is_b;
  };
  std::vector<std::uint32_t> first_, next_, neighbor_, level_, queue_;
  std::vector<std::uint8_t> loaded_;
  std::vector<entry> entries_;
};

}  // namespace impulse::detail
