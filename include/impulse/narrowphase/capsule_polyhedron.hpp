// impulse/narrowphase/capsule_polyhedron.hpp — a capsule against a box or a
// convex hull.
//
// A capsule is a segment (its core) grown by its radius. Everything runs in
// the polyhedron's frame:
//
// - Core outside the polyhedron: GJK (gjk.hpp) gives the distance d from
//   the segment and the closest points; the shapes touch if d is within
//   the radius plus the margin, along the normal from the core's closest
//   point to the polyhedron's. If that normal is within about 2.6° of a
//   face's and the segment lies along that face (within about 2.9°), the
//   capsule rests on it: the segment is clipped to the face's side planes
//   and each end below the face plus the radius and margin is a point, so
//   that a capsule lying on a box stands on two points, not one. Else one
//   point, midway between the two surfaces.
// - Core inside or through it (GJK finds them overlapping): the separating
//   axis test between the segment and the polyhedron (its face normals,
//   and the cross products of the segment with each of its edges), faces
//   preferred as in box_box.hpp; a face clips the segment as above, an
//   edge gives one point.
//
// Feature ids: a face contact (2·face + the segment's end, 0 from the end
// at −half_height, 1 from the other), an edge contact bit 31 and the edge,
// a single point from GJK bit 30 and the face whose normal is closest to
// the contact normal. While a capsule rolls or rests on one face, its ids
// hold.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <span>

#include "../math/transform.hpp"
#include "../shapes/box.hpp"
#include "../shapes/capsule.hpp"
#include "../shapes/convex_hull.hpp"
#include "analytic.hpp"
#include "gjk.hpp"
#include "hull_hull.hpp"
#include "manifold.hpp"
#include "tolerances.hpp"

namespace impulse::narrowphase {

namespace detail {

/// The capsule against the polyhedron `poly` (with the interface of
/// convex_hull), which GJK sees as `shape`: the normal from the capsule
/// into the polyhedron.
template <class Poly, class Shape, scalar_type T>
contact_manifold<T> collide_capsule_polyhedron(const capsule<T>& c, const transform<T>& pose_c, const Poly& poly,
                                               const Shape& shape, const transform<T>& pose_p, T margin) {
  using face_plane = typename convex_hull<T>::face_plane;
  const transform<T> relative = inverse_mul(pose_p, pose_c);  // the capsule in the polyhedron's frame
  const vec3<T> axis = rotate(relative.rotation, vec3<T>::unit_y());
  const vec3<T> p0 = relative.position - axis * c.half_height, p1 = relative.position + axis * c.half_height;
  const T r = c.radius;
  contact_manifold<T> m;

  // The segment clipped to face f's side planes; each end within reach of
  // the face a point. False if none is.
  const auto face_contact = [&](std::size_t f) {
    const face_plane& plane = poly.plane(f);
    const std::span<const std::uint32_t> polygon = poly.face(f);
    const std::span<const vec3<T>> vertices = poly.vertices();
    T t0 = T(0), t1 = T(1);  // the kept part of p0 + (p1 − p0)·t
    const vec3<T> d = p1 - p0;
    for (std::size_t k = 0; k < polygon.size(); ++k) {
      const vec3<T> a = vertices[polygon[k]], b = vertices[polygon[(k + 1) % polygon.size()]];
      const vec3<T> w = cross(b - a, plane.normal);  // out of the face, across its edge ab
      const T at0 = dot(w, p0 - a), slope = dot(w, d);
      if (slope == T(0)) {
        if (at0 > T(0)) return false;
        continue;
      }
      const T t = -at0 / slope;
      if (slope > T(0)) t1 = std::min(t1, t);
      else t0 = std::max(t0, t);
    }
    if (t0 > t1) return false;
    m.normal = apply_direction(pose_p, -plane.normal);
    const T ends[2] = {t0, t1};
    for (std::uint32_t e = 0; e < 2; ++e) {
      if (e == 1 && t1 - t0 <= T(0)) break;  // one point where the kept part is a point
      const vec3<T> x = p0 + d * ends[e];
      const T height = plane.distance(x);
      if (height - r > margin) continue;
      m.add({apply(pose_p, x - plane.normal * ((r + height) * T(0.5))), r - height, std::uint32_t(2 * f) | e});
    }
    return !m.empty();
  };
  // The face whose normal is closest to n.
  const auto nearest_face = [&](const vec3<T>& n) {
    std::size_t best = 0;
    for (std::size_t f = 1; f < poly.face_count(); ++f)
      if (dot(poly.plane(f).normal, n) > dot(poly.plane(best).normal, n)) best = f;
    return best;
  };

  const gjk_result<T> g =
      run_gjk(capsule<T>{r, c.half_height}, relative, shape, transform<T>::identity()).result;
  if (!g.overlapping && g.distance > T(0)) {
    if (g.distance - r > margin) return m;
    const vec3<T> n = (g.on_b - g.on_a) / g.distance;  // from the core into the polyhedron
    const std::size_t f = nearest_face(-n);
    const vec3<T> fn = poly.plane(f).normal;
    if (dot(fn, -n) > tolerances<T>::same_normal_cosine &&
        std::abs(dot(axis, fn)) < tolerances<T>::segment_along_face_sine && face_contact(f))
      return m;
    m.normal = apply_direction(pose_p, n);
    m.add({apply(pose_p, (g.on_a + n * r + g.on_b) * T(0.5)), r - g.distance, (1u << 30) | std::uint32_t(f)});
    return m;
  }

  // The core reaches into the polyhedron: the separating axis test.
  struct best {
    T separation = -std::numeric_limits<T>::infinity();
    std::size_t index = 0;
    vec3<T> axis{};
  } face, edge;
  for (std::size_t f = 0; f < poly.face_count(); ++f) {
    const face_plane& p = poly.plane(f);
    const T s = std::min(p.distance(p0), p.distance(p1)) - r;
    if (s > face.separation) face = {s, f, p.normal};
  }
  // An edge's axis L (across the segment and the edge) counts only where
  // the edge is the polyhedron's support along it: L between the normals
  // of the edge's two faces (the segment's arc on the Gauss map, a whole
  // great circle, crosses the edge's arc there). L is across the segment,
  // which then projects to one value.
  const std::span<const vec3<T>> vertices = poly.vertices();
  const std::span<const hull_edge> edges = poly.edges();
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const vec3<T> a = vertices[edges[e].a], ab = vertices[edges[e].b] - a;
    vec3<T> L = cross(p1 - p0, ab);
    const T l2 = length_squared(L);
    if (!(l2 > tolerances<T>::parallel_edge_sine_squared * length_squared(p1 - p0) * length_squared(ab))) continue;
    L /= std::sqrt(l2);
    const vec3<T> n1 = poly.plane(edges[e].face_ab).normal, n2 = poly.plane(edges[e].face_ba).normal;
    if (dot(L, n1 + n2) < T(0)) L = -L;  // out of the polyhedron
    if (dot(cross(n1, L), cross(L, n2)) < T(0)) continue;
    const T s = dot(L, p0 - a) - r;
    if (s > edge.separation) edge = {s, e, L};
  }
  const T tolerance = tolerances<T>::face_preference_of_size * std::min(r, least_half_extent(poly));
  const bool edge_wins =
      edge.separation >
      face.separation + tolerances<T>::face_preference_of_depth * std::abs(face.separation) + tolerance;
  if (!edge_wins && face_contact(face.index)) return m;
  if (edge.separation == -std::numeric_limits<T>::infinity()) {
    // No edge axis (a segment parallel to every edge cannot happen for a
    // solid, but a zero-length core can): the face, through its deepest end.
    const face_plane& p = poly.plane(face.index);
    const vec3<T> x = p.distance(p0) < p.distance(p1) ? p0 : p1;
    const T height = p.distance(x);
    m.normal = apply_direction(pose_p, -p.normal);
    m.add({apply(pose_p, x - p.normal * ((r + height) * T(0.5))), r - height, std::uint32_t(2 * face.index)});
    return m;
  }
  const vec3<T> L = edge.axis;  // out of the polyhedron, towards the capsule
  const hull_edge& e = edges[edge.index];
  const segment_closest<T> closest = closest_points_of_segments(p0, p1, vertices[e.a], vertices[e.b]);
  const vec3<T> on_capsule = closest.on_first - L * r;
  m.normal = apply_direction(pose_p, -L);
  m.add({apply(pose_p, (on_capsule + closest.on_second) * T(0.5)), -dot(on_capsule - closest.on_second, L),
         (1u << 31) | std::uint32_t(edge.index)});
  return m;
}

}  // namespace detail

template <scalar_type T>
contact_manifold<T> collide(const capsule<T>& a, const transform<T>& pose_a, const box<T>& b, const transform<T>& pose_b,
                            T margin = T(0)) {
  return detail::collide_capsule_polyhedron(a, pose_a, detail::box_polyhedron<T>(b), b, pose_b, margin);
}
template <scalar_type T>
contact_manifold<T> collide(const box<T>& a, const transform<T>& pose_a, const capsule<T>& b, const transform<T>& pose_b,
                            T margin = T(0)) {
  return collide(b, pose_b, a, pose_a, margin).flipped();
}
template <scalar_type T>
contact_manifold<T> collide(const capsule<T>& a, const transform<T>& pose_a, const convex_hull<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) {
  return detail::collide_capsule_polyhedron(a, pose_a, b, b, pose_b, margin);
}
template <scalar_type T>
contact_manifold<T> collide(const convex_hull<T>& a, const transform<T>& pose_a, const capsule<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) {
  return collide(b, pose_b, a, pose_a, margin).flipped();
}

}  // namespace impulse::narrowphase
