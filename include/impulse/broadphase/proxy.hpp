// impulse/broadphase/proxy.hpp — what every broad phase stores and reports.
//
// A proxy is an axis-aligned box with the user's data, named by a stable
// proxy_id. A pair is two proxies whose boxes overlap (closed boxes:
// touching faces count), reported once, lower slot first. Rays are
// impulse::ray (math/ray.hpp).
#pragma once

#include <cmath>
#include <cstdint>

#include "../core/error.hpp"
#include "../math/aabb.hpp"
#include "../math/ray.hpp"
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
