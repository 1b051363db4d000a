// impulse/dynamics/detail/constraint_graph.hpp — contacts colored so that no two
// of one color move the same body, and cut into batches of W.
//
// Gauss–Seidel solves one row after another because each row reads the
// velocities the last one wrote. Rows that share no moving body do not
// read each other's writes, so they can be solved together, one per SIMD
// lane, and give the answer the one-by-one sweep would in some order.
// Greedy coloring of the contact graph finds such sets (Catto, "Solver2D"
// and Box2D v3's constraint_graph.c; Tonge, "Iterative Rigid Body
// Solvers", GDC 2012): each contact takes the lowest color neither of its
// bodies has yet. Static and kinematic bodies do not count: the solver
// never changes their velocities, so any number of lanes may read them.
// The colors are then solved one after another, each batch of W contacts
// of one color as W lanes.
//
// The order of the sweep is color by color rather than the contacts'
// own order; a tower's contacts alternate between two colors, so the
// sweep goes over every other contact and then over the rest. Coloring
// is a function of the contact order alone: the same contacts give the
// same batches, and a run stays deterministic. Within a color the
// contacts go by their first moving body, for the workers (below).
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include "../contact_constraint.hpp"

namespace impulse::detail {

/// Contacts in color order, cut into batches that share no moving body.
class constraint_graph {
 public:
  /// Colors past this many (a body touching more than 64 others) are
  /// left over and solved one by one after the batches.
  static constexpr int max_colors = 64;

  /// Batches of at most `width` contacts. A body moves under impulses
  /// when its inverse mass is not zero.
  template <scalar_type T>
  void build(std::span<const solver_body<T>> bodies, std::span<const contact_constraint<T>> contacts, int width) {
    build(bodies, contacts, contacts.size(), [](std::size_t k) { return std::uint32_t(k); }, width);
  }

  /// The same for the contacts `members` names, in that order: for
  /// members that share no moving body with the other contacts, their
  /// colors are those the whole set gives them.
  template <scalar_type T>
  void build(std::span<const solver_body<T>> bodies, std::span<const contact_constraint<T>> contacts,
             std::span<const std::uint32_t> members, int width) {
    build(bodies, contacts, members.size(), [members](std::size_t k) { return members[k]; }, width);
  }

  [[nodiscard]] std::size_t batch_count() const noexcept { return batch_starts_.size() - 1; }
  /// The colors that have contacts; color q's batches are
  /// [first_batch(q), first_batch(q + 1)), and share no moving body.
  [[nodiscard]] std::size_t color_count() const noexcept {
    return color_starts_.empty() ? 0 : color_starts_.size() - 1;
  }
  [[nodiscard]] std::uint32_t first_batch(std::size_t q) const noexcept { return color_starts_[q]; }
  /// The contacts of batch k, by their place in the contact array.
  [[nodiscard]] std::span<const std::uint32_t> batch(std::size_t k) const noexcept {
    return std::span<const std::uint32_t>(order_).subspan(batch_starts_[k], batch_starts_[k + 1] - batch_starts_[k]);
  }
  /// Contacts no color could take.
  [[nodiscard]] std::span<const std::uint32_t> leftover() const noexcept {
    return std::span<const std::uint32_t>(order_).subspan(leftover_start_);
  }

 private:
  /// The k-th of `count` contacts is contacts[id(k)].
  template <scalar_type T, class Id>
  void build(std::span<const solver_body<T>> bodies, std::span<const contact_constraint<T>> contacts,
             std::size_t count, Id id, int width) {
    used_.assign(bodies.size(), 0);
    color_of_.resize(count);
    std::uint32_t counts[max_colors + 1] = {};
    for (std::size_t k = 0; k < count; ++k) {
      const std::uint32_t a = contacts[id(k)].body_a, b = contacts[id(k)].body_b;
      const bool moves_a = bodies[a].inverse_mass > T(0), moves_b = bodies[b].inverse_mass > T(0);
      const std::uint64_t taken = (moves_a ? used_[a] : 0) | (moves_b ? used_[b] : 0);
      const int color = taken == ~std::uint64_t(0) ? max_colors : std::countr_zero(~taken);
      if (color < max_colors) {
        const std::uint64_t bit = std::uint64_t(1) << color;
        if (moves_a) used_[a] |= bit;
        if (moves_b) used_[b] |= bit;
      }
      color_of_[k] = std::uint8_t(color);
      ++counts[color];
    }
    // Within a color, the contacts by their first moving body (a counting
    // sort), then by color (another, which keeps that order). A color's
    // batches are solved as if at once, so their order within it changes
    // nothing they compute; but a body's contacts in every color then fall
    // at about the same place in each, and when workers split each color
    // in ranges, a body stays with one worker from color to color (`pile`:
    // 14 % of its bodies changed worker between its two colors in the
    // contacts' own order). The contacts left over, solved one by one,
    // keep the contacts' own order.
    by_body_.assign(bodies.size() + 1, 0);
    first_body_.resize(count);
    for (std::size_t k = 0; k < count; ++k) {
      const std::uint32_t a = contacts[id(k)].body_a, b = contacts[id(k)].body_b;
      const bool moves_a = bodies[a].inverse_mass > T(0), moves_b = bodies[b].inverse_mass > T(0);
      first_body_[k] = moves_a && moves_b ? std::min(a, b) : moves_a ? a : b;
      ++by_body_[first_body_[k] + 1];
    }
    for (std::size_t i = 1; i < by_body_.size(); ++i) by_body_[i] += by_body_[i - 1];
    by_body_order_.resize(count);
    for (std::size_t k = 0; k < count; ++k) by_body_order_[by_body_[first_body_[k]]++] = std::uint32_t(k);
    std::uint32_t start[max_colors + 2] = {};
    for (int c = 0; c <= max_colors; ++c) start[c + 1] = start[c] + counts[c];
    order_.resize(count);
    std::uint32_t next[max_colors + 1];
    for (int c = 0; c <= max_colors; ++c) next[c] = start[c];
    for (const std::uint32_t k : by_body_order_)
      if (color_of_[k] < max_colors) order_[next[color_of_[k]]++] = id(k);
    for (std::size_t k = 0; k < count; ++k)
      if (color_of_[k] == max_colors) order_[next[max_colors]++] = id(k);
    batch_starts_.clear();
    color_starts_.clear();
    for (int c = 0; c < max_colors; ++c) {
      if (start[c] == start[c + 1]) continue;
      color_starts_.push_back(std::uint32_t(batch_starts_.size()));
      for (std::uint32_t s = start[c]; s < start[c + 1]; s += std::uint32_t(width)) batch_starts_.push_back(s);
    }
    color_starts_.push_back(std::uint32_t(batch_starts_.size()));
    batch_starts_.push_back(start[max_colors]);
    leftover_start_ = start[max_colors];
  }

  std::vector<std::uint64_t> used_;      // per body: the colors its contacts have
  std::vector<std::uint8_t> color_of_;  // per member
  std::vector<std::uint32_t> first_body_;     // per member: its first moving body
  std::vector<std::uint32_t> by_body_;        // per body: where its contacts start in by_body_order_
  std::vector<std::uint32_t> by_body_order_;  // members by first moving body
  std::vector<std::uint32_t> order_;          // contacts by color, then first moving body
  std::vector<std::uint32_t> batch_starts_;
  std::vector<std::uint32_t> color_starts_{0};  // each color's first batch, then the batch count
  std::uint32_t leftover_start_ = 0;
};

}  // namespace impulse::detail
