// impulse/broadphase/sweep_and_prune.hpp — sorted endpoints on three axes,
// kept sorted between steps, with the pair set updated from the swaps, in
// regions of space that each sort only their own boxes.
//
// Each region is an incremental sweep and prune (detail/sap_region.hpp:
// Baraff 1992; Cohen et al., I-COLLIDE 1995; Terdiman 2007): the lower and
// upper ends of its boxes sorted on x, y and z, kept sorted by insertion
// sort as the boxes move, and its pair set edited at each swap of a lower
// and an upper end. The regions tile space as a grid of cells (the outer
// cells reach to infinity) and a box belongs to every cell it overlaps, as
// in Bullet's multi-SAP and PhysX's MBP. Why regions: in one set of sorted
// lists an end overtakes every end of every box between its old and new
// place along the axis, wherever the boxes are on the other two axes; with
// k cells along an axis, a region's lists hold about 1/k³ of the boxes over
// 1/k of the length, so an end overtakes about k² times fewer. On 10 000
// boxes moving at random (bench/broadphase), one set of lists swaps 344 000
// ends a step, 180 regions 16 000 between them; what is left of the cost is
// the boxes' moves between regions and the bookkeeping of the regions.
//
// The grid is chosen from the boxes when the regions are built: about one
// region per `boxes_per_region` boxes (64 unless given: 64 to 128 were the
// fastest on the benchmark's scenes at 10 000 and 100 000), cut along the
// axes where the boxes' centers spread most, no cell thinner than twice the
// boxes' mean extent there. It is built afresh when the number of boxes
// has doubled or fallen to a quarter since, so that it follows a world as
// it grows (bodies added a few a frame) at O(n log n) amortised; boxes that
// wander off the grid are still found, in its outer cells, only slower.
// A box over more than 8 cells (a ground plane) stays out of the regions and
// is tested against every box instead.
//
// A pair is reported once, by the region of the first cell that both
// boxes' cell ranges share (per axis, the larger of their lowest cells),
// although every region the two share finds it. Queries and rays use the
// same rule against the query's and the ray's cell ranges.
//
// Worst case: everything moving far along an axis on which the boxes in a
// region are densely packed. Every end passes every end it overtakes, so a
// step costs O(n · ends overtaken) and a scene shaken at random (or all
// boxes jumping across the world) costs O(n² / regions) per step;
// bench/broadphase measures it. A box crossing into a region costs that
// region a merge of the box's ends, O(its boxes), and one out, a pass.
//
// Queries and ray casts read the x axis of each region they touch: a box
// overlaps a query only if its lower x end lies in [query.lower.x − widest,
// query.upper.x], where widest is the region's widest box along x, a binary
// search away. Both see the boxes as of the last update.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "../core/error.hpp"
#include "../core/policy.hpp"
#include "../math/aabb.hpp"
#include "detail/sap_region.hpp"
#include "detail/pair_tracker.hpp"
#include "proxy.hpp"
#include "detail/proxy_store.hpp"

namespace impulse::broadphase {

template <scalar_type T>
class basic_sweep_and_prune {
 public:
  basic_sweep_and_prune() = default;
  /// Regions of about this many boxes each (at least 1).
  explicit basic_sweep_and_prune(std::size_t boxes_per_region) : boxes_per_region_(boxes_per_region) {
    if (boxes_per_region == 0)
      impulse::detail::report_error(error_code::invalid_parameter, "sweep_and_prune: boxes_per_region must be >= 1");
  }

  proxy_id create(const aabb<T>& box, std::uint64_t user_data) {
    const proxy_id id = store_.insert(box, user_data);
    std::uint32_t h;
    if (free_handles_.empty()) {
      h = std::uint32_t(handles_.size());
      handles_.emplace_back();
      boxes_.emplace_back();
    } else {
      h = free_handles_.back();
      free_handles_.pop_back();
    }
    handles_[h] = {id, proxy_state::added};
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
    // A box added since the last update is in no region yet: it just goes.
    // One already placed leaves its regions at the next update.
    handles_[h].state = handles_[h].state == proxy_state::added ? proxy_state::dropped : proxy_state::removed;
    destroyed_.push_back(h);
  }

  void update() {
    if (!store_.take_changed()) return pairs_.keep();  // nothing came, moved or went
    for (const std::uint32_t h : destroyed_) {
      if (handles_[h].state == proxy_state::removed) unplace(h);
      handles_[h].state = proxy_state::free;
      free_handles_.push_back(h);
    }
    destroyed_.clear();
    const std::size_t n = store_.size();
    if (regions_.empty() || n > 2 * grid_boxes_ || 4 * n < grid_boxes_) {
      regrid();
    } else {
      for (const std::uint32_t h : moved_) {
        if (handles_[h].state != proxy_state::moved) continue;
        handles_[h].state = proxy_state::resting;
        replace(h, store_.box(handles_[h].id));
      }
      for (const std::uint32_t h : added_) {
        if (handles_[h].state != proxy_state::added) continue;
        handles_[h].state = proxy_state::resting;
        place(h, store_.box(handles_[h].id));
      }
    }
    moved_.clear();
    added_.clear();

    swaps_ = 0;
    found_.clear();
    for (std::uint32_t r = 0; r < regions_.size(); ++r) {
      regions_[r].update();
      swaps_ += regions_[r].swaps();
      regions_[r].for_each_pair([&](std::uint32_t a, std::uint32_t b) {
        if (first_shared_cell(handles_[a].cells, handles_[b].cells) == r)
          found_.push_back(pair_of(handles_[a].id, handles_[b].id));
      });
    }
    // The boxes too big for the regions, against every box.
    for (std::size_t i = 0; i < big_.size(); ++i) {
      const std::uint32_t b = big_[i];
      for (std::size_t j = i + 1; j < big_.size(); ++j)
        if (overlaps(boxes_[b], boxes_[big_[j]])) found_.push_back(pair_of(handles_[b].id, handles_[big_[j]].id));
      for (std::uint32_t h = 0; h < handles_.size(); ++h)
        if (handles_[h].state == proxy_state::resting && !handles_[h].big && overlaps(boxes_[b], boxes_[h]))
          found_.push_back(pair_of(handles_[b].id, handles_[h].id));
    }
    pairs_.publish(found_);
  }

  [[nodiscard]] std::span<const proxy_pair> pairs() const noexcept { return pairs_.pairs(); }
  [[nodiscard]] std::span<const proxy_pair> begun() const noexcept { return pairs_.begun(); }
  [[nodiscard]] std::span<const proxy_pair> ended() const noexcept { return pairs_.ended(); }

  /// Every proxy whose box, as of the last update, overlaps `region`.
  template <class Callback>
  void query(const aabb<T>& region, Callback&& callback) const {
    detail::proxy_store<T>::require_box(region);
    if (regions_.empty()) return;
    const cell_range cells = cells_of(region);
    for_each_cell(cells, [&](std::uint32_t r) {
      regions_[r].query(region, [&](std::uint32_t h, const aabb<T>&) {
        if (handles_[h].state != proxy_state::removed && first_shared_cell(handles_[h].cells, cells) == r)
          callback(handles_[h].id);
      });
    });
    for (const std::uint32_t b : big_)
      if (handles_[b].state != proxy_state::removed && overlaps(boxes_[b], region)) callback(handles_[b].id);
  }

  /// Every proxy whose box, as of the last update, the segment enters; the
  /// regions nearer the ray's start first and, within one, in order of
  /// lower x end along the ray's direction, so that a clipping callback
  /// cuts the walk short.
  template <class Callback>
  void ray_cast(const ray<T>& r, T max_fraction, Callback&& callback) const {
    detail::require_ray(r, max_fraction);
    if (regions_.empty()) return;
    // The cells of the unclipped segment's box, widened by a few ulps: a box
    // that ray_enters accepts lies within rounding of the segment, and the
    // cell that reports it must be one of these.
    aabb<T> reach{r.origin, r.origin};
    const vec3<T> end = r.origin + r.translation * max_fraction;
    for (int axis = 0; axis < 3; ++axis) {
      const T slack = T(8) * std::numeric_limits<T>::epsilon() * (std::abs(r.origin[axis]) + std::abs(end[axis]));
      reach.lower[axis] = std::min(r.origin[axis], end[axis]) - slack;
      reach.upper[axis] = std::max(r.origin[axis], end[axis]) + slack;
    }
    const cell_range cells = cells_of(reach);
    const auto enter = [&](std::uint32_t h, const aabb<T>& box) {
      if (handles_[h].state == proxy_state::removed) return;
      if (const auto t = ray_enters(r, max_fraction, box)) max_fraction = callback(handles_[h].id, *t);
    };
    for_each_cell(cells, [&](std::uint32_t c) {
      if (max_fraction <= T(0)) return;
      regions_[c].ray_cast(r, max_fraction, [&](std::uint32_t h, const aabb<T>& box) {
        if (first_shared_cell(handles_[h].cells, cells) == c) enter(h, box);
      });
    }, r.translation);
    for (std::size_t i = 0; i < big_.size() && max_fraction > T(0); ++i) enter(big_[i], boxes_[big_[i]]);
  }

  [[nodiscard]] const aabb<T>& box(proxy_id id) const { return store_.box(id); }
  [[nodiscard]] std::uint64_t user_data(proxy_id id) const { return store_.user_data(id); }
  [[nodiscard]] bool contains(proxy_id id) const noexcept { return store_.contains(id); }
  [[nodiscard]] std::size_t size() const noexcept { return store_.size(); }

  /// Ends moved past others in the last update, over all regions and axes:
  /// the work of the incremental sort, for tests and the benchmark.
  [[nodiscard]] std::size_t swaps() const noexcept { return swaps_; }
  /// Regions of the current grid.
  [[nodiscard]] std::size_t region_count() const noexcept { return regions_.size(); }
  /// Boxes kept out of the regions, each over more than 8 cells.
  [[nodiscard]] std::size_t big_count() const noexcept { return big_.size(); }

 private:
  static constexpr std::uint32_t no_handle = 0xffffffffu;
  static constexpr int max_cells = 8;  ///< a box over more is kept out of the regions

  enum class proxy_state : std::uint8_t {
    resting,  ///< placed, not moved since the last update
    moved,    ///< placed, on the moved list
    added,    ///< created since the last update: in no region yet
    removed,  ///< destroyed since the last update: still in its regions
    dropped,  ///< created and destroyed between two updates: nothing to undo
    free,
  };
  /// The cells a box overlaps, lowest and highest per axis.
  struct cell_range {
    std::int32_t lo[3]{};
    std::int32_t hi[3]{};
    [[nodiscard]] int count() const noexcept {
      return (hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
    }
    [[nodiscard]] bool contains(const std::int32_t c[3]) const noexcept {
      return lo[0] <= c[0] && c[0] <= hi[0] && lo[1] <= c[1] && c[1] <= hi[1] && lo[2] <= c[2] && c[2] <= hi[2];
    }
    friend bool operator==(const cell_range&, const cell_range&) = default;
  };
  struct handle {
    proxy_id id{};
    proxy_state state = proxy_state::free;
    bool big = false;
    cell_range cells{};
    /// Its index in each region of its cells, in for_each_cell's order; for
    /// a big box, local[0] is its place in big_.
    std::uint32_t local[max_cells]{};
  };

  /// The cell along `axis` that holds `value`; the outer cells reach out to
  /// infinity.
  [[nodiscard]] std::int32_t cell_along(int axis, T value) const noexcept {
    const T c = std::floor((value - origin_[axis]) * inverse_cell_[axis]);
    if (!(c > T(0))) return 0;
    return c >= T(cells_[axis] - 1) ? cells_[axis] - 1 : std::int32_t(c);
  }
  [[nodiscard]] cell_range cells_of(const aabb<T>& box) const noexcept {
    cell_range range;
    for (int axis = 0; axis < 3; ++axis) {
      range.lo[axis] = cell_along(axis, box.lower[axis]);
      range.hi[axis] = cell_along(axis, box.upper[axis]);
    }
    return range;
  }
  [[nodiscard]] std::uint32_t region_of(const std::int32_t c[3]) const noexcept {
    return std::uint32_t((c[0] * cells_[1] + c[1]) * cells_[2] + c[2]);
  }
  /// The region that reports what two cell ranges share: per axis the larger
  /// of their lowest cells (in both ranges whenever they meet).
  [[nodiscard]] std::uint32_t first_shared_cell(const cell_range& a, const cell_range& b) const noexcept {
    const std::int32_t c[3]{std::max(a.lo[0], b.lo[0]), std::max(a.lo[1], b.lo[1]), std::max(a.lo[2], b.lo[2])};
    return region_of(c);
  }
  /// Calls f(region) for every cell of the range, each axis taken in the
  /// direction of `towards` (ascending where it is zero).
  template <class F>
  void for_each_cell(const cell_range& range, F&& f, const vec3<T>& towards = {}) const {
    std::int32_t c[3];
    const auto from = [&](int axis) { return towards[axis] < T(0) ? range.hi[axis] : range.lo[axis]; };
    const auto step = [&](int axis) { return towards[axis] < T(0) ? -1 : 1; };
    const auto within = [&](int axis) { return range.lo[axis] <= c[axis] && c[axis] <= range.hi[axis]; };
    for (c[0] = from(0); within(0); c[0] += step(0))
      for (c[1] = from(1); within(1); c[1] += step(1))
        for (c[2] = from(2); within(2); c[2] += step(2)) f(region_of(c));
  }

  /// Puts a box in the regions of its cells (or among the big ones).
  void place(std::uint32_t h, const aabb<T>& box) {
    handle& x = handles_[h];
    boxes_[h] = box;
    x.cells = cells_of(box);
    x.big = x.cells.count() > max_cells;
    if (x.big) {
      x.local[0] = std::uint32_t(big_.size());
      big_.push_back(h);
      return;
    }
    int k = 0;
    for_each_cell(x.cells, [&](std::uint32_t r) { x.local[k++] = regions_[r].insert(h, box); });
  }

  /// Takes a box out of its regions (or out of the big ones).
  void unplace(std::uint32_t h) {
    handle& x = handles_[h];
    if (x.big) {
      const std::uint32_t last = big_.back();
      big_[x.local[0]] = last;
      handles_[last].local[0] = x.local[0];
      big_.pop_back();
      return;
    }
    int k = 0;
    for_each_cell(x.cells, [&](std::uint32_t r) { regions_[r].erase(x.local[k++]); });
  }

  /// A placed box moved: it moves within the regions it stays in, leaves
  /// those it left and joins those it entered.
  void replace(std::uint32_t h, const aabb<T>& box) {
    handle& x = handles_[h];
    const cell_range now = cells_of(box);
    if (!x.big && now == x.cells) {
      boxes_[h] = box;
      int k = 0;
      for_each_cell(now, [&](std::uint32_t r) { regions_[r].move(x.local[k++], box); });
      return;
    }
    if (x.big || now.count() > max_cells) {
      unplace(h);
      place(h, box);
      return;
    }
    const cell_range was = x.cells;
    std::uint32_t was_local[max_cells];
    std::copy(std::begin(x.local), std::end(x.local), was_local);
    // Where a cell of `was` sits in for_each_cell's order over it.
    const auto was_index = [&](const std::int32_t c[3]) {
      const std::int32_t n1 = was.hi[1] - was.lo[1] + 1, n2 = was.hi[2] - was.lo[2] + 1;
      return ((c[0] - was.lo[0]) * n1 + (c[1] - was.lo[1])) * n2 + (c[2] - was.lo[2]);
    };
    std::int32_t c[3];
    for (c[0] = was.lo[0]; c[0] <= was.hi[0]; ++c[0])
      for (c[1] = was.lo[1]; c[1] <= was.hi[1]; ++c[1])
        for (c[2] = was.lo[2]; c[2] <= was.hi[2]; ++c[2])
          if (!now.contains(c)) regions_[region_of(c)].erase(was_local[was_index(c)]);
    int k = 0;
    for (c[0] = now.lo[0]; c[0] <= now.hi[0]; ++c[0])
      for (c[1] = now.lo[1]; c[1] <= now.hi[1]; ++c[1])
        for (c[2] = now.lo[2]; c[2] <= now.hi[2]; ++c[2]) {
          sap_region& region = regions_[region_of(c)];
          if (was.contains(c)) {
            x.local[k] = was_local[was_index(c)];
            region.move(x.local[k], box);
          } else {
            x.local[k] = region.insert(h, box);
          }
          ++k;
        }
    x.cells = now;
    boxes_[h] = box;
  }

  /// Chooses the grid from the live boxes and places them all afresh.
  void regrid() {
    live_.clear();
    for (std::uint32_t h = 0; h < handles_.size(); ++h) {
      const proxy_state s = handles_[h].state;
      if (s == proxy_state::resting || s == proxy_state::moved || s == proxy_state::added) {
        handles_[h].state = proxy_state::resting;
        live_.push_back(h);
      }
    }
    // The centers' bounds and the boxes' mean extent, per axis.
    aabb<T> bounds{vec3<T>::splat(std::numeric_limits<T>::max()), vec3<T>::splat(std::numeric_limits<T>::lowest())};
    vec3<T> mean_extent{};
    for (const std::uint32_t h : live_) {
      const aabb<T>& box = store_.box(handles_[h].id);
      const vec3<T> center = (box.lower + box.upper) * T(0.5);
      bounds.lower = min(bounds.lower, center);
      bounds.upper = max(bounds.upper, center);
      mean_extent += (box.upper - box.lower) / T(live_.size());
    }
    // Cut the longest cell in two … until there are enough regions or no
    // cell may be cut thinner than twice the mean extent.
    const std::size_t wanted = std::max<std::size_t>(1, live_.size() / boxes_per_region_);
    cells_[0] = cells_[1] = cells_[2] = 1;
    while (std::size_t(cells_[0]) * std::size_t(cells_[1]) * std::size_t(cells_[2]) < wanted) {
      int axis = -1;
      T longest = T(0);
      for (int a = 0; a < 3; ++a) {
        const T span = bounds.upper[a] - bounds.lower[a];
        if (span / T(cells_[a] + 1) >= T(2) * mean_extent[a] && span / T(cells_[a]) > longest) {
          longest = span / T(cells_[a]);
          axis = a;
        }
      }
      if (axis < 0) break;
      ++cells_[axis];
    }
    for (int a = 0; a < 3; ++a) {
      origin_[a] = live_.empty() ? T(0) : bounds.lower[a];
      const T span = live_.empty() ? T(0) : bounds.upper[a] - bounds.lower[a];
      inverse_cell_[a] = cells_[a] > 1 ? T(cells_[a]) / span : T(0);
    }
    regions_.assign(std::size_t(cells_[0]) * std::size_t(cells_[1]) * std::size_t(cells_[2]), sap_region{});
    big_.clear();
    for (const std::uint32_t h : live_) place(h, store_.box(handles_[h].id));
    grid_boxes_ = std::max<std::size_t>(1, live_.size());
  }

  using sap_region = detail::sap_region<T>;

  detail::proxy_store<T> store_;
  detail::pair_tracker pairs_;
  std::vector<proxy_pair> found_;

  std::vector<handle> handles_;
  std::vector<aabb<T>> boxes_;  ///< per handle, as of the last update
  std::vector<std::uint32_t> handle_of_slot_;
  std::vector<std::uint32_t> free_handles_, moved_, added_, destroyed_, big_, live_;

  std::vector<sap_region> regions_;
  vec3<T> origin_{}, inverse_cell_{};
  std::int32_t cells_[3]{1, 1, 1};
  std::size_t boxes_per_region_ = 64;
  std::size_t grid_boxes_ = 0;  ///< live boxes when the grid was chosen
  std::size_t swaps_ = 0;
};

/// The sweep-and-prune policy, for a config's `broadphase`.
struct sweep_and_prune {
  static constexpr policy_kind kind = policy_kind::broadphase;
  template <scalar_type T>
  using type = basic_sweep_and_prune<T>;
};

}  // namespace impulse::broadphase
