// impulse/shapes/triangle_mesh.hpp — static triangle soup for level geometry.
//
// Vertices and index triples, counter-clockwise seen from the free side.
// Static only: it need not be closed, so it has no volume and no mass
// properties. The narrow phase adds a bounding-volume tree over its
// triangles; this file holds the geometry and its bounds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "../core/error.hpp"
#include "../core/policy.hpp"
#include "../math/aabb.hpp"
#include "../math/scalar_traits.hpp"
#include "../math/transform.hpp"

namespace impulse {

template <scalar_type T>
class triangle_mesh {
 public:
  static constexpr policy_kind kind = policy_kind::shape;

  /// Copies the mesh after checking it: finite vertices, indices in range,
  /// at least one triangle, and no triangle of zero area.
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
    mesh.indices_.assign(indices.begin(), indices.end());
    return mesh;
  }

  [[nodiscard]] std::span<const vec3<T>> vertices() const noexcept { return vertices_; }
  [[nodiscard]] std::size_t triangle_count() const noexcept { return indices_.size() / 3; }
  /// The three corners of triangle t.
  void triangle(std::size_t t, vec3<T>& a, vec3<T>& b, vec3<T>& c) const noexcept {
    a = vertices_[indices_[3 * t]];
    b = vertices_[indices_[3 * t + 1]];
    c = vertices_[indices_[3 * t + 2]];
  }

  aabb<T> local_aabb() const noexcept { return bounds_; }
  aabb<T> world_aabb(const transform<T>& pose) const noexcept {
    aabb<T> box{apply(pose, vertices_[0]), apply(pose, vertices_[0])};
    for (const vec3<T>& v : vertices_) box = merge(box, apply(pose, v));
    return box;
  }

 private:
  std::vector<vec3<T>> vertices_;
  std::vector<std::uint32_t> indices_;
  aabb<T> bounds_{};
};

}  // namespace impulse
