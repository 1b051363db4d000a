// impulse/narrowphase/time_of_impact.hpp — when two moving convex shapes
// first come within a target distance of each other, for continuous
// collision detection.
//
// Motion. Each shape moves as a CCD stage sees a body over one step: from
// its pose at the start to its pose at the end (a `sweep`, after Box2D's
// b2Sweep and the from/to transforms of Bullet's convex casts), its center
// of rotation (the center of mass, given in the shape's frame) on a
// straight line at constant speed, and its orientation turning about that
// center at a constant angular velocity, the shortest rotation from start
// to end (so a body must turn less than half a turn per step; one that
// turns more is seen turning the short way). Time t runs over [0, 1].
//
// Method: conservative advancement (Mirtich, "Impulse-based Dynamic
// Simulation of Rigid Body Systems", PhD thesis, 1996, §2.4; also Bullet's
// btContinuousConvexCollision). At time t, GJK (gjk.hpp) gives the
// distance d and the unit normal n from A's closest point to B's. With n
// held fixed, the gap between the support planes of A and B along n starts
// at d and closes no faster than
//     bound = n·(v_A − v_B) + |n × ω_A|·r_A + |n × ω_B|·r_B,
// v the centers' velocities, ω the angular velocities, r each shape's
// farthest point from its center of rotation: the first term is the
// centers' approach along n, the others the most any point can add by
// turning (a point at offset ρ from its center moves along n at
// n·(ω × ρ) = ρ·(n × ω) ≤ r·|n × ω|; Mirtich's |ω|·r is the same bound
// without the projection, looser when ω is not across n). The distance is never less than that gap, so the shapes stay at
// least `target` apart until t + (d − target)/bound: advance to there and
// repeat. The signed projection (not its absolute value) is what makes the
// bound tight for a head-on approach, which then ends exactly in one step;
// a bound ≤ 0 means the gap along n can only open, and the shapes never
// meet. Every t the iteration visits is safe (at least `target` apart,
// within GJK's tolerance), so the answer never lets a fast body through;
// the price is slow progress when a spinning body's turning term dominates
// while it slides past the other (a near miss can take many iterations).
// Over 4 000 random pairs of boxes, capsules, spheres and hulls, moving up
// to 4 m and turning up to 3 rad in the step: 6.5 GJK calls on average,
// 27 pairs over 32, and one near miss out of the 64 iterations.
//
// Ends:
// - hit: d < target + tolerance at t (t may be 0 when they start that
//   close). normal, on_a, on_b, distance are GJK's at t.
// - separated: t would pass 1 (or the bound says they can only part); t
//   is 1, and normal, points and distance are GJK's at the last time
//   visited.
// - overlapping: they overlap at t = 0 already; there is no normal (it is
//   zero): the discrete narrow phase (collide, EPA) has to resolve them.
// - failed: max_iterations ran out; t is the last safe time, and normal,
//   points and distance are GJK's there.
//
// Planes and meshes are not convex shapes with a support function and do
// not enter here (a mesh will, triangle by triangle).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "../math/quat.hpp"
#include "../math/scalar_traits.hpp"
#include "../math/transform.hpp"
#include "../shapes/capsule.hpp"
#include "../shapes/sphere.hpp"
#include "gjk.hpp"

namespace impulse::narrowphase {

/// A shape's motion over one step, t in [0, 1] (see the top of this file).
template <scalar_type T>
struct sweep {
  transform<T> start = transform<T>::identity();  ///< pose at t = 0
  transform<T> end = transform<T>::identity();    ///< pose at t = 1
  vec3<T> local_center{};  ///< m, shape frame: the point the shape turns about (its center of mass)
};

/// The motion of a sweep, resolved once: the center's start and
/// displacement, the start orientation and the rotation vector over [0, 1].
template <scalar_type T>
struct sweep_motion {
  vec3<T> center{};        ///< world, m: the center of rotation at t = 0
  vec3<T> translation{};   ///< m over the interval: the center's velocity per unit t
  quat<T> rotation = quat<T>::identity();  ///< at t = 0
  vec3<T> angle{};         ///< rad over the interval, world: the angular velocity per unit t
  vec3<T> local_center{};

  explicit sweep_motion(const sweep<T>& s) noexcept
      : center(apply(s.start, s.local_center)),
        translation(apply(s.end, s.local_center) - apply(s.start, s.local_center)),
        rotation(s.start.rotation),
        angle(rotation_between(s.start.rotation, s.end.rotation)),
        local_center(s.local_center) {}

  /// The pose at time t: the center moved by t·translation, the
  /// orientation turned by t·angle (exactly the end pose at t = 1, up to
  /// rounding).
  transform<T> at(T t) const noexcept {
    const quat<T> q = integrate(rotation, angle, t);
    return {center + translation * t - rotate(q, local_center), q};
  }
};

enum class toi_state : std::uint8_t {
  hit,          ///< within target + tolerance at t
  separated,    ///< never within target + tolerance over [0, 1]
  overlapping,  ///< overlapping already at t = 0
  failed,       ///< out of iterations; t is the last time known to be safe
};

template <scalar_type T>
struct toi_options {
  /// m, ≥ 0: the separation to stop at. The CCD stage places the bodies at
  /// the time found, and the contact it then wants is a speculative one a
  /// little apart, not an overlap that rounding could push either way;
  /// Box2D's linear slop (5 mm), for shapes of about a metre.
  T target = T(0.005);
  /// m, > 0: how close to `target` counts as there. Box2D's quarter of the
  /// slop. Smaller costs iterations on rotating shapes; it should stay
  /// above the rounding of poses in T (about 1e-3 m for float at 1e4 m from
  /// the origin).
  T tolerance = T(0.00125);
  /// Head-on approaches end in 2 GJK calls; a spinning body that slides
  /// past another can take dozens (see the top of this file). As Bullet's
  /// continuous convex collision.
  int max_iterations = 64;
};

template <scalar_type T>
struct toi_result {
  toi_state state = toi_state::separated;
  T t = T(1);            ///< in [0, 1]: the time of impact, or see toi_state
  vec3<T> normal{};      ///< unit, world, from A's closest point to B's, at t (zero when overlapping)
  vec3<T> on_a{};        ///< world, m: A's point closest to B at t
  vec3<T> on_b{};        ///< world, m: B's point closest to A at t
  T distance = T(0);     ///< m: between them at t
  int iterations = 0;    ///< GJK distance calls made
};

namespace detail {

/// The farthest any point of the shape lies from `center` (shape frame):
/// a ball's center offset plus its radius, a capsule's farther cap, a
/// hull's farthest vertex, and otherwise the farthest corner of the
/// shape's local box (exact for a box).
template <class Shape, scalar_type T>
T reach_from(const Shape& shape, const vec3<T>& center) noexcept {
  if constexpr (requires { shape.vertices(); }) {
    T farthest = T(0);
    for (const vec3<T>& v : shape.vertices()) farthest = std::max(farthest, length_squared(v - center));
    return std::sqrt(farthest);
  } else {
    const auto bounds = shape.local_aabb();
    const vec3<T> corner = max(abs(bounds.lower - center), abs(bounds.upper - center));
    return length(corner);
  }
}
template <scalar_type T>
T reach_from(const sphere<T>& s, const vec3<T>& center) noexcept {
  return length(center) + s.radius;
}
template <scalar_type T>
T reach_from(const capsule<T>& c, const vec3<T>& center) noexcept {
  const vec3<T> top{T(0), c.half_height, T(0)};
  return std::max(length(top - center), length(top + center)) + c.radius;
}

}  // namespace detail

/// When shape a moving along sweep_a and shape b along sweep_b first come
/// within options.target (+ options.tolerance) of each other, by
/// conservative advancement (see the top of this file). Both shapes need a
/// `support(direction)` in their own frame.
template <class A, class B, scalar_type T>
toi_result<T> time_of_impact(const A& a, const sweep<T>& sweep_a, const B& b, const sweep<T>& sweep_b,
                             const toi_options<T>& options = {}) noexcept {
  const sweep_motion<T> ma{sweep_a}, mb{sweep_b};
  const T reach_a = detail::reach_from(a, sweep_a.local_center), reach_b = detail::reach_from(b, sweep_b.local_center);
  const vec3<T> relative = ma.translation - mb.translation;  // A's velocity relative to B, per unit t
  toi_result<T> out;
  T t = T(0);
  for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
    out.iterations = iteration;
    const gjk_result<T> g = gjk_distance(a, ma.at(t), b, mb.at(t));
    if (g.overlapping) {
      // Only at t = 0: afterwards every step stops `target` short, and an
      // overlap means target ≈ 0 met rounding; the previous normal stands.
      out.state = iteration == 1 ? toi_state::overlapping : toi_state::hit;
      out.t = t, out.distance = T(0), out.on_a = g.on_a, out.on_b = g.on_b;
      return out;
    }
    out.t = t, out.distance = g.distance, out.on_a = g.on_a, out.on_b = g.on_b;
    out.normal = normalize_or(g.on_b - g.on_a, out.normal);
    if (g.distance < options.target + options.tolerance) {
      out.state = toi_state::hit;
      return out;
    }
    const T bound = dot(out.normal, relative) + length(cross(out.normal, ma.angle)) * reach_a +
                    length(cross(out.normal, mb.angle)) * reach_b;
    const T remaining = g.distance - options.target;
    // The gap closes at most at `bound`: it cannot reach the target by t = 1.
    if (!(bound > T(0)) || !(remaining < bound * (T(1) - t))) {
      out.state = toi_state::separated;
      out.t = T(1);
      return out;
    }
    t += remaining / bound;
  }
  out.state = toi_state::failed;
  return out;
}

}  // namespace impulse::narrowphase
