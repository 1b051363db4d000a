// impulse/particles/plane_collider.hpp — oriented planes that particles bounce off.
//
// A plane is n·x + d ≥ 0 on its free side. An infinite plane is a half-space:
// a particle found behind it after the move is projected back onto it, which
// is exact at any speed because the whole space behind is solid. A finite
// rectangle is a thin board, solid from both sides: the segment a particle
// travelled this step is tested against it (a swept test), so a particle fast
// enough to cross the board within one step is still stopped. In both cases
// the contact then
//  - reflects the normal velocity with restitution e, only if the particle is
//    moving into the plane (one that already separates keeps its speed), and
//  - scales the tangential velocity by (1 − μ), a per-contact friction loss
//    (the model of the standard `particles` scene, not Coulomb's law: a
//    particle lying on a plane loses that fraction every step).
#pragma once

#include <cmath>
#include <cstdint>
#include <span>

#include "../math/scalar_traits.hpp"
#include "force.hpp"

namespace impulse::particles {

template <class T>
struct plane_collider {
  /// Unit normal pointing to the free side.
  vec3<T> normal{T(0), T(1), T(0)};
  /// d in n·x + d ≥ 0, m: the plane is at distance −d from the origin along n.
  T offset = T(0);
  /// e ∈ [0, 1]: the normal speed after a bounce over the speed before.
  T restitution = T(0.5);
  /// μ ∈ [0, 1]: the fraction of tangential velocity removed at each contact.
  T friction = T(0.2);

  /// A finite rectangle instead of a half-space: centered at `center` (on the
  /// plane), spanning ±half_u along axis_u and ±half_v along normal × axis_u.
  bool finite = false;
  vec3<T> center{};
  vec3<T> axis_u{T(1), T(0), T(0)};
  T half_u = T(0), half_v = T(0);

  /// The half-space n·x + d ≥ 0.
  static plane_collider half_space(const vec3<T>& n, T d, T restitution, T friction) {
    plane_collider p;
    p.normal = n;
    p.offset = d;
    p.restitution = restitution;
    p.friction = friction;
    return p;
  }
  /// A two-sided rectangle; axis_u must be a unit vector perpendicular to n.
  static plane_collider rectangle(const vec3<T>& center, const vec3<T>& n, const vec3<T>& axis_u,
                                  T half_u, T half_v, T restitution, T friction) {
    plane_collider p = half_space(n, -dot(n, center), restitution, friction);
    p.finite = true;
    p.center = center;
    p.axis_u = axis_u;
    p.half_u = half_u;
    p.half_v = half_v;
    return p;
  }

  /// Signed distance n·x + d, m: negative behind the plane.
  T distance(const vec3<T>& x) const noexcept { return dot(normal, x) + offset; }

  /// How far behind the plane rounding can leave a particle at x that was
  /// just projected onto it, m: s = n·x + d and x − s·n each round every
  /// term once, ~8ε·(|x| + |d|); this is twice that, plus 16ε of headroom
  /// near the origin. "No particle behind a plane" means distance(x) ≥ −rounding_at(x).
  T rounding_at(const vec3<T>& x) const noexcept {
    return T(16) * scalar_traits<T>::epsilon * (T(1) + std::abs(offset) + max_component(abs(x)));
  }

  void validate(std::uint32_t index = no_object) const {
    using detail::require;
    const T tolerance = scalar_traits<T>::unit_tolerance;
    detail::require_finite(normal, "plane_collider: normal is not finite", index);
    detail::require_finite(offset, "plane_collider: offset is not finite", index);
    require(length_squared(normal) > scalar_traits<T>::zero_length_squared, error_code::degenerate_shape,
            "plane_collider: normal has zero length", index);
    require(std::abs(length(normal) - T(1)) <= tolerance, error_code::not_normalized,
            "plane_collider: normal is not a unit vector", index);
    require(restitution >= T(0) && restitution <= T(1), error_code::invalid_parameter,
            "plane_collider: restitution is outside [0, 1]", index);
    require(friction >= T(0) && friction <= T(1), error_code::invalid_parameter,
            "plane_collider: friction is outside [0, 1]", index);
    if (!finite) return;
    detail::require_finite(center, "plane_collider: center is not finite", index);
    detail::require_finite(axis_u, "plane_collider: axis_u is not finite", index);
    require(std::isfinite(half_u) && std::isfinite(half_v) && half_u > T(0) && half_v > T(0),
            error_code::degenerate_shape, "plane_collider: a rectangle's half extents must be positive",
            index);
    require(std::abs(length(axis_u) - T(1)) <= tolerance &&
                std::abs(dot(axis_u, normal)) <= tolerance,
            error_code::not_normalized, "plane_collider: axis_u is not a unit vector in the plane", index);
    require(std::abs(dot(normal, center) + offset) <= tolerance * (T(1) + length(center)),
            error_code::invalid_parameter, "plane_collider: center is not on the plane", index);
  }
};

namespace detail {

/// Velocity after contact with a plane of unit normal n (facing the particle)
/// in the lanes of `touching`: the normal speed into the plane times −e
/// (`minus_restitution`), the tangential velocity times 1 − μ (`keep`).
/// Always inlined: as a call, its vector arguments go through memory (GCC
/// 12 outlines it otherwise).
template <class T, int W>
[[gnu::always_inline]] inline void plane_response(T minus_restitution, T keep, batch_mask<T, W> touching,
                                                  const vec3_batch<T, W>& n, vec3_batch<T, W>& v) noexcept {
  const batch<T, W> vn = dot(v, n);
  const vec3_batch<T, W> tangential = v - n * vn;
  const batch<T, W> zero = batch<T, W>::broadcast(T(0));
  const batch<T, W> vn_after = select(touching & (vn < zero), vn * minus_restitution, vn);
  const vec3_batch<T, W> answered = tangential * keep + n * vn_after;
  // The lanes not touching keep their v as it was: (v − n·vn) + n·vn is v
  // only to rounding, and whether a lane took that rounding would depend on
  // the other lanes of its batch, so on the width (lockstep determinism).
  v = {select(touching, answered.x, v.x), select(touching, answered.y, v.y), select(touching, answered.z, v.z)};
}

/// A half-space as the particle kernel uses it, made from a plane_collider
/// once a step: its normal and offset, −e, and 1 − μ (the tangential
/// velocity kept); `risky` when pushing a lane out of it can leave the lane
/// behind a plane checked before it (particle_system::prepare_planes).
/// `axis` is 0, 1 or 2 when the normal is ±1 along that axis and 0 along
/// the others (floors and walls), −1 otherwise.
template <class T>
struct half_space_rule {
  vec3<T> normal;
  T offset, minus_restitution, keep;
  bool risky;
  int axis;

  static half_space_rule of(const plane_collider<T>& plane, bool risky) noexcept {
    const vec3<T>& n = plane.normal;
    int axis = -1;
    for (int i = 0; i < 3; ++i)
      if (std::abs(n[i]) == T(1) && n[(i + 1) % 3] == T(0) && n[(i + 2) % 3] == T(0)) axis = i;
    return {n, plane.offset, -plane.restitution, T(1) - plane.friction, risky, axis};
  }
};

/// n·x + d. When the normal is ±1 along an axis this is ±x_i + d: one
/// fused multiply-add instead of a dot product's three products and an
/// add, and the same value, the other two products being zeros.
template <class T, int W>
[[gnu::always_inline]] inline batch<T, W> distance(const half_space_rule<T>& h,
                                                   const vec3_batch<T, W>& x) noexcept {
  switch (h.axis) {
    case 0: return x.x * h.normal.x + h.offset;
    case 1: return x.y * h.normal.y + h.offset;
    case 2: return x.z * h.normal.z + h.offset;
    default: return dot(x, vec3_batch<T, W>::broadcast(h.normal)) + h.offset;
  }
}

/// Half-space: lanes behind are projected onto the plane, and their
/// velocities answered (plane_response). Returns whether any was.
template <class T, int W>
[[gnu::always_inline]] inline bool collide_half_space(const half_space_rule<T>& h, vec3_batch<T, W>& x,
                                                      vec3_batch<T, W>& v) noexcept {
  const batch<T, W> s = distance(h, x);
  const batch<T, W> zero = batch<T, W>::broadcast(T(0));
  if (!any_less(s, zero)) return false;  // the common case, tested on the compare's own mask
  const batch_mask<T, W> behind = s < zero;
  const vec3_batch<T, W> n = vec3_batch<T, W>::broadcast(h.normal);
  const vec3_batch<T, W> projected = x - n * s;
  x = {select(behind, projected.x, x.x), select(behind, projected.y, x.y), select(behind, projected.z, x.z)};
  plane_response(h.minus_restitution, h.keep, behind, n, v);
  return true;
}

/// plane_collider::rounding_at for each lane.
template <class T, int W>
batch<T, W> rounding_at(const plane_collider<T>& plane, const vec3_batch<T, W>& x) noexcept {
  const batch<T, W> largest = max(max(abs(x.x), abs(x.y)), abs(x.z));
  return (largest + (T(1) + std::abs(plane.offset))) * (T(16) * scalar_traits<T>::epsilon);
}

template <class T, int W>
batch<T, W> distance(const plane_collider<T>& plane, const vec3_batch<T, W>& x) noexcept {
  return dot(x, vec3_batch<T, W>::broadcast(plane.normal)) + plane.offset;
}

/// Lanes behind the half-space by more than rounding.
template <class T, int W>
batch_mask<T, W> behind_half_space(const plane_collider<T>& plane, const vec3_batch<T, W>& x) noexcept {
  return distance(plane, x) < -rounding_at(plane, x);
}

/// Moves the lanes of `lanes_in` onto the line where planes a and b meet:
/// x' = x − α·n_a − β·n_b with n_a·x' + d_a = 0 = n_b·x' + d_b, i.e.
/// α = (s_a − c·s_b)/(1 − c²), β = (s_b − c·s_a)/(1 − c²), c = n_a·n_b.
/// The point of a crease nearest to a particle driven into it.
template <class T, int W>
void project_onto_crease(const plane_collider<T>& a, const plane_collider<T>& b, batch_mask<T, W> lanes_in,
                         vec3_batch<T, W>& x) noexcept {
  const T c = dot(a.normal, b.normal);
  const T inverse = T(1) / (T(1) - c * c);
  const batch<T, W> s_a = distance(a, x), s_b = distance(b, x);
  const batch<T, W> alpha = (s_a - s_b * c) * inverse, beta = (s_b - s_a * c) * inverse;
  const vec3_batch<T, W> moved = x - vec3_batch<T, W>::broadcast(a.normal) * alpha -
                                 vec3_batch<T, W>::broadcast(b.normal) * beta;
  x = {select(lanes_in, moved.x, x.x), select(lanes_in, moved.y, x.y), select(lanes_in, moved.z, x.z)};
}

/// Rectangle: lanes whose move x0 -> x crossed it within its extent are put
/// back on the side they came from, just off the surface, and respond.
template <class T, int W>
void collide_rectangle(const plane_collider<T>& plane, const vec3_batch<T, W>& x0,
                       vec3_batch<T, W>& x, vec3_batch<T, W>& v) noexcept {
  using lanes = batch<T, W>;
  const vec3_batch<T, W> n = vec3_batch<T, W>::broadcast(plane.normal);
  const lanes zero = lanes::broadcast(T(0));
  const lanes s0 = dot(x0, n) + plane.offset;
  const lanes s1 = dot(x, n) + plane.offset;
  // From the front, arriving on or behind the plane; or from behind, arriving
  // in front. A particle exactly on the plane counts as in front.
  const batch_mask<T, W> crossed = ((s0 >= zero) & (s1 < zero)) | ((s0 < zero) & (s1 >= zero));
  if (none(crossed)) return;
  const lanes t = select(crossed, s0 / (s0 - s1), zero);
  vec3_batch<T, W> p = x0 + (x - x0) * t;
  p = p - n * (dot(p, n) + plane.offset);  // onto the plane, to rounding
  const vec3_batch<T, W> r = p - vec3_batch<T, W>::broadcast(plane.center);
  const vec3<T> axis_v = cross(plane.normal, plane.axis_u);
  const batch_mask<T, W> inside = (abs(dot(r, vec3_batch<T, W>::broadcast(plane.axis_u))) <= lanes::broadcast(plane.half_u)) &
                                  (abs(dot(r, vec3_batch<T, W>::broadcast(axis_v))) <= lanes::broadcast(plane.half_v));
  const batch_mask<T, W> hit = crossed & inside;
  if (none(hit)) return;
  // The side it came from, and a skin that keeps it strictly on that side:
  // 16 roundings of the largest coordinate on the board, so that the next
  // step's s0 has the right sign however far the particle then moves.
  const lanes side = select(s0 >= zero, lanes::broadcast(T(1)), lanes::broadcast(T(-1)));
  const vec3_batch<T, W> n_side = n * side;
  const T skin = T(16) * scalar_traits<T>::epsilon *
                 (T(1) + max_component(abs(plane.center)) + plane.half_u + plane.half_v);
  const vec3_batch<T, W> placed = p + n_side * skin;
  x = {select(hit, placed.x, x.x), select(hit, placed.y, x.y), select(hit, placed.z, x.z)};
  plane_response(-plane.restitution, T(1) - plane.friction, hit, n_side, v);
}

/// Lanes that the half-spaces' projections left behind one of them: those
/// in a crease of two (crease[a * planes + b]: not parallel) onto the line
/// where the two meet, and any still behind one back to where they started
/// the step (x0, which was inside), stopped.
template <class T, int W>
void settle_creases(std::span<const plane_collider<T>> planes, const unsigned char* crease,
                    const vec3_batch<T, W>& x0, vec3_batch<T, W>& x, vec3_batch<T, W>& v) noexcept {
  using lanes = batch<T, W>;
  // Projecting onto one half-space can push a particle back behind another
  // that meets it at an acute angle (a crease). Cyclic projection would
  // converge there only geometrically, by cos² of the angle per sweep, so
  // a lane still behind plane a while on or behind plane b is moved
  // straight onto the line where the two meet.
  bool residual = false;
  for (std::size_t a = 0; a < planes.size(); ++a) {
    if (planes[a].finite) continue;
    batch_mask<T, W> behind_a = behind_half_space(planes[a], x);
    if (none(behind_a)) continue;
    residual = true;
    for (std::size_t b = 0; b < planes.size() && any(behind_a); ++b) {
      if (b == a || planes[b].finite || !crease[a * planes.size() + b]) continue;
      const batch_mask<T, W> on_b = !(distance(planes[b], x) > rounding_at(planes[b], x));
      const batch_mask<T, W> in_crease = behind_a & on_b;
      if (none(in_crease)) continue;
      project_onto_crease(planes[a], planes[b], in_crease, x);
      behind_a = behind_a & !in_crease;
    }
  }
  if (!residual) return;  // the common case: one sweep settled every lane
  // Three or more planes meeting at a corner can still leave a lane
  // behind one: it goes back to where it started the step, which was
  // inside, and stops there. "No particle behind a plane" holds always.
  const lanes zero = lanes::broadcast(T(0));
  batch_mask<T, W> behind = zero < zero, was_behind = behind;
  for (const plane_collider<T>& plane : planes)
    if (!plane.finite) {
      behind = behind | behind_half_space(plane, x);
      was_behind = was_behind | behind_half_space(plane, x0);
    }
  const batch_mask<T, W> revert = behind & !was_behind;
  if (none(revert)) return;
  x = {select(revert, x0.x, x.x), select(revert, x0.y, x.y), select(revert, x0.z, x.z)};
  v = {select(revert, zero, v.x), select(revert, zero, v.y), select(revert, zero, v.z)};
}

}  // namespace detail
}  // namespace impulse::particles
