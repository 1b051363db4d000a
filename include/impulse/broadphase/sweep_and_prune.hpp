// impulse/broadphase/sweep_and_prune.hpp — sorted endpoints on three axes,
// kept sorted between steps, with the pair set updated from the swaps.
//
// Incremental sweep and prune (Baraff 1992; Cohen et al., I-COLLIDE 1995;
// Terdiman, "Sweep-and-prune", 2007). Each axis holds the boxes' lower and
// upper ends in one sorted array. When a box moves, each of its ends is
// sifted to its new place, as one step of insertion sort; every end it
// passes is an event:
//
//   a lower end passing an upper end of another box towards it: the two
//     intervals begin to overlap on this axis; if the boxes now overlap on
//     all three, the pair begins;
//   an upper end passing a lower end away from it: the intervals separate
//     on this axis, and the pair, if there was one, ends.
//
// Two ends of the same kind passing each other change nothing. Ends that
// compare equal are ordered lower before upper, so touching boxes overlap as
// in `overlaps`. Coherent motion moves few ends past few others, so a step
// costs O(n + swaps) and the pair set is never rebuilt: it lives in a hash
// set (detail/pair_set.hpp) that the swaps edit.
//
// Why this is correct, one axis at a time: a box's ends on an axis are
// sifted after its stored interval on that axis is updated, and insertion
// sort swaps exactly the pairs of ends whose order changes. A pair can only
// begin by a lower end passing an upper end and only end by the reverse, so
// testing the stored boxes at each "begin" swap and removing at each "end"
// swap leaves the set equal to the overlaps of the stored boxes after each
// axis of each box. When a box moves up, its upper end goes first (and when
// down, its lower end), so that its lower end never passes its own upper end.
//
// Worst case: everything moving far along an axis on which the boxes are
// densely packed. Every end passes every end it overtakes, so a step costs
// O(n · ends overtaken) and a scene shaken at random (or all boxes jumping
// across the world) costs O(n²) per step; bench/broadphase measures it. The
// same holds for adding boxes one at a time (each sifts in from the top), so
// when more are added in one update than about log₂ n, the arrays are
// sorted afresh and the pairs found by one sweep along x instead.
//
// Queries and ray casts read the x axis: a box overlaps a query only if its
// lower x end lies in [query.lower.x − widest, query.upper.x], where widest
// is the widest box along x, a binary search away.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "../core/policy.hpp"
#include "../math/aabb.hpp"
#include "detail/pair_set.hpp"
#include "pair_tracker.hpp"
#include "proxy.hpp"
#include "proxy_store.hpp"

namespace impulse::broadphase {

template <scalar_type T>
class basic_sweep_and_prune {
 public:
  basic_sweep_and_prune() {
    for (auto& ends : axes_) {
      ends.push_back({-std::numeric_limits<T>::infinity(), sentinel_data});  // a lower end: nothing sorts before it
      ends.push_back({std::numeric_limits<T>::infinity(), sentinel_data | 1u});  // an upper end: nothing after
    }
  }

  proxy_id create(const aabb<T>& box, std::uint64_t user_data) {
    const proxy_id id = store_.insert(box, user_data);
    std::uint32_t h;
    if (free_handles_.empty()) {
      h = std::uint32_t(handles_.size());
      handles_.emplace_back();
      boxes_.emplace_back();
      positions_.emplace_back();
    } else {
      h = free_handles_.back();
      free_handles_.pop_back();
    }
    handles_[h] = {id, proxy_state::added};
    boxes_[h] = box;
    if (handle_of_slot_.size() <= id.index) handle_of_slot_.resize(id.index + 1, no_handle);
    handle_of_slot_[id.index] = h;
    added_.push_back(h);
    return id;
  }

  void move(proxy_id id, const aabb<T>& box) {
    store_.set_box(id, box);
    const std::uint32_t h = handle_of_slot_[id.index];
    if (handles_[h].state == proxy_state::resting) {
      handles_[h].state = proxy_state::moved;
      moved_.push_back(h);
    }
  }

  void destroy(proxy_id id) {
    store_.erase(id);
    const std::uint32_t h = handle_of_slot_[id.index];
    handle_of_slot_[id.index] = no_handle;
    // A box added since the last update has no ends yet: it just goes.
    // One already sorted keeps its ends until the next update removes
    // them all in one pass.
    handles_[h].state = handles_[h].state == proxy_state::added ? proxy_state::dropped : proxy_state::removed;
    ++removed_count_;
  }

  void update() {
    swaps_ = 0;
    if (removed_count_ > 0) remove_destroyed();
    crossed_.resize(axes_[0].size() + 2 * added_.size());  // room for the longest walk
    std::erase_if(moved_, [&](std::uint32_t h) { return handles_[h].state != proxy_state::moved; });
    for (const std::uint32_t h : moved_) handles_[h].state = proxy_state::resting;
    // A few boxes moved: each sifts to its place. Many: every box takes its
    // new interval and one insertion sort pass per axis puts them in order,
    // which swaps each pair of ends once if their order changed, where box
    // by box two neighbours moving the same way pass each other twice (and
    // the pass walks memory in order). Past one in eight, the pass's O(n)
    // walk costs less than the swaps it saves.
    if (8 * moved_.size() >= handles_.size()) {
      for (int axis = 0; axis < 3; ++axis) {
        for (const std::uint32_t h : moved_) set_interval(axis, h, store_.box(handles_[h].id));
        sort_axis(axis);
      }
    } else {
      for (const std::uint32_t h : moved_) move_ends(h, store_.box(handles_[h].id));
    }
    moved_.clear();
    add_created();

    found_.clear();
    pair_set_.for_each([&](std::uint64_t key) {
      found_.push_back(pair_of(handles_[detail::pair_set::first(key)].id, handles_[detail::pair_set::second(key)].id));
    });
    pairs_.publish(found_);
  }

  [[nodiscard]] std::span<const proxy_pair> pairs() const noexcept { return pairs_.pairs(); }
  [[nodiscard]] std::span<const proxy_pair> begun() const noexcept { return pairs_.begun(); }
  [[nodiscard]] std::span<const proxy_pair> ended() const noexcept { return pairs_.ended(); }

  /// Every proxy whose box, as of the last update, overlaps `region`.
  template <class Callback>
  void query(const aabb<T>& region, Callback&& callback) const {
    detail::proxy_store<T>::require_box(region);
    const auto& x = axes_[0];
    for (std::size_t i = first_lower_end_from(region.lower.x - widest_x_); i < x.size(); ++i) {
      if (x[i].value > region.upper.x) break;
      if (is_upper(x[i])) continue;
      const std::uint32_t h = handle_of(x[i]);
      if (handles_[h].state != proxy_state::removed && overlaps(boxes_[h], region)) callback(handles_[h].id);
    }
  }

  /// Every proxy whose box, as of the last update, the segment enters, in
  /// order of lower x end along the ray's direction, so that a clipping
  /// callback ends the walk early.
  template <class Callback>
  void ray_cast(const ray<T>& r, T max_fraction, Callback&& callback) const {
    detail::require_ray(r, max_fraction);
    const auto& x = axes_[0];
    const auto visit = [&](std::size_t i) {
      const std::uint32_t h = handle_of(x[i]);
      if (handles_[h].state == proxy_state::removed) return;
      if (const auto t = ray_enters(r, max_fraction, boxes_[h])) max_fraction = callback(handles_[h].id, *t);
    };
    // The walk stops past the clipped end of the ray along x, with a few
    // ulps to spare: ray_enters divides where this multiplies, and a box
    // it would accept must not be cut off by rounding.
    const T x0 = r.origin.x, dx = r.translation.x;
    const auto end_x = [&] {
      const T end = x0 + max_fraction * dx;
      return end + (dx >= T(0) ? T(1) : T(-1)) * T(8) * std::numeric_limits<T>::epsilon() * (std::abs(x0) + std::abs(end));
    };
    if (dx >= T(0)) {
      // Boxes whose lower x end lies between the ray's start (less the
      // widest box) and its clipped end.
      for (std::size_t i = first_lower_end_from(x0 - widest_x_); i + 1 < x.size() && max_fraction > T(0); ++i) {
        if (x[i].value > end_x()) break;
        if (!is_upper(x[i])) visit(i);
      }
    } else {
      // Downwards from the ray's start: stop once even the widest box
      // starting here would end before the clipped end of the ray.
      std::size_t i = std::size_t(std::upper_bound(x.begin(), x.end(), x0,
                                                   [](T v, const end_point& e) { return v < e.value; }) -
                                  x.begin());
      while (i-- > 1 && max_fraction > T(0)) {
        if (x[i].value + widest_x_ < end_x()) break;
        if (!is_upper(x[i])) visit(i);
      }
    }
  }

  [[nodiscard]] const aabb<T>& box(proxy_id id) const { return store_.box(id); }
  [[nodiscard]] std::uint64_t user_data(proxy_id id) const { return store_.user_data(id); }
  [[nodiscard]] bool contains(proxy_id id) const noexcept { return store_.contains(id); }
  [[nodiscard]] std::size_t size() const noexcept { return store_.size(); }

  /// Ends moved past others in the last update, over all three axes: the
  /// work of the incremental sort, for tests and the benchmark.
  [[nodiscard]] std::size_t swaps() const noexcept { return swaps_; }

 private:
  static constexpr std::uint32_t no_handle = 0xffffffffu;
  static constexpr std::uint32_t sentinel_data = 0xfffffffeu;  // handle 0x7fffffff, never a real one

  struct end_point {
    T value;
    std::uint32_t data;  ///< handle << 1 | 1 for an upper end
  };
  static std::uint32_t handle_of(const end_point& e) noexcept { return e.data >> 1; }
  static bool is_upper(const end_point& e) noexcept { return (e.data & 1u) != 0; }
  /// The sort order: by value, lower ends before upper ends at equal values.
  static bool before(const end_point& a, const end_point& b) noexcept {
    return a.value < b.value || (a.value == b.value && !is_upper(a) && is_upper(b));
  }

  enum class proxy_state : std::uint8_t {
    resting,  ///< sorted, not moved since the last update
    moved,    ///< sorted, on the moved list
    added,    ///< created since the last update: no ends yet
    removed,  ///< destroyed since the last update: ends still in the arrays
    dropped,  ///< created and destroyed between two updates: nothing to undo
    free,
  };
  struct handle {
    proxy_id id{};
    proxy_state state = proxy_state::free;
  };
  /// Where a box's ends are in each axis's array, lower then upper.
  struct end_positions {
    std::uint32_t at[3][2]{};
  };

  /// Gives box h its new interval on one axis, in its stored box and its
  /// ends' values, without moving the ends. Returns whether it moved up.
  bool set_interval(int axis, std::uint32_t h, const aabb<T>& box) {
    const T lower = box.lower[axis], upper = box.upper[axis];
    aabb<T>& stored = boxes_[h];
    const bool up = lower > stored.lower[axis] || upper > stored.upper[axis];
    stored.lower[axis] = lower;
    stored.upper[axis] = upper;
    if (axis == 0) widest_x_ = std::max(widest_x_, upper - lower);
    const std::uint32_t* at = positions_[h].at[axis];
    axes_[axis][at[0]].value = lower;
    axes_[axis][at[1]].value = upper;
    return up;
  }

  void move_ends(std::uint32_t h, const aabb<T>& box) {
    for (int axis = 0; axis < 3; ++axis) {
      const std::uint32_t* at = positions_[h].at[axis];
      // Moving up, the upper end leads; moving down, the lower end.
      if (set_interval(axis, h, box)) {
        sift(axis, at[1]);
        sift(axis, at[0]);
      } else {
        sift(axis, at[0]);
        sift(axis, at[1]);
      }
    }
  }

  /// Insertion sort of a whole axis whose boxes all hold their new
  /// intervals: each end sifts down into the sorted part before it. The
  /// ends' positions are written once after the pass, not at every swap.
  void sort_axis(int axis) {
    auto& ends = axes_[axis];
    const std::uint32_t last = std::uint32_t(ends.size() - 1);
    std::size_t swaps = 0;
    for (std::uint32_t i = 1; i < last; ++i)
      if (before(ends[i], ends[i - 1]))
        swaps += is_upper(ends[i]) ? walk<down, true, false>(axis, i) : walk<down, false, false>(axis, i);
    swaps_ += swaps;
    for (std::uint32_t i = 1; i < last; ++i) positions_[handle_of(ends[i])].at[axis][is_upper(ends[i])] = i;
  }

  /// Moves the end at i to its sorted place, down or up, editing the pair
  /// set at each lower–upper crossing.
  void sift(int axis, std::uint32_t i) {
    const auto& ends = axes_[axis];
    if (before(ends[i], ends[i - 1]))
      swaps_ += is_upper(ends[i]) ? walk<down, true, true>(axis, i) : walk<down, false, true>(axis, i);
    else
      swaps_ += is_upper(ends[i]) ? walk<up, true, true>(axis, i) : walk<up, false, true>(axis, i);
  }

  static constexpr int down = -1, up = 1;

  /// Walks the end at i, an upper end or not, one place at a time in
  /// `direction` while it belongs beyond the next end, and returns the
  /// number of ends it passed. Without `track` the ends' positions are left
  /// for the caller to write. Which kind of end comes next is a coin toss
  /// that a branch predictor loses half the time, so the walk branches only
  /// on whether to go on: it notes every box it passes, counting only those
  /// whose end is of the other kind, and hands them to `cross`, in order,
  /// after it.
  template <int direction, bool upper, bool track>
  std::uint32_t walk(int axis, std::uint32_t i) {
    auto& ends = axes_[axis];
    const end_point e = ends[i];
    const std::uint32_t h = handle_of(e);
    // Whether e belongs beyond f: `before` with e's kind known. Ends of the
    // same kind at equal values stay as they are (a box landing on a floor
    // that others rest on does not walk past all their ends). The sentinels
    // (±infinity) stop every walk: the ends are finite.
    const auto beyond = [&](const end_point& f) {
      if constexpr (direction == down)
        return upper ? e.value < f.value : e.value < f.value || (e.value == f.value && is_upper(f));
      else
        return upper ? f.value < e.value || (f.value == e.value && !is_upper(f)) : f.value < e.value;
    };
    const std::uint32_t start = i;
    std::uint32_t* crossed = crossed_.data();
    std::size_t count = 0;
    while (beyond(ends[i + direction])) {
      const end_point f = ends[i + direction];
      crossed[count] = handle_of(f);
      count += is_upper(f) != upper;
      ends[i] = f;
      if constexpr (track) positions_[handle_of(f)].at[axis][is_upper(f)] = i;
      i += direction;
    }
    ends[i] = e;
    if constexpr (track) positions_[h].at[axis][upper] = i;
    // Down, a lower end passing upper ends begins overlaps and an upper end
    // passing lower ends ends them; up, the other way round.
    constexpr bool begins = (direction == down) != upper;
    for (std::size_t k = 0; k < count; ++k) cross(axis, h, crossed[k], begins);
    return direction == down ? start - i : i - start;
  }

  /// h's end passed one of g's ends of the other kind on `axis`: their
  /// intervals there began to overlap (begin) or separated. A separation
  /// can only end a pair that overlaps on the two other axes, and most do
  /// not: testing that first spares the pair set most lookups.
  void cross(int axis, std::uint32_t h, std::uint32_t g, bool begin) {
    const aabb<T>& a = boxes_[h];
    const aabb<T>& b = boxes_[g];
    if (begin) {
      if (overlaps(a, b)) pair_set_.insert(detail::pair_set::key_of(h, g));
      return;
    }
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    if (a.lower[u] <= b.upper[u] && b.lower[u] <= a.upper[u] && a.lower[v] <= b.upper[v] && b.lower[v] <= a.upper[v])
      pair_set_.erase(detail::pair_set::key_of(h, g));
  }

  /// Takes destroyed boxes' ends out of the arrays and their pairs out of
  /// the set, in one pass each.
  void remove_destroyed() {
    const auto gone = [&](std::uint32_t h) { return handles_[h].state == proxy_state::removed; };
    pair_set_.erase_if([&](std::uint64_t key) {
      return gone(detail::pair_set::first(key)) || gone(detail::pair_set::second(key));
    });
    for (int axis = 0; axis < 3; ++axis) {
      auto& ends = axes_[axis];
      std::size_t kept = 1;
      for (std::size_t i = 1; i + 1 < ends.size(); ++i) {
        const std::uint32_t h = handle_of(ends[i]);
        if (gone(h)) continue;
        ends[kept] = ends[i];
        positions_[h].at[axis][is_upper(ends[i])] = std::uint32_t(kept);
        ++kept;
      }
      ends[kept++] = ends.back();
      ends.resize(kept);
    }
    for (std::uint32_t h = 0; h < handles_.size(); ++h) {
      if (handles_[h].state == proxy_state::removed || handles_[h].state == proxy_state::dropped) {
        handles_[h].state = proxy_state::free;
        free_handles_.push_back(h);
      }
    }
    removed_count_ = 0;
    widest_x_ = T(0);
    for (std::uint32_t h = 0; h < handles_.size(); ++h)
      if (handles_[h].state == proxy_state::resting || handles_[h].state == proxy_state::moved)
        widest_x_ = std::max(widest_x_, boxes_[h].upper.x - boxes_[h].lower.x);
  }

  void add_created() {
    std::size_t count = 0;
    for (const std::uint32_t h : added_)
      if (handles_[h].state == proxy_state::added) ++count;
    if (count == 0) {
      added_.clear();
      return;
    }
    // One box sifted in from the top costs O(n); sorting afresh costs
    // O(n log n). Past about log₂ n new boxes, sort.
    const std::size_t total = axes_[0].size() / 2 - 1 + count;
    if (count > std::size_t(std::bit_width(total))) {
      for (const std::uint32_t h : added_) {
        if (handles_[h].state != proxy_state::added) continue;
        handles_[h].state = proxy_state::resting;
        boxes_[h] = store_.box(handles_[h].id);
      }
      added_.clear();
      rebuild();
      return;
    }
    for (const std::uint32_t h : added_) {
      if (handles_[h].state != proxy_state::added) continue;
      handles_[h].state = proxy_state::resting;
      // Enter at the top with the ends at +infinity on every axis (a box
      // that overlaps nothing), then move to the real box.
      const T far = std::numeric_limits<T>::infinity();
      for (int axis = 0; axis < 3; ++axis) {
        auto& ends = axes_[axis];
        const std::uint32_t top = std::uint32_t(ends.size() - 1);
        ends.insert(ends.end() - 1, {{far, h << 1}, {far, (h << 1) | 1u}});
        positions_[h].at[axis][0] = top;
        positions_[h].at[axis][1] = top + 1;
      }
      boxes_[h] = {vec3<T>::splat(far), vec3<T>::splat(far)};
      move_ends(h, store_.box(handles_[h].id));
    }
    added_.clear();
  }

  /// Every live box's ends sorted afresh, and the pairs found by one sweep
  /// along x with a list of the boxes whose x interval is open.
  void rebuild() {
    for (auto& ends : axes_) ends.resize(1);  // keep the lower sentinel
    widest_x_ = T(0);
    for (std::uint32_t h = 0; h < handles_.size(); ++h) {
      if (handles_[h].state != proxy_state::resting && handles_[h].state != proxy_state::moved) continue;
      const aabb<T>& box = boxes_[h];
      for (int axis = 0; axis < 3; ++axis) {
        axes_[axis].push_back({box.lower[axis], h << 1});
        axes_[axis].push_back({box.upper[axis], (h << 1) | 1u});
      }
      widest_x_ = std::max(widest_x_, box.upper.x - box.lower.x);
    }
    for (int axis = 0; axis < 3; ++axis) {
      auto& ends = axes_[axis];
      std::sort(ends.begin() + 1, ends.end(), before);
      ends.push_back({std::numeric_limits<T>::infinity(), sentinel_data | 1u});
      for (std::uint32_t i = 1; i + 1 < ends.size(); ++i)
        positions_[handle_of(ends[i])].at[axis][is_upper(ends[i])] = i;
    }
    pair_set_.clear();
    open_.clear();
    const auto& x = axes_[0];
    for (std::size_t i = 1; i + 1 < x.size(); ++i) {
      const std::uint32_t h = handle_of(x[i]);
      if (is_upper(x[i])) {
        open_.erase(std::find(open_.begin(), open_.end(), h));
        continue;
      }
      for (const std::uint32_t g : open_)
        if (overlaps(boxes_[h], boxes_[g])) pair_set_.insert(detail::pair_set::key_of(h, g));
      open_.push_back(h);
    }
  }

  /// The first end on the x axis at or above `value` (skipping the sentinel).
  std::size_t first_lower_end_from(T value) const {
    const auto& x = axes_[0];
    const auto it = std::lower_bound(x.begin() + 1, x.end() - 1, value,
                                     [](const end_point& e, T v) { return e.value < v; });
    return std::size_t(it - x.begin());
  }

  detail::proxy_store<T> store_;
  detail::pair_tracker pairs_;
  std::vector<proxy_pair> found_;

  std::vector<end_point> axes_[3];
  std::vector<handle> handles_;
  std::vector<aabb<T>> boxes_;  ///< per handle, as sorted: what its ends hold
  std::vector<end_positions> positions_;
  std::vector<std::uint32_t> handle_of_slot_;
  std::vector<std::uint32_t> free_handles_;
  std::vector<std::uint32_t> moved_, added_, open_, crossed_;
  detail::pair_set pair_set_;
  std::size_t removed_count_ = 0;
  std::size_t swaps_ = 0;
  T widest_x_ = T(0);
};

/// The sweep-and-prune policy, for a config's `broadphase`.
struct sweep_and_prune {
  static constexpr policy_kind kind = policy_kind::broadphase;
  template <scalar_type T>
  using type = basic_sweep_and_prune<T>;
};

}  // namespace impulse::broadphase
