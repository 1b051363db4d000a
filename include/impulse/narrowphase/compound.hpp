// impulse/narrowphase/compound.hpp — a compound's pair test and ray cast, child
// by child.
//
// The pair test (collide_compound) asks the compound's tree for the
// children whose boxes the other shape's box, grown by the margin,
// overlaps, has each tested by the pair test of its own shape (the
// dispatcher's table, dispatch.hpp: a compound needs no pair test of its
// own, and compiles none), and merges the children's manifolds by normal
// (detail/manifold_merger.hpp), as a mesh merges its triangles': two boxes
// side by side on a floor give one manifold of four corners, the hull
// around them would too, and a solver sees one face, not two that fight
// over the same rows.
//
// Feature ids: a child's test gives ids that are stable while its features
// touch; the child's index is mixed into them (compound_feature), so that
// the same corner of two children is two ids, and the same corner of the
// same child keeps its id step after step: warm starting carries each
// point's impulse as it does for a single shape.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "../math/aabb.hpp"
#include "../math/transform.hpp"
#include "../shapes/compound.hpp"
#include "detail/manifold_merger.hpp"
#include "manifold.hpp"
#include "ray_cast.hpp"
#include "tolerances.hpp"

namespace impulse::narrowphase {

namespace detail {

/// The id of a point of child `child` whose own test gave it `feature`.
/// The index is spread over all 32 bits by an odd multiplier (Knuth's
/// multiplicative hash), a different one for a compound that is B of the
/// pair than for one that is A, so that child i of A against child j of B
/// and child j of A against child i of B differ too.
constexpr std::uint32_t compound_feature(std::uint32_t feature, std::size_t child, bool is_b) noexcept {
  const std::uint32_t multiplier = is_b ? 0x85EBCA77u : 0x9E3779B1u;
  return feature ^ ((std::uint32_t(child) + 1u) * multiplier);
}

}  // namespace detail

/// The manifolds of compound `c` at `pose` against another shape whose
/// world box is `other_box`, written to `out` (at most out.size(), the
/// deepest first); returns how many. test(i, child_pose, part) writes
/// child i's manifolds against the other shape, the child at child_pose
/// (world), into `part`, with the normal from the pair's A into its B,
/// and returns how many. `is_b`: the compound is the pair's B.
template <scalar_type T, class ChildTest>
std::size_t collide_compound(const compound<T>& c, const transform<T>& pose, const aabb<T>& other_box, T margin,
                             bool is_b, std::span<contact_manifold<T>> out, ChildTest&& test) {
  detail::manifold_merger<T> merger(tolerances<T>::weld_fraction * c.thinnest_half_extent());
  aabb<T> near = expand(transform_aabb(other_box, inverse(pose)), margin);
  // A plane's box is unbounded, and turning it overflows: then every child.
  if (!is_finite(near.lower) || !is_finite(near.upper)) near = c.local_aabb();
  c.for_each_overlapping(near, [&](std::size_t i) {
    std::array<contact_manifold<T>, contact_manifold<T>::capacity> part;
    const std::size_t n = test(i, pose * c.child_at(i).pose, std::span<contact_manifold<T>>(part.data(), part.size()));
    for (std::size_t m = 0; m < n; ++m) {
      for (int p = 0; p < part[m].count; ++p) {
        std::uint32_t& feature = part[m].points[std::size_t(p)].feature;
        feature = detail::compound_feature(feature, i, is_b);
      }
      merger.add(part[m]);
    }
  });
  return merger.write(out, quat<T>::identity(), [](const vec3<T>& x) { return x; }, false);
}

/// The nearest hit of any child (ray_cast.hpp's conventions), walking the
/// tree along the ray, nearer boxes first; its feature is the child's index.
template <scalar_type T>
ray_hit<T> ray_cast(const ray<T>& r, const compound<T>& c, const transform<T>& pose, T max_fraction = T(1)) noexcept {
  ray_hit<T> best;
  if (!is_finite(r.origin) || !is_finite(r.translation) || !(max_fraction >= T(0))) return best;
  const vec3<T> origin = inverse_apply(pose, r.origin), translation = inverse_rotate(pose.rotation, r.translation);
  c.for_each_along_ray(origin, translation, max_fraction, [&](std::size_t i, T clip) {
    const ray_hit<T> h =
        c.visit(i, [&](const auto& s, const transform<T>& local) { return ray_cast(r, s, pose * local, clip); });
    if (!h || (best && !(h.fraction < best.fraction))) return clip;
    best = h;
    best.feature = std::uint32_t(i);
    return h.fraction;
  });
  return best;
}

}  // namespace impulse::narrowphase
