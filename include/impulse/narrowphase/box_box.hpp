// impulse/narrowphase/box_box.hpp — two boxes: the separating axis test,
// then the incident face clipped against the reference face.
//
// Two convex polyhedra are apart if and only if some axis separates their
// projections; for two boxes the candidates are the three face normals of
// each and the nine cross products of an edge of one with an edge of the
// other (Gottschalk et al., "OBBTree", 1996; Ericson §4.4.1). Any axis
// farther apart than the margin ends the test at once. Otherwise the axis
// of least penetration says how they touch:
//
// - a face normal: the box it belongs to gives the reference face, the
//   other box the incident face (its face most opposed to the reference
//   normal). The incident face is clipped against the four side planes of
//   the reference face (Sutherland–Hodgman), and the clipped points below
//   the reference face plus the margin, up to eight, are the contact
//   patch. Four are kept, one per quarter of the patch (split along the
//   reference face's axes through the patch's center): the farthest from
//   the center, so that the four span the patch, except that the deepest
//   point of all is kept in its quarter;
// - an edge pair: one contact, midway between the closest points of the
//   two edges.
//
// Faces are preferred: an edge pair wins only if its separation exceeds
// the best face's by 5 % of the latter's size plus 1 % of the smaller
// box's least half extent, and B's face wins over A's by the same rule.
// Without the bias, two faces resting on each other would hop between
// near-equal axes from step to step, and their contact points and ids with
// them (Catto, "Robust Contact Creation for Physics Simulations", GDC 2013,
// biases the choice the same way).
//
// All of it is done in A's frame, so that two boxes far from the origin
// lose no more precision than their distance from each other costs.
//
// Feature ids. A face contact: bit 13 set when the reference face is B's,
// bits 10–12 the reference face (axis · 2, + 1 for the positive side), bits
// 7–9 the incident face, and bits 0–1 the quarter of the patch. The quarter
// and not the clipping history: when a box rests on a box of its size,
// their corners jitter across each other's edges from step to step, and
// each corner of the patch is now an incident corner, now the crossing of
// two edges, now a reference corner; its quarter stays the same. An edge
// contact: bit 15 set, then A's edge and B's edge (axis · 4 + the two
// sides), 4 bits each. While the same features touch, the ids repeat.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>

#include "../math/transform.hpp"
#include "../shapes/box.hpp"
#include "analytic.hpp"
#include "detail/clipping.hpp"
#include "manifold.hpp"
#include "tolerances.hpp"

namespace impulse::narrowphase {

namespace detail {

template <scalar_type T>
struct oriented_box {
  vec3<T> center;
  vec3<T> axis[3];  ///< unit
  vec3<T> half;
};

/// Half the length of the box's projection on the unit direction L.
template <scalar_type T>
T projected_radius(const oriented_box<T>& b, const vec3<T>& L) noexcept {
  return b.half.x * std::abs(dot(L, b.axis[0])) + b.half.y * std::abs(dot(L, b.axis[1])) +
         b.half.z * std::abs(dot(L, b.axis[2]));
}

}  // namespace detail

template <scalar_type T>
contact_manifold<T> collide(const box<T>& a, const transform<T>& pose_a, const box<T>& b, const transform<T>& pose_b,
                            T margin = T(0)) noexcept {
  using detail::oriented_box;
  const transform<T> relative = inverse_mul(pose_a, pose_b);  // B in A's frame
  const oriented_box<T> A{{}, {vec3<T>::unit_x(), vec3<T>::unit_y(), vec3<T>::unit_z()}, a.half_extents};
  const oriented_box<T> B{relative.position,
                          {rotate(relative.rotation, vec3<T>::unit_x()), rotate(relative.rotation, vec3<T>::unit_y()),
                           rotate(relative.rotation, vec3<T>::unit_z())},
                          b.half_extents};
  const vec3<T>& t = B.center;
  contact_manifold<T> m;

  // The separating axis test: the least penetrating (most separated) axis
  // of each kind.
  struct best {
    T separation = -std::numeric_limits<T>::infinity();
    int index = -1;
  } face_a, face_b, edge;
  for (int i = 0; i < 3; ++i) {
    const T s = std::abs(t[i]) - (A.half[i] + detail::projected_radius(B, A.axis[i]));
    if (s > margin) return m;
    if (s > face_a.separation) face_a = {s, i};
  }
  for (int j = 0; j < 3; ++j) {
    const T s = std::abs(dot(t, B.axis[j])) - (detail::projected_radius(A, B.axis[j]) + B.half[j]);
    if (s > margin) return m;
    if (s > face_b.separation) face_b = {s, j};
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const vec3<T> L = cross(A.axis[i], B.axis[j]);
      // Edges within about 0.06° of parallel: their axis is a face axis
      // already tested, and its direction is rounding noise.
      const T l2 = length_squared(L);
      if (l2 < tolerances<T>::parallel_edge_sine_squared) continue;
      const vec3<T> axis = L / std::sqrt(l2);
      const T s = std::abs(dot(t, axis)) - (detail::projected_radius(A, axis) + detail::projected_radius(B, axis));
      if (s > margin) return m;
      if (s > edge.separation) edge = {s, 3 * i + j};
    }
  }
  const T tolerance =
      tolerances<T>::face_preference_of_size * std::min(min_component(a.half_extents), min_component(b.half_extents));
  const auto clearly_better = [&](T s, T than) {
    return s > than + tolerances<T>::face_preference_of_depth * std::abs(than) + tolerance;
  };
  const bool reference_is_b = clearly_better(face_b.separation, face_a.separation);
  const T best_face = reference_is_b ? face_b.separation : face_a.separation;

  if (edge.index >= 0 && clearly_better(edge.separation, best_face)) {
    // Edge against edge: the two edges that realise the axis, one point
    // midway between their closest points.
    const int i = edge.index / 3, j = edge.index % 3;
    vec3<T> L = normalize(cross(A.axis[i], B.axis[j]));
    if (dot(L, t) < T(0)) L = -L;  // from A towards B
    vec3<T> on_a{}, on_b = t;
    std::uint32_t sides_a = 0, sides_b = 0;
    for (int k = 0, bit = 0; k < 3; ++k) {
      if (k == i) continue;
      const bool positive = dot(L, A.axis[k]) > T(0);
      on_a += A.axis[k] * (positive ? A.half[k] : -A.half[k]);
      sides_a |= std::uint32_t(positive) << bit++;
    }
    for (int k = 0, bit = 0; k < 3; ++k) {
      if (k == j) continue;
      const bool positive = dot(L, B.axis[k]) < T(0);  // B's edge faces A: support along -L
      on_b += B.axis[k] * (positive ? B.half[k] : -B.half[k]);
      sides_b |= std::uint32_t(positive) << bit++;
    }
    const vec3<T> ea = A.axis[i] * A.half[i], eb = B.axis[j] * B.half[j];
    const auto closest = detail::closest_points_of_segments(on_a - ea, on_a + ea, on_b - eb, on_b + eb);
    const T depth = -dot(closest.on_second - closest.on_first, L);
    m.normal = apply_direction(pose_a, L);
    const std::uint32_t feature = (1u << 15) | ((std::uint32_t(i) * 4 + sides_a) << 4) | (std::uint32_t(j) * 4 + sides_b);
    m.add({apply(pose_a, (closest.on_first + closest.on_second) * T(0.5)), depth, feature});
    return m;
  }

  // Face against face: the reference face is the best face's, on the side
  // facing the other box.
  const oriented_box<T>& ref = reference_is_b ? B : A;
  const oriented_box<T>& inc = reference_is_b ? A : B;
  const int r = reference_is_b ? face_b.index : face_a.index;
  const vec3<T> towards = inc.center - ref.center;
  const bool ref_positive = dot(towards, ref.axis[r]) >= T(0);
  const vec3<T> n = ref_positive ? ref.axis[r] : -ref.axis[r];  // out of ref, towards inc
  const vec3<T> face_center = ref.center + n * ref.half[r];
  // The incident face: the one whose normal is most opposed to n.
  int k = 0;
  for (int c = 1; c < 3; ++c)
    if (std::abs(dot(n, inc.axis[c])) > std::abs(dot(n, inc.axis[k]))) k = c;
  const bool inc_positive = dot(n, inc.axis[k]) < T(0);
  const vec3<T> inc_center = inc.center + inc.axis[k] * (inc_positive ? inc.half[k] : -inc.half[k]);
  const vec3<T> P = inc.axis[(k + 1) % 3] * inc.half[(k + 1) % 3], Q = inc.axis[(k + 2) % 3] * inc.half[(k + 2) % 3];
  vec3<T> polygon[8] = {inc_center + P + Q, inc_center - P + Q, inc_center - P - Q, inc_center + P - Q};
  vec3<T> scratch[8];
  int count = 4;
  // The side planes: ±u and ±v of the reference box, through its faces.
  const int u = (r + 1) % 3, v = (r + 2) % 3;
  const struct {
    vec3<T> w;
    T limit;
  } sides[4] = {{ref.axis[u], dot(ref.axis[u], ref.center) + ref.half[u]},
                {-ref.axis[u], -dot(ref.axis[u], ref.center) + ref.half[u]},
                {ref.axis[v], dot(ref.axis[v], ref.center) + ref.half[v]},
                {-ref.axis[v], -dot(ref.axis[v], ref.center) + ref.half[v]}};
  for (int side = 0; side < 4 && count > 0; ++side) {
    count = detail::clip(polygon, count, sides[side].w, sides[side].limit, scratch);
    std::copy(scratch, scratch + count, polygon);
  }
  // The points below the reference face (plus the margin), one kept per
  // quarter of the patch they make.
  detail::patch_point<T> below[8];
  int found = 0;
  for (int c = 0; c < count; ++c) {
    const T separation = dot(n, polygon[c] - face_center);
    if (separation <= margin) below[found++] = {polygon[c], separation};
  }
  if (found == 0) return m;
  int chosen[4];
  detail::choose_by_quarter(below, found, ref.axis[u], ref.axis[v], chosen);
  const std::uint32_t faces = (std::uint32_t(reference_is_b) << 13) |
                              (std::uint32_t(2 * r + int(ref_positive)) << 10) |
                              (std::uint32_t(2 * k + int(inc_positive)) << 7);
  m.normal = apply_direction(pose_a, reference_is_b ? -n : n);
  for (int q = 0; q < 4; ++q) {
    if (chosen[q] < 0) continue;
    const detail::patch_point<T>& c = below[chosen[q]];
    m.add({apply(pose_a, c.x - n * (c.separation * T(0.5))), -c.separation, faces | std::uint32_t(q)});
  }
  return m;
}

}  // namespace impulse::narrowphase
