// impulse/shapes/triangle_mesh.hpp — static triangle soup for level geometry.
//
// Vertices and index triples, counter-clockwise seen from the free side.
// Static only: it need not be closed, so it has no volume and no mass
// properties. Built once by make(), which also builds what the narrow phase
// reads:
//
// - a bounding-volume tree over the triangles (detail/triangle_bvh.hpp),
//   queried by box (for_each_overlapping) and by segment
//   (for_each_along_ray) without allocating;
// - which edges of each triangle are active (active_edges): an edge is
//   active where something can rest against it — a boundary edge (one
//   triangle), an edge shared by more than two triangles or by two whose
//   windings disagree or that lie back to back, and a convex edge whose
//   faces meet more than 5° away from flat. A flat or concave edge between
//   two triangles is internal: a contact there takes the triangle's face
//   normal, so that a box sliding over a flat mesh does not catch on the
//   seams between its triangles (the active edges of Jolt Physics'
//   MeshShape, Bullet's btInternalEdgeUtility; narrowphase/mesh.hpp).
//   Neighbours are found by sorting the edges by their two vertices, and
//   vertices are compared by position, so an unwelded mesh (each triangle
//   with its own copies of shared corners) gets the same answer as a
//   welded one.
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
#include "../math/scalar_traits.hpp"
#include "../math/transform.hpp"
#include "detail/active_edges.hpp"
#include "detail/triangle_bvh.hpp"

namespace impulse {

template <scalar_type T>
class triangle_mesh {
 public:
  static constexpr policy_kind kind = policy_kind::shape;

  /// Bits of active_edges(t): edge ab (corners 0 → 1), bc, ca.
  static constexpr std::uint8_t edge_ab = 1, edge_bc = 2, edge_ca = 4;
  /// Two faces whose normals are closer than this cosine (5°, Jolt's
  /// default) meet flat: their shared edge is internal. A mesh that bends
  /// by less than that per edge (a tessellated gentle slope) is treated as
  /// smooth; a bend of more stops a sliding box as a real step would.
  static constexpr T flat_edge_cosine = T(0.9961946980917455);

  /// Copies the mesh after checking it: finite vertices, indices in range,
  /// at least one triangle, and no triangle of zero area. Builds the tree
  /// and the active edges (O(n log n) in the number of triangles).
  static triangle_mesh make(std::span<const vec3<T>> vertices, std::span<const std::uint32_t> indices) {
    if (indices.empty() || indices.size() % 3 != 0)
      detail::report_error(error_code::degenerate_shape, "triangle_mesh: needs whole triangles, at least one");
    triangle_mesh mesh;
    for (const vec3<T>& v : vertices) {
      if (!is_finite(v)) detail::report_error(error_code::non_finite, "triangle_mesh: a vertex is not finite");
      mesh.bounds_ = mesh.vertices_.empty() ? aabb<T>{v, v} : merge(mesh.bounds_, v);
      mesh.vertices_.push_back(v);
    }
    for (std::size_t t = 0; t < indices.size(); t += 3) {
      for (std::size_t k = 0; k < 3; ++k)
        if (indices[t + k] >= vertices.size())
          detail::report_error(error_code::out_of_range, "triangle_mesh: an index names a missing vertex",
                               std::uint32_t(t / 3));
      const vec3<T> a = vertices[indices[t]], b = vertices[indices[t + 1]], c = vertices[indices[t + 2]];
      // Zero area relative to the triangle's own size: ε² of its longest edge squared.
      const T scale = max_component(abs(b - a)) + max_component(abs(c - a));
      if (!(length_squared(cross(b - a, c - a)) > scalar_traits<T>::epsilon * scalar_traits<T>::epsilon * scale * scale * scale * scale))
        detail::report_error(error_code::degenerate_shape, "triangle_mesh: a triangle has zero area",
                             std::uint32_t(t / 3));
    }
    if (indices.size() / 3 >= std::size_t(0xffffffffu))
      detail::report_error(error_code::capacity_exceeded, "triangle_mesh: more triangles than 32-bit indices can name");
    mesh.indices_.assign(indices.begin(), indices.end());

    std::vector<aabb<T>> boxes(mesh.triangle_count());
    for (std::size_t t = 0; t < boxes.size(); ++t) boxes[t] = mesh.triangle_aabb(t);
    mesh.tree_.build(boxes);
    mesh.find_active_edges();
    return mesh;
  }

  /// Refuses a mesh with no triangle: a default-constructed or moved-from
  /// one, which make() never returns. The world checks every shape it is
  /// given this way.
  void validate() const {
    if (indices_.empty())
      detail::report_error(error_code::degenerate_shape,
                           "triangle_mesh: the mesh is empty (default-constructed or moved from); use make()");
  }

  [[nodiscard]] std::span<const vec3<T>> vertices() const noexcept { return vertices_; }
  [[nodiscard]] std::size_t triangle_count() const noexcept { return indices_.size() / 3; }
  /// The three corners of triangle t.
  void triangle(std::size_t t, vec3<T>& a, vec3<T>& b, vec3<T>& c) const noexcept {
    a = vertices_[indices_[3 * t]];
    b = vertices_[indices_[3 * t + 1]];
    c = vertices_[indices_[3 * t + 2]];
  }
  /// The tight box around triangle t, in the mesh's frame.
  [[nodiscard]] aabb<T> triangle_aabb(std::size_t t) const noexcept {
    vec3<T> a, b, c;
    triangle(t, a, b, c);
    return merge(aabb<T>{min(a, b), max(a, b)}, c);
  }
  /// Which of triangle t's edges are active: edge_ab | edge_bc | edge_ca.
  [[nodiscard]] std::uint8_t active_edges(std::size_t t) const noexcept { return active_[t]; }

  /// Calls f(t) for every triangle t whose tight box overlaps `local_box`
  /// (in the mesh's frame; touching counts), in the tree's order. Allocates
  /// nothing.
  template <class F>
  void for_each_overlapping(const aabb<T>& local_box, F&& f) const {
    const std::span<const std::uint32_t> order = tree_.order();
    tree_.for_each_leaf_overlapping(local_box, [&](std::uint32_t first, std::uint32_t count) {
      for (std::uint32_t i = first; i < first + count; ++i)
        if (overlaps(triangle_aabb(order[i]), local_box)) f(std::size_t(order[i]));
    });
  }

  /// Walks the triangles near the segment origin + s·translation, s in
  /// [0, max_fraction] (in the mesh's frame), leaves nearer along it first:
  /// f(t, clip) is called with the fraction the segment is clipped to so
  /// far and returns the new clip (its nearest hit, or clip unchanged);
  /// leaves entered beyond the clip are skipped. Every triangle the segment
  /// crosses before the final clip is passed to f. Allocates nothing.
  template <class F>
  void for_each_along_ray(const vec3<T>& origin, const vec3<T>& translation, T max_fraction, F&& f) const {
    // The slab test's rounding, in metres: a few ulps of the largest
    // coordinate it subtracts.
    const T reach = std::max(max_component(abs(bounds_.lower)), max_component(abs(bounds_.upper))) +
                    max_component(abs(origin));
    const T slack = T(16) * scalar_traits<T>::epsilon * reach;
    const std::span<const std::uint32_t> order = tree_.order();
    tree_.for_each_leaf_along(origin, translation, max_fraction, slack,
                              [&](std::uint32_t first, std::uint32_t count, T clip) {
                                for (std::uint32_t i = first; i < first + count; ++i) clip = f(std::size_t(order[i]), clip);
                                return clip;
                              });
  }

  /// The tree itself, for inspection and tests.
  [[nodiscard]] const detail::triangle_bvh<T>& tree() const noexcept { return tree_; }
  /// Bytes the mesh holds: vertices, indices, edge bits and its tree.
  [[nodiscard]] std::size_t memory_bytes() const noexcept {
    return vertices_.capacity() * sizeof(vec3<T>) + indices_.capacity() * sizeof(std::uint32_t) + active_.capacity() +
           tree_.memory_bytes();
  }

  aabb<T> local_aabb() const noexcept { return bounds_; }
  aabb<T> world_aabb(const transform<T>& pose) const noexcept {
    aabb<T> box{apply(pose, vertices_[0]), apply(pose, vertices_[0])};
    for (const vec3<T>& v : vertices_) box = merge(box, apply(pose, v));
    return box;
  }

 private:
  /// Finds each edge's neighbours and decides whether it is active (see
  /// the top of the file).
  void find_active_edges() {
    const std::size_t n = triangle_count();
    active_.assign(n, std::uint8_t(0));
    // Vertices by position: each gets the smallest index of the vertices at
    // its exact position.
    std::vector<std::uint32_t> by_position(vertices_.size()), canonical(vertices_.size());
    for (std::uint32_t i = 0; i < by_position.size(); ++i) by_position[i] = i;
    const auto less = [&](std::uint32_t x, std::uint32_t y) {
      const vec3<T>& p = vertices_[x];
      const vec3<T>& q = vertices_[y];
      if (p.x != q.x) return p.x < q.x;
      if (p.y != q.y) return p.y < q.y;
      if (p.z != q.z) return p.z < q.z;
      return x < y;
    };
    std::sort(by_position.begin(), by_position.end(), less);
    for (std::size_t i = 0; i < by_position.size(); ++i)
      canonical[by_position[i]] =
          i > 0 && vertices_[by_position[i]] == vertices_[by_position[i - 1]] ? canonical[by_position[i - 1]] : by_position[i];

    struct edge_record {
      std::uint32_t lo, hi;  // canonical vertices, lo < hi
      std::uint32_t triangle;
      std::uint8_t k;        // 0 ab, 1 bc, 2 ca
      bool forward;          // the triangle runs it lo -> hi
    };
    std::vector<edge_record> edges;
    edges.reserve(3 * n);
    for (std::uint32_t t = 0; t < n; ++t)
      for (std::uint8_t k = 0; k < 3; ++k) {
        const std::uint32_t p = canonical[indices_[3 * t + k]], q = canonical[indices_[3 * t + (k + 1) % 3]];
        edges.push_back({std::min(p, q), std::max(p, q), t, k, p < q});
      }
    std::sort(edges.begin(), edges.end(), [](const edge_record& x, const edge_record& y) {
      return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.triangle < y.triangle;
    });
    for (std::size_t i = 0; i < edges.size();) {
      std::size_t j = i + 1;
      while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
      const bool active = j - i != 2 || edge_is_active(edges[i].triangle, edges[i].k, edges[i + 1].triangle,
                                                      edges[i].forward == edges[i + 1].forward);
      if (active)
        for (std::size_t e = i; e < j; ++e) active_[edges[e].triangle] |= std::uint8_t(1u << edges[e].k);
      i = j;
    }
  }

  /// Whether the edge k of triangle t1, shared with triangle t2, is active.
  bool edge_is_active(std::uint32_t t1, std::uint8_t k, std::uint32_t t2, bool same_direction) const noexcept {
    if (same_direction) return true;  // the windings disagree: no consistent front side across it
    vec3<T> a1, b1, c1, a2, b2, c2;
    triangle(t1, a1, b1, c1);
    triangle(t2, a2, b2, c2);
    // t2's corner off the edge, by position (either copy of a shared
    // corner is at the same place).
    const vec3<T> p = k == 0 ? a1 : k == 1 ? b1 : c1, q = k == 0 ? b1 : k == 1 ? c1 : a1;
    const vec3<T> far = (a2 != p && a2 != q) ? a2 : (b2 != p && b2 != q) ? b2 : c2;
    return detail::shared_edge_active(a1, b1, c1, a2, b2, c2, p, far, flat_edge_cosine);
  }

  std::vector<vec3<T>> vertices_;
  std::vector<std::uint32_t> indices_;
  std::vector<std::uint8_t> active_;
  detail::triangle_bvh<T> tree_;
  aabb<T> bounds_{};
};

}  // namespace impulse
