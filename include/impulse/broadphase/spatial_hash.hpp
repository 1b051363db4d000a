// impulse/broadphase/spatial_hash.hpp — a uniform grid of cubic cells,
// hashed into a table of buckets and rebuilt at every update.
//
// Spatial hashing (Teschner et al., "Optimized spatial hashing for collision
// detection of deformable objects", VMV 2003; Ericson, Real-Time Collision
// Detection, §7.1). Space is cut into cubes of edge `cell_size()`; a box
// covers the cells floor(lower / cell) … floor(upper / cell) on each axis
// (64-bit cell coordinates, so boxes at 1e5 m and far beyond are fine) and
// is entered in each. Cells are hashed into a power-of-two table of buckets;
// two boxes can overlap only if they share a cell, so only boxes in the same
// bucket are compared, with `overlaps` on their exact boxes.
//
// The table is rebuilt at every update() as a counting sort, not kept up to
// date cell by cell: most boxes move every step in the scenes this is for,
// and a rebuild is a few linear passes over contiguous arrays (cell ranges;
// hash and count per bucket; prefix sum; scatter), with no per-cell lists
// to allocate or chase. Each entry carries a copy of its box, so that
// reading a bucket's pairs reads nothing else. Pairs are then read bucket
// by bucket.
//
// Each pair exactly once, with no set of pairs seen: two overlapping boxes
// share every cell of their intersection, so the pair is reported only from
// the cell holding the lower corner of the intersection (Ericson §7.1.6),
// which is max(lower cell of a, lower cell of b) on each axis: integer
// arithmetic, no rounding. A bucket may hold several cells (hash
// collisions), so each entry remembers which of its box's cells it stands
// for (its offset from the box's lower cell), and the pair is reported only
// when both entries stand for that very cell. Boxes in distinct cells that
// share a bucket are compared with `overlaps` and, overlapping or not, can
// be reported only once. Queries use the same rule with the query box.
//
// Cell size. Given to the constructor, it is kept. Left at 0, update()
// chooses it as twice the upper quartile of the boxes' largest extents
// (from a strided sample of at most 1024 boxes). A cell about the size of a
// typical box keeps the cells a box covers at 1 to 8 and the boxes per cell
// low; twice that size measured 1.2 to 1.6 times faster than once in the
// uniform, clustered and densely packed benchmark scenes (a box then covers
// 2 to 3 cells, and the entries saved outweigh the extra pair tests). The
// upper quartile rather than the median or mean because scenes mix sizes:
// with half the boxes points or 1000× smaller than the rest (the "points"
// and "mixed sizes" test scenes), the median lands on the small ones and the
// ordinary boxes then cover dozens of cells each, while a mean is dragged
// up by a few huge boxes; the upper quartile is the size of the ordinary
// boxes as long as fewer than a quarter of them are huge. (When three
// quarters are points, the spacing the boxes would have if spread evenly
// over their bounds stands in for the size.) The cell is chosen again when
// that statistic drifts by more than a factor of 2 either way from the
// value it was chosen for (hysteresis, so that it does not flip back and
// forth on a noisy sample).
//
// Huge boxes. A box covering more than 64 cells (more than 4 × 4 × 4; with
// the automatic cell, a box some 6 times the typical size or more) is not
// entered in the grid: it is kept in a separate list and tested against
// every box in a branch-free sweep over the boxes laid out as columns, under
// a nanosecond a box (clang vectorizes it). In the grid it would cost some
// 30 ns for each cell it covers, and two huge boxes that overlap would meet
// again in every cell they share; a box 1e4 cells wide would enter 1e12. A
// few huge boxes (the ground, walls, the "mixed sizes" scene) are thus
// cheap; the worst case is many huge boxes, h of them costing h·n box
// tests: choose the cell size for such a scene.
//
// Queries and rays see the boxes as of the last update(), like the pairs (a
// proxy destroyed since is skipped). A query visits the cells its box covers,
// or, when they outnumber the proxies, tests every box. A ray walks the
// cells along the segment slab by slab along its longest axis (Amanatides &
// Woo's traversal, "A fast voxel traversal algorithm for ray tracing", 1987,
// widened): in each slab it visits every cell within a rounding margin of
// the segment, so that a box ray_enters accepts by a hair is never in a cell
// the walk skipped; each box is tested once per cast (a stamp per proxy),
// with ray_enters on its exact box, and the walk stops once past the
// clipped max_fraction. When a plain walk would visit more cells than there
// are proxies (a ray long against the cell), the cast tests every box
// instead: a cell costs a hash and a lookup, about what a box test costs.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <vector>

#include "../core/error.hpp"
#include "../core/policy.hpp"
#include "../math/aabb.hpp"
#include "../math/trigonometry.hpp"
#include "detail/pair_tracker.hpp"
#include "proxy.hpp"
#include "detail/proxy_store.hpp"

namespace impulse::broadphase {

namespace detail {

/// Integer coordinates of a grid cell.
struct grid_cell {
  std::int64_t x = 0, y = 0, z = 0;
  friend constexpr bool operator==(const grid_cell&, const grid_cell&) = default;
};

/// The bucket of a cell in a table of 2^bits buckets (1 <= bits <= 32): a
/// linear mix of the coordinates with large odd constants, then a
/// multiply-xorshift finalizer, top bits kept (Fibonacci hashing). Neighbour
/// cells land in unrelated buckets. (Grouping cells in 4×4×4 blocks of
/// consecutive buckets, for locality, measured no faster.)
constexpr std::uint32_t spatial_hash_bucket(const grid_cell& c, unsigned bits) noexcept {
  std::uint64_t h = std::uint64_t(c.x) * 0x9E3779B97F4A7C15ull + std::uint64_t(c.y) * 0xC2B2AE3D27D4EB4Full +
                    std::uint64_t(c.z) * 0x165667B19E3779F9ull;
  h ^= h >> 31;
  h *= 0xD6E8FEB86659FD93ull;
  h ^= h >> 29;
  return std::uint32_t(h >> (64 - bits));
}

}  // namespace detail

template <scalar_type T>
class basic_spatial_hash {
 public:
  /// A box covering more cells than this is huge: kept out of the grid
  /// and tested against every box (see the file comment).
  static constexpr std::uint64_t max_cells_per_proxy = 64;
  /// The automatic cell is this factor × the upper quartile of the boxes'
  /// largest extents (see the file comment: measured on the benchmark scenes).
  static constexpr double cell_factor = 2.0;

  /// cell_size: the edge of a grid cell in metres, > 0 to fix it; 0 (the
  /// default) lets update() choose it from the boxes.
  explicit basic_spatial_hash(T cell_size = T(0)) {
    if (!std::isfinite(cell_size))
      impulse::detail::report_error(error_code::non_finite, "spatial hash: the cell size is not finite");
    if (cell_size < T(0))
      impulse::detail::report_error(error_code::invalid_parameter, "spatial hash: the cell size must be >= 0");
    if (cell_size > T(0)) {
      fixed_cell_ = true;
      set_cell(double(cell_size));
    }
  }

  proxy_id create(const aabb<T>& box, std::uint64_t user_data) { return store_.insert(box, user_data); }
  void move(proxy_id id, const aabb<T>& box) { store_.set_box(id, box); }
  void destroy(proxy_id id) { store_.erase(id); }

  void update() {
    if (!store_.take_changed()) return pairs_.keep();  // nothing came, moved or went
    choose_cell_size();
    build_grid();
    found_.clear();
    find_pairs_in_buckets();
    find_pairs_of_huge_boxes();
    pairs_.publish(found_);
  }

  [[nodiscard]] std::span<const proxy_pair> pairs() const noexcept { return pairs_.pairs(); }
  [[nodiscard]] std::span<const proxy_pair> begun() const noexcept { return pairs_.begun(); }
  [[nodiscard]] std::span<const proxy_pair> ended() const noexcept { return pairs_.ended(); }

  /// Every proxy whose box, as of the last update, overlaps `region`.
  template <class Callback>
  void query(const aabb<T>& region, Callback&& callback) const {
    detail::proxy_store<T>::require_box(region);
    const grid_cell lo = cell_of(region.lower), hi = cell_of(region.upper);
    const double cells = double(hi.x - lo.x + 1) * double(hi.y - lo.y + 1) * double(hi.z - lo.z + 1);
    if (cells > double(boxes_.size())) {
      // Fewer boxes than cells to visit: testing them all is cheaper.
      for (std::size_t d = 0; d < boxes_.size(); ++d)
        if (overlaps(boxes_[d], region) && store_.contains(ids_[d])) callback(ids_[d]);
      return;
    }
    for (grid_cell c{0, 0, lo.z}; c.z <= hi.z; ++c.z)
      for (c.y = lo.y; c.y <= hi.y; ++c.y)
        for (c.x = lo.x; c.x <= hi.x; ++c.x) {
          const std::uint32_t b = detail::spatial_hash_bucket(c, bits_);
          for (std::uint32_t e = starts_[b]; e < starts_[b + 1]; ++e) {
            const std::uint32_t d = entries_[e].proxy;
            const grid_cell l = cell_of(entries_[e].box.lower);
            // This entry must stand for cell c (not another cell in the
            // bucket), and c must hold the lower corner of the overlap.
            if (entry_cell(l, entries_[e].offset) != c) continue;
            if (std::max(l.x, lo.x) != c.x || std::max(l.y, lo.y) != c.y || std::max(l.z, lo.z) != c.z) continue;
            if (overlaps(entries_[e].box, region) && store_.contains(ids_[d])) callback(ids_[d]);
          }
        }
    for (const std::uint32_t d : huge_)
      if (overlaps(boxes_[d], region) && store_.contains(ids_[d])) callback(ids_[d]);
  }

  /// Every proxy whose box, as of the last update, the segment enters
  /// within [0, max_fraction], the fraction clipped by the callback's
  /// answers; cells are walked from the ray's origin outwards, so that a
  /// clipping callback ends the walk early. Marks the boxes it has tested
  /// (in a mutable array reused from cast to cast): two casts must not run
  /// on one broad phase at the same time.
  template <class Callback>
  void ray_cast(const ray<T>& r, T max_fraction, Callback&& callback) const {
    detail::require_ray(r, max_fraction);
    if (!(max_fraction > T(0))) return;
    const std::uint32_t stamp = next_stamp();
    // Returns false once the callback has stopped the cast.
    const auto test = [&](std::uint32_t d) {
      if (stamps_[d] == stamp) return true;
      stamps_[d] = stamp;
      if (const auto t = ray_enters(r, max_fraction, boxes_[d]); t && store_.contains(ids_[d]))
        max_fraction = callback(ids_[d], *t);
      return max_fraction > T(0);
    };
    for (const std::uint32_t d : huge_)
      if (!test(d)) return;

    // The margin covers the rounding of ray_enters (in T) against this exact
    // walk (in double): a few ulps of the largest coordinate involved.
    const double o[3] = {double(r.origin.x), double(r.origin.y), double(r.origin.z)};
    const double v[3] = {double(r.translation.x), double(r.translation.y), double(r.translation.z)};
    double scale = 0;
    for (int a = 0; a < 3; ++a) scale = std::max({scale, std::abs(o[a]), std::abs(o[a] + v[a])});
    const double margin = 16 * double(std::numeric_limits<T>::epsilon()) * scale + 1e-9 * cell_;
    const bool walkable = std::isfinite(margin);  // false for a double ray reaching past the double range
    int m = 0;  // the longest axis: the walk goes slab by slab along it
    for (int a = 1; a < 3; ++a)
      if (std::abs(v[a]) > std::abs(v[m])) m = a;

    // How many cells a plain voxel walk would visit; with more than there
    // are boxes, or cells beyond the clamped range, test every box.
    const double f0 = double(max_fraction);
    double walk_cells = walkable ? 0 : std::numeric_limits<double>::infinity();
    std::int64_t first[3], last[3];
    for (int a = 0; a < 3; ++a) {
      const double p0 = o[a], p1 = o[a] + f0 * v[a];
      first[a] = cell_of(v[a] >= 0 ? std::min(p0, p1) - margin : std::max(p0, p1) + margin);
      last[a] = cell_of(v[a] >= 0 ? std::max(p0, p1) + margin : std::min(p0, p1) - margin);
      if (std::abs(first[a]) >= cell_limit || std::abs(last[a]) >= cell_limit) walk_cells = std::numeric_limits<double>::infinity();
      walk_cells += double(std::abs(last[a] - first[a]) + 1);
    }
    if (walk_cells > double(boxes_.size())) {
      for (std::uint32_t d = 0; d < boxes_.size(); ++d)
        if (!test(d)) return;
      return;
    }

    const int a1 = (m + 1) % 3, a2 = (m + 2) % 3;
    const std::int64_t step = v[m] >= 0 ? 1 : -1;
    for (std::int64_t k = first[m];; k += step) {
      // The part of the segment within slab k (widened by the margin).
      double t0 = 0, t1 = double(max_fraction);
      if (v[m] != 0) {
        const double reach = margin / std::abs(v[m]);
        double s0 = (double(k) * cell_ - margin - o[m]) / v[m], s1 = (double(k + 1) * cell_ + margin - o[m]) / v[m];
        if (s0 > s1) std::swap(s0, s1);
        t1 += reach;
        if (s0 > t1) break;  // past the clipped end
        t0 = std::max(t0, s0);
        t1 = std::min(t1, s1);
      }
      if (t0 <= t1) {
        std::int64_t lo1, hi1, lo2, hi2;
        span_of(o[a1], v[a1], t0, t1, margin, lo1, hi1);
        span_of(o[a2], v[a2], t0, t1, margin, lo2, hi2);
        grid_cell c;
        std::int64_t* ck = m == 0 ? &c.x : m == 1 ? &c.y : &c.z;
        std::int64_t* c1 = a1 == 0 ? &c.x : a1 == 1 ? &c.y : &c.z;
        std::int64_t* c2 = a2 == 0 ? &c.x : a2 == 1 ? &c.y : &c.z;
        *ck = k;
        for (*c1 = lo1; *c1 <= hi1; ++*c1)
          for (*c2 = lo2; *c2 <= hi2; ++*c2) {
            const std::uint32_t b = detail::spatial_hash_bucket(c, bits_);
            for (std::uint32_t e = starts_[b]; e < starts_[b + 1]; ++e)
              if (!test(entries_[e].proxy)) return;
          }
      }
      if (k == last[m]) break;
    }
  }

  [[nodiscard]] const aabb<T>& box(proxy_id id) const { return store_.box(id); }
  [[nodiscard]] std::uint64_t user_data(proxy_id id) const { return store_.user_data(id); }
  [[nodiscard]] bool contains(proxy_id id) const noexcept { return store_.contains(id); }
  [[nodiscard]] std::size_t size() const noexcept { return store_.size(); }

  /// The cell edge in metres used by the last update (the constructor's
  /// when given; 0 when chosen automatically and no update has run yet).
  [[nodiscard]] T cell_size() const noexcept { return T(cell_); }
  /// Cell entries made by the last update (a box covering k cells makes k).
  [[nodiscard]] std::size_t cell_entries() const noexcept { return entries_.size(); }
  /// Buckets in the table of the last update (a power of two).
  [[nodiscard]] std::size_t bucket_count() const noexcept { return std::size_t(1) << bits_; }
  /// Boxes kept out of the grid as huge at the last update.
  [[nodiscard]] std::size_t huge_count() const noexcept { return huge_.size(); }

 private:
  using grid_cell = detail::grid_cell;

  /// Cell coordinates are clamped to ±2^52 (about 4.5e15 cells): past it a
  /// double no longer tells neighbouring integers apart, and the clamp is
  /// monotone, so far-off boxes just share an edge cell.
  static constexpr std::int64_t cell_limit = std::int64_t(1) << 52;
  static constexpr unsigned offset_bits = 10;  // per axis in an entry's offset (at most 64 cells are used)
  static constexpr std::uint32_t offset_mask = (1u << offset_bits) - 1;
  static constexpr std::uint32_t huge_mark = 0xffffffffu;
  static constexpr std::size_t sample_limit = 1024;
  static constexpr unsigned min_bits = 4;

  struct entry {
    aabb<T> box;           ///< the proxy's box, copied so that reading a bucket reads no other array
    std::uint32_t proxy;   ///< dense index as of the last update
    std::uint32_t offset;  ///< the cell, relative to the box's lower cell: x | y << 10 | z << 20
  };

  static constexpr std::uint32_t pack(std::uint64_t x, std::uint64_t y, std::uint64_t z) noexcept {
    return std::uint32_t(x | (y << offset_bits) | (z << (2 * offset_bits)));
  }
  static constexpr grid_cell entry_cell(const grid_cell& lower, std::uint32_t offset) noexcept {
    return {lower.x + std::int64_t(offset & offset_mask), lower.y + std::int64_t((offset >> offset_bits) & offset_mask),
            lower.z + std::int64_t(offset >> (2 * offset_bits))};
  }

  void set_cell(double cell) {
    cell_ = cell;
    inverse_cell_ = 1.0 / cell;
  }

  std::int64_t cell_of(double x) const noexcept {
    double v = x * inverse_cell_;
    // The clamp also catches an infinite product (a double box far beyond
    // 2^52 cells), and, written this way round, sends a NaN to the lower
    // end rather than into an undefined conversion. Floor by truncation and
    // a correction rather than std::floor, which is a library call on plain
    // x86-64 (no SSE4.1).
    v = v > -double(cell_limit) ? v : -double(cell_limit);
    v = v < double(cell_limit) ? v : double(cell_limit);
    const std::int64_t i = std::int64_t(v);
    return i - std::int64_t(double(i) > v);
  }
  grid_cell cell_of(const vec3<T>& p) const noexcept {
    return {cell_of(double(p.x)), cell_of(double(p.y)), cell_of(double(p.z))};
  }

  /// The cells along one axis of the segment o + t·v, t in [t0, t1], widened by the margin.
  void span_of(double o, double v, double t0, double t1, double margin, std::int64_t& lo, std::int64_t& hi) const {
    const double p0 = o + t0 * v, p1 = o + t1 * v;
    lo = cell_of(std::min(p0, p1) - margin);
    hi = cell_of(std::max(p0, p1) + margin);
  }

  std::uint32_t next_stamp() const {
    if (stamps_.size() < boxes_.size()) stamps_.resize(boxes_.size(), 0);
    if (++stamp_ == 0) {  // wrapped: old stamps could match again
      std::fill(stamps_.begin(), stamps_.end(), 0u);
      stamp_ = 1;
    }
    return stamp_;
  }

  /// The upper quartile of the largest extents in a strided sample, or,
  /// when three quarters of the boxes are points, the spacing they would
  /// have if spread evenly over their bounds (the few boxes with a size are
  /// then no guide). 0 when there is nothing to measure.
  double typical_size() {
    const auto& values = store_.values();
    const std::size_t n = values.size(), count = std::min(n, sample_limit);
    if (count == 0) return 0;
    sample_.clear();
    aabb<double> bounds = aabb<double>::empty();
    for (std::size_t j = 0; j < count; ++j) {
      const aabb<T>& b = values[j * n / count].box;
      const vec3<double> lo{double(b.lower.x), double(b.lower.y), double(b.lower.z)};
      const vec3<double> hi{double(b.upper.x), double(b.upper.y), double(b.upper.z)};
      // In double, where a float box's extent cannot overflow; a double box
      // spanning the whole range can, and counts as the largest there is.
      sample_.push_back(std::min(max_component(hi - lo), std::numeric_limits<double>::max()));
      bounds = merge(bounds, lo);
    }
    const auto quartile = sample_.begin() + std::ptrdiff_t(count * 3 / 4);
    std::nth_element(sample_.begin(), quartile, sample_.end());
    if (*quartile > 0) return *quartile;
    const double spread = std::min(max_component(bounds.upper - bounds.lower), std::numeric_limits<double>::max());
    return spread / portable_cbrt(double(n));
  }

  void choose_cell_size() {
    if (fixed_cell_) return;
    const double size = typical_size();
    if (size <= 0) {
      if (cell_ == 0) set_cell(1.0);  // all boxes one point, or none: any cell will do
      return;
    }
    if (chosen_for_ == 0 || size > 2 * chosen_for_ || size < 0.5 * chosen_for_) {
      chosen_for_ = size;
      // At most T's largest value, so that cell_size() stays finite, and at
      // least a 2^-40th of the largest coordinate, so that the coordinates
      // stay well inside the cell range (±2^52).
      set_cell(std::clamp(cell_factor * size, largest_coordinate() * 0x1p-40,
                          double(std::numeric_limits<T>::max())));
    }
  }

  double largest_coordinate() const {
    double largest = 0;
    for (const auto& p : store_.values())
      largest = std::max({largest, std::abs(double(p.box.lower.x)), std::abs(double(p.box.lower.y)),
                          std::abs(double(p.box.lower.z)), std::abs(double(p.box.upper.x)),
                          std::abs(double(p.box.upper.y)), std::abs(double(p.box.upper.z))});
    return largest;
  }

  /// The counting sort: every box's cells, hashed, then the entries laid
  /// out bucket by bucket, so that bucket b's entries are
  /// entries_[starts_[b] .. starts_[b + 1]).
  void build_grid() {
    const auto& values = store_.values();
    const std::size_t n = values.size();
    boxes_.resize(n);
    lower_cell_.resize(n);
    spans_.resize(n);
    ids_.assign(store_.ids().begin(), store_.ids().end());
    huge_.clear();

    std::size_t total = 0;
    for (std::size_t d = 0; d < n; ++d) {
      const aabb<T>& b = values[d].box;
      boxes_[d] = b;
      const grid_cell lo = cell_of(b.lower), hi = cell_of(b.upper);
      const std::uint64_t sx = std::uint64_t(hi.x - lo.x) + 1, sy = std::uint64_t(hi.y - lo.y) + 1,
                          sz = std::uint64_t(hi.z - lo.z) + 1;
      // Each axis first, so that the product cannot overflow.
      if (sx > max_cells_per_proxy || sy > max_cells_per_proxy || sz > max_cells_per_proxy ||
          sx * sy * sz > max_cells_per_proxy) {
        spans_[d] = huge_mark;
        huge_.push_back(std::uint32_t(d));
        continue;
      }
      lower_cell_[d] = lo;
      spans_[d] = pack(sx - 1, sy - 1, sz - 1);
      total += sx * sy * sz;
    }

    // About one bucket per entry: the cells are fewer than the entries (a
    // cell holds 1–2 boxes at the chosen size), so most buckets hold one cell.
    bits_ = std::max(min_bits, unsigned(std::bit_width(total)));
    const std::size_t buckets = std::size_t(1) << bits_;
    starts_.assign(buckets + 2, 0);
    keys_.resize(total);
    entries_.resize(total);

    // Hash every cell of every box, counting per bucket. One flat loop per
    // box (the offset counted up like an odometer, without branches) rather
    // than three nested ones, whose short, varying trip counts mispredict.
    std::size_t k = 0;
    for (std::size_t d = 0; d < n; ++d) {
      const std::uint32_t s = spans_[d];
      if (s == huge_mark) continue;
      const grid_cell lo = lower_cell_[d];
      const std::uint32_t ex = s & offset_mask, ey = (s >> offset_bits) & offset_mask;
      const std::size_t count = std::size_t(ex + 1) * (ey + 1) * ((s >> (2 * offset_bits)) + 1);
      std::uint32_t x = 0, y = 0, z = 0;
      for (std::size_t i = 0; i < count; ++i) {
        const std::uint32_t b = detail::spatial_hash_bucket(grid_cell{lo.x + x, lo.y + y, lo.z + z}, bits_);
        keys_[k++] = {b, std::uint32_t(d), pack(x, y, z)};
        ++starts_[b + 2];
        const std::uint32_t next_row = x == ex;
        x = next_row ? 0 : x + 1;
        y += next_row;
        const std::uint32_t next_layer = y > ey;
        y = next_layer ? 0 : y;
        z += next_layer;
      }
    }
    for (std::size_t b = 2; b < buckets + 2; ++b) starts_[b] += starts_[b - 1];
    // starts_[b + 1] is now where bucket b begins; filling moves it to
    // where b ends, which is where b + 1 begins.
    for (const key& e : keys_) entries_[starts_[e.bucket + 1]++] = {boxes_[e.proxy], e.proxy, e.offset};
  }

  /// Every pair of entries sharing a bucket whose boxes overlap, kept only
  /// from the cell holding the lower corner of the boxes' intersection.
  void find_pairs_in_buckets() {
    const std::size_t buckets = std::size_t(1) << bits_;
    for (std::size_t b = 0; b < buckets; ++b) {
      const std::uint32_t begin = starts_[b], end = starts_[b + 1];
      for (std::uint32_t i = begin; i + 1 < end; ++i) {
        const entry& ei = entries_[i];
        const aabb<T>& box_i = ei.box;
        for (std::uint32_t j = i + 1; j < end; ++j) {
          const entry& ej = entries_[j];
          // One branch, not six: which way it goes is anyone's guess.
          const aabb<T>& box_j = ej.box;
          const bool hit = (box_i.lower.x <= box_j.upper.x) & (box_j.lower.x <= box_i.upper.x) &
                           (box_i.lower.y <= box_j.upper.y) & (box_j.lower.y <= box_i.upper.y) &
                           (box_i.lower.z <= box_j.upper.z) & (box_j.lower.z <= box_i.upper.z) & (ej.proxy != ei.proxy);
          if (!hit) continue;
          // The lower cells again, from the boxes at hand: cheaper than a
          // load from an array indexed by proxy, which misses the cache.
          const grid_cell li = cell_of(box_i.lower), lj = cell_of(box_j.lower);
          const grid_cell corner{std::max(li.x, lj.x), std::max(li.y, lj.y), std::max(li.z, lj.z)};
          // The corner lies in both boxes' cell ranges, so both offsets fit.
          if (pack(std::uint64_t(corner.x - li.x), std::uint64_t(corner.y - li.y), std::uint64_t(corner.z - li.z)) !=
                  ei.offset ||
              pack(std::uint64_t(corner.x - lj.x), std::uint64_t(corner.y - lj.y), std::uint64_t(corner.z - lj.z)) !=
                  ej.offset)
            continue;
          found_.push_back(pair_of(ids_[ei.proxy], ids_[ej.proxy]));
        }
      }
    }
  }

  /// Each huge box against every box: the others in the grid, and the
  /// huge ones after it in the list. The boxes are laid out as six columns
  /// and tested a block at a time into a mask, a loop without branches
  /// (which clang vectorizes); the rare hits are then picked out of the mask.
  void find_pairs_of_huge_boxes() {
    if (huge_.empty()) return;
    const std::size_t n = boxes_.size(), padded = (n + sweep_block - 1) / sweep_block * sweep_block;
    for (auto& column : columns_) column.resize(padded);
    for (std::size_t d = 0; d < padded; ++d) {
      // Padding: an inverted box, which overlaps almost nothing.
      const aabb<T> b = d < n ? boxes_[d] : aabb<T>::empty();
      columns_[0][d] = b.lower.x, columns_[1][d] = b.lower.y, columns_[2][d] = b.lower.z;
      columns_[3][d] = b.upper.x, columns_[4][d] = b.upper.y, columns_[5][d] = b.upper.z;
    }
    for (const std::uint32_t h : huge_) {
      const aabb<T> box_h = boxes_[h];
      for (std::size_t base = 0; base < padded; base += sweep_block) {
        const T *lx = columns_[0].data() + base, *ly = columns_[1].data() + base, *lz = columns_[2].data() + base;
        const T *ux = columns_[3].data() + base, *uy = columns_[4].data() + base, *uz = columns_[5].data() + base;
        // One byte a box, so that eight are looked at in one word: hits are
        // rare, and only the set bytes are visited.
        std::uint8_t hit[sweep_block];
        for (std::size_t i = 0; i < sweep_block; ++i)
          hit[i] = std::uint8_t((lx[i] <= box_h.upper.x) & (box_h.lower.x <= ux[i]) & (ly[i] <= box_h.upper.y) &
                                (box_h.lower.y <= uy[i]) & (lz[i] <= box_h.upper.z) & (box_h.lower.z <= uz[i]));
        // The padding can overlap a box as large as the scalar range itself,
        // hence `valid`.
        const std::size_t valid = std::min(sweep_block, n - base);
        for (std::size_t group = 0; group < valid; group += 8) {
          std::uint64_t word;
          std::memcpy(&word, hit + group, sizeof word);
          for (; word != 0; word &= word - 1) {
            const std::size_t i = group + std::size_t(std::countr_zero(word)) / 8;
            const std::uint32_t d = std::uint32_t(base + i);
            if (i >= valid || d == h || (spans_[d] == huge_mark && d < h)) continue;
            found_.push_back(pair_of(ids_[h], ids_[d]));
          }
        }
      }
    }
  }

  detail::proxy_store<T> store_;
  detail::pair_tracker pairs_;
  std::vector<proxy_pair> found_;

  bool fixed_cell_ = false;
  double cell_ = 0, inverse_cell_ = 0;
  double chosen_for_ = 0;  ///< the typical size the automatic cell was chosen for
  std::vector<double> sample_;

  // The grid as of the last update, by dense index at that update.
  std::vector<aabb<T>> boxes_;
  std::vector<proxy_id> ids_;
  std::vector<grid_cell> lower_cell_;
  std::vector<std::uint32_t> spans_;  ///< cells covered less one per axis, packed; huge_mark for a huge box
  std::vector<std::uint32_t> huge_;
  unsigned bits_ = min_bits;
  std::vector<std::uint32_t> starts_ = std::vector<std::uint32_t>((std::size_t(1) << min_bits) + 2, 0u);
  struct key {
    std::uint32_t bucket, proxy, offset;
  };
  std::vector<key> keys_;  ///< each entry's bucket, in build order (scratch)
  std::vector<entry> entries_;

  static constexpr std::size_t sweep_block = 256;
  std::vector<T> columns_[6];  ///< lower x, y, z, upper x, y, z of every box, when there are huge ones

  mutable std::vector<std::uint32_t> stamps_;  ///< per box: the last ray cast that tested it
  mutable std::uint32_t stamp_ = 0;
};

/// The spatial-hash policy, for a config's `broadphase`.
struct spatial_hash {
  static constexpr policy_kind kind = policy_kind::broadphase;
  template <scalar_type T>
  using type = basic_spatial_hash<T>;
};

}  // namespace impulse::broadphase
