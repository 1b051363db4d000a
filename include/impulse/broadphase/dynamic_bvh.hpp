// impulse/broadphase/dynamic_bvh.hpp — a dynamic bounding volume hierarchy
// over fat boxes: the broad phase of Box2D (b2DynamicTree, b2BroadPhase)
// and Bullet (btDbvtBroadphase), reporting exact pairs.
//
// Each proxy is a leaf of a dynamic AABB tree (detail/dynamic_tree.hpp)
// that holds a fat box: the proxy's exact box grown by a margin on every
// side and stretched along its last displacement. A move that keeps the
// exact box inside the fat one costs the tree nothing; one that leaves it
// re-inserts the leaf with a fresh fat box. Small jitter and slow drift,
// most of what a physics step produces, never touch the tree.
//
// Pairs come in two layers, as in Box2D's pair management:
//   - candidates: the pairs whose FAT boxes overlap. They change only
//     where a fat box changed (a re-insertion, a create, a destroy), so a
//     candidate between two unchanged fat boxes is carried over, and new
//     candidates are found by one traversal of the tree against itself
//     (Bullet's btDbvt::collideTT in its self-collision form) that opens
//     only subtrees holding a changed leaf: the changed leaves and their
//     ancestors are stamped with the update's number first, and a pair of
//     subtrees neither of which is stamped is skipped whole.
//   - pairs: the candidates whose EXACT boxes overlap, tested afresh every
//     update in one pass over the candidate list. An exact overlap implies
//     a fat one, so nothing is missed, and a pair ends as soon as the exact
//     boxes part, even while the fat boxes still overlap.
// Measured at 10^4 and 10^5 boxes with three quarters of them moving every
// step, this took about half the time of re-finding every moved proxy's pairs
// in the tree each update (by queries or by the same stamped traversal):
// a fifth of the proxies or fewer leave their fat boxes in a step, and a linear
// pass over the candidates is cheap next to a traversal.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "../core/error.hpp"
#include "../core/policy.hpp"
#include "../core/task_system.hpp"
#include "../math/aabb.hpp"
#include "../math/vec3.hpp"
#include "detail/dynamic_tree.hpp"
#include "detail/pair_tracker.hpp"
#include "proxy.hpp"
#include "detail/proxy_store.hpp"

namespace impulse::broadphase {

template <scalar_type T>
class basic_dynamic_bvh {
 public:
  /// margin: how far (m, finite, >= 0) a leaf's fat box reaches beyond the
  /// exact box on every side. A proxy may drift this far before the tree
  /// sees it; a larger margin means fewer re-insertions but looser boxes
  /// and more candidate pairs to test. 0.1 m is Box2D's b2_aabbMargin, a
  /// few steps of a body at walking speed at 60 Hz. Refused with
  /// error_code::non_finite or invalid_parameter.
  explicit basic_dynamic_bvh(T margin = T(0.1)) : margin_(margin) {
    if (!std::isfinite(margin))
      impulse::detail::report_error(error_code::non_finite, "dynamic_bvh: the margin is not finite");
    if (margin < T(0))
      impulse::detail::report_error(error_code::invalid_parameter, "dynamic_bvh: the margin must be >= 0");
  }

  proxy_id create(const aabb<T>& box, std::uint64_t user_data);

  void move(proxy_id id, const aabb<T>& box);

  /// move() for a caller that moves many proxies across workers (the
  /// world's step): when the proxy is here and `box` is valid and inside
  /// its fat box, stores the box, as move() would, and returns true; else
  /// changes nothing and returns false, and the caller calls move().
  /// Calls for distinct proxies may run at once, with no other call
  /// between them; moved_within() then follows, on one thread, when any
  /// returned true. Most proxies of a step take this way, and the tree
  /// sees only those that leave their fat boxes, in the caller's order.
  [[nodiscard]] bool move_within(proxy_id id, const aabb<T>& box) noexcept {
    if (!store_.contains(id) || !detail::proxy_store<T>::valid_box(box)) return false;
    slot_data& s = slots_[id.index];
    if (!impulse::contains(tree_.box(s.leaf), box)) return false;
    store_.place(id, box);
    s.exact = box;
    return true;
  }
  /// After move_within() returned true: the next update() tests the moved boxes.
  void moved_within() noexcept { store_.mark_changed(); }

  void destroy(proxy_id id);

  void update() { update(task_system{}); }

  /// The same, the carried candidates checked across the hook's workers
  /// (core/task_system.hpp): the same pairs and candidates, in the same
  /// order, for any worker count.
  void update(const task_system& tasks);

  [[nodiscard]] std::span<const proxy_pair> pairs() const noexcept { return pairs_.pairs(); }
  [[nodiscard]] std::span<const proxy_pair> begun() const noexcept { return pairs_.begun(); }
  [[nodiscard]] std::span<const proxy_pair> ended() const noexcept { return pairs_.ended(); }

  /// Calls callback(id) for every proxy whose exact box overlaps `box`.
  template <class Callback>
  void query(const aabb<T>& box, Callback&& callback) const {
    detail::proxy_store<T>::require_box(box);
    tree_.query(box, [&](std::int32_t leaf) {
      const std::uint32_t slot = tree_.nodes()[leaf].payload;
      if (overlaps(slots_[slot].exact, box)) callback(id_of(slot));
    });
  }

  /// Reports each proxy whose exact box the segment enters within
  /// [0, max_fraction], clipping the segment to whatever the callback
  /// returns, and prunes the tree with the clipped segment. A fat box
  /// contains the exact one, and the slab test is monotone in the box, so
  /// a node's test never rejects a segment that enters a leaf below it.
  template <class Callback>
  void ray_cast(const ray<T>& r, T max_fraction, Callback&& callback) const {
    detail::require_ray(r, max_fraction);
    if (tree_.root() == detail::null_node || !(max_fraction > T(0))) return;
    const auto& nodes = tree_.nodes();
    detail::node_stack stack;
    stack.push(tree_.root());
    while (!stack.empty()) {
      const detail::tree_node<T>& n = nodes[stack.pop()];
      if (!ray_enters(r, max_fraction, n.box)) continue;
      if (n.is_leaf()) {
        if (const auto t = ray_enters(r, max_fraction, slots_[n.payload].exact)) {
          max_fraction = callback(id_of(n.payload), *t);
          if (!(max_fraction > T(0))) return;
        }
      } else {
        stack.push(n.child2);
        stack.push(n.child1);
      }
    }
  }

  [[nodiscard]] const aabb<T>& box(proxy_id id) const { return store_.box(id); }
  [[nodiscard]] std::uint64_t user_data(proxy_id id) const { return store_.user_data(id); }
  [[nodiscard]] bool contains(proxy_id id) const noexcept { return store_.contains(id); }
  [[nodiscard]] std::size_t size() const noexcept { return store_.size(); }

  // Read-only measures of the structure, for tests, benchmarks and tuning.

  /// The fat-box margin (m) given at construction.
  [[nodiscard]] T margin() const noexcept { return margin_; }
  /// How many proxies left their fat box, and were re-inserted into the
  /// tree, through the moves applied by the last update().
  [[nodiscard]] std::size_t reinserted() const noexcept { return reinserted_; }
  /// The tree's height: edges on the longest root-to-leaf path (0 for one
  /// proxy or none); log2(n) at best.
  [[nodiscard]] int height() const noexcept { return tree_.height(); }
  /// Nodes in the tree: 2n − 1 for n proxies (0 for none).
  [[nodiscard]] std::size_t node_count() const noexcept { return tree_.node_count(); }
  /// The tree's surface-area-heuristic cost: the internal nodes' summed
  /// surface areas over the root's, the expected number of internal nodes
  /// a small box or ray inside the root enters. Lower is better; for boxes
  /// spread through a volume it grows like the cube root of n in a good
  /// tree, for boxes along a line like log n, in a degenerate one like n.
  [[nodiscard]] T sah_cost() const noexcept { return tree_.sah_cost(); }
  /// The candidate pairs (fat boxes overlapping) at the last update, each
  /// tested on the exact boxes.
  [[nodiscard]] std::size_t candidate_count() const noexcept { return candidates_.size(); }
  /// The fat box of a proxy's leaf, for tests and debug drawing.
  [[nodiscard]] const aabb<T>& fat_box(proxy_id id) const {
    store_.require(id);
    return tree_.box(slots_[id.index].leaf);
  }

 private:
  struct slot_data {
    aabb<T> exact;  ///< the proxy's box, next to what the candidate test needs with it
    std::int32_t leaf = detail::null_node;
    std::uint32_t generation = 0;  ///< of the proxy in this slot, to name it in pairs
    std::uint32_t changed = 0;     ///< epoch of the last change to this slot's fat box
  };
  struct candidate {
    std::uint32_t a, b;  ///< proxy slots
  };
  struct node_pair {
    std::int32_t x, y;
  };

  /// Box2D's b2_aabbMultiplier: the fat box reaches this many of the last
  /// displacements ahead, so that a body in steady motion leaves it every
  /// few steps rather than every step. Against 2, it cut re-insertions by
  /// a third at 10^5 boxes in steady motion, for 40 % more candidates;
  /// re-insertions are the dearer of the two, though the step time moved
  /// by less than the noise of the machine it was measured on.
  static constexpr T prediction = T(4);

  [[nodiscard]] proxy_id id_of(std::uint32_t slot) const noexcept { return proxy_id{slot, slots_[slot].generation}; }

  /// The fat box for a proxy that left its old one: the margin all round,
  /// and the predicted displacement ahead of it, at most the fat box's own
  /// size along each axis. A jump longer than that size is a teleport, not
  /// a motion to predict: stretching the box across it would only put a
  /// long, empty box into the tree.
  aabb<T> fatten(const aabb<T>& old, const aabb<T>& box) const noexcept {
    aabb<T> fat = expand(box, margin_);
    const vec3<T> displacement = center(box) - center(old);
    const vec3<T> size = fat.upper - fat.lower;
    for (int axis = 0; axis < 3; ++axis) {
      if (std::abs(displacement[axis]) > size[axis]) continue;
      const T ahead = std::clamp(displacement[axis] * prediction, -size[axis], size[axis]);
      if (ahead < T(0))
        fat.lower[axis] += ahead;
      else
        fat.upper[axis] += ahead;
    }
    return fat;
  }

  void fat_box_changed(std::uint32_t slot) {
    if (slots_[slot].changed == epoch_) return;
    slots_[slot].changed = epoch_;
    changed_.push_back(slot);
  }

  /// Once in 2^32 updates the stamps start over, so that an old stamp can
  /// never be mistaken for the current one.
  void restart_epochs() noexcept {
    for (slot_data& s : slots_) s.changed = 0;
    for (auto& n : tree_.nodes()) n.mark = 0;
    epoch_ = 1;
  }

  /// Keeps a candidate for the next update and reports it as a pair when
  /// the exact boxes overlap.
  void keep_candidate(std::uint32_t a, std::uint32_t b) {
    next_candidates_.push_back({a, b});
    const slot_data& x = slots_[a];
    const slot_data& y = slots_[b];
    if (overlaps(x.exact, y.exact)) found_.push_back(pair_of(proxy_id{a, x.generation}, proxy_id{b, y.generation}));
  }

  /// The last update's candidates whose fat boxes have not changed, kept,
  /// and reported as pairs where their exact boxes overlap; in the
  /// candidates' order. Chunk c of the candidates writes what it keeps
  /// from place c·chunk on, so the chunks can run on any worker; then the
  /// chunks' lists are closed up in order. The time goes into reading two
  /// slots at random for each candidate (`pile` carries ten candidates a
  /// box). The lists are written in place, not cleared and grown: filling
  /// them with zeros first more than doubled the pass's time.
  void keep_candidates(const task_system& tasks) {
    const std::uint32_t count = std::uint32_t(candidates_.size());
    const std::uint32_t chunks = (count + chunk - 1) / chunk;
    next_candidates_.resize(count);
    if (touching_.size() < count) touching_.resize(count);
    kept_.resize(chunks);
    auto judge = [&](std::uint32_t first, std::uint32_t last, std::uint32_t) {
      for (std::uint32_t c = first; c < last; ++c) {
        const std::uint32_t begin = c * chunk, end = std::min(count, begin + chunk);
        std::uint32_t candidates = begin, pairs = begin;
        for (std::uint32_t i = begin; i < end; ++i) {
          const candidate k = candidates_[i];
          const slot_data& x = slots_[k.a];
          const slot_data& y = slots_[k.b];
          if (x.changed == epoch_ || y.changed == epoch_) continue;
          next_candidates_[candidates++] = k;
          if (overlaps(x.exact, y.exact))
            touching_[pairs++] = pair_of(proxy_id{k.a, x.generation}, proxy_id{k.b, y.generation});
        }
        kept_[c] = {candidates - begin, pairs - begin};
      }
    };
    impulse::detail::parallel_for(tasks, chunks, min_chunks, judge);
    std::uint32_t candidates = 0;
    found_.clear();
    for (std::uint32_t c = 0; c < chunks; ++c) {
      const std::uint32_t begin = c * chunk;
      if (candidates != begin)
        std::copy_n(next_candidates_.begin() + begin, kept_[c].candidates, next_candidates_.begin() + candidates);
      candidates += kept_[c].candidates;
      found_.insert(found_.end(), touching_.begin() + begin, touching_.begin() + begin + kept_[c].pairs);
    }
    next_candidates_.resize(candidates);
  }
  /// What chunk of carried candidates kept: candidates, and pairs among them.
  struct kept_count {
    std::uint32_t candidates, pairs;
  };
  /// Candidates a chunk judges, and the chunks a worker takes at a time at
  /// the least: about 5 ns a candidate, so a range is 10 µs or more.
  static constexpr std::uint32_t chunk = 1024, min_chunks = 2;

  /// Every pair of leaves whose fat boxes overlap and at least one of
  /// which is stamped: each stamped subtree against itself (its halves each
  /// against themselves and against each other), opening a pair of
  /// distinct subtrees only when their boxes overlap and one of them is
  /// stamped. Every pair of leaves meets once, at the subtree where their
  /// paths from the root part.
  void find_new_candidates() {
    const auto& nodes = tree_.nodes();
    const std::uint32_t epoch = epoch_;
    // Tested before pushing, so the stack holds only pairs to open.
    const auto push_if_candidate = [&](std::int32_t x, std::int32_t y) {
      const detail::tree_node<T>& a = nodes[x];
      const detail::tree_node<T>& b = nodes[y];
      if ((a.mark == epoch || b.mark == epoch) && overlaps(a.box, b.box)) cross_.push_back({x, y});
    };
    selves_.clear();
    cross_.clear();
    if (nodes[tree_.root()].mark == epoch) selves_.push_back(tree_.root());
    while (!selves_.empty()) {
      const detail::tree_node<T>& a = nodes[selves_.back()];
      selves_.pop_back();
      if (a.is_leaf()) continue;
      if (nodes[a.child1].mark == epoch) selves_.push_back(a.child1);
      if (nodes[a.child2].mark == epoch) selves_.push_back(a.child2);
      push_if_candidate(a.child1, a.child2);
      while (!cross_.empty()) {
        const auto [x, y] = cross_.back();
        cross_.pop_back();
        const detail::tree_node<T>& p = nodes[x];
        const detail::tree_node<T>& q = nodes[y];
        // Open the taller side, so that the two sides shrink together.
        if (p.is_leaf() && q.is_leaf()) {
          keep_candidate(p.payload, q.payload);
        } else if (q.is_leaf() || (!p.is_leaf() && p.height >= q.height)) {
          push_if_candidate(p.child1, y);
          push_if_candidate(p.child2, y);
        } else {
          push_if_candidate(x, q.child1);
          push_if_candidate(x, q.child2);
        }
      }
    }
  }

  T margin_;
  detail::proxy_store<T> store_;
  detail::dynamic_tree<T> tree_;
  detail::pair_tracker pairs_;
  std::vector<proxy_pair> found_;
  std::vector<slot_data> slots_;                         ///< by proxy slot
  std::vector<candidate> candidates_, next_candidates_;  ///< fat-box overlaps, each once
  std::vector<std::uint32_t> changed_;                   ///< slots whose fat box changed since the last update, each once
  std::vector<std::int32_t> selves_;                     ///< scratch for the self traversal
  std::vector<node_pair> cross_;                         ///< scratch for the self traversal
  std::vector<proxy_pair> touching_;                     ///< scratch for keep_candidates, by candidate
  std::vector<kept_count> kept_;                         ///< scratch for keep_candidates, by chunk
  std::uint32_t epoch_ = 1;
  std::size_t reinserted_ = 0, reinserted_since_update_ = 0;
};

// The members that do the work out of the class, not inline: where a
// program declares the tree extern (IMPULSE_EXTERN_TEMPLATES,
// core/extern_templates.hpp), its files then compile none of them.

template <scalar_type T>
proxy_id basic_dynamic_bvh<T>::create(const aabb<T>& box, std::uint64_t user_data) {
  const proxy_id id = store_.insert(box, user_data);  // validates before anything changes
  if (id.index >= slots_.size()) slots_.resize(id.index + 1);
  slot_data& s = slots_[id.index];
  s.exact = box;
  s.generation = id.generation;
  s.leaf = tree_.create_leaf(expand(box, margin_), id.index);
  fat_box_changed(id.index);
  return id;
}

template <scalar_type T>
void basic_dynamic_bvh<T>::move(proxy_id id, const aabb<T>& box) {
  store_.set_box(id, box);  // validates before anything changes
  slot_data& s = slots_[id.index];
  const aabb<T> old = s.exact;
  s.exact = box;
  if (impulse::contains(tree_.box(s.leaf), box)) return;  // the tree and the candidates stand
  tree_.move_leaf(s.leaf, fatten(old, box));
  fat_box_changed(id.index);
  ++reinserted_since_update_;
}

template <scalar_type T>
void basic_dynamic_bvh<T>::destroy(proxy_id id) {
  store_.erase(id);  // validates before anything changes
  tree_.destroy_leaf(slots_[id.index].leaf);
  slots_[id.index].leaf = detail::null_node;
  fat_box_changed(id.index);  // its candidates go at the next update
}

template <scalar_type T>
void basic_dynamic_bvh<T>::update(const task_system& tasks) {
  if (!store_.take_changed()) {  // nothing came, moved or went
    reinserted_ = 0;
    return pairs_.keep();
  }
  // Stamp every leaf whose fat box changed, and its ancestors, stopping
  // at the first ancestor already stamped: the path above it is done.
  auto& nodes = tree_.nodes();
  for (const std::uint32_t slot : changed_) {
    std::int32_t node = slots_[slot].leaf;
    while (node != detail::null_node && nodes[node].mark != epoch_) {
      nodes[node].mark = epoch_;
      node = nodes[node].parent;
    }
  }

  keep_candidates(tasks);
  if (!changed_.empty() && tree_.root() != detail::null_node) find_new_candidates();
  candidates_.swap(next_candidates_);
  pairs_.publish(found_);

  changed_.clear();
  reinserted_ = reinserted_since_update_;
  reinserted_since_update_ = 0;
  if (++epoch_ == 0) restart_epochs();
}

/// The dynamic BVH policy, for a config's `broadphase`.
struct dynamic_bvh {
  static constexpr policy_kind kind = policy_kind::broadphase;
  template <scalar_type T>
  using type = basic_dynamic_bvh<T>;
};

}  // namespace impulse::broadphase
