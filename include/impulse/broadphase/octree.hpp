// impulse/broadphase/octree.hpp — a loose octree: each box filed by its size
// and its center, kept as a sorted array of occupied cells (a linear octree).
//
// Ulrich, "Loose Octrees", Game Programming Gems (2000); Ericson, Real-Time
// Collision Detection (2005) §7.3 (octrees: linear, hash-based octrees,
// Morton keys, loose octrees). The root is a cube of edge e_0 (a power of two); a node at depth
// d is one of the 8^d cells of edge e_d = e_0 / 2^d, and its *loose* box is
// the cell grown by half its edge on every side (looseness k = 2: twice the
// cell's edge). A box whose center lies in a cell and whose largest extent
// is at most e_d lies inside that cell's loose box, so every box is filed,
// without any search, in the cell of depth
//
//     d = min(max_depth, floor(log2(e_0 / largest extent)))
//
// that holds its center. Small boxes sink deep, big ones stay near the
// root, and a box that moves a little keeps its cell: coherent motion costs
// one key computation and no list surgery.
//
// Layout. A node is an occupied cell, named by a 64-bit key: its depth,
// then its Morton code at that depth, so that in key order the cells of one
// depth are contiguous and every aligned block of cells is one run. update()
// keeps the proxies in one array sorted by key: a proxy whose key changed is
// taken out and merged back in (O(n + k log k) for k changes), the others
// stay where they are. The nodes are then one pass over that array (the run
// of each key, with the tight box of its proxies), the proxies' boxes are
// copied beside them in the same order, and the nodes are gathered into
// blocks of 4×4×4 cells of one depth: a small open-addressing table (our
// own: no std::unordered_map) maps a block to a 64-bit mask of its occupied
// cells and its first node, so that one lookup answers for a neighbourhood
// and a node is found by counting bits. Nothing is allocated once the
// arrays have grown.
//
// Pairs. Two proxies overlap only if each lies in the other's node's loose
// box. Each node therefore looks, at its own depth and at every occupied
// depth above it, for the cells whose nodes may reach the tight box of its
// proxies — two or three per axis, fewer when the boxes filed at a depth
// stick out of their cells by less than the loose half edge, which update()
// measures — and tests its proxies against theirs. A pair across depths is
// found once, by the deeper node; a pair at one depth once, by the node
// with the smaller key; a pair in one node, by that node: no set is needed.
// Queries and rays descend each occupied depth's run as an implicit octree
// (each cell's descendants are a sub-run, found by binary search), pruned
// by loose boxes, rays nearest cell first.
//
// The root is built around the data: its edge is the power of two at least
// 1.5 times the data's largest extent, so that boxes may wander a sixth of
// it beyond the data before the root must grow. A box created or moved
// outside the root cell makes the root be chosen again around all proxies
// and every key recomputed (a rebuild, not a re-root by doubling: O(n log n),
// rare, since the data must spread by a sixth of the root's edge each time);
// when the data shrinks to an eighth of the root, update() rebuilds it
// smaller, so that a scene that has moved away does not end up crowded into
// a few deep cells.
//
// Exactness. The root's corner is a multiple of e_0/16 and e_0 is at least
// 2^(max_depth + 4) rounding steps of the farthest coordinate, so every cell
// corner, and every loose box, is exact in T, 1e5 m from the origin as at
// it. A box is filed only where the loose box computed by loose_box()
// contains it (should rounding of its center say otherwise, one level up);
// the pair search enumerates cells with a margin that covers its own
// rounding; and pruning a query or a ray by a box that contains the
// proxy's box never loses a hit, because comparisons and the slab test are
// monotone in the box's corners even in floating point. Pairs, queries and
// rays are decided on the proxies' own boxes with overlaps()/ray_enters().
//
// Worst cases. Boxes much smaller than e_0 / 2^max_depth all land in the
// deepest cells, and a cell's proxies are tested all against all: a scene
// thousands of times wider than its boxes (or a few far outliers that make
// the root that wide) wants a larger max_depth. Many boxes overlapping one
// another cost what their pairs cost.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "../core/error.hpp"
#include "../core/policy.hpp"
#include "../math/aabb.hpp"
#include "detail/pair_tracker.hpp"
#include "proxy.hpp"
#include "detail/proxy_store.hpp"

namespace impulse::broadphase {

template <scalar_type T>
class basic_octree {
 public:
  /// Deepest tree that can be asked for: keys hold 16 bits per axis, and
  /// 2^16 cells across the root is already finer than a float resolves.
  static constexpr int max_supported_depth = 16;

  basic_octree() = default;

  /// max_depth (0 to 16, default 8): how many times the root cube may be
  /// halved. Boxes smaller than the root's edge / 2^max_depth all share the
  /// deepest cells, so a small cap crowds small boxes together (all-pairs
  /// tests within a cell); a large one only adds depths to look through,
  /// and once the deepest cells are about as small as the smallest boxes
  /// it gains nothing. The root is 1.5 to 3 times the scene, so 8 suits
  /// scenes up to about 100 times as wide as their smallest boxes; 0 makes
  /// one cell of everything (brute force).
  explicit basic_octree(int max_depth) : max_depth_(max_depth) {
    if (max_depth < 0 || max_depth > max_supported_depth)
      impulse::detail::report_error(error_code::invalid_parameter, "octree: max_depth must be in [0, 16]");
  }

  /// Boxes must be finite, not inverted, and within ±largest/64 of T
  /// (about 5e36 in float): beyond it the root's edge would overflow.
  proxy_id create(const aabb<T>& box, std::uint64_t user_data) {
    require_in_range(box);
    const proxy_id id = store_.insert(box, user_data);
    if (entries_.size() <= id.index) {
      entries_.resize(id.index + 1);
      dirty_flags_.resize(id.index + 1);
    }
    entry& e = entries_[id.index];
    e.box = box;
    e.id = id;
    if (!has_root_ || !impulse::contains(root_cell_, box)) {
      regrow();
    } else {
      e.key = key_of(box);
      mark_dirty(id.index);
    }
    return id;
  }

  void move(proxy_id id, const aabb<T>& box) {
    store_.require(id);
    require_in_range(box);
    store_.set_box(id, box);
    entry& e = entries_[id.index];
    e.box = box;
    if (!impulse::contains(root_cell_, box)) return regrow();
    const std::uint64_t key = key_of(box);
    if (key == e.key) return;  // the same cell: the box is updated in place
    e.key = key;
    mark_dirty(id.index);
  }

  void destroy(proxy_id id) {
    store_.erase(id);  // validates first
    entries_[id.index].key = dead_key;
    mark_dirty(id.index);
    if (store_.size() == 0) has_root_ = false;  // the next box chooses the root afresh
  }

  void update() {
    if (!store_.take_changed()) return pairs_.keep();  // nothing came, moved or went
    found_.clear();
    refresh();
    if (should_shrink()) {
      regrow();
      refresh();
    }
    find_pairs();
    pairs_.publish(found_);
  }

  [[nodiscard]] std::span<const proxy_pair> pairs() const noexcept { return pairs_.pairs(); }
  [[nodiscard]] std::span<const proxy_pair> begun() const noexcept { return pairs_.begun(); }
  [[nodiscard]] std::span<const proxy_pair> ended() const noexcept { return pairs_.ended(); }

  /// Calls callback(id) for every proxy whose box overlaps `box`, descending
  /// the cells whose loose boxes overlap it. Sees every create, move and
  /// destroy so far: proxies that changed cell since the last update() are
  /// tested one by one.
  template <class Callback>
  void query(const aabb<T>& box, Callback&& callback) const {
    detail::proxy_store<T>::require_box(box);
    for (const std::uint32_t slot : dirty_)
      if (entries_[slot].key != dead_key && overlaps(entries_[slot].box, box)) callback(entries_[slot].id);
    if (!tree_current_) return;
    for (std::uint32_t depths = depths_; depths != 0; depths &= depths - 1) {
      const int d = std::countr_zero(depths);
      query_cell(d, {0, {0, 0, 0}}, 0, level_begin_[d], level_end_[d], box, callback);
    }
  }

  /// Calls callback(id, fraction) for every proxy whose box the segment
  /// enters within [0, max_fraction], taking the callback's answer as the
  /// new max_fraction (0 stops). Within each depth, cells are visited
  /// nearest entry first, so that a clipping callback prunes early.
  template <class Callback>
  void ray_cast(const ray<T>& r, T max_fraction, Callback&& callback) const {
    detail::require_ray(r, max_fraction);
    if (!(max_fraction > T(0))) return;
    for (const std::uint32_t slot : dirty_) {
      const entry& e = entries_[slot];
      if (e.key == dead_key) continue;
      if (const auto t = ray_enters(r, max_fraction, e.box)) {
        max_fraction = callback(e.id, *t);
        if (!(max_fraction > T(0))) return;
      }
    }
    if (!tree_current_) return;
    for (std::uint32_t depths = depths_; depths != 0; depths &= depths - 1) {
      const int d = std::countr_zero(depths);
      if (!ray_cell(d, {0, {0, 0, 0}}, 0, level_begin_[d], level_end_[d], r, max_fraction, callback)) return;
    }
  }

  [[nodiscard]] const aabb<T>& box(proxy_id id) const { return store_.box(id); }
  [[nodiscard]] std::uint64_t user_data(proxy_id id) const { return store_.user_data(id); }
  [[nodiscard]] bool contains(proxy_id id) const noexcept { return store_.contains(id); }
  [[nodiscard]] std::size_t size() const noexcept { return store_.size(); }

  /// Occupied cells as of the last update(): 0 when empty.
  [[nodiscard]] std::size_t node_count() const noexcept { return nodes_.size(); }
  /// The depth of the cell where the proxy is filed (0 is the root), as of now.
  [[nodiscard]] int depth_of(proxy_id id) const {
    store_.require(id);
    return depth_of_key(entries_[id.index].key);
  }
  /// The root cell (not its loose box): every proxy's box lies inside it.
  /// aabb::empty() while there are no proxies.
  [[nodiscard]] aabb<T> root_box() const noexcept { return has_root_ ? root_cell_ : aabb<T>::empty(); }
  [[nodiscard]] int max_depth() const noexcept { return max_depth_; }

 private:
  static constexpr std::uint64_t dead_key = ~std::uint64_t(0);  // never a real key (those use 53 bits)
  static constexpr std::uint64_t code_mask = (std::uint64_t(1) << 48) - 1;
  // Runs of at most this many nodes are tested node by node rather than
  // split into eight: below it the binary searches cost more.
  static constexpr std::uint32_t small_range = 8;

  struct entry {  ///< a proxy, by slot index
    aabb<T> box;
    proxy_id id;
    std::uint64_t key = dead_key;  ///< its cell now (dead_key once destroyed)
  };
  struct item {  ///< a proxy in key order
    std::uint64_t key;
    std::uint32_t slot;
    friend bool operator<(const item& a, const item& b) noexcept {
      return a.key != b.key ? a.key < b.key : a.slot < b.slot;
    }
  };
  struct cell {
    int depth;
    std::uint32_t xyz[3];
  };
  struct node {  ///< an occupied cell, as of the last update (its key is in node_keys_)
    aabb<T> tight;             ///< around its proxies' boxes
    std::uint32_t begin, end;  ///< its proxies in sorted_ and packed_*
  };
  /// 4×4×4 cells of one depth: which are nodes, and the first of them
  /// (the others follow in Morton order, so a node's index is the first's
  /// plus the number of occupied cells before it).
  struct block {
    std::uint64_t key;  ///< the cells' keys without their low 6 bits
    std::uint64_t occupied;
    std::uint32_t first;
  };

  // ---- keys --------------------------------------------------------------

  /// Spreads the low 16 bits of v so that bit i lands on bit 3i.
  static constexpr std::uint64_t spread(std::uint64_t v) noexcept {
    v &= 0xffff;
    v = (v | v << 16) & 0x0000ff0000ffull;
    v = (v | v << 8) & 0x00f00f00f00full;
    v = (v | v << 4) & 0x0c30c30c30c3ull;
    v = (v | v << 2) & 0x249249249249ull;
    return v;
  }
  /// The inverse of spread.
  static constexpr std::uint32_t compact(std::uint64_t v) noexcept {
    v &= 0x249249249249ull;
    v = (v | v >> 2) & 0x0c30c30c30c3ull;
    v = (v | v >> 4) & 0x00f00f00f00full;
    v = (v | v >> 8) & 0x0000ff0000ffull;
    v = (v | v >> 16) & 0xffff;
    return std::uint32_t(v);
  }
  static constexpr std::uint64_t morton(std::uint32_t x, std::uint32_t y, std::uint32_t z) noexcept {
    return spread(x) | spread(y) << 1 | spread(z) << 2;
  }
  static constexpr std::uint64_t key_of(const cell& c) noexcept {
    return std::uint64_t(c.depth) << 48 | morton(c.xyz[0], c.xyz[1], c.xyz[2]);
  }
  static constexpr int depth_of_key(std::uint64_t key) noexcept { return int(key >> 48); }
  static constexpr cell cell_of(std::uint64_t key) noexcept {
    const std::uint64_t code = key & code_mask;
    return {depth_of_key(key), {compact(code), compact(code >> 1), compact(code >> 2)}};
  }
  /// std::popcount, unless that would be a library call (x86-64 without
  /// POPCNT): the bit trick is then several times faster.
  static constexpr std::uint32_t count_bits(std::uint64_t v) noexcept {
#if defined(__x86_64__) && !defined(__POPCNT__)
    v = v - (v >> 1 & 0x5555555555555555ull);
    v = (v & 0x3333333333333333ull) + (v >> 2 & 0x3333333333333333ull);
    v = (v + (v >> 4)) & 0x0f0f0f0f0f0f0f0full;
    return std::uint32_t((v * 0x0101010101010101ull) >> 56);
#else
    return std::uint32_t(std::popcount(v));
#endif
  }
  /// The cells of a block whose coordinate along `axis` lies in [a, b]
  /// (0 ≤ a ≤ b ≤ 3), as a mask over the block's Morton order.
  static constexpr std::uint64_t slab_mask(int axis, std::uint32_t a, std::uint32_t b) noexcept {
    std::uint64_t mask = 0;
    for (std::uint32_t bit = 0; bit < 64; ++bit) {
      const std::uint32_t v = (bit >> axis & 1) | (bit >> (axis + 3) & 1) << 1;  // the axis's two bits
      if (a <= v && v <= b) mask |= std::uint64_t(1) << bit;
    }
    return mask;
  }

  /// overlaps() from math/aabb.hpp without its short-circuit branches: in
  /// the pair search the answer is mostly no, after a varying number of
  /// axes, which the branch predictor cannot learn.
  static bool touch(const aabb<T>& a, const aabb<T>& b) noexcept {
    return (a.lower.x <= b.upper.x) & (b.lower.x <= a.upper.x) & (a.lower.y <= b.upper.y) &
           (b.lower.y <= a.upper.y) & (a.lower.z <= b.upper.z) & (b.lower.z <= a.upper.z);
  }

  // ---- filing ------------------------------------------------------------

  /// The cell a box belongs in: depth from its size, position from its
  /// center; then, should rounding leave the box a hair outside that cell's
  /// loose box, the nearest ancestor whose loose box holds it.
  cell cell_for(const aabb<T>& b) const noexcept {
    const T size = std::max({b.upper.x - b.lower.x, b.upper.y - b.lower.y, b.upper.z - b.lower.z});
    int d = max_depth_;
    while (d > 0 && edge_[d] < size) --d;
    const T center[3] = {(b.lower.x + b.upper.x) * T(0.5), (b.lower.y + b.upper.y) * T(0.5),
                         (b.lower.z + b.upper.z) * T(0.5)};
    const T corner[3] = {root_lower_.x, root_lower_.y, root_lower_.z};
    const T last = T((std::uint32_t(1) << d) - 1);
    cell c{d, {}};
    for (int a = 0; a < 3; ++a)
      c.xyz[a] = std::uint32_t(std::clamp(std::floor((center[a] - corner[a]) * inverse_edge_[d]), T(0), last));
    while (c.depth > 0 && !impulse::contains(loose_box(c), b)) {
      --c.depth;
      for (auto& x : c.xyz) x >>= 1;
    }
    return c;
  }
  std::uint64_t key_of(const aabb<T>& b) const noexcept { return key_of(cell_for(b)); }

  /// A cell's loose box. Every loose box is computed here, so that filing
  /// and pruning agree to the last bit (K·e is exact: e is a power of two
  /// and K < 2^16, so a fused multiply-add changes nothing).
  T loose_lower(int depth, std::uint32_t k, T corner) const noexcept {
    return (corner + T(k) * edge_[depth]) - edge_[depth] * T(0.5);
  }
  T loose_upper(int depth, std::uint32_t k, T corner) const noexcept {
    return (corner + T(k) * edge_[depth]) + edge_[depth] * T(1.5);
  }
  aabb<T> loose_box(const cell& c) const noexcept {
    return {{loose_lower(c.depth, c.xyz[0], root_lower_.x), loose_lower(c.depth, c.xyz[1], root_lower_.y),
             loose_lower(c.depth, c.xyz[2], root_lower_.z)},
            {loose_upper(c.depth, c.xyz[0], root_lower_.x), loose_upper(c.depth, c.xyz[1], root_lower_.y),
             loose_upper(c.depth, c.xyz[2], root_lower_.z)}};
  }

  /// The cells along one axis at a depth whose nodes may reach [lo, hi] (a
  /// node's tight box, inside the root's loose box), given that no node of
  /// that depth sticks out of its cell by more than `reach` (at most half
  /// the edge: the loose box; often less, as when the boxes filed at a
  /// depth are all well under its cell size): cell K may reach [lo, hi]
  /// when (lo - corner - reach)/e - 1 ≤ K ≤ (hi - corner + reach)/e. Computed,
  /// those bounds are off by less than 3·2^d·ε cells (|lo - corner| ≤
  /// 1.5 e_0, and multiplying by a power of two is exact), so widening them
  /// by margin_[depth] keeps every such cell; a cell too many only costs a
  /// lookup.
  bool cells_reaching(int depth, T lo, T hi, T corner, T reach, std::uint32_t& first,
                      std::uint32_t& last) const noexcept {
    // |values| < 2^18 here, so int conversions are safe; truncation and one
    // correction are much cheaper than std::floor and std::ceil without SSE4.1.
    const T x0 = (lo - corner - reach) * inverse_edge_[depth] - T(1) - margin_[depth];
    const T x1 = (hi - corner + reach) * inverse_edge_[depth] + margin_[depth];
    int k0 = int(x0), k1 = int(x1);
    k0 += T(k0) < x0;  // ceil
    k1 -= T(k1) > x1;  // floor
    const int top = (1 << depth) - 1;
    if (k0 > k1 || k1 < 0 || k0 > top) return false;
    first = std::uint32_t(std::max(k0, 0));
    last = std::uint32_t(std::min(k1, top));
    return true;
  }

  static void prefetch(const void* p) noexcept {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p);
#else
    (void)p;
#endif
  }

  /// Refuses what the store refuses, and boxes too far out for a root.
  static void require_in_range(const aabb<T>& box) {
    detail::proxy_store<T>::require_box(box);
    constexpr T limit = std::numeric_limits<T>::max() / T(64);
    const vec3<T> far = max(abs(box.lower), abs(box.upper));
    if (far.x > limit || far.y > limit || far.z > limit)
      impulse::detail::report_error(error_code::invalid_parameter,
                                    "octree: the box lies beyond ±(largest finite value / 64) of its scalar type");
  }

  void mark_dirty(std::uint32_t slot) {
    if (dirty_flags_[slot]) return;
    dirty_flags_[slot] = 1;
    dirty_.push_back(slot);
  }

  // ---- the root ----------------------------------------------------------

  /// The root edge for data spanning `bounds`: a power of two at least 1.5
  /// times the largest extent, and at least 2^(max_depth + 4) rounding
  /// steps of the farthest coordinate, so that the deepest cells stay wider
  /// than the scalar's resolution there (finer cells far from the origin
  /// would only sort rounding noise) and cell corners stay exact.
  T root_edge_for(const aabb<T>& bounds) const noexcept {
    const vec3<T> extent = bounds.upper - bounds.lower;
    const vec3<T> far = max(abs(bounds.lower), abs(bounds.upper));
    const T largest = std::max({extent.x, extent.y, extent.z});
    const T magnitude = std::max({far.x, far.y, far.z});
    T wanted = std::max(T(1.5) * largest, std::ldexp(magnitude * std::numeric_limits<T>::epsilon(), max_depth_ + 4));
    if (!(wanted > T(0))) wanted = T(1);  // a single point at the origin: any size will do
    T e = std::ldexp(T(1), std::ilogb(wanted));
    if (e < wanted) e *= T(2);
    return e;
  }

  /// Chooses the root around all proxies and files them all again.
  void regrow() {
    aabb<T> bounds = aabb<T>::empty();
    for (const auto& p : store_.values()) bounds = merge(bounds, p.box);
    T e = root_edge_for(bounds);
    const vec3<T> mid = center(bounds);
    for (;;) {
      // The corner snapped to a sixteenth of the edge, so that cell corners
      // are round numbers; the 1.5× slack leaves room for the snap.
      const T snap = e / T(16);
      root_lower_ = {std::floor((mid.x - e * T(0.5)) / snap) * snap, std::floor((mid.y - e * T(0.5)) / snap) * snap,
                     std::floor((mid.z - e * T(0.5)) / snap) * snap};
      root_cell_ = {root_lower_, root_lower_ + vec3<T>::splat(e)};
      if (impulse::contains(root_cell_, bounds)) break;
      e *= T(2);  // only if rounding far away defeated the slack
    }
    for (int d = 0; d <= max_supported_depth; ++d) {
      edge_[d] = std::ldexp(e, -d);
      inverse_edge_[d] = std::ldexp(T(1) / e, d);
      margin_[d] = T(4 * (1 << d) + 8) * std::numeric_limits<T>::epsilon();  // the bound, with room to spare
    }
    has_root_ = true;
    tree_current_ = false;  // the nodes' cells meant other places: skip them until update()
    for (const proxy_id id : store_.ids()) {
      entries_[id.index].key = key_of(entries_[id.index].box);
      mark_dirty(id.index);
    }
  }

  /// After refresh(): true when a root a quarter the size (or smaller)
  /// would hold the data.
  bool should_shrink() const noexcept {
    if (nodes_.empty()) return false;
    aabb<T> bounds = aabb<T>::empty();
    for (const node& n : nodes_) bounds = merge(bounds, n.tight);
    return root_edge_for(bounds) * T(4) <= edge_[0];
  }

  // ---- update ------------------------------------------------------------

  void refresh() {
    resort();
    build_nodes();
    build_blocks();
    tree_current_ = true;
  }

  /// Takes the proxies whose cell changed out of the sorted array and
  /// merges them back in at their new keys; the rest keep their places.
  void resort() {
    if (dirty_.empty()) return;
    std::size_t kept = 0;
    for (const item& it : sorted_)
      if (!dirty_flags_[it.slot]) sorted_[kept++] = it;
    sorted_.resize(kept);
    fresh_.clear();
    for (const std::uint32_t slot : dirty_) {
      dirty_flags_[slot] = 0;
      if (entries_[slot].key != dead_key) fresh_.push_back({entries_[slot].key, slot});
    }
    dirty_.clear();
    std::sort(fresh_.begin(), fresh_.end());
    merged_.resize(sorted_.size() + fresh_.size());
    std::merge(sorted_.begin(), sorted_.end(), fresh_.begin(), fresh_.end(), merged_.begin());
    sorted_.swap(merged_);
  }

  /// One pass over the sorted proxies: their boxes and ids side by side,
  /// a node for each run of one key, and how far the nodes of each depth
  /// stick out of their cells.
  void build_nodes() {
    const std::size_t n = sorted_.size();
    packed_box_.resize(n);
    packed_id_.resize(n);
    nodes_.clear();
    node_keys_.clear();
    depths_ = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
      // The entries are read in space order, not slot order: ask for them a
      // few ahead, so that the cache misses overlap.
      if (i + 8 < n) prefetch(&entries_[sorted_[i + 8].slot]);
      const item it = sorted_[i];
      const entry& e = entries_[it.slot];
      packed_box_[i] = e.box;
      packed_id_[i] = e.id;
      if (node_keys_.empty() || node_keys_.back() != it.key) {
        const int d = depth_of_key(it.key);
        const auto index = std::uint32_t(nodes_.size());
        if (!(depths_ >> d & 1)) level_begin_[d] = index;
        level_end_[d] = index + 1;
        depths_ |= 1u << d;
        nodes_.push_back({e.box, i, i});
        node_keys_.push_back(it.key);
      }
      node& last = nodes_.back();
      last.end = i + 1;
      last.tight = merge(last.tight, e.box);
    }
    for (auto& r : reach_) r[0] = r[1] = r[2] = T(0);
    const T corner[3] = {root_lower_.x, root_lower_.y, root_lower_.z};
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      const node& n = nodes_[i];
      const cell c = cell_of(node_keys_[i]);
      const T e = edge_[c.depth];
      T* r = reach_[c.depth];
      const T lo[3] = {n.tight.lower.x, n.tight.lower.y, n.tight.lower.z};
      const T hi[3] = {n.tight.upper.x, n.tight.upper.y, n.tight.upper.z};
      for (int a = 0; a < 3; ++a) {
        const T lower = corner[a] + T(c.xyz[a]) * e;  // exact, as in loose_lower
        r[a] = std::max({r[a], lower - lo[a], hi[a] - (lower + e)});
      }
    }
  }

  /// The blocks, in an open-addressing table at most half full.
  void build_blocks() {
    std::size_t count = 0;
    for (std::size_t i = 0; i < node_keys_.size(); ++i) count += i == 0 || (node_keys_[i] >> 6) != (node_keys_[i - 1] >> 6);
    std::size_t capacity = 16;
    while (capacity < 2 * count) capacity *= 2;
    table_.assign(capacity, {dead_key, 0, 0});
    table_shift_ = 64 - std::countr_zero(capacity);
    const std::size_t mask = capacity - 1;
    std::size_t b = 0;
    for (std::uint32_t i = 0; i < node_keys_.size(); ++i) {
      const std::uint64_t key = node_keys_[i] >> 6;
      if (i == 0 || key != (node_keys_[i - 1] >> 6)) {
        b = bucket_of(key);
        while (table_[b].key != dead_key) b = (b + 1) & mask;
        table_[b] = {key, 0, i};
      }
      table_[b].occupied |= std::uint64_t(1) << (node_keys_[i] & 63);
    }
  }
  std::size_t bucket_of(std::uint64_t key) const noexcept {
    return std::size_t((key * 0x9e3779b97f4a7c15ull) >> table_shift_);  // Fibonacci hashing
  }
  const block* find_block(std::uint64_t key) const noexcept {
    const std::size_t mask = table_.size() - 1;
    for (std::size_t b = bucket_of(key);; b = (b + 1) & mask) {
      if (table_[b].key == key) return &table_[b];
      if (table_[b].key == dead_key) return nullptr;
    }
  }

  void find_pairs() {
    static constexpr auto slabs = [] {
      struct {
        std::uint64_t mask[3][4][4];
      } t{};
      for (int axis = 0; axis < 3; ++axis)
        for (std::uint32_t a = 0; a < 4; ++a)
          for (std::uint32_t b = a; b < 4; ++b) t.mask[axis][a][b] = slab_mask(axis, a, b);
      return t;
    }();
    const T corner[3] = {root_lower_.x, root_lower_.y, root_lower_.z};
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      const node& n = nodes_[i];
      const std::uint64_t own_key = node_keys_[i];
      if (n.end - n.begin > 1) pairs_within(n.begin, n.end);
      const int depth = depth_of_key(own_key);
      const std::uint64_t own_block = own_key >> 6;
      const unsigned own_bit = unsigned(own_key & 63);
      const std::uint64_t after_own = own_bit == 63 ? 0 : ~std::uint64_t(0) << (own_bit + 1);
      for (std::uint32_t depths = depths_ & ((2u << depth) - 1); depths != 0; depths &= depths - 1) {
        const int d = std::countr_zero(depths);
        std::uint32_t first[3], last[3];
        if (!cells_reaching(d, n.tight.lower.x, n.tight.upper.x, corner[0], reach_[d][0], first[0], last[0]) ||
            !cells_reaching(d, n.tight.lower.y, n.tight.upper.y, corner[1], reach_[d][1], first[1], last[1]) ||
            !cells_reaching(d, n.tight.lower.z, n.tight.upper.z, corner[2], reach_[d][2], first[2], last[2]))
          continue;
        const std::uint64_t depth_bits = std::uint64_t(d) << 42;
        for (std::uint32_t bz = first[2] >> 2; bz <= last[2] >> 2; ++bz) {
          const std::uint64_t mz = slabs.mask[2][bz == first[2] >> 2 ? first[2] & 3 : 0][bz == last[2] >> 2 ? last[2] & 3 : 3];
          const std::uint64_t kz = depth_bits | spread(bz) << 2;
          for (std::uint32_t by = first[1] >> 2; by <= last[1] >> 2; ++by) {
            const std::uint64_t myz =
                mz & slabs.mask[1][by == first[1] >> 2 ? first[1] & 3 : 0][by == last[1] >> 2 ? last[1] & 3 : 3];
            const std::uint64_t kyz = kz | spread(by) << 1;
            for (std::uint32_t bx = first[0] >> 2; bx <= last[0] >> 2; ++bx) {
              const std::uint64_t key = kyz | spread(bx);
              if (d == depth && key < own_block) continue;  // those nodes find their pairs with n themselves
              const block* b = find_block(key);
              if (!b) continue;
              std::uint64_t hits =
                  b->occupied & myz &
                  slabs.mask[0][bx == first[0] >> 2 ? first[0] & 3 : 0][bx == last[0] >> 2 ? last[0] & 3 : 3];
              if (key == own_block) hits &= after_own;
              for (; hits != 0; hits &= hits - 1) {
                const std::uint64_t below = (hits ^ (hits - 1)) >> 1;  // the bits under the lowest hit
                const node& m = nodes_[b->first + count_bits(b->occupied & below)];
                if (touch(m.tight, n.tight)) pairs_between(n.begin, n.end, m.begin, m.end, m.tight);
              }
            }
          }
        }
      }
    }
  }

  void pairs_within(std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t i = begin; i < end; ++i) {
      const aabb<T> a = packed_box_[i];
      for (std::uint32_t j = i + 1; j < end; ++j)
        if (touch(a, packed_box_[j])) found_.push_back(pair_of(packed_id_[i], packed_id_[j]));
    }
  }

  /// Packed [a0, a1) against packed [b0, b1), whose boxes lie in b_bound:
  /// a proxy that misses the bound skips the inner loop.
  void pairs_between(std::uint32_t a0, std::uint32_t a1, std::uint32_t b0, std::uint32_t b1, const aabb<T>& b_bound) {
    for (std::uint32_t i = a0; i < a1; ++i) {
      const aabb<T> a = packed_box_[i];
      if (!touch(a, b_bound)) continue;
      for (std::uint32_t j = b0; j < b1; ++j)
        if (touch(a, packed_box_[j])) found_.push_back(pair_of(packed_id_[i], packed_id_[j]));
    }
  }

  // ---- descents for queries and rays --------------------------------------

  /// Splits nodes [begin, end) of one depth, those under cell c (shallower,
  /// with Morton code `code`), into c's eight children's runs: child j's is
  /// [bounds[j], bounds[j + 1]).
  void split(int depth, const cell& c, std::uint64_t code, std::uint32_t begin, std::uint32_t end,
             std::uint32_t (&bounds)[9]) const noexcept {
    const int shift = 3 * (depth - c.depth - 1);
    bounds[0] = begin;
    bounds[8] = end;
    auto from = node_keys_.begin() + begin;
    for (std::uint64_t j = 1; j < 8; ++j) {
      from = std::lower_bound(from, node_keys_.begin() + end, std::uint64_t(depth) << 48 | (code * 8 + j) << shift);
      bounds[j] = std::uint32_t(from - node_keys_.begin());
    }
  }
  static cell child_of(const cell& c, int j) noexcept {
    return {c.depth + 1, {2 * c.xyz[0] + std::uint32_t(j & 1), 2 * c.xyz[1] + std::uint32_t(j >> 1 & 1),
                          2 * c.xyz[2] + std::uint32_t(j >> 2 & 1)}};
  }

  template <class Callback>
  void query_node(const node& n, const aabb<T>& box, Callback& callback) const {
    for (std::uint32_t i = n.begin; i < n.end; ++i) {
      const std::uint32_t slot = sorted_[i].slot;
      if (!dirty_flags_[slot] && overlaps(entries_[slot].box, box)) callback(entries_[slot].id);  // else from dirty_
    }
  }

  /// The nodes [begin, end) of one depth under cell c (Morton code `code`).
  template <class Callback>
  void query_cell(int depth, const cell& c, std::uint64_t code, std::uint32_t begin, std::uint32_t end,
                  const aabb<T>& box, Callback& callback) const {
    if (end - begin <= small_range) {
      for (std::uint32_t i = begin; i < end; ++i)
        if (overlaps(loose_box(cell_of(node_keys_[i])), box)) query_node(nodes_[i], box, callback);
      return;
    }
    if (!overlaps(loose_box(c), box)) return;
    std::uint32_t bounds[9];
    split(depth, c, code, begin, end, bounds);
    for (int j = 0; j < 8; ++j)
      if (bounds[j] < bounds[j + 1])
        query_cell(depth, child_of(c, j), code * 8 + std::uint64_t(j), bounds[j], bounds[j + 1], box, callback);
  }

  /// False once the callback has stopped the cast.
  template <class Callback>
  bool ray_node(const node& n, const ray<T>& r, T& max_fraction, Callback& callback) const {
    for (std::uint32_t i = n.begin; i < n.end; ++i) {
      const std::uint32_t slot = sorted_[i].slot;
      if (dirty_flags_[slot]) continue;  // tested from dirty_
      const entry& e = entries_[slot];
      if (const auto t = ray_enters(r, max_fraction, e.box)) {
        max_fraction = callback(e.id, *t);
        if (!(max_fraction > T(0))) return false;
      }
    }
    return true;
  }

  /// Like query_cell, nearest entry first. False once the callback has
  /// stopped the cast.
  template <class Callback>
  bool ray_cell(int depth, const cell& c, std::uint64_t code, std::uint32_t begin, std::uint32_t end,
                const ray<T>& r, T& max_fraction, Callback& callback) const {
    struct entered {
      T t;
      std::uint32_t index;
    };
    entered order[small_range > 8 ? small_range : 8];
    int count = 0;
    // Insertion sort by entry fraction: at most eight entries (std::sort
    // here also trips g++ 12's -Warray-bounds at -O3).
    const auto sort_by_entry = [&order](int n) {
      for (int a = 1; a < n; ++a) {
        const entered x = order[a];
        int b = a;
        for (; b > 0 && x.t < order[b - 1].t; --b) order[b] = order[b - 1];
        order[b] = x;
      }
    };
    if (end - begin <= small_range) {
      for (std::uint32_t i = begin; i < end; ++i)
        if (const auto t = ray_enters(r, max_fraction, loose_box(cell_of(node_keys_[i])))) order[count++] = {*t, i};
      sort_by_entry(count);
      for (int k = 0; k < count; ++k)
        if (order[k].t <= max_fraction && !ray_node(nodes_[order[k].index], r, max_fraction, callback)) return false;
      return true;
    }
    if (!ray_enters(r, max_fraction, loose_box(c))) return true;
    std::uint32_t bounds[9];
    split(depth, c, code, begin, end, bounds);
    for (int j = 0; j < 8; ++j)
      if (bounds[j] < bounds[j + 1])
        if (const auto t = ray_enters(r, max_fraction, loose_box(child_of(c, j)))) order[count++] = {*t, std::uint32_t(j)};
    sort_by_entry(count);
    for (int k = 0; k < count; ++k) {
      const int j = int(order[k].index);
      if (order[k].t > max_fraction) continue;  // clipped since
      if (!ray_cell(depth, child_of(c, j), code * 8 + std::uint64_t(j), bounds[j], bounds[j + 1], r, max_fraction,
                    callback))
        return false;
    }
    return true;
  }

  detail::proxy_store<T> store_;
  detail::pair_tracker pairs_;
  int max_depth_ = 8;

  // The root.
  bool has_root_ = false;
  bool tree_current_ = false;  ///< nodes_ and sorted_ agree with the root and every clean entry
  vec3<T> root_lower_{};
  aabb<T> root_cell_ = aabb<T>::empty();
  T edge_[max_supported_depth + 1]{};          ///< cell edge by depth (powers of two)
  T inverse_edge_[max_supported_depth + 1]{};  ///< their exact inverses
  T margin_[max_supported_depth + 1]{};        ///< rounding allowance of cells_reaching, in cells
  T reach_[max_supported_depth + 1][3]{};      ///< by depth and axis: how far nodes stick out of their cells

  std::vector<entry> entries_;        ///< by proxy slot index
  std::vector<std::uint32_t> dirty_;  ///< slots whose cell changed (or that came or went) since the last update
  std::vector<std::uint8_t> dirty_flags_;  ///< by slot: 1 when in dirty_ (apart from entries_: resort scans it in space order)
  std::vector<item> sorted_;          ///< live proxies in key order, as of the last update

  // Built by update() from sorted_; kept so that a warm step allocates nothing.
  std::vector<node> nodes_;
  std::vector<std::uint64_t> node_keys_;  ///< in key order: by depth, then Morton code
  std::uint32_t depths_ = 0;  ///< bit d set when some node has depth d
  std::uint32_t level_begin_[max_supported_depth + 1]{}, level_end_[max_supported_depth + 1]{};  ///< nodes by depth
  std::vector<block> table_;
  int table_shift_ = 60;
  std::vector<aabb<T>> packed_box_;
  std::vector<proxy_id> packed_id_;
  std::vector<item> fresh_, merged_;
  std::vector<proxy_pair> found_;
};

/// The loose-octree policy, for a config's `broadphase`.
struct octree {
  static constexpr policy_kind kind = policy_kind::broadphase;
  template <scalar_type T>
  using type = basic_octree<T>;
};

}  // namespace impulse::broadphase
