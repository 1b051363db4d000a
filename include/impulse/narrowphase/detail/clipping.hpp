// impulse/narrowphase/detail/clipping.hpp — what the face contacts of box–box
// and of the general polyhedra share: cutting the incident face down to the
// reference face (Sutherland–Hodgman), and keeping four points of the patch
// that stay the same points while the faces rest on each other.
#pragma once

#include <algorithm>
#include <cmath>

#include "../../math/vec3.hpp"
#include "../tolerances.hpp"

namespace impulse::narrowphase::detail {

/// Keeps the part of the convex polygon `in` where dot(w, x) <= limit, in
/// `out`, which must have room for count + 1 points (Sutherland–Hodgman,
/// one plane). Returns how many points it wrote.
template <scalar_type T>
int clip(const vec3<T>* in, int count, const vec3<T>& w, T limit, vec3<T>* out) noexcept {
  int kept = 0;
  for (int k = 0; k < count; ++k) {
    const vec3<T>& p = in[k];
    const vec3<T>& q = in[(k + 1) % count];
    const T dp = dot(w, p) - limit, dq = dot(w, q) - limit;
    if (dp <= T(0)) out[kept++] = p;
    if ((dp <= T(0)) != (dq <= T(0))) out[kept++] = p + (q - p) * (dp / (dp - dq));
  }
  return kept;
}

/// A point of a clipped patch and its height above the reference face
/// (negative: below it, overlapping).
template <scalar_type T>
struct patch_point {
  vec3<T> x;
  T separation;
};

/// Chooses at most four of the patch's points, one per quarter of the patch
/// (split along the reference face's unit axes u and v through the patch's
/// center): the one farthest from the center, so that the four span the
/// patch, except that the deepest point of all is kept in its quarter.
/// `chosen[q]` is the index of quarter q's point, or −1; the quarter is the
/// point's feature id. The quarter, not the clipping history: when a box
/// rests on a box of its size, their corners jitter across each other's
/// edges from step to step, and each corner of the patch is now an incident
/// corner, now the crossing of two edges, now a reference corner; its
/// quarter stays the same. An offset within 1 % of the patch's size counts
/// as negative, so that the two ends of a line of contact do not toss
/// between quarters across it.
template <scalar_type T>
void choose_by_quarter(const patch_point<T>* points, int count, const vec3<T>& u, const vec3<T>& v,
                       int chosen[4]) noexcept {
  vec3<T> center{};
  for (int c = 0; c < count; ++c) center += points[c].x;
  center /= T(count);
  T spread = T(0);
  for (int c = 0; c < count; ++c)
    spread = std::max(spread, std::max(std::abs(dot(points[c].x - center, u)), std::abs(dot(points[c].x - center, v))));
  const T dead_band = tolerances<T>::quarter_dead_band * spread;
  const auto quarter = [&](const vec3<T>& x) {
    return int(dot(x - center, u) > dead_band) | (int(dot(x - center, v) > dead_band) << 1);
  };
  int deepest = 0;
  for (int q = 0; q < 4; ++q) chosen[q] = -1;
  for (int c = 0; c < count; ++c) {
    if (points[c].separation < points[deepest].separation) deepest = c;
    int& slot = chosen[quarter(points[c].x)];
    if (slot < 0 || length_squared(points[c].x - center) > length_squared(points[slot].x - center)) slot = c;
  }
  chosen[quarter(points[deepest].x)] = deepest;
}

}  // namespace impulse::narrowphase::detail
