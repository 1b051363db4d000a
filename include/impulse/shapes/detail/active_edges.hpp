// impulse/shapes/detail/active_edges.hpp — whether an edge two triangles
// share is one something can rest against (active), or an internal seam
// the narrow phase looks past (triangle_mesh.hpp says why; heightfield.hpp
// asks the same of its grid).
#pragma once

#include "../../math/scalar_traits.hpp"
#include "../../math/vec3.hpp"

namespace impulse::detail {

/// Triangles (a1, b1, c1) and (a2, b2, c2), wound the same way round, share
/// an edge through p; `far` is the second's corner off it. The edge is
/// active where they lie back to back (a sheet folded onto itself) or meet
/// convex with normals further apart than flat_cosine; flat or concave, it
/// is internal.
template <scalar_type T>
[[nodiscard]] bool shared_edge_active(const vec3<T>& a1, const vec3<T>& b1, const vec3<T>& c1, const vec3<T>& a2,
                                      const vec3<T>& b2, const vec3<T>& c2, const vec3<T>& p, const vec3<T>& far,
                                      T flat_cosine) noexcept {
  const vec3<T> n1 = normalize_or(cross(b1 - a1, c1 - a1), vec3<T>::unit_y());
  const vec3<T> n2 = normalize_or(cross(b2 - a2, c2 - a2), vec3<T>::unit_y());
  const T cosine = dot(n1, n2);
  if (cosine < T(-0.999)) return true;
  // Concave (the second rises above the first's plane) or flat: internal.
  if (dot(n1, far - p) >= T(0)) return false;
  return cosine < flat_cosine;
}

}  // namespace impulse::detail
