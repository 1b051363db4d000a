// impulse/narrowphase/analytic.hpp — closed-form pair tests between
// spheres, capsules, boxes and planes.
//
// Each `collide(a, pose_a, b, pose_b, margin)` returns the contact manifold
// of shape a at pose_a against shape b at pose_b (manifold.hpp: the normal
// points from a into b), empty when they are farther apart than `margin`.
// The swapped pair (plane against sphere, …) is the same test with the
// manifold flipped.
//
// A sphere is a point grown by its radius and a capsule a segment grown by
// its radius, so every test between them is one between the closest points
// of two cores (Ericson, "Real-Time Collision Detection", §5.1): the normal
// lies along the line joining them and the depth is the radii less their
// distance. When the cores meet (concentric spheres, crossing segments) that
// line has no direction; the normal is then +y (any direction is right, and
// a fixed one keeps the result deterministic). Two nearly parallel
// capsules, one lying along the other, touch along a line: they get two
// points, at the ends of the overlap, so that one can rest on the other.
// A sphere against a box takes the box's closest point to the center, or,
// for a center inside the box, the face nearest to it. A box or a capsule
// against a plane reports each of its corners (or cap centers) below the
// plane's surface plus the margin; a box keeps four of its corners
// (reduce_to_four).
//
// Feature ids: a sphere has one feature; a capsule's two cap centers are
// 0 and 1; a box's corners are numbered by the signs of their coordinates
// (bit 0 set: +x, bit 1: +y, bit 2: +z), and the box feature nearest a
// sphere by three base-3 digits, one per axis (0 between the faces, 1 at −h,
// 2 at +h), so that a sphere rolling across one face keeps its id.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <span>

#include "../math/scalar_traits.hpp"
#include "../math/transform.hpp"
#include "../shapes/box.hpp"
#include "../shapes/capsule.hpp"
#include "../shapes/plane.hpp"
#include "../shapes/sphere.hpp"
#include "manifold.hpp"
#include "tolerances.hpp"

namespace impulse::narrowphase {

namespace detail {

template <scalar_type T>
struct segment_closest {
  T s = T(0), t = T(0);  ///< parameters along the first and second segment, in [0, 1]
  vec3<T> on_first{}, on_second{};
};

/// The closest points of segments p0 p1 and q0 q1 (Ericson §5.1.9); a
/// segment of zero length is a point, and parallel segments give one of
/// their closest pairs.
template <scalar_type T>
segment_closest<T> closest_points_of_segments(const vec3<T>& p0, const vec3<T>& p1, const vec3<T>& q0,
                                              const vec3<T>& q1) noexcept {
  const vec3<T> d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const T a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  constexpr T tiny = scalar_traits<T>::zero_length_squared;
  segment_closest<T> out;
  if (a <= tiny && e <= tiny) {
    // Two points.
  } else if (a <= tiny) {
    out.t = std::clamp(f / e, T(0), T(1));
  } else {
    const T c = dot(d1, r);
    if (e <= tiny) {
      out.s = std::clamp(-c / a, T(0), T(1));
    } else {
      const T b = dot(d1, d2), denominator = a * e - b * b;  // ≥ 0; 0 when parallel
      out.s = denominator > T(0) ? std::clamp((b * f - c * e) / denominator, T(0), T(1)) : T(0);
      out.t = (b * out.s + f) / e;
      if (out.t < T(0)) {
        out.t = T(0);
        out.s = std::clamp(-c / a, T(0), T(1));
      } else if (out.t > T(1)) {
        out.t = T(1);
        out.s = std::clamp((b - c) / a, T(0), T(1));
      }
    }
  }
  out.on_first = p0 + d1 * out.s;
  out.on_second = q0 + d2 * out.t;
  return out;
}

/// The point of segment p0 p1 closest to x.
template <scalar_type T>
vec3<T> closest_point_on_segment(const vec3<T>& p0, const vec3<T>& p1, const vec3<T>& x) noexcept {
  const vec3<T> d = p1 - p0;
  const T a = dot(d, d);
  if (a <= scalar_traits<T>::zero_length_squared) return p0;
  return p0 + d * std::clamp(dot(x - p0, d) / a, T(0), T(1));
}

/// Adds the contact of a ball (center a, radius ra) against a ball (center
/// b, radius rb) to m, setting m's normal, if they are within `margin`.
template <scalar_type T>
void add_ball_contact(const vec3<T>& a, T ra, const vec3<T>& b, T rb, T margin, std::uint32_t feature,
                      contact_manifold<T>& m) noexcept {
  const vec3<T> d = b - a;
  const T distance = length(d);
  if (distance - ra - rb > margin) return;
  m.normal = normalize_or(d, vec3<T>::unit_y());
  const vec3<T> on_a = a + m.normal * ra, on_b = b - m.normal * rb;
  m.add({(on_a + on_b) * T(0.5), ra + rb - distance, feature});
}

/// A plane's unit normal and offset in world space: n·x + offset = 0 on its
/// surface, > 0 outside the solid.
template <scalar_type T>
struct world_plane {
  vec3<T> normal;
  T offset;
};
template <scalar_type T>
world_plane<T> in_world(const plane<T>& p, const transform<T>& pose) noexcept {
  const vec3<T> n = apply_direction(pose, p.normal);
  return {n, p.offset - dot(n, pose.position)};
}

/// The two cap centers of a capsule in world space, feature 0 then 1.
template <scalar_type T>
std::array<vec3<T>, 2> capsule_ends(const capsule<T>& c, const transform<T>& pose) noexcept {
  const vec3<T> half = apply_direction(pose, vec3<T>{T(0), c.half_height, T(0)});
  return {pose.position - half, pose.position + half};
}

}  // namespace detail

// ---- sphere ---------------------------------------------------------------

template <scalar_type T>
contact_manifold<T> collide(const sphere<T>& a, const transform<T>& pose_a, const sphere<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) noexcept {
  contact_manifold<T> m;
  detail::add_ball_contact(pose_a.position, a.radius, pose_b.position, b.radius, margin, 0u, m);
  return m;
}

template <scalar_type T>
contact_manifold<T> collide(const sphere<T>& a, const transform<T>& pose_a, const plane<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) noexcept {
  const detail::world_plane<T> p = detail::in_world(b, pose_b);
  const vec3<T>& c = pose_a.position;
  const T height = dot(p.normal, c) + p.offset;  // of the center above the surface
  contact_manifold<T> m;
  if (height - a.radius > margin) return m;
  m.normal = -p.normal;
  m.add({c - p.normal * ((a.radius + height) * T(0.5)), a.radius - height, 0u});
  return m;
}

template <scalar_type T>
contact_manifold<T> collide(const sphere<T>& a, const transform<T>& pose_a, const box<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) noexcept {
  const vec3<T> center = inverse_apply(pose_b, pose_a.position);  // in the box's frame
  const vec3<T>& h = b.half_extents;
  contact_manifold<T> m;
  std::uint32_t feature = 0;
  vec3<T> nearest = center;  // on the box's surface or inside it
  bool inside = true;
  for (int axis = 2; axis >= 0; --axis) {
    feature *= 3;
    if (center[axis] < -h[axis]) nearest[axis] = -h[axis], feature += 1, inside = false;
    else if (center[axis] > h[axis]) nearest[axis] = h[axis], feature += 2, inside = false;
  }
  if (!inside) {
    const vec3<T> d = nearest - center;
    const T distance = length(d);
    if (distance - a.radius > margin) return m;
    const vec3<T> n = normalize_or(d, vec3<T>::unit_y());
    m.normal = apply_direction(pose_b, n);
    m.add({apply(pose_b, (center + n * a.radius + nearest) * T(0.5)), a.radius - distance, feature});
    return m;
  }
  // The center is inside: out through the nearest face.
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (h[k] - std::abs(center[k]) < h[axis] - std::abs(center[axis])) axis = k;
  const T side = center[axis] < T(0) ? T(-1) : T(1);
  vec3<T> n{};
  n[axis] = -side;  // from the sphere into the box: the box lies beyond the face
  vec3<T> on_face = center;
  on_face[axis] = side * h[axis];
  const T depth = a.radius + (h[axis] - std::abs(center[axis]));
  feature = std::uint32_t(side < T(0) ? 1 : 2);
  for (int k = 0; k < axis; ++k) feature *= 3;
  m.normal = apply_direction(pose_b, n);
  m.add({apply(pose_b, (center + n * a.radius + on_face) * T(0.5)), depth, feature});
  return m;
}

template <scalar_type T>
contact_manifold<T> collide(const sphere<T>& a, const transform<T>& pose_a, const capsule<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) noexcept {
  const auto [b0, b1] = detail::capsule_ends(b, pose_b);
  const vec3<T> core = detail::closest_point_on_segment(b0, b1, pose_a.position);
  contact_manifold<T> m;
  detail::add_ball_contact(pose_a.position, a.radius, core, b.radius, margin, 0u, m);
  return m;
}

// ---- capsule --------------------------------------------------------------

template <scalar_type T>
contact_manifold<T> collide(const capsule<T>& a, const transform<T>& pose_a, const capsule<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) noexcept {
  const auto [a0, a1] = detail::capsule_ends(a, pose_a);
  const auto [b0, b1] = detail::capsule_ends(b, pose_b);
  contact_manifold<T> m;
  const vec3<T> da = a1 - a0, db = b1 - b0;
  const T la = dot(da, da), lb = dot(db, db);
  constexpr T tiny = scalar_traits<T>::zero_length_squared;
  // Nearly parallel (the cores' directions within about 0.5° of each
  // other): the two ends of their overlap along a, each against b's core.
  if (la > tiny && lb > tiny &&
      length_squared(cross(da, db)) <= tolerances<T>::parallel_capsule_sine_squared * la * lb) {
    const T s0 = std::clamp(dot(b0 - a0, da) / la, T(0), T(1)), s1 = std::clamp(dot(b1 - a0, da) / la, T(0), T(1));
    const T lo = std::min(s0, s1), hi = std::max(s0, s1);
    if (hi > lo) {
      for (const T s : {lo, hi}) {
        const vec3<T> on_a = a0 + da * s;
        const vec3<T> on_b = detail::closest_point_on_segment(b0, b1, on_a);
        detail::add_ball_contact(on_a, a.radius, on_b, b.radius, margin, s == lo ? 1u : 2u, m);
      }
      // Both points share one normal: the one through the overlap's middle
      // (the two can differ by rounding when the cores meet at an angle).
      if (m.count == 2) {
        const vec3<T> mid = a0 + da * ((lo + hi) * T(0.5));
        m.normal = normalize_or(detail::closest_point_on_segment(b0, b1, mid) - mid, m.normal);
      }
      if (!m.empty()) return m;
    }
  }
  const detail::segment_closest<T> c = detail::closest_points_of_segments(a0, a1, b0, b1);
  detail::add_ball_contact(c.on_first, a.radius, c.on_second, b.radius, margin, 0u, m);
  return m;
}

template <scalar_type T>
contact_manifold<T> collide(const capsule<T>& a, const transform<T>& pose_a, const plane<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) noexcept {
  const detail::world_plane<T> p = detail::in_world(b, pose_b);
  const auto ends = detail::capsule_ends(a, pose_a);
  contact_manifold<T> m;
  m.normal = -p.normal;
  for (std::uint32_t k = 0; k < 2; ++k) {
    const T height = dot(p.normal, ends[k]) + p.offset;
    if (height - a.radius <= margin) m.add({ends[k] - p.normal * ((a.radius + height) * T(0.5)), a.radius - height, k});
  }
  return m;
}

template <scalar_type T>
contact_manifold<T> collide(const capsule<T>& a, const transform<T>& pose_a, const sphere<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) noexcept {
  return collide(b, pose_b, a, pose_a, margin).flipped();
}

// ---- box ------------------------------------------------------------------

template <scalar_type T>
contact_manifold<T> collide(const box<T>& a, const transform<T>& pose_a, const plane<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) noexcept {
  const detail::world_plane<T> p = detail::in_world(b, pose_b);
  contact_point<T> below[8];
  int count = 0;
  for (std::uint32_t k = 0; k < 8; ++k) {
    const vec3<T> corner{(k & 1u) ? a.half_extents.x : -a.half_extents.x, (k & 2u) ? a.half_extents.y : -a.half_extents.y,
                         (k & 4u) ? a.half_extents.z : -a.half_extents.z};
    const vec3<T> x = apply(pose_a, corner);
    const T height = dot(p.normal, x) + p.offset;
    if (height <= margin) below[count++] = {x - p.normal * (height * T(0.5)), -height, k};
  }
  contact_manifold<T> m;
  m.normal = -p.normal;
  reduce_to_four(std::span<const contact_point<T>>(below, std::size_t(count)), m.normal, m);
  return m;
}

template <scalar_type T>
contact_manifold<T> collide(const box<T>& a, const transform<T>& pose_a, const sphere<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) noexcept {
  return collide(b, pose_b, a, pose_a, margin).flipped();
}

// ---- plane ----------------------------------------------------------------

template <scalar_type T>
contact_manifold<T> collide(const plane<T>& a, const transform<T>& pose_a, const sphere<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) noexcept {
  return collide(b, pose_b, a, pose_a, margin).flipped();
}
template <scalar_type T>
contact_manifold<T> collide(const plane<T>& a, const transform<T>& pose_a, const capsule<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) noexcept {
  return collide(b, pose_b, a, pose_a, margin).flipped();
}
template <scalar_type T>
contact_manifold<T> collide(const plane<T>& a, const transform<T>& pose_a, const box<T>& b,
                            const transform<T>& pose_b, T margin = T(0)) noexcept {
  return collide(b, pose_b, a, pose_a, margin).flipped();
}

}  // namespace impulse::narrowphase
