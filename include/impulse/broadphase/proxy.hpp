// impulse/broadphase/proxy.hpp — what every broad phase stores and reports.
//
// A proxy is an axis-aligned box with the user's data, named by a stable
// proxy_id. A pair is two proxies whose boxes overlap (closed boxes:
// touching faces count), reported once, lower slot first. A ray is a
// segment origin + t·translation, t ∈ [0, max_fraction], as in Box2D's
// b2RayCastInput: a fraction rather than a distance, so that the caller can
// clip the segment as hits come in.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>

#include "../core/error.hpp"
#include "../math/aabb.hpp"
#include "../math/vec3.hpp"
#include "fwd.hpp"

namespace impulse {

struct proxy_pair {
  proxy_id a;  ///< the proxy with the lower slot index
  proxy_id b;

  friend constexpr bool operator==(const proxy_pair&, const proxy_pair&) = default;
  /// Slot order first, so that pairs sort the same way in every broad phase.
  friend constexpr bool operator<(const proxy_pair& x, const proxy_pair& y) noexcept {
    if (x.a.index != y.a.index) return x.a.index < y.a.index;
    if (x.b.index != y.b.index) return x.b.index < y.b.index;
    if (x.a.generation != y.a.generation) return x.a.generation < y.a.generation;
    return x.b.generation < y.b.generation;
  }
};

/// The pair of two distinct proxies, in canonical order.
constexpr proxy_pair pair_of(proxy_id x, proxy_id y) noexcept {
  return x.index < y.index ? proxy_pair{x, y} : proxy_pair{y, x};
}

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

namespace broadphase::detail {

/// Refuses a ray that is not finite or a negative or non-finite maximum.
template <scalar_type T>
void require_ray(const ray<T>& r, T max_fraction) {
  if (!is_finite(r.origin) || !is_finite(r.translation) || !std::isfinite(max_fraction))
    impulse::detail::report_error(error_code::non_finite, "broad phase: the ray is not finite");
  if (max_fraction < T(0))
    impulse::detail::report_error(error_code::invalid_parameter, "broad phase: max_fraction must be >= 0");
}

}  // namespace broadphase::detail
}  // namespace impulse
