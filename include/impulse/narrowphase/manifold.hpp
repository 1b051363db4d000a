// impulse/narrowphase/manifold.hpp — what a pair test reports: one normal
// and up to four contact points, each with its depth and a feature id.
//
// The normal is a unit vector pointing from shape A into shape B: pushing B
// along it (or A against it) separates them. Each point lies midway between
// the two surfaces along the normal, and its depth is how far they
// interpenetrate there (negative: how far apart they still are, reported
// when a pair test is given a margin, so that a solver can act before
// contact). The feature id names the pair of features (faces, edges,
// vertices) that made the point, so that while the same features touch the
// same id comes back step after step and a solver can carry the point's
// impulse over (warm starting).
//
// Four points are enough for a face resting on a face: any more add nothing
// a solver can use, and cost iterations. A pair test that finds more (a box
// on a plane, a clipped face) keeps four by `reduce_to_four`.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>

#include "../math/vec3.hpp"
#include "tolerances.hpp"

namespace impulse {

template <scalar_type T>
struct contact_point {
  vec3<T> position{};         ///< world, midway between the surfaces
  T depth = T(0);             ///< m: > 0 overlapping, < 0 apart (within the margin)
  std::uint32_t feature = 0;  ///< the touching features, stable while they touch
};

template <scalar_type T>
struct contact_manifold {
  static constexpr int capacity = 4;

  vec3<T> normal{T(0), T(1), T(0)};  ///< unit, from A into B
  std::array<contact_point<T>, capacity> points{};
  int count = 0;

  [[nodiscard]] bool empty() const noexcept { return count == 0; }
  [[nodiscard]] std::span<const contact_point<T>> contacts() const noexcept {
    return {points.data(), std::size_t(count)};
  }
  void add(const contact_point<T>& p) noexcept {
    if (count < capacity) points[std::size_t(count++)] = p;
  }
  /// The same contact seen from B: the normal reversed, the points kept.
  [[nodiscard]] contact_manifold flipped() const noexcept {
    contact_manifold m = *this;
    m.normal = -normal;
    return m;
  }
};

/// Keeps at most four of `candidates` in `out`: the deepest (the solver's
/// most important point), then the one farthest from it, then the one that
/// makes the largest triangle with those two, then the one that adds the
/// most area outside that triangle (distances and areas measured across
/// the normal; on a line, its two ends and the deepest). The kept points span nearly the largest area the candidates
/// offer, so a box keeps resting on its corners, and the choice depends on
/// positions alone, so it does not flicker while they hold still.
template <scalar_type T>
void reduce_to_four(std::span<const contact_point<T>> candidates, const vec3<T>& normal,
                    contact_manifold<T>& out) noexcept {
  out.count = 0;
  if (candidates.size() <= std::size_t(contact_manifold<T>::capacity)) {
    for (const contact_point<T>& p : candidates) out.add(p);
    return;
  }
  const auto pick = [&](auto&& score) {
    std::size_t best = 0;
    T best_score = score(candidates[0]);
    for (std::size_t i = 1; i < candidates.size(); ++i) {
      const T s = score(candidates[i]);
      if (s > best_score) best_score = s, best = i;
    }
    return candidates[best];
  };
  // Distances and areas across the normal: the candidates' spread in the
  // contact plane, whatever their depths.
  const auto across = [&](const vec3<T>& d) { return length_squared(d - normal * dot(d, normal)); };
  const contact_point<T> a = pick([](const contact_point<T>& p) { return p.depth; });
  const contact_point<T> b = pick([&](const contact_point<T>& p) { return across(p.position - a.position); });
  // Signed area (twice) of the triangle a, b, p across the normal.
  const auto area = [&](const contact_point<T>& p) {
    return dot(cross(b.position - a.position, p.position - a.position), normal);
  };
  const contact_point<T> c = pick([&](const contact_point<T>& p) { return std::abs(area(p)); });
  // The fourth on the side of ab away from c, adding the most area there,
  // or, past ac and bc, outside the triangle the farthest.
  const T side = area(c) < T(0) ? T(-1) : T(1);
  const auto added = [&](const contact_point<T>& p) {
    const T across_ab = -side * area(p);
    const T across_bc = -side * dot(cross(c.position - b.position, p.position - b.position), normal);
    const T across_ca = -side * dot(cross(a.position - c.position, p.position - c.position), normal);
    return std::max(across_ab, std::max(across_bc, across_ca));
  };
  const contact_point<T> d = pick(added);
  out.add(a);
  out.add(b);
  if (std::abs(area(c)) <= narrowphase::tolerances<T>::collinear_fraction * across(b.position - a.position)) {
    // All on one line, to 0.1 % of ab's length (rounding leaves the points
    // of a capsule lying across a face a hair off it): its two ends (b and
    // the farthest from b), and the deepest if it lies between them.
    const contact_point<T> e = pick([&](const contact_point<T>& p) { return across(p.position - b.position); });
    if (across(e.position - b.position) > across(a.position - b.position)) out.add(e);
    return;
  }
  out.add(c);
  if (added(d) > T(0)) out.add(d);  // else every candidate lies within abc
}

}  // namespace impulse
