// impulse/narrowphase/triangle.hpp — the point of a triangle closest to a
// given point, and which of its seven Voronoi regions that point is in.
//
// The regions of a triangle abc: its three vertices, its three edges and
// its face. The test walks them in order of cost (Ericson, "Real-Time
// Collision Detection", §5.1.5): a vertex region is decided by two dot
// products, an edge region by the sign of one barycentric coordinate of the
// projection (a triple product written as differences of dot products),
// and what is left is the face. The region is what a mesh contact needs to
// know: a hit on an edge or a vertex shared with a neighbouring triangle is
// a candidate for the internal-edge fix that keeps objects from snagging on
// a flat mesh.
//
// A degenerate triangle (its corners on one line, or all at one point) has
// no face: its closest point is then the nearest on its three edges, and the
// region says which edge or vertex that was.
#pragma once

#include <cstdint>

#include "../math/vec3.hpp"
#include "analytic.hpp"
#include "tolerances.hpp"

namespace impulse::narrowphase {

enum class triangle_region : std::uint8_t { vertex_a, vertex_b, vertex_c, edge_ab, edge_bc, edge_ca, face };

template <scalar_type T>
struct triangle_point {
  vec3<T> point{};
  triangle_region region = triangle_region::face;
  vec3<T> barycentric{};  ///< weights of a, b, c: point = a·x + b·y + c·z, each in [0, 1], summing to 1
};

template <scalar_type T>
triangle_point<T> closest_point_on_triangle(const vec3<T>& p, const vec3<T>& a, const vec3<T>& b,
                                            const vec3<T>& c) noexcept {
  const vec3<T> ab = b - a, ac = c - a, ap = p - a;
  const T d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= T(0) && d2 <= T(0)) return {a, triangle_region::vertex_a, {T(1), T(0), T(0)}};

  const vec3<T> bp = p - b;
  const T d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= T(0) && d4 <= d3) return {b, triangle_region::vertex_b, {T(0), T(1), T(0)}};

  const vec3<T> cp = p - c;
  const T d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= T(0) && d5 <= d6) return {c, triangle_region::vertex_c, {T(0), T(0), T(1)}};

  // The face's area (twice, squared) decides whether there is a face at all.
  const T area2 = length_squared(cross(ab, ac));
  const T scale = length_squared(ab) * length_squared(ac);
  if (!(area2 > tolerances<T>::degenerate_triangle * scale) || !(scale > T(0))) {
    // Degenerate: the nearest of the three edges.
    const auto on_edge = [&](const vec3<T>& from, const vec3<T>& to) {
      return detail::closest_point_on_segment(from, to, p);
    };
    const vec3<T> candidates[3] = {on_edge(a, b), on_edge(b, c), on_edge(c, a)};
    int best = 0;
    for (int k = 1; k < 3; ++k)
      if (length_squared(candidates[k] - p) < length_squared(candidates[best] - p)) best = k;
    const vec3<T>& q = candidates[best];
    // Its weights along that edge (the vertex regions were taken above, so
    // the point lies strictly between the edge's ends or they coincide).
    const vec3<T>& from = best == 0 ? a : best == 1 ? b : c;
    const vec3<T>& to = best == 0 ? b : best == 1 ? c : a;
    const T length2 = length_squared(to - from);
    const T t = length2 > T(0) ? dot(q - from, to - from) / length2 : T(0);
    vec3<T> weights{};
    weights[best] = T(1) - t;
    weights[(best + 1) % 3] = t;
    const triangle_region edges[3] = {triangle_region::edge_ab, triangle_region::edge_bc, triangle_region::edge_ca};
    return {q, edges[best], weights};
  }

  const T vc = d1 * d4 - d3 * d2;
  if (vc <= T(0) && d1 >= T(0) && d3 <= T(0)) {
    const T t = d1 / (d1 - d3);
    return {a + ab * t, triangle_region::edge_ab, {T(1) - t, t, T(0)}};
  }
  const T vb = d5 * d2 - d1 * d6;
  if (vb <= T(0) && d2 >= T(0) && d6 <= T(0)) {
    const T t = d2 / (d2 - d6);
    return {a + ac * t, triangle_region::edge_ca, {T(1) - t, T(0), t}};
  }
  const T va = d3 * d6 - d5 * d4;
  if (va <= T(0) && (d4 - d3) >= T(0) && (d5 - d6) >= T(0)) {
    const T t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b + (c - b) * t, triangle_region::edge_bc, {T(0), T(1) - t, t}};
  }
  const T inverse = T(1) / (va + vb + vc);
  const T v = vb * inverse, w = vc * inverse;
  return {a + ab * v + ac * w, triangle_region::face, {T(1) - v - w, v, w}};
}

}  // namespace impulse::narrowphase
