// impulse/narrowphase/mesh.hpp — a static triangle mesh against a sphere, a
// capsule, a box or a convex hull, and a ray against a mesh.
//
// `collide(mesh, pose_mesh, shape, pose_shape, margin, out)` queries the
// mesh's tree (shapes/detail/triangle_bvh.hpp) with the shape's box in the
// mesh's frame, tests each triangle it returns, and merges the triangles'
// manifolds whose normals agree within about 2.6° (cosine > 0.999) into one
// (the points of both, points within 1e-4 of the shape's size of each other
// welded into the deeper, then reduce_to_four, or the two ends of a line of
// points), so that a box resting on a
// flat mesh gets one manifold of four points however many triangles it
// spans. It writes at most out.size() manifolds, the deepest first, and
// returns how many. Normals point from the mesh (A) into the shape (B); the
// swapped overload returns the same manifolds flipped.
//
// Per triangle, in a frame with the mesh's axes and its origin at the
// shape's position (so that a mesh far from the origin costs no more
// precision than the shape's distance from its triangles):
// - sphere: the closest point on the triangle (triangle.hpp, Ericson §5.1.5).
// - capsule: the closest points of the core segment and the triangle (the
//   segment's ends against the triangle, the segment against each edge,
//   and the segment through the face; Ericson §5.1.10). A contact along
//   the face normal clips the segment to the triangle's prism and reports
//   each end within reach, so that a capsule lying on a mesh stands on two
//   points.
// - box and hull: the separating axis test between the triangle and the
//   polyhedron (Gregorius, GDC 2013; Ericson §5.2.1): the triangle's
//   normal, the polyhedron's face normals, and the cross products of the
//   triangle's three edges with every edge of the polyhedron. hull_hull.hpp
//   prunes edge pairs on the Gauss map, which assumes each edge's two faces
//   are less than 180° apart; a triangle's edges are 180° arcs (front and
//   back face), so here every pair is tried, in both orientations, with the
//   exact projections of the triangle's corners and the polyhedron's
//   vertices. An edge pair becomes the contact normal only where both edges
//   support their shapes along it (the triangle's edge faces out along it,
//   the polyhedron's lies between its faces), so that its closest points are
//   the contact. Faces are preferred over edges, the triangle's face over
//   the polyhedron's, unless clearly worse (5 % plus 1 % of the
//   polyhedron's least half extent, as in hull_hull.hpp). A face contact
//   clips the polyhedron's incident face to the triangle (the triangle's
//   face the reference) or the triangle to the polyhedron's face (its face
//   the reference), Sutherland–Hodgman, one point per quarter of the patch
//   (detail/clipping.hpp).
//
// One-sided. A mesh is a surface seen from its front (the side its
// triangles turn counter-clockwise on). A triangle whose plane has the
// shape's origin (its pose's position) behind it gives no contact: a shape
// that has sunk more than halfway through is let through rather than
// pushed out of the back, which a thin wall seen from behind would do
// (Jolt's EBackFaceMode::IgnoreBackFaces). A contact normal that points
// behind the triangle's plane is treated as an internal feature's (below):
// a triangle only ever pushes towards its front.
//
// No snagging on internal edges. A flat mesh made of many triangles has
// seams that a single face would not: a box sliding over it finds, at the
// triangle it slides onto, an edge (or a vertex) whose separating axis is
// horizontal and is stopped as if by a step — "ghost" or "internal edge"
// collisions. The mesh marks each edge active or internal when it is built
// (triangle_mesh.hpp); here a contact whose feature on the triangle is an
// internal edge, or a vertex neither of whose edges in this triangle is
// active, takes the triangle's face normal instead, and its depth and
// points are recomputed along it (a face contact; for a shape that is only
// near the edge and not over the triangle that yields nothing, and the
// neighbour gives the contact). This is what Jolt Physics does with its
// active edges (ActiveEdges::FixNormal) and Bullet with
// btAdjustInternalEdgeContacts; written here from their descriptions.
//
// Feature ids: bits 8–31 the triangle's index (cut to 24 bits), bits 0–7
// the contact within the triangle: bits 5–6 the kind (0 the triangle's face
// as the reference, 1 the shape's face as the reference, 2 edge against
// edge, 3 closest points of a sphere or capsule core), bits 2–4 the
// triangle's feature (a triangle_region: 0–2 corners a, b, c, 3–5 edges ab,
// bc, ca, 6 the face), bits 0–1 the quarter of a clipped patch or a
// capsule's segment end. Merged manifolds keep each point's id.
//
// `ray_cast(ray, mesh, pose, max_fraction)`: the nearest hit of the front of
// any triangle (ray_cast_triangle, Möller–Trumbore), walking the tree
// nearer boxes first and skipping boxes beyond the nearest hit so far. The
// back of a triangle is not hit (one-sided, as the contacts). Feature: the
// triangle's index; on a tie (a ray through a shared edge) the lower index.
//
// Nothing allocates per query or per triangle, except for a hull of more
// than 64 vertices or faces (its vertices and planes carried into the
// working frame; scratch_buffer).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <span>
#include <utility>

#include "../math/ray.hpp"
#include "../math/transform.hpp"
#include "../shapes/box.hpp"
#include "../shapes/capsule.hpp"
#include "../shapes/convex_hull.hpp"
#include "../shapes/sphere.hpp"
#include "../shapes/heightfield.hpp"
#include "../shapes/triangle_mesh.hpp"
#include "analytic.hpp"
#include "detail/clipping.hpp"
#include "detail/manifold_merger.hpp"
#include "hull_hull.hpp"
#include "manifold.hpp"
#include "ray_cast.hpp"
#include "tolerances.hpp"
#include "triangle.hpp"

namespace impulse::narrowphase {

namespace detail {

/// The kinds of contact in bits 5–6 of a mesh feature id.
enum class mesh_contact : std::uint32_t { triangle_face = 0, shape_face = 1, edges = 2, closest = 3 };

constexpr std::uint32_t mesh_feature(std::uint32_t triangle, mesh_contact kind, triangle_region region,
                                     std::uint32_t slot) noexcept {
  return ((triangle & 0xffffffu) << 8) | (std::uint32_t(kind) << 5) | (std::uint32_t(region) << 2) | (slot & 3u);
}

/// One triangle of a mesh as a convex shape, in the mesh's frame: the
/// support and vertices that GJK, EPA and time_of_impact ask of a shape,
/// for the sweeps of continuous collision against a mesh.
template <scalar_type T>
struct convex_triangle {
  std::array<vec3<T>, 3> v;

  [[nodiscard]] vec3<T> support(const vec3<T>& d) const noexcept {
    const T a = dot(v[0], d), b = dot(v[1], d), c = dot(v[2], d);
    return a >= b ? (a >= c ? v[0] : v[2]) : (b >= c ? v[1] : v[2]);
  }
  [[nodiscard]] std::span<const vec3<T>> vertices() const noexcept { return v; }
};

/// A triangle in the working frame: its corners, unit front normal, which
/// of its edges are active (triangle_mesh::edge_ab …) and its index.
template <scalar_type T>
struct mesh_triangle {
  std::array<vec3<T>, 3> v;
  vec3<T> normal;
  std::uint8_t active;
  std::uint32_t index;
};

/// Whether a contact on this feature of the triangle keeps its own normal:
/// the face, an active edge, or a corner with an active edge in this
/// triangle.
inline bool keeps_normal(triangle_region region, std::uint8_t active) noexcept {
  constexpr std::uint8_t ab = 1, bc = 2, ca = 4;
  switch (region) {
    case triangle_region::vertex_a: return (active & (ab | ca)) != 0;
    case triangle_region::vertex_b: return (active & (ab | bc)) != 0;
    case triangle_region::vertex_c: return (active & (bc | ca)) != 0;
    case triangle_region::edge_ab: return (active & ab) != 0;
    case triangle_region::edge_bc: return (active & bc) != 0;
    case triangle_region::edge_ca: return (active & ca) != 0;
    case triangle_region::face: return true;
  }
  return true;
}

/// The region of an edge k (0 ab, 1 bc, 2 ca) or of its corners.
inline triangle_region edge_region(int k) noexcept { return triangle_region(3 + k); }
inline triangle_region corner_region(int k) noexcept { return triangle_region(k % 3); }

// ---- sphere and capsule ----------------------------------------------------

/// A ball (center, radius r) against a triangle.
template <scalar_type T>
void collide_ball_triangle(const vec3<T>& center, T r, const mesh_triangle<T>& tri, T margin,
                           contact_manifold<T>& m) noexcept {
  const vec3<T>& n = tri.normal;
  const T height = dot(n, center - tri.v[0]);
  if (!(height >= T(0)) || height - r > margin) return;  // behind, or too high above the plane
  const triangle_point<T> q = closest_point_on_triangle(center, tri.v[0], tri.v[1], tri.v[2]);
  const vec3<T> d = center - q.point;
  const T distance = length(d);
  if (distance - r > margin) return;
  if (q.region == triangle_region::face || !keeps_normal(q.region, tri.active) ||
      !(distance > tolerances<T>::core_offset_fraction * r)) {
    // Along the face normal: the sphere's lowest point against the plane.
    m.normal = n;
    m.add({center - n * ((r + height) * T(0.5)), r - height,
           mesh_feature(tri.index, mesh_contact::closest, triangle_region::face, 0)});
    return;
  }
  const vec3<T> normal = d / distance;
  m.normal = normal;
  m.add({(q.point + center - normal * r) * T(0.5), r - distance, mesh_feature(tri.index, mesh_contact::closest, q.region, 0)});
}

/// A capsule (core p0 p1, radius r) against a triangle.
template <scalar_type T>
void collide_capsule_triangle(const vec3<T>& p0, const vec3<T>& p1, T r, const mesh_triangle<T>& tri, T margin,
                              contact_manifold<T>& m) noexcept {
  const vec3<T>& n = tri.normal;
  const vec3<T>& a = tri.v[0];
  const T h0 = dot(n, p0 - a), h1 = dot(n, p1 - a);
  if (!(h0 + h1 >= T(0)) || std::min(h0, h1) - r > margin) return;  // the core's middle behind, or all too high

  // The closest points of the segment and the triangle.
  T best = std::numeric_limits<T>::infinity();
  vec3<T> on_segment{}, on_triangle{};
  triangle_region region = triangle_region::face;
  const auto consider = [&](const vec3<T>& s, const vec3<T>& t, triangle_region at) {
    const T d2 = length_squared(s - t);
    if (d2 < best) best = d2, on_segment = s, on_triangle = t, region = at;
  };
  for (const vec3<T>& p : {p0, p1}) {
    const triangle_point<T> q = closest_point_on_triangle(p, tri.v[0], tri.v[1], tri.v[2]);
    consider(p, q.point, q.region);
  }
  for (int k = 0; k < 3; ++k) {
    const segment_closest<T> c = closest_points_of_segments(p0, p1, tri.v[std::size_t(k)], tri.v[std::size_t((k + 1) % 3)]);
    consider(c.on_first, c.on_second,
             c.t <= T(0) ? corner_region(k) : c.t >= T(1) ? corner_region(k + 1) : edge_region(k));
  }
  if ((h0 > T(0)) != (h1 > T(0)) && h0 != h1) {  // through the plane: through the face?
    const vec3<T> x = p0 + (p1 - p0) * (h0 / (h0 - h1));
    const triangle_point<T> q = closest_point_on_triangle(x, tri.v[0], tri.v[1], tri.v[2]);
    if (q.region == triangle_region::face) consider(x, x, triangle_region::face);
  }
  const T distance = std::sqrt(best);
  if (distance - r > margin) return;

  const vec3<T> normal = distance > tolerances<T>::core_offset_fraction * r ? (on_segment - on_triangle) / distance : n;
  if (region != triangle_region::face && keeps_normal(region, tri.active) &&
      distance > tolerances<T>::core_offset_fraction * r && dot(normal, n) >= T(0)) {
    m.normal = normal;
    m.add({(on_triangle + on_segment - normal * r) * T(0.5), r - distance,
           mesh_feature(tri.index, mesh_contact::closest, region, 0)});
    return;
  }
  // Along the face normal: the segment clipped to the triangle's prism (its
  // side planes pushed out by 1e-4 of the radius, so that a core standing
  // exactly on an edge or a corner is not clipped away by rounding on both
  // sides of it), each end within reach.
  T t0 = T(0), t1 = T(1);
  const vec3<T> d = p1 - p0;
  const T slack = tolerances<T>::prism_slack_fraction * r;
  for (int k = 0; k < 3; ++k) {
    const vec3<T>& p = tri.v[std::size_t(k)];
    const vec3<T> w = normalize_or(cross(tri.v[std::size_t((k + 1) % 3)] - p, n), n);  // out across the edge
    const T at0 = dot(w, p0 - p) - slack, slope = dot(w, d);
    if (slope == T(0)) {
      if (at0 > T(0)) return;
      continue;
    }
    const T t = -at0 / slope;
    if (slope > T(0)) t1 = std::min(t1, t);
    else t0 = std::max(t0, t);
  }
  if (!(t0 <= t1)) return;
  m.normal = n;
  const T ends[2] = {t0, t1};
  for (std::uint32_t e = 0; e < 2; ++e) {
    if (e == 1 && !(t1 > t0)) break;  // one point where the kept part is a point
    const vec3<T> x = p0 + d * ends[e];
    const T height = dot(n, x - a);
    if (height - r > margin) continue;
    m.add({x - n * ((r + height) * T(0.5)), r - height,
           mesh_feature(tri.index, mesh_contact::triangle_face, triangle_region::face, e)});
  }
}

// ---- box and hull ------------------------------------------------------------

/// A polyhedron (the interface of convex_hull) carried into the working
/// frame: its vertices and face planes there.
template <class Poly, scalar_type T>
struct posed_polyhedron {
  using face_plane = typename convex_hull<T>::face_plane;
  const Poly& poly;
  const vec3<T>* vertices;
  std::size_t vertex_count;
  const face_plane* planes;
  T least_half_extent;
  /// A point inside it (the middle of its bounds), for the one-sided test:
  /// a hull's origin may lie outside it.
  vec3<T> inside;
};

/// Which of the triangle's corners lie farthest along u (within
/// `tolerance`): a corner, an edge or the face.
template <scalar_type T>
triangle_region supporting_feature(const mesh_triangle<T>& tri, const vec3<T>& u, T tolerance) noexcept {
  const T d[3] = {dot(u, tri.v[0]), dot(u, tri.v[1]), dot(u, tri.v[2])};
  const T top = std::max(d[0], std::max(d[1], d[2]));
  const bool at[3] = {d[0] >= top - tolerance, d[1] >= top - tolerance, d[2] >= top - tolerance};
  if (at[0] && at[1] && at[2]) return triangle_region::face;
  if (at[0] && at[1]) return triangle_region::edge_ab;
  if (at[1] && at[2]) return triangle_region::edge_bc;
  if (at[2] && at[0]) return triangle_region::edge_ca;
  return at[0] ? triangle_region::vertex_a : at[1] ? triangle_region::vertex_b : triangle_region::vertex_c;
}

/// The separating axis test and the contact of a polyhedron and a triangle
/// (see the top of the file).
template <class Poly, scalar_type T>
void collide_polyhedron_triangle(const posed_polyhedron<Poly, T>& P, const mesh_triangle<T>& tri, T margin,
                                 contact_manifold<T>& m) {
  const vec3<T>& n = tri.normal;
  const vec3<T>& a = tri.v[0];
  if (dot(n, a - P.inside) > T(0)) return;  // the shape's middle is behind the triangle
  const vec3<T>* V = P.vertices;
  const std::size_t vertex_count = P.vertex_count;

  // The triangle's face: the polyhedron's lowest vertex above its plane.
  T face_t = std::numeric_limits<T>::infinity();
  std::uint32_t deepest = 0;
  for (std::uint32_t i = 0; i < vertex_count; ++i) {
    const T s = dot(n, V[i] - a);
    if (s < face_t) face_t = s, deepest = i;
  }
  if (face_t > margin) return;
  // The polyhedron's faces: the triangle's lowest corner above each.
  T face_p = -std::numeric_limits<T>::infinity();
  std::size_t face_p_index = 0;
  for (std::size_t f = 0; f < P.poly.face_count(); ++f) {
    const T s = std::min(P.planes[f].distance(tri.v[0]), std::min(P.planes[f].distance(tri.v[1]), P.planes[f].distance(tri.v[2])));
    if (s > margin) return;
    if (s > face_p) face_p = s, face_p_index = f;
  }
  // Edge pairs, both orientations, exact projections.
  struct edge_axis {
    T separation = -std::numeric_limits<T>::infinity();
    int k = 0;
    std::size_t j = 0;
    vec3<T> normal{};  // from the triangle into the polyhedron
  } edge;
  const std::span<const hull_edge> edges = P.poly.edges();
  for (int k = 0; k < 3; ++k) {
    const vec3<T>& p = tri.v[std::size_t(k)];
    const vec3<T> et = tri.v[std::size_t((k + 1) % 3)] - p;
    const vec3<T>& opposite = tri.v[std::size_t((k + 2) % 3)];
    const vec3<T> out_t = cross(et, n);  // out of the triangle across this edge, in its plane
    for (std::size_t j = 0; j < edges.size(); ++j) {
      const hull_edge& e = edges[j];
      const vec3<T> ep = V[e.b] - V[e.a];
      vec3<T> L = cross(et, ep);
      const T l2 = length_squared(L);
      // Within about 0.06° of parallel: the axis is a face's, tested above.
      if (!(l2 > tolerances<T>::parallel_edge_sine_squared * length_squared(et) * length_squared(ep))) continue;
      L /= std::sqrt(l2);
      const T tp = dot(L, p), to = dot(L, opposite);
      const T t_lo = std::min(tp, to), t_hi = std::max(tp, to);
      T p_lo = std::numeric_limits<T>::infinity(), p_hi = -p_lo;
      for (std::size_t i = 0; i < vertex_count; ++i) {
        const T x = dot(L, V[i]);
        p_lo = std::min(p_lo, x);
        p_hi = std::max(p_hi, x);
      }
      const T along = p_lo - t_hi, against = t_lo - p_hi;  // separations pushing the polyhedron along ±L
      if (std::max(along, against) > margin) return;
      // A candidate normal only where both edges support their shapes:
      // the polyhedron's edge faces −N (between its two faces' normals),
      // the triangle's edge faces N (outward across it, or along ±n).
      const vec3<T> n1 = P.planes[e.face_ab].normal, n2 = P.planes[e.face_ba].normal;
      const vec3<T> N = dot(L, n1 + n2) > T(0) ? -L : L;
      if (dot(cross(n1, -N), cross(-N, n2)) < -tolerances<T>::edge_support_slack) continue;
      if (dot(N, out_t) < -tolerances<T>::edge_support_slack * length(out_t)) continue;
      const T s = dot(N, L) > T(0) ? along : against;
      if (s > edge.separation) edge = {s, k, j, N};
    }
  }

  const T tolerance = tolerances<T>::face_preference_of_size * P.least_half_extent;
  const auto clearly_better = [&](T s, T than) {
    return s > than + tolerances<T>::face_preference_of_depth * std::abs(than) + tolerance;
  };
  // Corners within this of each other along a normal are one feature.
  const T feature_tolerance =
      tolerances<T>::feature_fraction *
      std::max(length(tri.v[1] - tri.v[0]), std::max(length(tri.v[2] - tri.v[1]), length(tri.v[0] - tri.v[2])));

  // The triangle's face as the reference: the polyhedron's incident face
  // (of the faces at its deepest vertex, the most opposed to n) clipped to
  // the triangle's side planes.
  const auto triangle_face_contact = [&] {
    std::size_t k = 0;
    T most_opposed = std::numeric_limits<T>::infinity();
    for (std::size_t f = 0; f < P.poly.face_count(); ++f) {
      const std::span<const std::uint32_t> polygon = P.poly.face(f);
      if (std::find(polygon.begin(), polygon.end(), deepest) == polygon.end()) continue;
      const T c = dot(n, P.planes[f].normal);
      if (c < most_opposed) most_opposed = c, k = f;
    }
    const std::span<const std::uint32_t> incident = P.poly.face(k);
    const std::size_t room = incident.size() + 4;
    scratch_buffer<vec3<T>, 64> first(room), second(room);
    vec3<T>* polygon = first.data();
    vec3<T>* scratch = second.data();
    int count = int(incident.size());
    for (std::size_t c = 0; c < incident.size(); ++c) polygon[c] = V[incident[c]];
    for (std::size_t c = 0; c < 3 && count > 0; ++c) {
      const vec3<T>& p = tri.v[c];
      const vec3<T> w = cross(tri.v[(c + 1) % 3] - p, n);  // out of the triangle across its edge
      count = clip(polygon, count, w, dot(w, p), scratch);
      std::swap(polygon, scratch);
    }
    scratch_buffer<patch_point<T>, 64> below(std::size_t(count) + 1);
    int found = 0;
    for (int c = 0; c < count; ++c) {
      const T separation = dot(n, polygon[c] - a);
      if (separation <= margin) below[std::size_t(found++)] = {polygon[c], separation};
    }
    if (found == 0) return false;
    const vec3<T> u = normalize(tri.v[1] - tri.v[0]);
    int chosen[4];
    choose_by_quarter(below.data(), found, u, cross(n, u), chosen);
    m.normal = n;
    for (int q = 0; q < 4; ++q) {
      if (chosen[q] < 0) continue;
      const patch_point<T>& c = below[std::size_t(chosen[q])];
      m.add({c.x - n * (c.separation * T(0.5)), -c.separation,
             mesh_feature(tri.index, mesh_contact::triangle_face, triangle_region::face, std::uint32_t(q))});
    }
    return true;
  };
  // The polyhedron's face as the reference: the triangle clipped to it.
  const auto shape_face_contact = [&] {
    const typename posed_polyhedron<Poly, T>::face_plane& plane = P.planes[face_p_index];
    const vec3<T> N = -plane.normal;
    const triangle_region region = supporting_feature(tri, N, feature_tolerance);
    if (!keeps_normal(region, tri.active) || dot(N, n) < T(0)) return false;
    const std::span<const std::uint32_t> face = P.poly.face(face_p_index);
    const std::size_t room = face.size() + 4;
    scratch_buffer<vec3<T>, 64> first(room), second(room);
    vec3<T>* polygon = first.data();
    vec3<T>* scratch = second.data();
    int count = 3;
    for (std::size_t c = 0; c < 3; ++c) polygon[c] = tri.v[c];
    for (std::size_t c = 0; c < face.size() && count > 0; ++c) {
      const vec3<T>& p = V[face[c]];
      const vec3<T> w = cross(V[face[(c + 1) % face.size()]] - p, plane.normal);
      count = clip(polygon, count, w, dot(w, p), scratch);
      std::swap(polygon, scratch);
    }
    scratch_buffer<patch_point<T>, 64> below(std::size_t(count) + 1);
    int found = 0;
    for (int c = 0; c < count; ++c) {
      const T separation = plane.distance(polygon[c]);
      if (separation <= margin) below[std::size_t(found++)] = {polygon[c], separation};
    }
    if (found == 0) return false;
    const vec3<T> u = normalize(V[face[1]] - V[face[0]]);
    int chosen[4];
    choose_by_quarter(below.data(), found, u, cross(plane.normal, u), chosen);
    m.normal = N;
    for (int q = 0; q < 4; ++q) {
      if (chosen[q] < 0) continue;
      const patch_point<T>& c = below[std::size_t(chosen[q])];
      m.add({c.x - plane.normal * (c.separation * T(0.5)), -c.separation,
             mesh_feature(tri.index, mesh_contact::shape_face, region, std::uint32_t(q))});
    }
    return true;
  };
  const auto edge_contact = [&] {
    const triangle_region region = edge_region(edge.k);
    if (!keeps_normal(region, tri.active) || dot(edge.normal, n) < T(0)) return false;
    const hull_edge& e = edges[edge.j];
    const segment_closest<T> c = closest_points_of_segments(tri.v[std::size_t(edge.k)], tri.v[std::size_t((edge.k + 1) % 3)],
                                                            V[e.a], V[e.b]);
    m.normal = edge.normal;
    m.add({(c.on_first + c.on_second) * T(0.5), -dot(c.on_second - c.on_first, edge.normal),
           mesh_feature(tri.index, mesh_contact::edges, region, 0)});
    return true;
  };

  // The preferred axis first, then the others from the least penetrating;
  // an axis at an internal feature (or pointing behind the triangle) gives
  // way to the triangle's face.
  enum axis { triangle_face, shape_face, edge_pair };
  const bool have_edge = edge.separation > -std::numeric_limits<T>::infinity();
  axis preferred = clearly_better(face_p, face_t) ? shape_face : triangle_face;
  const T preferred_separation = preferred == shape_face ? face_p : face_t;
  if (have_edge && clearly_better(edge.separation, preferred_separation)) preferred = edge_pair;
  const auto attempt = [&](axis x) {
    switch (x) {
      case triangle_face: return triangle_face_contact();
      case shape_face: return shape_face_contact();
      case edge_pair: return have_edge && edge_contact();
    }
    return false;
  };
  if (attempt(preferred)) return;
  if (preferred != triangle_face && triangle_face_contact()) return;
  // The triangle's face clipped to nothing (the polyhedron is beside it,
  // not over it): the other axes, least penetrating first.
  const bool edge_first = have_edge && edge.separation >= face_p;
  for (const axis x : {edge_first ? edge_pair : shape_face, edge_first ? shape_face : edge_pair})
    if (x != preferred && attempt(x)) return;
}

// ---- the walk over the triangles ---------------------------------------------

/// The working frame: the mesh's axes, the origin at the shape's position.
template <scalar_type T>
struct mesh_frame {
  vec3<T> shape_in_mesh;  ///< the shape's position in the mesh's frame
  quat<T> shape_rotation; ///< the shape's axes in the working frame
  quat<T> mesh_rotation;  ///< the working frame's axes in world
  vec3<T> shape_position; ///< world

  mesh_frame(const transform<T>& pose_mesh, const transform<T>& pose_shape) noexcept
      : shape_in_mesh(inverse_apply(pose_mesh, pose_shape.position)),
        shape_rotation(conjugate(pose_mesh.rotation) * pose_shape.rotation),
        mesh_rotation(pose_mesh.rotation),
        shape_position(pose_shape.position) {}

  [[nodiscard]] vec3<T> to_world(const vec3<T>& x) const noexcept { return shape_position + rotate(mesh_rotation, x); }
};

/// Calls test(triangle, manifold) for every triangle near `local_box` (the
/// shape's box in the working frame, grown by the margin), then merges and
/// writes the manifolds.
template <scalar_type T, class Mesh, class Test>
std::size_t collide_mesh(const Mesh& mesh, const mesh_frame<T>& frame, const aabb<T>& local_box, T weld,
                         bool flip, std::span<contact_manifold<T>> out, Test&& test) {
  manifold_merger<T> merger(weld);
  const aabb<T> query{local_box.lower + frame.shape_in_mesh, local_box.upper + frame.shape_in_mesh};
  mesh.for_each_overlapping(query, [&](std::size_t t) {
    mesh_triangle<T> tri;
    mesh.triangle(t, tri.v[0], tri.v[1], tri.v[2]);
    // The normal from the mesh's own coordinates, before the shift, so that
    // every triangle of a flat mesh has the same one to the last bit.
    tri.normal = normalize_or(cross(tri.v[1] - tri.v[0], tri.v[2] - tri.v[0]), vec3<T>::unit_y());
    for (vec3<T>& v : tri.v) v -= frame.shape_in_mesh;
    tri.active = mesh.active_edges(t);
    tri.index = std::uint32_t(t);
    contact_manifold<T> m;
    test(tri, m);
    merger.add(m);
  });
  return merger.write(out, frame.mesh_rotation, [&](const vec3<T>& x) { return frame.to_world(x); }, flip);
}

template <scalar_type T, class Mesh>
std::size_t collide_mesh_shape(const Mesh& mesh, const transform<T>& pose_mesh, const sphere<T>& s,
                               const transform<T>& pose_shape, T margin, std::span<contact_manifold<T>> out, bool flip) {
  const mesh_frame<T> frame(pose_mesh, pose_shape);
  const aabb<T> box = aabb<T>::from_center_half_extents({}, vec3<T>::splat(s.radius + margin));
  return collide_mesh(mesh, frame, box, tolerances<T>::weld_fraction * s.radius, flip, out,
                      [&](const mesh_triangle<T>& tri, contact_manifold<T>& m) {
                        collide_ball_triangle(vec3<T>{}, s.radius, tri, margin, m);
                      });
}

template <scalar_type T, class Mesh>
std::size_t collide_mesh_shape(const Mesh& mesh, const transform<T>& pose_mesh, const capsule<T>& c,
                               const transform<T>& pose_shape, T margin, std::span<contact_manifold<T>> out, bool flip) {
  const mesh_frame<T> frame(pose_mesh, pose_shape);
  const vec3<T> half = rotate(frame.shape_rotation, vec3<T>{T(0), c.half_height, T(0)});
  const aabb<T> box = aabb<T>::from_center_half_extents({}, abs(half) + vec3<T>::splat(c.radius + margin));
  return collide_mesh(mesh, frame, box, tolerances<T>::weld_fraction * c.radius, flip, out,
                      [&](const mesh_triangle<T>& tri, contact_manifold<T>& m) {
                        collide_capsule_triangle(-half, half, c.radius, tri, margin, m);
                      });
}

template <class Poly, scalar_type T, class Mesh>
std::size_t collide_mesh_polyhedron(const Mesh& mesh, const transform<T>& pose_mesh, const Poly& poly,
                                    const aabb<T>& local_bounds, const transform<T>& pose_shape, T margin,
                                    std::span<contact_manifold<T>> out, bool flip) {
  using face_plane = typename convex_hull<T>::face_plane;
  const mesh_frame<T> frame(pose_mesh, pose_shape);
  const std::span<const vec3<T>> local = poly.vertices();
  scratch_buffer<vec3<T>, 64> vertices(local.size());
  for (std::size_t i = 0; i < local.size(); ++i) vertices[i] = rotate(frame.shape_rotation, local[i]);
  scratch_buffer<face_plane, 64> planes(poly.face_count());
  for (std::size_t f = 0; f < poly.face_count(); ++f)
    planes[f] = {rotate(frame.shape_rotation, poly.plane(f).normal), poly.plane(f).offset};  // the origins coincide
  const T least = least_half_extent(poly);
  const posed_polyhedron<Poly, T> posed{poly,  vertices.data(), local.size(), planes.data(),
                                        least, rotate(frame.shape_rotation, center(local_bounds))};
  const aabb<T> box = expand(transform_aabb(local_bounds, transform<T>{{}, frame.shape_rotation}), margin);
  return collide_mesh(mesh, frame, box, tolerances<T>::weld_fraction * least, flip, out,
                      [&](const mesh_triangle<T>& tri, contact_manifold<T>& m) {
                        collide_polyhedron_triangle(posed, tri, margin, m);
                      });
}

template <scalar_type T, class Mesh>
std::size_t collide_mesh_shape(const Mesh& mesh, const transform<T>& pose_mesh, const box<T>& b,
                               const transform<T>& pose_shape, T margin, std::span<contact_manifold<T>> out, bool flip) {
  return collide_mesh_polyhedron(mesh, pose_mesh, box_polyhedron<T>(b), b.local_aabb(), pose_shape, margin, out, flip);
}

template <scalar_type T, class Mesh>
std::size_t collide_mesh_shape(const Mesh& mesh, const transform<T>& pose_mesh, const convex_hull<T>& h,
                               const transform<T>& pose_shape, T margin, std::span<contact_manifold<T>> out, bool flip) {
  return collide_mesh_polyhedron(mesh, pose_mesh, h, h.local_aabb(), pose_shape, margin, out, flip);
}

template <class S>
inline constexpr bool mesh_pairs_with = false;
template <scalar_type T>
inline constexpr bool mesh_pairs_with<sphere<T>> = true;
template <scalar_type T>
inline constexpr bool mesh_pairs_with<capsule<T>> = true;
template <scalar_type T>
inline constexpr bool mesh_pairs_with<box<T>> = true;
template <scalar_type T>
inline constexpr bool mesh_pairs_with<convex_hull<T>> = true;

/// The static shapes made of triangles: a triangle mesh, and a heightfield
/// (shapes/heightfield.hpp), whose cells' triangles the same code tests,
/// found from its grid rather than a tree.
template <class M>
inline constexpr bool triangle_source = false;
template <scalar_type T>
inline constexpr bool triangle_source<triangle_mesh<T>> = true;
template <scalar_type T>
inline constexpr bool triangle_source<heightfield<T>> = true;

}  // namespace detail

/// The contact manifolds of a static mesh (or heightfield) and a sphere,
/// capsule, box or convex hull: at most out.size(), deepest first; returns
/// how many it wrote. Normals from the mesh into the shape. A shape whose
/// pose is not finite touches nothing (0).
template <scalar_type T, template <class> class Mesh, class S>
  requires detail::triangle_source<Mesh<T>> && detail::mesh_pairs_with<S>
std::size_t collide(const Mesh<T>& mesh, const transform<T>& pose_mesh, const S& shape,
                    const transform<T>& pose_shape, T margin, std::span<contact_manifold<T>> out) {
  return detail::collide_mesh_shape(mesh, pose_mesh, shape, pose_shape, margin, out, false);
}

/// The same with the shape first: normals from the shape into the mesh.
template <scalar_type T, template <class> class Mesh, class S>
  requires detail::triangle_source<Mesh<T>> && detail::mesh_pairs_with<S>
std::size_t collide(const S& shape, const transform<T>& pose_shape, const Mesh<T>& mesh,
                    const transform<T>& pose_mesh, T margin, std::span<contact_manifold<T>> out) {
  return detail::collide_mesh_shape(mesh, pose_mesh, shape, pose_shape, margin, out, true);
}

/// The nearest hit of the ray on the front of any of the mesh's (or the
/// heightfield's) triangles (see the top of the file). Feature: the
/// triangle's index (a heightfield's: cell · 2 + half).
template <scalar_type T, template <class> class Mesh>
  requires detail::triangle_source<Mesh<T>>
ray_hit<T> ray_cast(const ray<T>& r, const Mesh<T>& mesh, const transform<T>& pose, T max_fraction = T(1)) noexcept {
  if (!is_finite(r.origin) || !is_finite(r.translation) || !(max_fraction >= T(0))) return {};
  const ray<T> local{inverse_apply(pose, r.origin), inverse_apply_direction(pose, r.translation)};
  ray_hit<T> best;
  mesh.for_each_along_ray(local.origin, local.translation, max_fraction, [&](std::size_t t, T clip) {
    vec3<T> a, b, c;
    mesh.triangle(t, a, b, c);
    // Cast to the full length, not the clip, so that each triangle's hit
    // is the same whatever was found before it (ties go to the lower index).
    const ray_hit<T> h = ray_cast_triangle(local, a, b, c, max_fraction);
    if (!h || h.feature != 0) return clip;  // a miss, or the back
    if (!best || h.fraction < best.fraction || (h.fraction == best.fraction && t < best.feature)) {
      best = h;
      best.feature = std::uint32_t(t);
    }
    return best.fraction;
  });
  if (best) {
    best.point = apply(pose, best.point);
    best.normal = apply_direction(pose, best.normal);
  }
  return best;
}

}  // namespace impulse::narrowphase
