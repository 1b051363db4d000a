// impulse/world/detail/shape_cast.hpp — one convex shape swept along a
// straight line against one body's shape: where along the line they first
// touch, the point and the target's surface normal there. world::shape_cast
// takes the nearest over the bodies the broad phase finds.
//
// A convex target is met by conservative advancement (narrowphase/
// time_of_impact.hpp) between a quarter and a half of `cast_tolerance`
// short of touching, never past, the point on the target's surface;
// a triangle mesh or a heightfield triangle by triangle (each a convex
// shape of three corners), a compound child by child; a plane in closed form. A shape that starts overlapping its
// target hits it at fraction 0, with the normal of least penetration
// (narrowphase/epa.hpp; a plane's own normal), unless it moves out along
// that normal; one that starts within the tolerance likewise.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <type_traits>

#include "../../narrowphase/epa.hpp"
#include "../../narrowphase/mesh.hpp"
#include "../../narrowphase/time_of_impact.hpp"
#include "../../shapes/compound.hpp"
#include "../../shapes/plane.hpp"
#include "../../shapes/heightfield.hpp"
#include "../../shapes/triangle_mesh.hpp"

namespace impulse::detail {

/// Where a cast shape first touches a target: the fraction of the
/// translation, the touching point and the target's outward normal there.
template <scalar_type T>
struct cast_contact {
  T fraction = T(1);
  vec3<T> point{};
  vec3<T> normal{};
};

/// m: how close to touching a cast ends, short of it.
template <scalar_type T>
inline constexpr T cast_tolerance = T(0.0005);

template <class S, class T>
concept convex_shape = requires(const S& s, const vec3<T>& d) { s.support(d); };

/// `shape` at `pose` moving by `translation` against the convex `target`
/// at rest at `target_pose`, within max_fraction.
template <class S, class Target, scalar_type T>
std::optional<cast_contact<T>> cast_convex(const S& shape, const transform<T>& pose, const vec3<T>& translation,
                                           const Target& target, const transform<T>& target_pose, T max_fraction) {
  // Stopped a little short of touching, where GJK still has two points
  // apart to give (at touching it has none).
  narrowphase::toi_options<T> options;
  options.target = cast_tolerance<T> / T(2);
  options.tolerance = cast_tolerance<T> / T(2);
  const narrowphase::sweep<T> path{pose, {pose.position + translation * max_fraction, pose.rotation}, {}};
  const narrowphase::sweep<T> still{target_pose, target_pose, {}};
  const narrowphase::toi_result<T> hit = narrowphase::time_of_impact(shape, path, target, still, options);
  if (hit.state == narrowphase::toi_state::overlapping) {
    const narrowphase::epa_result<T> deep = narrowphase::epa_penetration(shape, pose, target, target_pose);
    if (!(dot(translation, deep.normal) > T(0))) return std::nullopt;  // on its way out
    return cast_contact<T>{T(0), deep.on_b, -deep.normal};
  }
  if (hit.state == narrowphase::toi_state::separated) return std::nullopt;
  // Within the tolerance at the start, the gap along the normal only opens
  // if the shape does not move into it: nothing to meet (a character
  // walking along a wall it stands a skin from).
  // (Into it by a thousandth of the move or more: rounding tilts the
  // normal of a shape moved exactly along a surface by about an ulp.)
  if (hit.t == T(0) && !(dot(translation, hit.normal) > T(1e-3) * length(translation))) return std::nullopt;
  // A hit, or out of iterations at the last time known to be short of one.
  return cast_contact<T>{hit.t * max_fraction, hit.on_b, -hit.normal};
}

/// Against a plane's half-space: the shape's deepest point along the
/// plane's normal reaches the surface.
template <class S, scalar_type T>
std::optional<cast_contact<T>> cast_plane(const S& shape, const transform<T>& pose, const vec3<T>& translation,
                                          const plane<T>& target, const transform<T>& target_pose, T max_fraction) {
  const vec3<T> n = rotate(target_pose.rotation, target.normal);
  const vec3<T> on_surface = apply(target_pose, target.normal * -target.offset);
  const vec3<T> deepest = apply(pose, shape.support(inverse_rotate(pose.rotation, -n)));
  const T gap = dot(n, deepest - on_surface);
  const T closing = -dot(n, translation);
  if (gap <= T(0)) {
    if (!(closing > T(0))) return std::nullopt;  // on its way out
    return cast_contact<T>{T(0), deepest - n * gap, n};
  }
  if (!(closing > T(0)) || gap > closing * max_fraction) return std::nullopt;
  const T fraction = gap / closing;
  return cast_contact<T>{fraction, deepest + translation * fraction, n};
}

/// Against each triangle of a mesh near the swept shape; the nearest.
template <class S, scalar_type T, class Mesh>
std::optional<cast_contact<T>> cast_mesh(const S& shape, const transform<T>& pose, const vec3<T>& translation,
                                         const Mesh& mesh, const transform<T>& mesh_pose, T max_fraction) {
  const aabb<T> swept = merge(shape.world_aabb(pose),
                              shape.world_aabb({pose.position + translation * max_fraction, pose.rotation}));
  std::optional<cast_contact<T>> best;
  T reach = max_fraction;
  mesh.for_each_overlapping(transform_aabb(swept, inverse(mesh_pose)), [&](std::size_t t) {
    narrowphase::detail::convex_triangle<T> triangle;
    mesh.triangle(t, triangle.v[0], triangle.v[1], triangle.v[2]);
    const std::optional<cast_contact<T>> hit = cast_convex(shape, pose, translation, triangle, mesh_pose, reach);
    if (hit && (!best || hit->fraction < best->fraction)) best = hit, reach = hit->fraction;
  });
  return best;
}

/// Against each child of a compound near the swept shape; the nearest.
template <class S, scalar_type T>
std::optional<cast_contact<T>> cast_compound(const S& shape, const transform<T>& pose, const vec3<T>& translation,
                                             const compound<T>& target, const transform<T>& target_pose,
                                             T max_fraction) {
  const aabb<T> swept = merge(shape.world_aabb(pose),
                              shape.world_aabb({pose.position + translation * max_fraction, pose.rotation}));
  std::optional<cast_contact<T>> best;
  T reach = max_fraction;
  target.for_each_overlapping(transform_aabb(swept, inverse(target_pose)), [&](std::size_t i) {
    const std::optional<cast_contact<T>> hit = target.visit(i, [&](const auto& child, const transform<T>& local) {
      return cast_convex(shape, pose, translation, child, target_pose * local, reach);
    });
    if (hit && (!best || hit->fraction < best->fraction)) best = hit, reach = hit->fraction;
  });
  return best;
}

/// The cast against any target shape.
template <class S, class Target, scalar_type T>
std::optional<cast_contact<T>> cast_shape(const S& shape, const transform<T>& pose, const vec3<T>& translation,
                                          const Target& target, const transform<T>& target_pose, T max_fraction) {
  if constexpr (std::is_same_v<Target, plane<T>>) {
    return cast_plane(shape, pose, translation, target, target_pose, max_fraction);
  } else if constexpr (std::is_same_v<Target, triangle_mesh<T>> || std::is_same_v<Target, heightfield<T>>) {
    return cast_mesh(shape, pose, translation, target, target_pose, max_fraction);
  } else if constexpr (std::is_same_v<Target, compound<T>>) {
    return cast_compound(shape, pose, translation, target, target_pose, max_fraction);
  } else if constexpr (convex_shape<Target, T>) {
    return cast_convex(shape, pose, translation, target, target_pose, max_fraction);
  } else {
    return std::nullopt;  // a user's shape without a support function: not cast against
  }
}

}  // namespace impulse::detail
