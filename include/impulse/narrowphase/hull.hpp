// impulse/narrowphase/hull.hpp — convex hulls against planes and spheres.
//
// A hull against a plane: each vertex below the plane's surface plus the
// margin is a candidate (its id the vertex's index), and four are kept
// (reduce_to_four), as for a box.
//
// A sphere against a hull, in the hull's frame: the face whose plane lies
// farthest above the center decides. If even that plane is below it, the
// center is inside the hull and the way out is through that face: the depth
// is the radius plus how far the center is below it. Otherwise the point of
// the hull nearest the center comes from GJK between the center and the
// hull (gjk.hpp: a sphere enters it as a point), and the sphere touches if
// that point lies within the radius plus the margin. The feature id is that
// face's index: it holds while the sphere rolls across one face.
#pragma once

#include <cstdint>
#include <limits>
#include <span>

#include "../math/transform.hpp"
#include "../shapes/convex_hull.hpp"
#include "../shapes/plane.hpp"
#include "../shapes/sphere.hpp"
#include "analytic.hpp"
#include "detail/scratch_buffer.hpp"
#include "gjk.hpp"
#include "manifold.hpp"

namespace impulse::narrowphase {

template <scalar_type T>
contact_manifold<T> collide(const convex_hull<T>& a, const transform<T>& pose_a, const plane<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) {
  const detail::world_plane<T> p = detail::in_world(b, pose_b);
  const std::span<const vec3<T>> vertices = a.vertices();
  detail::scratch_buffer<contact_point<T>, 64> below(vertices.size());
  std::size_t count = 0;
  for (std::uint32_t k = 0; k < vertices.size(); ++k) {
    const vec3<T> x = apply(pose_a, vertices[k]);
    const T height = dot(p.normal, x) + p.offset;
    if (height <= margin) below[count++] = {x - p.normal * (height * T(0.5)), -height, k};
  }
  contact_manifold<T> m;
  m.normal = -p.normal;
  reduce_to_four(std::span<const contact_point<T>>(below.data(), count), m.normal, m);
  return m;
}

template <scalar_type T>
contact_manifold<T> collide(const plane<T>& a, const transform<T>& pose_a, const convex_hull<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) {
  return collide(b, pose_b, a, pose_a, margin).flipped();
}

template <scalar_type T>
contact_manifold<T> collide(const sphere<T>& a, const transform<T>& pose_a, const convex_hull<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) noexcept {
  const vec3<T> center = inverse_apply(pose_b, pose_a.position);  // in the hull's frame
  std::uint32_t face = 0;
  T highest = -std::numeric_limits<T>::infinity();
  for (std::uint32_t f = 0; f < b.face_count(); ++f) {
    const T d = b.plane(f).distance(center);
    if (d > highest) highest = d, face = f;
  }
  contact_manifold<T> m;
  if (highest - a.radius > margin) return m;  // a face's plane separates them
  // Outside: the hull's point nearest the center.
  gjk_result<T> g;
  if (highest > T(0))
    g = detail::run_gjk(sphere<T>{a.radius}, transform<T>{center, quat<T>::identity()}, b, transform<T>::identity())
            .result;
  if (highest <= T(0) || g.overlapping) {
    // Inside (or on the surface, where GJK finds no direction): out through
    // the nearest face.
    const vec3<T> n = b.plane(face).normal;
    m.normal = apply_direction(pose_b, -n);
    const vec3<T> on_face = center - n * highest, deepest = center - n * a.radius;
    m.add({apply(pose_b, (on_face + deepest) * T(0.5)), a.radius - highest, face});
    return m;
  }
  if (g.distance - a.radius > margin) return m;
  const vec3<T> n = (g.on_b - center) / g.distance;  // from the sphere into the hull
  m.normal = apply_direction(pose_b, n);
  m.add({apply(pose_b, (center + n * a.radius + g.on_b) * T(0.5)), a.radius - g.distance, face});
  return m;
}

template <scalar_type T>
contact_manifold<T> collide(const convex_hull<T>& a, const transform<T>& pose_a, const sphere<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) noexcept {
  return collide(b, pose_b, a, pose_a, margin).flipped();
}

}  // namespace impulse::narrowphase
