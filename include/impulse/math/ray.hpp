// impulse/math/ray.hpp — a ray, and where it enters a box.
//
// A ray is a segment origin + t·translation, t ∈ [0, max_fraction], as in
// Box2D's b2RayCastInput: a fraction rather than a distance, so that the
// caller can clip the segment as hits come in. The broad phases, the narrow
// phase's ray casts and a mesh's tree all take it.
#pragma once

#include <cmath>
#include <optional>
#include <utility>

#include "aabb.hpp"
#include "vec3.hpp"

namespace impulse {

template <scalar_type T>
struct ray {
  vec3<T> origin{};
  vec3<T> translation{};  ///< the segment's end at fraction 1 is origin + translation
};

/// The fraction t ∈ [0, max_fraction] at which the ray enters the box (0
/// when it starts inside), or nothing. Slab test; an axis along which the
/// ray does not move is a test of the origin alone, so a zero component
/// never divides.
template <scalar_type T>
[[nodiscard]] std::optional<T> ray_enters(const ray<T>& r, T max_fraction, const aabb<T>& box) noexcept {
  T enter = T(0), leave = max_fraction;
  for (int axis = 0; axis < 3; ++axis) {
    const T o = r.origin[axis], d = r.translation[axis], lo = box.lower[axis], hi = box.upper[axis];
    if (d == T(0)) {
      if (o < lo || o > hi) return std::nullopt;
      continue;
    }
    const T inverse = T(1) / d;
    T t0 = (lo - o) * inverse, t1 = (hi - o) * inverse;
    if (t0 > t1) std::swap(t0, t1);
    enter = std::fmax(enter, t0);
    leave = std::fmin(leave, t1);
    if (enter > leave) return std::nullopt;
  }
  return enter;
}

}  // namespace impulse
