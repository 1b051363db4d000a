// impulse/math/aabb.hpp — axis-aligned bounding box.
//
// Closed box [lower, upper]. aabb::empty() is inverted (lower = +max,
// upper = -max), the identity of merge, so a box can be grown point by point
// from it; is_valid is false for it until something is merged in.
#pragma once

#include <limits>

#include "mat3.hpp"
#include "transform.hpp"
#include "vec3.hpp"

namespace impulse {

template <scalar_type T>
struct aabb {
  using scalar = T;

  vec3<T> lower{};
  vec3<T> upper{};

  static constexpr aabb empty() noexcept {
    constexpr T big = std::numeric_limits<T>::max();
    return {vec3<T>::splat(big), vec3<T>::splat(-big)};
  }
  static constexpr aabb from_center_half_extents(const vec3<T>& center, const vec3<T>& half) noexcept {
    return {center - half, center + half};
  }

  friend constexpr bool operator==(const aabb&, const aabb&) = default;
};

template <scalar_type T> constexpr vec3<T> center(const aabb<T>& b) noexcept { return (b.lower + b.upper) * T(0.5); }
template <scalar_type T> constexpr vec3<T> half_extents(const aabb<T>& b) noexcept { return (b.upper - b.lower) * T(0.5); }

template <scalar_type T>
constexpr bool is_valid(const aabb<T>& b) noexcept {
  return b.lower.x <= b.upper.x && b.lower.y <= b.upper.y && b.lower.z <= b.upper.z;
}

template <scalar_type T>
constexpr bool contains(const aabb<T>& b, const vec3<T>& p) noexcept {
  return b.lower.x <= p.x && p.x <= b.upper.x && b.lower.y <= p.y && p.y <= b.upper.y &&
         b.lower.z <= p.z && p.z <= b.upper.z;
}

/// True when `inner` lies entirely inside `outer` (touching faces count).
template <scalar_type T>
constexpr bool contains(const aabb<T>& outer, const aabb<T>& inner) noexcept {
  return contains(outer, inner.lower) && contains(outer, inner.upper);
}

/// True when the boxes share at least one point (touching faces overlap).
template <scalar_type T>
constexpr bool overlaps(const aabb<T>& a, const aabb<T>& b) noexcept {
  return a.lower.x <= b.upper.x && b.lower.x <= a.upper.x && a.lower.y <= b.upper.y &&
         b.lower.y <= a.upper.y && a.lower.z <= b.upper.z && b.lower.z <= a.upper.z;
}

template <scalar_type T>
constexpr aabb<T> merge(const aabb<T>& a, const aabb<T>& b) noexcept {
  return {min(a.lower, b.lower), max(a.upper, b.upper)};
}

template <scalar_type T>
constexpr aabb<T> merge(const aabb<T>& a, const vec3<T>& p) noexcept {
  return {min(a.lower, p), max(a.upper, p)};
}

/// The box grown by `margin` on every side (fat AABBs for the broad phase).
template <scalar_type T>
constexpr aabb<T> expand(const aabb<T>& b, T margin) noexcept {
  const vec3<T> m = vec3<T>::splat(margin);
  return {b.lower - m, b.upper + m};
}

/// Surface area: the cost metric of the surface-area heuristic in a BVH.
template <scalar_type T>
constexpr T surface_area(const aabb<T>& b) noexcept {
  const vec3<T> d = b.upper - b.lower;
  return T(2) * (d.x * d.y + d.y * d.z + d.z * d.x);
}

template <scalar_type T>
constexpr T volume(const aabb<T>& b) noexcept {
  const vec3<T> d = b.upper - b.lower;
  return d.x * d.y * d.z;
}

/// World box of a body-space box under a rigid transform: the tightest
/// axis-aligned box around the rotated box (Arvo, Graphics Gems 1990). The
/// rotated half extents are |R|·h, with |R| the elementwise absolute value.
template <scalar_type T>
constexpr aabb<T> transform_aabb(const aabb<T>& b, const transform<T>& t) noexcept {
  const mat3<T> r = to_mat3(t.rotation);
  const vec3<T> h = half_extents(b);
  const mat3<T> abs_r = mat3<T>::from_columns(abs(r.col[0]), abs(r.col[1]), abs(r.col[2]));
  return aabb<T>::from_center_half_extents(apply(t, center(b)), abs_r * h);
}

}  // namespace impulse
