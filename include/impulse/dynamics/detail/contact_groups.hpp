// impulse/dynamics/detail/contact_groups.hpp — a step's contacts split into
// groups that share no body the solve changes, one per worker.
//
// Across workers, the solver sweeps each color's batches in ranges, and
// every color of every sweep ends with a wait for the slowest worker:
// `pile` (100 columns of 10 boxes) waits about 84 times a step, for a few
// microseconds of work each. Contacts that share no body through any chain
// of contacts, islands, do not read each other's writes at all. When the
// contacts fall apart into islands small enough to share out evenly, each
// worker solves its own group of islands from the first sweep to the last
// and waits once (Jolt solves its islands apart the same way).
//
// What is shared: bodies that no impulse moves and that are at rest
// (static ground, a kinematic body standing still). The solve reads their
// velocities, zero, and writes nothing to them; they join no island and
// belong to no group, and the solver moves them once the groups are done.
// A kinematic body that moves joins the islands it touches, like a body
// that impulses move.
//
// The groups change which contacts share a batch, not what any contact
// computes: each lane of a batch computes what it would alone, and each
// island's contacts keep their colors and their order (a contact's color
// depends only on the contacts before it that share its bodies, all in its
// island). So the bodies come out the same, bit for bit, for any number of
// groups.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "../contact_constraint.hpp"
#include "constraint_graph.hpp"

namespace impulse::detail {

class contact_groups {
 public:
  /// The heaviest group may hold this many times its even share of the
  /// contacts, at most; past it the islands are too few or too large to
  /// share out, and the solver sweeps the colors across the workers.
  static constexpr double most_uneven = 1.15;

  /// Whether body i is read and never written by the solve: no impulse
  /// moves it and it is at rest, with no load.
  template <scalar_type T>
  [[nodiscard]] static bool fixed(const solver_body<T>& b) noexcept {
    const vec3<T> zero{};
    return b.inverse_mass == T(0) && b.linear_velocity == zero && b.angular_velocity == zero &&
           b.force_linear == zero && b.force_angular == zero;
  }

  /// Splits the contacts into `count` groups of whole islands, each island
  /// to one group in the order of its first contact, cut where the running
  /// count of contacts passes each group's share; and the bodies with
  /// them. False, and no groups, when the heaviest group would hold more
  /// than most_uneven times its share.
  ///
  /// A split depends only on which bodies each contact joins and on which
  /// bodies move: when those are as at the last split, as they are in most
  /// steps of a scene at rest, its groups stand and nothing is worked out
  /// again (in `pile` at two workers, the calling thread's 30–37 µs a step
  /// became 8–10 µs, the comparison and the steps that split afresh).
  template <scalar_type T>
  bool split(std::span<const solver_body<T>> bodies, std::span<const contact_constraint<T>> contacts,
             std::uint32_t count) {
    if (same_as_last(bodies, contacts, count)) return count_ != 0;
    count_ = 0;
    const std::size_t n = bodies.size();
    if (count < 2 || contacts.empty()) return false;
    // Every contact takes a color when its bodies have 65 contacts or
    // fewer between them (constraint_graph.hpp, max_colors): one left
    // over is solved alone, and writes the bodies at rest that groups share.
    degree_.assign(n, 0);
    for (const contact_constraint<T>& c : contacts) {
      if (bodies[c.body_a].inverse_mass > T(0)) ++degree_[c.body_a];
      if (bodies[c.body_b].inverse_mass > T(0)) ++degree_[c.body_b];
    }
    for (const contact_constraint<T>& c : contacts)
      if (std::uint64_t(degree_[c.body_a]) + degree_[c.body_b] > constraint_graph::max_colors + 1) return false;
    parent_.resize(n);
    for (std::size_t i = 0; i < n; ++i) parent_[i] = fixed(bodies[i]) ? fixed_body : std::uint32_t(i);
    for (const contact_constraint<T>& c : contacts)
      if (parent_[c.body_a] != fixed_body && parent_[c.body_b] != fixed_body) unite(c.body_a, c.body_b);
    // Each island by its first contact: its place in that order, and how
    // many contacts it has.
    island_of_.assign(n, none);
    weights_.clear();
    contact_island_.resize(contacts.size());
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      const std::uint32_t a = contacts[k].body_a, b = contacts[k].body_b;
      const std::uint32_t root = parent_[a] != fixed_body ? find(a) : parent_[b] != fixed_body ? find(b) : fixed_body;
      if (root == fixed_body) {  // two bodies at rest: nothing to solve, any group reads it
        contact_island_[k] = 0;
        if (weights_.empty()) weights_.push_back(0);
        ++weights_[0];
        continue;
      }
      if (island_of_[root] == none) {
        island_of_[root] = std::uint32_t(weights_.size());
        weights_.push_back(0);
      }
      contact_island_[k] = island_of_[root];
      ++weights_[island_of_[root]];
    }
    // Island s to group ⌊(contacts before it + half its own)·count/total⌋.
    const std::uint64_t total = contacts.size();
    group_of_island_.resize(weights_.size());
    std::vector<std::uint64_t>& load = loads_;
    load.assign(count, 0);
    std::uint64_t before = 0;
    for (std::size_t s = 0; s < weights_.size(); ++s) {
      const std::uint32_t g =
          std::min(count - 1, std::uint32_t((2 * before + weights_[s]) * count / (2 * total)));
      group_of_island_[s] = g;
      load[g] += weights_[s];
      before += weights_[s];
    }
    if (double(*std::max_element(load.begin(), load.end())) * count > most_uneven * double(total)) return false;
    // The contacts and bodies of each group, in their own order (two
    // counting sorts); bodies on no contact go to groups by index.
    contact_starts_.assign(count + 1, 0);
    for (std::size_t k = 0; k < contacts.size(); ++k) ++contact_starts_[group_of_island_[contact_island_[k]] + 1];
    body_group_.resize(n);
    body_starts_.assign(count + 1, 0);
    fixed_.clear();
    for (std::size_t i = 0; i < n; ++i) {
      if (parent_[i] == fixed_body) {
        body_group_[i] = fixed_body;
        fixed_.push_back(std::uint32_t(i));
        continue;
      }
      const std::uint32_t island = island_of_[find(std::uint32_t(i))];
      body_group_[i] = island != none ? group_of_island_[island] : std::uint32_t(i * count / n);
      ++body_starts_[body_group_[i] + 1];
    }
    for (std::uint32_t g = 0; g < count; ++g) {
      contact_starts_[g + 1] += contact_starts_[g];
      body_starts_[g + 1] += body_starts_[g];
    }
    contacts_.resize(contacts.size());
    next_.assign(contact_starts_.begin(), contact_starts_.end() - 1);
    for (std::size_t k = 0; k < contacts.size(); ++k)
      contacts_[next_[group_of_island_[contact_island_[k]]]++] = std::uint32_t(k);
    bodies_.resize(body_starts_[count]);
    next_.assign(body_starts_.begin(), body_starts_.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
      if (body_group_[i] != fixed_body) bodies_[next_[body_group_[i]]++] = std::uint32_t(i);
    count_ = count;
    return true;
  }

  /// Groups after a successful split; 0 otherwise.
  [[nodiscard]] std::uint32_t size() const noexcept { return count_; }
  /// Group g's contacts, in the contacts' order.
  [[nodiscard]] std::span<const std::uint32_t> contacts(std::uint32_t g) const noexcept {
    return std::span<const std::uint32_t>(contacts_).subspan(contact_starts_[g], contact_starts_[g + 1] - contact_starts_[g]);
  }
  /// Group g's bodies, in their order: each body the solve may change is
  /// in exactly one group.
  [[nodiscard]] std::span<const std::uint32_t> bodies(std::uint32_t g) const noexcept {
    return std::span<const std::uint32_t>(bodies_).subspan(body_starts_[g], body_starts_[g + 1] - body_starts_[g]);
  }
  /// The bodies in no group: read by every group, written by none.
  [[nodiscard]] std::span<const std::uint32_t> fixed_bodies() const noexcept { return fixed_; }

 private:
  static constexpr std::uint32_t fixed_body = ~std::uint32_t(0), none = ~std::uint32_t(0);

  /// Whether a split's inputs are those of the last call, kept for the
  /// next: the groups asked for, each contact's bodies, and each body's
  /// part in the split (fixed, or moved by impulses).
  template <scalar_type T>
  bool same_as_last(std::span<const solver_body<T>> bodies, std::span<const contact_constraint<T>> contacts,
                    std::uint32_t count) {
    bool same = count == asked_ && contacts.size() == last_pairs_.size() && bodies.size() == last_roles_.size();
    asked_ = count;
    last_pairs_.resize(contacts.size());
    last_roles_.resize(bodies.size());
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      const std::uint64_t pair = std::uint64_t(contacts[k].body_a) << 32 | contacts[k].body_b;
      same = same && last_pairs_[k] == pair;
      last_pairs_[k] = pair;
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const std::uint8_t role = fixed(bodies[i]) ? 2 : bodies[i].inverse_mass > T(0) ? 1 : 0;
      same = same && last_roles_[i] == role;
      last_roles_[i] = role;
    }
    return same;
  }

  /// The root of body i's island; i is not a fixed body.
  std::uint32_t find(std::uint32_t i) noexcept {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void unite(std::uint32_t a, std::uint32_t b) noexcept {
    a = find(a), b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

  std::uint32_t count_ = 0;
  std::uint32_t asked_ = 0;                    // the last split's group count asked for
  std::vector<std::uint64_t> last_pairs_;      // per contact at the last split: its bodies
  std::vector<std::uint8_t> last_roles_;       // per body at the last split: fixed 2, moved by impulses 1, else 0
  std::vector<std::uint32_t> degree_;          // per body: its contacts, when impulses move it
  std::vector<std::uint32_t> parent_;          // per body: union-find, or fixed_body
  std::vector<std::uint32_t> island_of_;       // per root body: its island's place, by first contact
  std::vector<std::uint32_t> weights_;         // per island: its contacts
  std::vector<std::uint32_t> contact_island_;  // per contact
  std::vector<std::uint32_t> group_of_island_;
  std::vector<std::uint64_t> loads_;           // per group: its contacts
  std::vector<std::uint32_t> body_group_;      // per body: its group, or fixed_body
  std::vector<std::uint32_t> contact_starts_, body_starts_, next_;
  std::vector<std::uint32_t> contacts_, bodies_, fixed_;
};

}  // namespace impulse::detail
