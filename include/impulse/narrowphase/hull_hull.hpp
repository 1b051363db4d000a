// impulse/narrowphase/hull_hull.hpp — convex polyhedra against each other:
// hull–hull and box–hull, by the separating axis test and clipping.
//
// The method of box_box.hpp, for polyhedra of any shape (Gregorius, "The
// Separating Axis Test between Convex Polyhedra", GDC 2013). Two convex
// polyhedra are apart if and only if a face normal of one, or the cross
// product of an edge of each, separates them. Every face of each is tried
// against the other's support point, and every pair of edges whose arcs on
// the Gauss map cross: an edge is the arc between the normals of its two
// faces, and two edges build a face of the Minkowski difference A − B,
// whose normal is a candidate axis, only if A's arc crosses the arc of B's
// negated normals. The test costs a few dot products and drops nearly all
// pairs. Any axis farther apart than the margin ends the test at once.
//
// The rest is as for two boxes: faces are preferred over edges, and A's
// face over B's, unless clearly worse (5 % plus 1 % of the smaller
// polyhedron's least half extent); a face contact clips the incident face
// (the other polyhedron's face most opposed to the reference normal) to
// the reference face's side planes (Sutherland–Hodgman) and keeps one point
// per quarter of the patch; an edge contact is one point midway between
// the closest points of the two edges. If the clipped patch is empty (the
// bias chose a face that only an edge touches), the edge contact is used.
//
// All of it runs in A's frame, so that two polyhedra far from the origin
// lose no more precision than their distance from each other costs. B's
// vertices and face planes are carried into that frame once; for up to 64
// of each they are kept on the stack, so a resting pair allocates nothing.
//
// Feature ids. A face contact: bits 0–1 the quarter of the patch, bits
// 2–15 the incident face, bits 16–29 the reference face, bit 30 set when
// the reference face is B's. An edge contact: bit 31 set, then A's edge in
// bits 15–29 and B's in bits 0–14. (Indices are cut to those widths: ids
// need only differ between the features of one pair.)
//
// A box enters as a polyhedron with 8 vertices, 6 faces and 12 edges
// (box_polyhedron, below): box–box itself stays with box_box.hpp, whose
// axes and supports are closed forms.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>

#include "../math/transform.hpp"
#include "../shapes/box.hpp"
#include "../shapes/convex_hull.hpp"
#include "analytic.hpp"
#include "detail/clipping.hpp"
#include "detail/scratch_buffer.hpp"
#include "manifold.hpp"
#include "tolerances.hpp"

namespace impulse::narrowphase {

namespace detail {

/// A box seen as a convex_hull: the same vertices(), face(f), plane(f) and
/// edges(), built from the half extents without allocating. Vertex i has
/// the sign of x in bit 0, of y in bit 1 and of z in bit 2 (set: +); face
/// 2·axis + 1 is the face on the axis' positive side, 2·axis its negative.
template <scalar_type T>
class box_polyhedron {
 public:
  using face_plane = typename convex_hull<T>::face_plane;

  explicit box_polyhedron(const box<T>& b) noexcept {
    const vec3<T> h = b.half_extents;
    for (std::uint32_t i = 0; i < 8; ++i)
      vertices_[i] = {(i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z};
    for (int axis = 0; axis < 3; ++axis) {
      vec3<T> n{};
      n[axis] = T(1);
      planes_[std::size_t(2 * axis)] = {-n, -h[axis]};
      planes_[std::size_t(2 * axis + 1)] = {n, -h[axis]};
    }
    least_half_extent_ = min_component(h);
  }

  [[nodiscard]] std::span<const vec3<T>> vertices() const noexcept { return vertices_; }
  [[nodiscard]] std::size_t face_count() const noexcept { return 6; }
  [[nodiscard]] std::span<const std::uint32_t> face(std::size_t f) const noexcept { return topology.faces[f]; }
  [[nodiscard]] const face_plane& plane(std::size_t f) const noexcept { return planes_[f]; }
  [[nodiscard]] std::span<const hull_edge> edges() const noexcept { return topology.edges; }
  [[nodiscard]] T least_half_extent() const noexcept { return least_half_extent_; }

 private:
  struct topology_tables {
    std::array<std::array<std::uint32_t, 4>, 6> faces;
    std::array<hull_edge, 12> edges;
  };
  // Each face counter-clockwise seen from outside; each edge once, with the
  // face whose boundary runs a -> b and the one whose boundary runs b -> a.
  static constexpr topology_tables make_topology() noexcept {
    topology_tables t{{{{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}}}, {}};
    // Each edge is run a -> b by one face and b -> a by the other: the one
    // that runs it from the lower index names it, the other is found after.
    std::size_t count = 0;
    for (std::uint32_t f = 0; f < 6; ++f)
      for (std::size_t k = 0; k < 4; ++k)
        if (t.faces[f][k] < t.faces[f][(k + 1) % 4]) t.edges[count++] = {t.faces[f][k], t.faces[f][(k + 1) % 4], f, 0};
    for (std::uint32_t f = 0; f < 6; ++f)
      for (std::size_t k = 0; k < 4; ++k)
        for (hull_edge& e : t.edges)
          if (e.a == t.faces[f][(k + 1) % 4] && e.b == t.faces[f][k]) e.face_ba = f;
    return t;
  }
  static constexpr topology_tables topology = make_topology();

  std::array<vec3<T>, 8> vertices_;
  std::array<face_plane, 6> planes_;
  T least_half_extent_;
};

template <scalar_type T>
T least_half_extent(const convex_hull<T>& hull) noexcept {
  const aabb<T> bounds = hull.local_aabb();
  return min_component(bounds.upper - bounds.lower) * T(0.5);
}
template <scalar_type T>
T least_half_extent(const box_polyhedron<T>& b) noexcept {
  return b.least_half_extent();
}

/// The separating axis test and the contact of two polyhedra, each with the
/// interface of convex_hull (vertices, faces, planes, edges).
template <class PA, class PB, scalar_type T>
contact_manifold<T> collide_polyhedra(const PA& a, const transform<T>& pose_a, const PB& b, const transform<T>& pose_b,
                                      T margin) {
  using face_plane = typename convex_hull<T>::face_plane;
  const transform<T> relative = inverse_mul(pose_a, pose_b);  // B in A's frame
  const std::span<const vec3<T>> va = a.vertices();
  // B's vertices and face planes in A's frame.
  const std::span<const vec3<T>> b_local = b.vertices();
  scratch_buffer<vec3<T>, 64> vb(b_local.size());
  for (std::size_t i = 0; i < b_local.size(); ++i) vb[i] = apply(relative, b_local[i]);
  scratch_buffer<face_plane, 64> planes_b(b.face_count());
  for (std::size_t f = 0; f < b.face_count(); ++f) {
    const vec3<T> n = rotate(relative.rotation, b.plane(f).normal);
    planes_b[f] = {n, b.plane(f).offset - dot(n, relative.position)};
  }
  const auto lowest = [](const vec3<T>* points, std::size_t count, const vec3<T>& n) {
    T low = dot(n, points[0]);
    for (std::size_t i = 1; i < count; ++i) low = std::min(low, dot(n, points[i]));
    return low;
  };
  contact_manifold<T> m;

  struct best {
    T separation = -std::numeric_limits<T>::infinity();
    std::size_t index = 0;
    std::size_t other = 0;
    vec3<T> axis{};
  } face_a, face_b, edge;
  for (std::size_t f = 0; f < a.face_count(); ++f) {
    const face_plane& p = a.plane(f);
    const T s = lowest(vb.data(), b_local.size(), p.normal) + p.offset;
    if (s > margin) return m;
    if (s > face_a.separation) face_a = {s, f, 0, p.normal};
  }
  for (std::size_t f = 0; f < b.face_count(); ++f) {
    const face_plane& p = planes_b[f];
    const T s = lowest(va.data(), va.size(), p.normal) + p.offset;
    if (s > margin) return m;
    if (s > face_b.separation) face_b = {s, f, 0, p.normal};
  }
  // Edge pairs that build a face of A − B; the axis points away from A's
  // inside (the mean of its vertices).
  vec3<T> inside_a{};
  for (const vec3<T>& v : va) inside_a += v;
  inside_a /= T(va.size());
  // An edge's arc on the Gauss map runs from one face's unit normal to the
  // other's. Two arcs (each shorter than half a circle) cross if the ends
  // of each lie on opposite sides of the other's plane, and the two lie in
  // the same hemisphere. A − B's faces pair A's normals with B's reversed,
  // so B's arcs are of its negated normals. They are kept one array per
  // coordinate, so that each of A's arcs is tested against all of B's in
  // a loop the compiler vectorises: this test, not the axes, is where the
  // time goes on hulls of a few dozen edges.
  const std::span<const hull_edge> edges_a = a.edges(), edges_b = b.edges();
  const std::size_t nb = edges_b.size();
  scratch_buffer<T, 9 * 128> columns(9 * nb);
  T* const from[3] = {columns.data(), columns.data() + nb, columns.data() + 2 * nb};
  T* const to[3] = {columns.data() + 3 * nb, columns.data() + 4 * nb, columns.data() + 5 * nb};
  T* const plane_b[3] = {columns.data() + 6 * nb, columns.data() + 7 * nb, columns.data() + 8 * nb};
  for (std::size_t j = 0; j < nb; ++j) {
    const vec3<T> c = -planes_b[edges_b[j].face_ab].normal, d = -planes_b[edges_b[j].face_ba].normal;
    const vec3<T> d_x_c = cross(d, c);
    for (int k = 0; k < 3; ++k) from[k][j] = c[k], to[k][j] = d[k], plane_b[k][j] = d_x_c[k];
  }
  scratch_buffer<std::int32_t, 128> crossing(nb);
  for (std::size_t i = 0; i < edges_a.size(); ++i) {
    const hull_edge& ea = edges_a[i];
    const vec3<T> n1 = a.plane(ea.face_ab).normal, n2 = a.plane(ea.face_ba).normal, plane_a = cross(n2, n1);
    std::int32_t* const hits = crossing.data();
    for (std::size_t j = 0; j < nb; ++j) {
      const T cba = from[0][j] * plane_a.x + from[1][j] * plane_a.y + from[2][j] * plane_a.z;
      const T dba = to[0][j] * plane_a.x + to[1][j] * plane_a.y + to[2][j] * plane_a.z;
      const T adc = n1.x * plane_b[0][j] + n1.y * plane_b[1][j] + n1.z * plane_b[2][j];
      const T bdc = n2.x * plane_b[0][j] + n2.y * plane_b[1][j] + n2.z * plane_b[2][j];
      hits[j] = std::int32_t(cba * dba < T(0)) & std::int32_t(adc * bdc < T(0)) & std::int32_t(cba * bdc > T(0));
    }
    const vec3<T> pa = va[ea.a], da = va[ea.b] - pa;
    for (std::size_t j = 0; j < nb; ++j) {
      if (!hits[j]) continue;
      const hull_edge& eb = edges_b[j];
      const vec3<T> pb = vb[eb.a], db = vb[eb.b] - pb;
      vec3<T> L = cross(da, db);
      // Edges within about 0.06° of parallel: their axis is a face axis
      // already tested, and its direction is rounding noise.
      const T l2 = length_squared(L);
      if (!(l2 > tolerances<T>::parallel_edge_sine_squared * length_squared(da) * length_squared(db))) continue;
      L /= std::sqrt(l2);
      if (dot(L, pa - inside_a) < T(0)) L = -L;
      const T s = dot(L, pb - pa);
      if (s > margin) return m;
      if (s > edge.separation) edge = {s, i, j, L};
    }
  }

  const T tolerance = tolerances<T>::face_preference_of_size * std::min(least_half_extent(a), least_half_extent(b));
  const auto clearly_better = [&](T s, T than) {
    return s > than + tolerances<T>::face_preference_of_depth * std::abs(than) + tolerance;
  };
  const bool prefer_b = clearly_better(face_b.separation, face_a.separation);
  const best& preferred = prefer_b ? face_b : face_a;

  const auto edge_contact = [&] {
    const hull_edge& ea = edges_a[edge.index];
    const hull_edge& eb = edges_b[edge.other];
    const segment_closest<T> c = closest_points_of_segments(va[ea.a], va[ea.b], vb[eb.a], vb[eb.b]);
    const T depth = -dot(c.on_second - c.on_first, edge.axis);
    m.normal = apply_direction(pose_a, edge.axis);
    const std::uint32_t feature =
        (1u << 31) | ((std::uint32_t(edge.index) & 0x7fffu) << 15) | (std::uint32_t(edge.other) & 0x7fffu);
    m.add({apply(pose_a, (c.on_first + c.on_second) * T(0.5)), depth, feature});
    return m;
  };
  const bool have_edge = edge.separation > -std::numeric_limits<T>::infinity();
  if (have_edge && clearly_better(edge.separation, preferred.separation)) return edge_contact();

  // Face against face, in A's frame: the face of `face` as the reference,
  // the incident face clipped to it. False if nothing is left below it.
  const auto face_contact = [&](const best& face, bool reference_is_b) {
    const vec3<T> n = face.axis;  // out of the reference polyhedron
    const std::span<const std::uint32_t> ref_face = reference_is_b ? b.face(face.index) : a.face(face.index);
    const vec3<T>* ref_vertices = reference_is_b ? vb.data() : va.data();
    const T ref_offset = reference_is_b ? planes_b[face.index].offset : a.plane(face.index).offset;
    // The incident face: of the faces at the other polyhedron's deepest
    // vertex (its support along −n), the one most opposed to n. Most
    // opposed over all faces would do for a resting pair, but on a deep
    // overlap it can be a face off to the side, which clips to nothing.
    const vec3<T>* inc_vertices = reference_is_b ? va.data() : vb.data();
    const std::size_t inc_vertex_count = reference_is_b ? va.size() : b_local.size();
    std::uint32_t deepest = 0;
    for (std::uint32_t i = 1; i < inc_vertex_count; ++i)
      if (dot(n, inc_vertices[i]) < dot(n, inc_vertices[deepest])) deepest = i;
    std::size_t k = 0;
    T most_opposed = std::numeric_limits<T>::infinity();
    const std::size_t incident_faces = reference_is_b ? a.face_count() : b.face_count();
    for (std::size_t f = 0; f < incident_faces; ++f) {
      const std::span<const std::uint32_t> polygon = reference_is_b ? a.face(f) : b.face(f);
      if (std::find(polygon.begin(), polygon.end(), deepest) == polygon.end()) continue;
      const T c = dot(n, reference_is_b ? a.plane(f).normal : planes_b[f].normal);
      if (c < most_opposed) most_opposed = c, k = f;
    }
    const std::span<const std::uint32_t> inc_face = reference_is_b ? a.face(k) : b.face(k);
    // Clipping a convex polygon by a plane adds at most one point.
    const std::size_t room = inc_face.size() + ref_face.size() + 1;
    scratch_buffer<vec3<T>, 64> first(room), second(room);
    vec3<T>* polygon = first.data();
    vec3<T>* scratch = second.data();
    int count = int(inc_face.size());
    for (std::size_t c = 0; c < inc_face.size(); ++c) polygon[c] = inc_vertices[inc_face[c]];
    for (std::size_t c = 0; c < ref_face.size() && count > 0; ++c) {
      const vec3<T> p = ref_vertices[ref_face[c]], q = ref_vertices[ref_face[(c + 1) % ref_face.size()]];
      const vec3<T> w = cross(q - p, n);  // out of the face, across its edge pq
      count = clip(polygon, count, w, dot(w, p), scratch);
      std::swap(polygon, scratch);
    }
    scratch_buffer<patch_point<T>, 64> below(std::size_t(count) + 1);
    int found = 0;
    for (int c = 0; c < count; ++c) {
      const T separation = dot(n, polygon[std::size_t(c)]) + ref_offset;
      if (separation <= margin) below[std::size_t(found++)] = {polygon[std::size_t(c)], separation};
    }
    if (found == 0) return false;
    const vec3<T> u = normalize(ref_vertices[ref_face[1]] - ref_vertices[ref_face[0]]);
    int chosen[4];
    choose_by_quarter(below.data(), found, u, cross(n, u), chosen);
    const std::uint32_t faces = (std::uint32_t(reference_is_b) << 30) | ((std::uint32_t(face.index) & 0x3fffu) << 16) |
                                ((std::uint32_t(k) & 0x3fffu) << 2);
    m.normal = apply_direction(pose_a, reference_is_b ? -n : n);
    for (int q = 0; q < 4; ++q) {
      if (chosen[q] < 0) continue;
      const patch_point<T>& c = below[std::size_t(chosen[q])];
      m.add({apply(pose_a, c.x - n * (c.separation * T(0.5))), -c.separation, faces | std::uint32_t(q)});
    }
    return true;
  };
  if (face_contact(preferred, prefer_b)) return m;
  // The bias chose a face that clips to nothing: a deep overlap whose least
  // penetration is along another axis. Take that axis.
  const best& other = prefer_b ? face_a : face_b;
  if (have_edge && edge.separation >= other.separation) return edge_contact();
  if (face_contact(other, !prefer_b)) return m;
  return have_edge ? edge_contact() : m;
}

}  // namespace detail

template <scalar_type T>
contact_manifold<T> collide(const convex_hull<T>& a, const transform<T>& pose_a, const convex_hull<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) {
  return detail::collide_polyhedra(a, pose_a, b, pose_b, margin);
}

template <scalar_type T>
contact_manifold<T> collide(const box<T>& a, const transform<T>& pose_a, const convex_hull<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) {
  return detail::collide_polyhedra(detail::box_polyhedron<T>(a), pose_a, b, pose_b, margin);
}

template <scalar_type T>
contact_manifold<T> collide(const convex_hull<T>& a, const transform<T>& pose_a, const box<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) {
  return detail::collide_polyhedra(a, pose_a, detail::box_polyhedron<T>(b), pose_b, margin);
}

}  // namespace impulse::narrowphase
