// impulse/broadphase/detail/sap_region.hpp — one region of a sweep and
// prune: the boxes that overlap it, their ends sorted on three axes and kept
// sorted between updates, and the pairs among them, edited at the swaps.
//
// Incremental sweep and prune (Baraff 1992; Cohen et al., I-COLLIDE 1995;
// Terdiman, "Sweep-and-prune", 2007). Each axis holds the members' lower and
// upper ends in one sorted array. When a member moves, each of its ends
// walks to its new place, as one step of insertion sort; every end it
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
// in `overlaps`. Coherent motion moves few ends past few others, so an
// update costs O(n + swaps), and the pair set is never rebuilt: it lives in
// a hash set (pair_set.hpp) that the swaps edit.
//
// Why this is correct, one axis at a time: a member's ends on an axis walk
// after its stored interval on that axis is updated, and insertion sort
// swaps exactly the pairs of ends whose order changes. A pair can only
// begin by a lower end passing an upper end and only end by the reverse, so
// testing the stored boxes at each "begin" swap and removing at each "end"
// swap leaves the set equal to the overlaps of the stored boxes after each
// axis of each member. When a member moves up, its upper end goes first (and
// when down, its lower end), so that its lower end never passes its own
// upper end.
//
// Members join and leave between updates (created and destroyed boxes, and
// boxes moving into or out of the region): leavers' ends are taken out in
// one pass per axis, joiners' ends merged in by one pass per axis, and a
// joiner's pairs found by scanning the x axis around it. Many joiners at
// once (a fresh region) are sorted afresh and swept.
//
// A member is named by a local index; the region keeps, per member, the
// caller's handle (`owner`), the box it is sorted by and the box it is to
// move to at the next update. Nothing here checks input: the broad phase
// that owns the regions does.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <vector>

#include "../../math/aabb.hpp"
#include "../proxy.hpp"
#include "pair_set.hpp"

namespace impulse::broadphase::detail {

template <scalar_type T>
class sap_region {
 public:
  sap_region() {
    for (auto& ends : axes_) {
      ends.push_back({-std::numeric_limits<T>::infinity(), sentinel_data});  // a lower end: nothing sorts before it
      ends.push_back({std::numeric_limits<T>::infinity(), sentinel_data | 1u});  // an upper end: nothing after
    }
  }

  /// A new member, sorted in at the next update; returns its local index.
  std::uint32_t insert(std::uint32_t owner, const aabb<T>& box) {
    std::uint32_t m;
    if (free_.empty()) {
      m = std::uint32_t(members_.size());
      members_.emplace_back();
      boxes_.emplace_back();
      positions_.emplace_back();
    } else {
      m = free_.back();
      free_.pop_back();
    }
    members_[m] = {owner, box, member_state::added};
    added_.push_back(m);
    ++size_;
    return m;
  }

  /// The member is to have this box from the next update on.
  void move(std::uint32_t m, const aabb<T>& box) {
    members_[m].next = box;
    if (members_[m].state == member_state::resting) {
      members_[m].state = member_state::moved;
      moved_.push_back(m);
    }
  }

  /// The member leaves at the next update (at once if it never got in).
  void erase(std::uint32_t m) {
    members_[m].state = members_[m].state == member_state::added ? member_state::dropped : member_state::removed;
    ++removed_count_;
    --size_;
  }

  /// Brings the arrays and the pair set up to date with the members' boxes.
  void update() {
    swaps_ = 0;
    if (removed_count_ > 0) remove_left();
    crossed_.resize(axes_[0].size());  // room for the longest walk
    std::erase_if(moved_, [&](std::uint32_t m) { return members_[m].state != member_state::moved; });
    for (const std::uint32_t m : moved_) members_[m].state = member_state::resting;
    // A few members moved: each walks its ends to their places. Many: every
    // member takes its new interval and one insertion-sort pass per axis
    // puts them in order, which swaps each pair of ends once if their order
    // changed, where member by member two neighbours moving the same way
    // pass each other twice (and the pass walks memory in order). Past one
    // in eight, the pass's O(n) walk costs less than the swaps it saves.
    if (8 * moved_.size() >= members_.size()) {
      for (int axis = 0; axis < 3; ++axis) {
        for (const std::uint32_t m : moved_) set_interval(axis, m, members_[m].next);
        sort_axis(axis);
      }
    } else {
      for (const std::uint32_t m : moved_) move_ends(m, members_[m].next);
    }
    moved_.clear();
    add_joined();
  }

  /// Calls f(owner a, owner b) for every overlapping pair of members.
  template <class F>
  void for_each_pair(F&& f) const {
    pairs_.for_each([&](std::uint64_t key) {
      f(members_[pair_set::first(key)].owner, members_[pair_set::second(key)].owner);
    });
  }

  /// Calls f(owner, box) for every member whose sorted box overlaps `region`.
  template <class F>
  void query(const aabb<T>& region, F&& f) const {
    const auto& x = axes_[0];
    for (std::size_t i = first_end_from(region.lower.x - widest_x_); i < x.size(); ++i) {
      if (x[i].value > region.upper.x) break;
      if (is_upper(x[i])) continue;
      const std::uint32_t m = member_of(x[i]);
      if (members_[m].state != member_state::removed && overlaps(boxes_[m], region)) f(members_[m].owner, boxes_[m]);
    }
  }

  /// Calls f(owner, box) for every member whose sorted box the segment may
  /// enter before `max_fraction` (which f may lower, clipping the walk), in
  /// order of lower x end along the ray's direction.
  template <class F>
  void ray_cast(const ray<T>& r, T& max_fraction, F&& f) const {
    const auto& x = axes_[0];
    const auto visit = [&](std::size_t i) {
      const std::uint32_t m = member_of(x[i]);
      if (members_[m].state != member_state::removed) f(members_[m].owner, boxes_[m]);
    };
    // The walk stops past the clipped end of the ray along x, with a few
    // ulps to spare: ray_enters divides where this multiplies, and a box
    // it would accept must not be cut off by rounding.
    const T x0 = r.origin.x, dx = r.translation.x;
    const auto end_x = [&] {
      const T end = x0 + max_fraction * dx;
      const T slack = T(8) * std::numeric_limits<T>::epsilon() * (std::abs(x0) + std::abs(end));
      return dx >= T(0) ? end + slack : end - slack;
    };
    if (dx >= T(0)) {
      // Members whose lower x end lies between the ray's start (less the
      // widest member) and its clipped end.
      for (std::size_t i = first_end_from(x0 - widest_x_); i + 1 < x.size() && max_fraction > T(0); ++i) {
        if (x[i].value > end_x()) break;
        if (!is_upper(x[i])) visit(i);
      }
    } else {
      // Downwards from the ray's start: stop once even the widest member
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

  /// Members, counting those that join at the next update and not those
  /// that leave.
  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  /// Ends moved past others in the last update, over all three axes.
  [[nodiscard]] std::size_t swaps() const noexcept { return swaps_; }

 private:
  static constexpr std::uint32_t sentinel_data = 0xfffffffeu;  // member 0x7fffffff, never a real one

  struct end_point {
    T value;
    std::uint32_t data;  ///< member << 1 | 1 for an upper end
  };
  static std::uint32_t member_of(const end_point& e) noexcept { return e.data >> 1; }
  static bool is_upper(const end_point& e) noexcept { return (e.data & 1u) != 0; }
  /// The sort order: by value, lower ends before upper ends at equal values.
  static bool before(const end_point& a, const end_point& b) noexcept {
    return a.value < b.value || (a.value == b.value && !is_upper(a) && is_upper(b));
  }

  enum class member_state : std::uint8_t {
    resting,  ///< sorted, not moved since the last update
    moved,    ///< sorted, on the moved list
    added,    ///< joined since the last update: no ends yet
    removed,  ///< left since the last update: ends still in the arrays
    dropped,  ///< joined and left between two updates: nothing to undo
    free,
  };
  struct member {
    std::uint32_t owner = 0;
    aabb<T> next{};  ///< the box to take at the next update
    member_state state = member_state::free;
  };
  /// Where a member's ends are in each axis's array, lower then upper.
  struct end_positions {
    std::uint32_t at[3][2]{};
  };

  /// Gives member m its new interval on one axis, in its sorted box and its
  /// ends' values, without moving the ends. Returns whether it moved up.
  bool set_interval(int axis, std::uint32_t m, const aabb<T>& box) {
    const T lower = box.lower[axis], upper = box.upper[axis];
    aabb<T>& stored = boxes_[m];
    const bool up = lower > stored.lower[axis] || upper > stored.upper[axis];
    stored.lower[axis] = lower;
    stored.upper[axis] = upper;
    if (axis == 0) widest_x_ = std::max(widest_x_, upper - lower);
    const std::uint32_t* at = positions_[m].at[axis];
    axes_[axis][at[0]].value = lower;
    axes_[axis][at[1]].value = upper;
    return up;
  }

  void move_ends(std::uint32_t m, const aabb<T>& box) {
    for (int axis = 0; axis < 3; ++axis) {
      const std::uint32_t* at = positions_[m].at[axis];
      // Moving up, the upper end leads; moving down, the lower end.
      if (set_interval(axis, m, box)) {
        sift(axis, at[1]);
        sift(axis, at[0]);
      } else {
        sift(axis, at[0]);
        sift(axis, at[1]);
      }
    }
  }

  /// Insertion sort of a whole axis whose members all hold their new
  /// intervals: each end walks down into the sorted part before it. The
  /// ends' positions are written once after the pass, not at every swap.
  void sort_axis(int axis) {
    auto& ends = axes_[axis];
    const std::uint32_t last = std::uint32_t(ends.size() - 1);
    std::size_t swaps = 0;
    for (std::uint32_t i = 1; i < last; ++i)
      if (before(ends[i], ends[i - 1]))
        swaps += is_upper(ends[i]) ? walk<down, true, false>(axis, i) : walk<down, false, false>(axis, i);
    swaps_ += swaps;
    note_positions(axis);
  }

  void note_positions(int axis) {
    const auto& ends = axes_[axis];
    for (std::uint32_t i = 1; i + 1 < ends.size(); ++i) positions_[member_of(ends[i])].at[axis][is_upper(ends[i])] = i;
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
  /// on whether to go on: it notes every member it passes, counting only
  /// those whose end is of the other kind, and hands them to `cross`, in
  /// order, after it.
  template <int direction, bool upper, bool track>
  std::uint32_t walk(int axis, std::uint32_t i) {
    auto& ends = axes_[axis];
    const end_point e = ends[i];
    const std::uint32_t m = member_of(e);
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
      crossed[count] = member_of(f);
      count += is_upper(f) != upper;
      ends[i] = f;
      if constexpr (track) positions_[member_of(f)].at[axis][is_upper(f)] = i;
      i += direction;
    }
    ends[i] = e;
    if constexpr (track) positions_[m].at[axis][upper] = i;
    // Down, a lower end passing upper ends begins overlaps and an upper end
    // passing lower ends ends them; up, the other way round.
    constexpr bool begins = (direction == down) != upper;
    for (std::size_t k = 0; k < count; ++k) cross(axis, m, crossed[k], begins);
    return direction == down ? start - i : i - start;
  }

  /// m's end passed one of n's ends of the other kind on `axis`: their
  /// intervals there began to overlap (begin) or separated. A separation
  /// can only end a pair that overlaps on the two other axes, and most do
  /// not: testing that first spares the pair set most lookups.
  void cross(int axis, std::uint32_t m, std::uint32_t n, bool begin) {
    const aabb<T>& a = boxes_[m];
    const aabb<T>& b = boxes_[n];
    if (begin) {
      if (overlaps(a, b)) pairs_.insert(pair_set::key_of(m, n));
      return;
    }
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    if (a.lower[u] <= b.upper[u] && b.lower[u] <= a.upper[u] && a.lower[v] <= b.upper[v] && b.lower[v] <= a.upper[v])
      pairs_.erase(pair_set::key_of(m, n));
  }

  /// Takes the leavers' ends out of the arrays and their pairs out of the
  /// set, in one pass each.
  void remove_left() {
    const auto gone = [&](std::uint32_t m) { return members_[m].state == member_state::removed; };
    pairs_.erase_if([&](std::uint64_t key) { return gone(pair_set::first(key)) || gone(pair_set::second(key)); });
    for (int axis = 0; axis < 3; ++axis) {
      auto& ends = axes_[axis];
      std::size_t kept = 1;
      for (std::size_t i = 1; i + 1 < ends.size(); ++i)
        if (!gone(member_of(ends[i]))) ends[kept++] = ends[i];
      ends[kept++] = ends.back();
      ends.resize(kept);
      note_positions(axis);
    }
    for (std::uint32_t m = 0; m < members_.size(); ++m) {
      if (members_[m].state == member_state::removed || members_[m].state == member_state::dropped) {
        members_[m].state = member_state::free;
        free_.push_back(m);
      }
    }
    removed_count_ = 0;
    widest_x_ = T(0);
    for (std::uint32_t m = 0; m < members_.size(); ++m)
      if (members_[m].state == member_state::resting || members_[m].state == member_state::moved)
        widest_x_ = std::max(widest_x_, boxes_[m].upper.x - boxes_[m].lower.x);
  }

  /// Sorts in the members that joined since the last update and finds
  /// their pairs.
  void add_joined() {
    joined_.clear();
    for (const std::uint32_t m : added_) {
      if (members_[m].state != member_state::added) continue;
      members_[m].state = member_state::resting;
      boxes_[m] = members_[m].next;
      widest_x_ = std::max(widest_x_, boxes_[m].upper.x - boxes_[m].lower.x);
      joined_.push_back(m);
    }
    added_.clear();
    if (joined_.empty()) return;
    // A sweep over everything costs O(n log n + pairs); scanning around
    // each joiner costs O(its neighbours along x) each. Past about log₂ n
    // joiners, sweep.
    if (joined_.size() > std::size_t(std::bit_width(size_))) {
      rebuild();
      return;
    }
    // Merge the joiners' ends (sorted) into each axis, then pair each
    // joiner with every member it overlaps (joiners among them: the set
    // takes a pair once).
    for (int axis = 0; axis < 3; ++axis) {
      incoming_.clear();
      for (const std::uint32_t m : joined_) {
        incoming_.push_back({boxes_[m].lower[axis], m << 1});
        incoming_.push_back({boxes_[m].upper[axis], (m << 1) | 1u});
      }
      std::sort(incoming_.begin(), incoming_.end(), before);
      auto& ends = axes_[axis];
      merged_.clear();
      std::merge(ends.begin(), ends.end(), incoming_.begin(), incoming_.end(), std::back_inserter(merged_), before);
      ends.swap(merged_);
      note_positions(axis);
    }
    for (const std::uint32_t m : joined_) {
      const auto& x = axes_[0];
      const aabb<T>& box = boxes_[m];
      for (std::size_t i = first_end_from(box.lower.x - widest_x_); i < x.size(); ++i) {
        if (x[i].value > box.upper.x) break;
        const std::uint32_t n = member_of(x[i]);
        if (!is_upper(x[i]) && n != m && overlaps(boxes_[n], box))
          pairs_.insert(pair_set::key_of(m, n));
      }
    }
  }

  /// Every member's ends sorted afresh, and the pairs found by one sweep
  /// along x with a list of the members whose x interval is open.
  void rebuild() {
    for (auto& ends : axes_) ends.resize(1);  // keep the lower sentinel
    widest_x_ = T(0);
    for (std::uint32_t m = 0; m < members_.size(); ++m) {
      if (members_[m].state != member_state::resting && members_[m].state != member_state::moved) continue;
      const aabb<T>& box = boxes_[m];
      for (int axis = 0; axis < 3; ++axis) {
        axes_[axis].push_back({box.lower[axis], m << 1});
        axes_[axis].push_back({box.upper[axis], (m << 1) | 1u});
      }
      widest_x_ = std::max(widest_x_, box.upper.x - box.lower.x);
    }
    for (int axis = 0; axis < 3; ++axis) {
      auto& ends = axes_[axis];
      std::sort(ends.begin() + 1, ends.end(), before);
      ends.push_back({std::numeric_limits<T>::infinity(), sentinel_data | 1u});
      note_positions(axis);
    }
    pairs_.clear();
    open_.clear();
    const auto& x = axes_[0];
    for (std::size_t i = 1; i + 1 < x.size(); ++i) {
      const std::uint32_t m = member_of(x[i]);
      if (is_upper(x[i])) {
        open_.erase(std::find(open_.begin(), open_.end(), m));
        continue;
      }
      for (const std::uint32_t n : open_)
        if (overlaps(boxes_[m], boxes_[n])) pairs_.insert(pair_set::key_of(m, n));
      open_.push_back(m);
    }
  }

  /// The first end on the x axis at or above `value` (skipping the sentinel).
  std::size_t first_end_from(T value) const {
    const auto& x = axes_[0];
    const auto it = std::lower_bound(x.begin() + 1, x.end() - 1, value,
                                     [](const end_point& e, T v) { return e.value < v; });
    return std::size_t(it - x.begin());
  }

  std::vector<end_point> axes_[3];
  std::vector<member> members_;
  std::vector<aabb<T>> boxes_;  ///< per member, as sorted: what its ends hold
  std::vector<end_positions> positions_;
  std::vector<std::uint32_t> free_, moved_, added_, joined_, open_, crossed_;
  std::vector<end_point> incoming_, merged_;
  pair_set pairs_;
  std::size_t size_ = 0;
  std::size_t removed_count_ = 0;
  std::size_t swaps_ = 0;
  T widest_x_ = T(0);
};

}  // namespace impulse::broadphase::detail
