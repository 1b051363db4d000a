// impulse/shapes/convex_hull.hpp — a convex polyhedron, built as the hull of a point cloud.
//
// Built once by quickhull (Barber, Dobkin & Huhdanpaa, ACM TOMS 1996) with the
// fat planes and face merging of Dirk Gregorius' "Implementing Quickhull"
// (GDC 2014); the construction is in detail/quickhull.hpp. Stored as what the
// narrow phase reads: the vertices on the hull, the faces as convex polygons
// with their planes, and every edge once with the two faces that meet at it —
// the face normals and edge directions of the separating axis test, and the
// support points of GJK.
//
// Tolerance. Points closer than tolerance() to the hull count as on it:
// duplicates, points on faces and edges and nearly coplanar points are
// dropped, and faces that meet at an edge flatter than that are one polygon
// (a box's eight corners give six quads, not twelve triangles). tolerance()
// is Gregorius' 3·(max|x| + max|y| + max|z|)·ε, with ε the machine epsilon
// of T and the coordinates measured from the center of the points' bounding
// box, so a hull far from the origin is as good as one at it (evaluating its
// planes at world coordinates x adds rounding of about ε·|x|). What the
// construction guarantees, in units of tolerance():
// - every plane supports the hull: no vertex is outside any face's plane;
// - every input point is within about one of every plane, and every hull
//   vertex is an input point;
// - a face's vertices lie within about two of its plane, and its polygon is
//   convex within one;
// except for hulls thinner than about a thousand tolerances across (in
// float, about 1/3000 of their size), whose rim faces may lie farther from
// their planes: their planes still support the hull.
//
// Plane convention, as impulse::plane: a face lies in n·x + offset = 0 with n
// the unit outward normal, so plane(f).distance(x) = n·x + offset is the
// signed distance from the face's plane, negative inside.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "../core/error.hpp"
#include "../core/policy.hpp"
#include "../math/aabb.hpp"
#include "../math/scalar_traits.hpp"
#include "../math/transform.hpp"
#include "../math/vec3.hpp"
#include "detail/quickhull.hpp"
#include "mass_properties.hpp"

namespace impulse {

/// An edge of a convex hull: two vertex indices and the two faces that meet
/// there. The same type for float and double hulls.
struct hull_edge {
  std::uint32_t a;        ///< one vertex
  std::uint32_t b;        ///< the other vertex
  std::uint32_t face_ab;  ///< the face whose boundary runs a -> b (counter-clockwise seen from outside)
  std::uint32_t face_ba;  ///< the face whose boundary runs b -> a
};

template <scalar_type T>
class convex_hull {
 public:
  using scalar = T;
  using edge = hull_edge;
  static constexpr policy_kind kind = policy_kind::shape;

  /// The plane of a face: n·x + offset = 0, n the unit outward normal.
  struct face_plane {
    vec3<T> normal;  ///< unit, pointing out of the hull
    T offset;        ///< m: minus the distance of the plane from the origin along n

    /// Signed distance of x from the plane (m), negative on the inside.
    constexpr T distance(const vec3<T>& x) const noexcept { return dot(normal, x) + offset; }
  };

  /// The convex hull of `points`, which may hold duplicates and points inside
  /// or on the hull (they are dropped). Reports error_code::non_finite for a
  /// NaN or infinite coordinate (the object is the point's index) and
  /// error_code::degenerate_shape when the points do not enclose a volume
  /// thicker than tolerance(): fewer than four, all coincident, collinear or
  /// coplanar.
  static convex_hull from_points(std::span<const vec3<T>> points) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!is_finite(points[i]))
        detail::report_error(error_code::non_finite, "convex_hull: a point has a NaN or infinite coordinate",
                             static_cast<std::uint32_t>(i));
    }
    if (points.size() < 4)
      detail::report_error(error_code::degenerate_shape, "convex_hull: fewer than 4 points cannot enclose a volume");
    if (points.size() >= 0xffffffffu)
      detail::report_error(error_code::capacity_exceeded, "convex_hull: more points than 32-bit indices can name");

    // The builder works in double on coordinates centered on the bounding box
    // and scaled by a power of two (exact) into [-1, 1]: the tolerance is then
    // relative to the size of the cloud, not its distance from the origin,
    // and no product in the construction can overflow or underflow.
    vec3<double> lo = widen(points[0]), hi = lo;
    for (const vec3<T>& p : points) {
      lo = min(lo, widen(p));
      hi = max(hi, widen(p));
    }
    const vec3<double> center = lo * 0.5 + hi * 0.5;
    const vec3<double> half = hi * 0.5 - lo * 0.5;
    const double largest = max_component(half);
    if (!(largest > 0)) detail::report_error(error_code::degenerate_shape, "convex_hull: all points coincide");
    const double tolerance = 3 * (half.x + half.y + half.z) * double(scalar_traits<T>::epsilon);
    // The same for the double arithmetic of the construction: for a float
    // hull, 2^29 times finer (see detail::quickhull::build).
    const double construction_tolerance = 3 * (half.x + half.y + half.z) * scalar_traits<double>::epsilon;
    int exponent = 0;
    std::frexp(largest, &exponent);
    const double scale = std::ldexp(1.0, -exponent);  // largest·scale in [0.5, 1)
    if (!std::isfinite(tolerance) || !std::isfinite(scale) || !(tolerance * scale > 0))
      detail::report_error(error_code::invalid_parameter,
                           "convex_hull: the points span a range too large or too small for double arithmetic");

    std::vector<vec3<double>> local(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) local[i] = (widen(points[i]) - center) * scale;
    detail::quickhull builder;
    detail::quickhull_output out;
    switch (builder.build(local, construction_tolerance * scale, tolerance * scale, out)) {
      case detail::quickhull_status::ok: break;
      case detail::quickhull_status::coincident:
        detail::report_error(error_code::degenerate_shape, "convex_hull: all points coincide within the tolerance");
      case detail::quickhull_status::collinear:
        detail::report_error(error_code::degenerate_shape, "convex_hull: all points lie on a line within the tolerance");
      case detail::quickhull_status::coplanar:
        detail::report_error(error_code::degenerate_shape, "convex_hull: all points lie in a plane within the tolerance");
    }

    convex_hull hull;
    hull.tolerance_ = static_cast<T>(tolerance);
    hull.vertices_.reserve(out.vertex_points.size());
    for (const std::uint32_t p : out.vertex_points) hull.vertices_.push_back(points[p]);
    hull.bounds_ = {hull.vertices_[0], hull.vertices_[0]};
    for (const vec3<T>& v : hull.vertices_) hull.bounds_ = merge(hull.bounds_, v);
    hull.face_offsets_ = std::move(out.face_offsets);
    hull.face_vertices_ = std::move(out.face_vertices);
    hull.planes_.reserve(out.normals.size());
    for (std::size_t f = 0; f < out.normals.size(); ++f) {
      // The offset is taken with the normal as stored, so that the plane
      // still passes through the supporting vertex after rounding to T.
      const vec3<T> n = narrow(out.normals[f]);
      hull.planes_.push_back({n, static_cast<T>(-dot(widen(n), widen(hull.vertices_[out.supports[f]])))});
    }
    hull.edges_.reserve(out.edges.size());
    for (const detail::quickhull_edge& e : out.edges) hull.edges_.push_back({e.a, e.b, e.face_ab, e.face_ba});
    return hull;
  }

  /// The points of the input that are vertices of the hull, in input order.
  /// Refuses a moved-from hull, which has no vertices: from_points never
  /// returns one. The world checks every shape it is given this way.
  void validate() const {
    if (vertices_.empty())
      detail::report_error(error_code::degenerate_shape,
                           "convex_hull: the hull is empty (moved from); use from_points()");
  }

  [[nodiscard]] std::span<const vec3<T>> vertices() const noexcept { return vertices_; }
  [[nodiscard]] std::size_t vertex_count() const noexcept { return vertices_.size(); }

  [[nodiscard]] std::size_t face_count() const noexcept { return planes_.size(); }
  /// Vertex indices of face f, counter-clockwise seen from outside.
  [[nodiscard]] std::span<const std::uint32_t> face(std::size_t f) const noexcept {
    IMPULSE_ASSERT(f < face_count());
    return {face_vertices_.data() + face_offsets_[f], face_offsets_[f + 1] - face_offsets_[f]};
  }
  [[nodiscard]] const face_plane& plane(std::size_t f) const noexcept {
    IMPULSE_ASSERT(f < face_count());
    return planes_[f];
  }
  [[nodiscard]] std::span<const face_plane> planes() const noexcept { return planes_; }

  /// Every edge once.
  [[nodiscard]] std::span<const edge> edges() const noexcept { return edges_; }

  /// m: the half-thickness of the fat planes the hull was built with (see
  /// the top of this file for what it bounds).
  [[nodiscard]] T tolerance() const noexcept { return tolerance_; }

  /// Index of the vertex farthest along `direction` (the first of equals).
  /// A scan of every vertex: for the few dozen vertices of a typical
  /// collision hull it beats hill climbing, which needs adjacency lookups.
  [[nodiscard]] std::uint32_t support_index(const vec3<T>& direction) const noexcept {
    std::uint32_t best = 0;
    T best_distance = dot(vertices_[0], direction);
    for (std::uint32_t i = 1; i < vertices_.size(); ++i) {
      const T d = dot(vertices_[i], direction);
      if (d > best_distance) {
        best_distance = d;
        best = i;
      }
    }
    return best;
  }
  /// The vertex farthest along `direction` (GJK's support mapping).
  [[nodiscard]] vec3<T> support(const vec3<T>& direction) const noexcept {
    return vertices_[support_index(direction)];
  }

  /// The tight box around the vertices, in shape space.
  [[nodiscard]] aabb<T> local_aabb() const noexcept { return bounds_; }
  /// The world box of the local box (constant time; at most √3 times wider
  /// than the tight box of the rotated hull).
  [[nodiscard]] aabb<T> world_aabb(const transform<T>& pose) const noexcept { return transform_aabb(bounds_, pose); }

 private:
  convex_hull() = default;

  static vec3<double> widen(const vec3<T>& v) noexcept { return {double(v.x), double(v.y), double(v.z)}; }
  static vec3<T> narrow(const vec3<double>& v) noexcept {
    return {static_cast<T>(v.x), static_cast<T>(v.y), static_cast<T>(v.z)};
  }

  std::vector<vec3<T>> vertices_;
  std::vector<std::uint32_t> face_offsets_;   // face f is face_vertices_[face_offsets_[f], face_offsets_[f + 1])
  std::vector<std::uint32_t> face_vertices_;
  std::vector<face_plane> planes_;
  std::vector<edge> edges_;
  aabb<T> bounds_{};
  T tolerance_ = T(0);
};

/// The solid hull filled with `density`: each convex face fanned into
/// triangles from its first vertex, then the polyhedron integrals.
template <scalar_type T>
mass_properties<T> mass_properties_of(const convex_hull<T>& hull, T density) {
  std::vector<std::uint32_t> triangles;
  for (std::size_t f = 0; f < hull.face_count(); ++f) {
    const std::span<const std::uint32_t> polygon = hull.face(f);
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
      triangles.insert(triangles.end(), {polygon[0], polygon[k], polygon[k + 1]});
  }
  return polyhedron_mass_properties<T>(hull.vertices(), triangles, density);
}

}  // namespace impulse
