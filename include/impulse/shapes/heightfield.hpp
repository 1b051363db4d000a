// impulse/shapes/heightfield.hpp — static terrain: a grid of heights.
//
// `columns` × `rows` samples, sample (i, k) at x = i·spacing_x,
// z = k·spacing_z, y = its height, in the shape's frame. Each cell between
// four samples is two triangles split along the diagonal from (i, k) to
// (i + 1, k + 1), counter-clockwise seen from above (+y is the free side),
// unless the cell is a hole. Static only, as a triangle mesh: no volume,
// no mass properties.
//
// The narrow phase treats it as the mesh it stands for (narrowphase/
// mesh.hpp: the same per-triangle tests, the same merging, one-sided from
// above), with what a mesh keeps in a tree found from the grid: the cells
// under a box are a range of columns and rows, and their triangles are
// made from the heights when asked. Active edges are decided as a mesh's
// are (shapes/detail/active_edges.hpp): an edge is active at the grid's
// border, beside a hole, and where its two triangles meet convex by more
// than 5°; a flat or concave edge is internal, so that nothing snags on
// the seams of flat ground.
//
// Memory: a height a sample (4 bytes in float), a byte of active edges a
// triangle and a byte a cell for holes: about 8 bytes a sample, where the
// same terrain as a triangle_mesh takes about 90 (its vertices, indices,
// edge bits and tree nodes; docs/narrowphase.md, "Heightfields").
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "../core/error.hpp"
#include "../core/policy.hpp"
#include "../math/aabb.hpp"
#include "../math/transform.hpp"
#include "detail/active_edges.hpp"

namespace impulse {

template <scalar_type T>
class heightfield {
 public:
  static constexpr policy_kind kind = policy_kind::shape;
  /// Bits of active_edges(t), as triangle_mesh's: edge ab, bc, ca.
  static constexpr std::uint8_t edge_ab = 1, edge_bc = 2, edge_ca = 4;
  /// As triangle_mesh::flat_edge_cosine: 5°.
  static constexpr T flat_edge_cosine = T(0.9961946980917455);

  /// Checks and copies the grid: at least 2 × 2 samples, positive finite
  /// spacings, finite heights (row k's columns at heights[k·columns + i]),
  /// and either no holes or one flag a cell (cell (i, k) at
  /// holes[k·(columns − 1) + i], nonzero for a hole).
  static heightfield make(std::size_t columns, std::size_t rows, T spacing_x, T spacing_z,
                          std::span<const T> heights, std::span<const std::uint8_t> holes = {}) {
    if (columns < 2 || rows < 2)
      detail::report_error(error_code::degenerate_shape, "heightfield: needs at least 2 x 2 samples");
    if (columns > 65536 || rows > 65536)
      detail::report_error(error_code::capacity_exceeded, "heightfield: at most 65536 samples a side");
    if (!std::isfinite(spacing_x) || !std::isfinite(spacing_z) || !(spacing_x > T(0)) || !(spacing_z > T(0)))
      detail::report_error(error_code::invalid_parameter, "heightfield: spacings must be positive and finite");
    if (heights.size() != columns * rows)
      detail::report_error(error_code::invalid_parameter, "heightfield: needs columns x rows heights");
    const std::size_t cells = (columns - 1) * (rows - 1);
    if (!holes.empty() && holes.size() != cells)
      detail::report_error(error_code::invalid_parameter, "heightfield: needs no holes or one flag per cell");
    heightfield h;
    h.columns_ = columns, h.rows_ = rows, h.dx_ = spacing_x, h.dz_ = spacing_z;
    h.heights_.assign(heights.begin(), heights.end());
    T low = heights[0], high = heights[0];
    for (const T y : heights) {
      if (!std::isfinite(y)) detail::report_error(error_code::non_finite, "heightfield: a height is not finite");
      low = std::min(low, y), high = std::max(high, y);
    }
    h.holes_.assign(cells, std::uint8_t(0));
    for (std::size_t c = 0; c < holes.size(); ++c) h.holes_[c] = holes[c] != 0;
    h.bounds_ = {{T(0), low, T(0)}, {T(columns - 1) * spacing_x, high, T(rows - 1) * spacing_z}};
    h.find_active_edges();
    return h;
  }

  /// Refuses an empty field (default-constructed or moved from).
  void validate() const {
    if (heights_.empty())
      detail::report_error(error_code::degenerate_shape,
                           "heightfield: the field is empty (default-constructed or moved from); use make()");
  }

  [[nodiscard]] std::size_t columns() const noexcept { return columns_; }
  [[nodiscard]] std::size_t rows() const noexcept { return rows_; }
  [[nodiscard]] T spacing_x() const noexcept { return dx_; }
  [[nodiscard]] T spacing_z() const noexcept { return dz_; }
  [[nodiscard]] T height(std::size_t i, std::size_t k) const noexcept { return heights_[k * columns_ + i]; }
  [[nodiscard]] bool hole(std::size_t i, std::size_t k) const noexcept { return holes_[k * (columns_ - 1) + i] != 0; }
  /// Bytes the field holds: heights, holes and edge bits.
  [[nodiscard]] std::size_t memory_bytes() const noexcept {
    return heights_.capacity() * sizeof(T) + holes_.capacity() + active_.capacity();
  }
  /// Two a cell, holes included (they have no triangles to give).
  [[nodiscard]] std::size_t triangle_count() const noexcept { return 2 * holes_.size(); }

  /// Triangle t's corners: cell t / 2, the half by t % 2.
  void triangle(std::size_t t, vec3<T>& a, vec3<T>& b, vec3<T>& c) const noexcept {
    const std::size_t cell = t / 2, i = cell % (columns_ - 1), k = cell / (columns_ - 1);
    const vec3<T> p00 = sample(i, k), p11 = sample(i + 1, k + 1);
    a = p00;
    if (t % 2 == 0) b = sample(i, k + 1), c = p11;
    else b = p11, c = sample(i + 1, k);
  }
  [[nodiscard]] std::uint8_t active_edges(std::size_t t) const noexcept { return active_[t]; }

  /// f(t) for each triangle of a cell under `box` (shape frame) whose
  /// heights reach it; holes give none.
  template <class F>
  void for_each_overlapping(const aabb<T>& box, F&& f) const {
    std::size_t i0, i1, k0, k1;
    if (!cells_under(box.lower.x, box.upper.x, box.lower.z, box.upper.z, i0, i1, k0, k1)) return;
    for (std::size_t k = k0; k <= k1; ++k)
      for (std::size_t i = i0; i <= i1; ++i) {
        if (hole(i, k)) continue;
        const T a = height(i, k), b = height(i + 1, k), c = height(i, k + 1), d = height(i + 1, k + 1);
        if (std::max({a, b, c, d}) < box.lower.y || std::min({a, b, c, d}) > box.upper.y) continue;
        const std::size_t cell = k * (columns_ - 1) + i;
        f(2 * cell);
        f(2 * cell + 1);
      }
  }

  /// f(t, clip) for the triangles of the cells under the segment from
  /// origin over translation·max_fraction (shape frame); f returns the
  /// fraction to go on to. Cells are visited in rows, not along the ray.
  template <class F>
  void for_each_along_ray(const vec3<T>& origin, const vec3<T>& translation, T max_fraction, F&& f) const {
    const vec3<T> end = origin + translation * max_fraction;
    const aabb<T> box{min(origin, end), max(origin, end)};
    std::size_t i0, i1, k0, k1;
    if (!cells_under(box.lower.x, box.upper.x, box.lower.z, box.upper.z, i0, i1, k0, k1)) return;
    T clip = max_fraction;
    for (std::size_t k = k0; k <= k1; ++k)
      for (std::size_t i = i0; i <= i1; ++i) {
        if (hole(i, k)) continue;
        const std::size_t cell = k * (columns_ - 1) + i;
        clip = f(2 * cell, clip);
        clip = f(2 * cell + 1, clip);
      }
  }

  aabb<T> local_aabb() const noexcept { return bounds_; }
  aabb<T> world_aabb(const transform<T>& pose) const noexcept { return transform_aabb(bounds_, pose); }

 private:
  [[nodiscard]] vec3<T> sample(std::size_t i, std::size_t k) const noexcept {
    return {T(i) * dx_, height(i, k), T(k) * dz_};
  }

  /// The columns and rows of cells under [x0, x1] × [z0, z1]; false if none.
  bool cells_under(T x0, T x1, T z0, T z1, std::size_t& i0, std::size_t& i1, std::size_t& k0,
                   std::size_t& k1) const noexcept {
    const T cx = T(columns_ - 1), cz = T(rows_ - 1);
    const T a = std::floor(x0 / dx_), b = std::floor(x1 / dx_), c = std::floor(z0 / dz_), d = std::floor(z1 / dz_);
    if (!(b >= T(0) && a < cx && d >= T(0) && c < cz)) return false;  // also refuses NaN
    i0 = std::size_t(std::max(a, T(0))), i1 = std::size_t(std::min(b, cx - T(1)));
    k0 = std::size_t(std::max(c, T(0))), k1 = std::size_t(std::min(d, cz - T(1)));
    return true;
  }

  /// Each triangle's edges: active at the border, beside a hole, and where
  /// its neighbour meets it convex by more than 5° (see the top).
  void find_active_edges() {
    active_.assign(triangle_count(), std::uint8_t(0));
    const std::size_t cx = columns_ - 1, cz = rows_ - 1;
    // The triangle across each edge: (cell offset, half), or none.
    const auto neighbour = [&](std::size_t i, std::size_t k, int di, int dk, int half, std::size_t& t) {
      const long ni = long(i) + di, nk = long(k) + dk;
      if (ni < 0 || nk < 0 || ni >= long(cx) || nk >= long(cz) || hole(std::size_t(ni), std::size_t(nk))) return false;
      t = 2 * (std::size_t(nk) * cx + std::size_t(ni)) + std::size_t(half);
      return true;
    };
    for (std::size_t k = 0; k < cz; ++k)
      for (std::size_t i = 0; i < cx; ++i) {
        if (hole(i, k)) continue;
        const std::size_t t0 = 2 * (k * cx + i), t1 = t0 + 1;
        // Triangle 0 (p00, p01, p11): ab the cell's x-side at i (across:
        // the left cell's triangle 1), bc its far z-side (the next row's
        // triangle 1), ca the diagonal (this cell's triangle 1).
        // Triangle 1 (p00, p11, p10): ab the diagonal, bc the x-side at
        // i + 1 (the right cell's triangle 0), ca the near z-side (the row
        // before's triangle 0).
        const struct {
          std::size_t t;
          std::uint8_t bit;
          int di, dk, half;
        } edges[] = {{t0, edge_ab, -1, 0, 1}, {t0, edge_bc, 0, 1, 1}, {t0, edge_ca, 0, 0, 1},
                     {t1, edge_ab, 0, 0, 0},  {t1, edge_bc, 1, 0, 0}, {t1, edge_ca, 0, -1, 0}};
        for (const auto& e : edges) {
          std::size_t other;
          if (!neighbour(i, k, e.di, e.dk, e.half, other) || crease_is_active(e.t, e.bit, other))
            active_[e.t] |= e.bit;
        }
      }
  }

  /// Whether the edge `bit` of triangle t, shared with triangle u, is active.
  bool crease_is_active(std::size_t t, std::uint8_t bit, std::size_t u) const noexcept {
    vec3<T> a, b, c, d, e, f;
    triangle(t, a, b, c);
    triangle(u, d, e, f);
    const vec3<T> p = bit == edge_ab ? a : bit == edge_bc ? b : c, q = bit == edge_ab ? b : bit == edge_bc ? c : a;
    const vec3<T> far = (d != p && d != q) ? d : (e != p && e != q) ? e : f;
    return detail::shared_edge_active(a, b, c, d, e, f, p, far, flat_edge_cosine);
  }

  std::size_t columns_ = 0, rows_ = 0;
  T dx_ = T(1), dz_ = T(1);
  std::vector<T> heights_;
  std::vector<std::uint8_t> holes_;
  std::vector<std::uint8_t> active_;
  aabb<T> bounds_{};
};

}  // namespace impulse
