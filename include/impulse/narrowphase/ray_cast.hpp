// impulse/narrowphase/ray_cast.hpp — where a ray first meets a shape.
//
// The ray is impulse::ray (math/ray.hpp), as the broad phases take
// it: the segment origin + t·translation for t in [0, max_fraction], as in
// Box2D's b2RayCastInput. Every `ray_cast(ray, shape, pose, max_fraction)`
// returns a ray_hit: the fraction t of the first point of the shape on the
// segment, that point, the unit normal of the surface there (pointing out
// of the shape), and a feature id. Internally each cast works with the unit
// direction and distances along it (again as Box2D does), so that a short
// or a long translation costs no accuracy, and turns the distance back into
// a fraction at the end.
//
// Conventions, the same for every shape:
// - The shapes are closed solids. A ray whose origin lies inside one, or on
//   its surface, hits at fraction 0, at its origin, with the normal minus
//   its direction (as Box2D's and Jolt's casts against solid convex shapes
//   do): the caller learns that it starts inside, and a normal that is at
//   least unit and finite. A triangle has no inside (see below).
// - Grazing counts: a ray that runs along a face or an edge touches the
//   closed shape, and hits where it first touches it.
// - Degenerate input is a miss, never NaN: a non-finite origin or
//   translation, a translation of zero length (or one whose length squared
//   underflows or overflows T), a max_fraction that is negative or NaN.
//   max_fraction may be +∞ (a ray without end).
//
// Per shape:
// - sphere: the quadratic in the distance along the unit direction, with
//   the discriminant taken from the distance of the center from the ray's
//   line rather than as b² − c, which cancels catastrophically once the
//   origin is far from the sphere compared with its radius (Haines et al.,
//   "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems,
//   2019).
// - box: the slab test in the box's frame (Kay and Kajiya 1986; Ericson,
//   "Real-Time Collision Detection", §5.3.3). Feature: the face, named as
//   analytic.hpp names box features, one base-3 digit per axis (1 for the
//   face at −h, 2 at +h): −x 1, +x 2, −y 3, +y 6, −z 9, +z 18.
// - capsule: exact, in its frame: the infinite cylinder about the core
//   segment, kept where its hit lies between the caps, and the two cap
//   balls; the first of the three (a ray through a flat end of the finite
//   cylinder has met that end's ball before). Feature: 0 the cap at −h, 1
//   the cap at +h (the cap centers' ids in analytic.hpp), 2 the side.
// - plane: one-sided, solid below its surface. A ray from below starts
//   inside; one from above hits if it moves down.
// - convex hull: the ray clipped against every face plane (Cyrus and Beck
//   1978; Ericson §5.3.8): the last plane it enters through is the face it
//   hits. Feature: that face's index.
// - triangle (ray_cast_triangle): Möller and Trumbore ("Fast, minimum
//   storage ray/triangle intersection", 1997), both sides. The normal faces
//   the ray's origin, and the feature says which side was hit: 0 the front
//   (the side the corners a, b, c turn counter-clockwise on, a mesh's free
//   side), 1 the back, so a mesh cast that wants one side drops the other.
//   Barycentric weights of a, b, c come with the hit. A ray in the
//   triangle's plane misses it (it has no area to cross). Not watertight: a
//   ray through an edge shared by two triangles hits both in exact
//   arithmetic, but rounding can let it through between them by an ulp;
//   a mesh cast that must not leak wants Woop, Benthin and Wald's
//   watertight test (2013).
// - anything with a support function (gjk_ray_cast): GJK ray casting (van
//   den Bergen, "Ray Casting against General Convex Objects with
//   Application to Continuous Collision Detection", JGT 2004). It keeps a
//   point x on the ray, starting at the origin, and GJK's simplex of
//   support points of the shape seen from x. While a support plane (normal
//   v, x's offset from the shape's nearest simplex point) has x strictly in
//   front, x cannot be inside: it moves forward onto that plane, or, if the
//   ray does not approach the plane, the ray misses. When x stands on the
//   shape (the simplex's nearest point within a relative tolerance of x),
//   the last plane moved to is the surface's, and its normal the hit's.
//   Spheres and capsules enter, as in gjk.hpp, as their cores (a point, a
//   segment) grown by the radius: x moves onto a plane at the radius from
//   the core's support plane, and stands on the shape once its distance
//   from the core is the radius, so that these end in a few iterations
//   rather than crawling over a curved surface. The arithmetic runs in
//   double, as in gjk.hpp. x stands on a polytope once the simplex's
//   nearest point is within 1e-7 (float) or 1e-12 (double) of the
//   simplex's size, and on a rounded shape once its distance from the core
//   is the radius to 8 double ulps; at most 64 iterations. On a face, x
//   finally steps onto the plane through the three support points, exact
//   to rounding, rather than stopping where GJK's nearest point became too
//   short to have a reliable direction. Against the analytic casts on
//   10 000 random rays (tests/narrowphase/test_ray_cast.cpp) the hit
//   agrees to 5e-7 (float: the analytic casts' own rounding) and 5e-15
//   (double) of 1 m plus the origin's distance, in at most 11 iterations.
//
// No call allocates.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "../math/ray.hpp"
#include "../math/scalar_traits.hpp"
#include "../math/transform.hpp"
#include "../shapes/box.hpp"
#include "../shapes/capsule.hpp"
#include "../shapes/convex_hull.hpp"
#include "../shapes/plane.hpp"
#include "../shapes/sphere.hpp"
#include "gjk.hpp"
#include "tolerances.hpp"

namespace impulse::narrowphase {

template <scalar_type T>
struct ray_hit {
  bool hit = false;
  /// Of the ray's translation, in [0, max_fraction]: point = origin + fraction·translation.
  T fraction = T(0);
  vec3<T> point{};   ///< world, m: where the ray first meets the shape
  vec3<T> normal{};  ///< world, unit: out of the shape (a triangle's: towards the ray's origin)
  /// Which part was hit: a box's face, a capsule's cap or side, a hull's
  /// face index, a triangle's side (see the top of this file); 0 otherwise.
  std::uint32_t feature = 0;
  vec3<T> barycentric{};  ///< triangles only: the weights of a, b, c at the point

  explicit constexpr operator bool() const noexcept { return hit; }
};

namespace detail {

/// A ray as unit direction and distances along it.
template <scalar_type T>
struct unit_ray {
  vec3<T> origin;
  vec3<T> direction;  ///< unit
  T length;           ///< m: of the translation, > 0 and finite
  T max_fraction;     ///< ≥ 0, may be +∞
  T max_distance;     ///< m: max_fraction·length, may be +∞
};

/// False for a ray that is a miss by the rules above (not finite, no
/// length, a negative or NaN max_fraction).
template <scalar_type T>
bool prepare_ray(const ray<T>& r, T max_fraction, unit_ray<T>& out) noexcept {
  if (!is_finite(r.origin) || !is_finite(r.translation) || !(max_fraction >= T(0))) return false;
  const T length = impulse::length(r.translation);
  if (!(length > T(0)) || !std::isfinite(length)) return false;
  out = {r.origin, r.translation / length, length, max_fraction, max_fraction * length};
  return true;
}

/// The hit at distance s along the ray (s ≤ max_distance), with a world normal.
template <scalar_type T>
ray_hit<T> hit_at(const unit_ray<T>& r, T s, const vec3<T>& normal, std::uint32_t feature) noexcept {
  ray_hit<T> h;
  h.hit = true;
  // s ≤ max_fraction·length, but the quotient may round an ulp past it.
  h.fraction = std::min(s / r.length, r.max_fraction);
  h.point = r.origin + r.direction * s;
  h.normal = normal;
  h.feature = feature;
  return h;
}

/// The convention for an origin inside (or on) a solid shape.
template <scalar_type T>
ray_hit<T> hit_inside(const unit_ray<T>& r, std::uint32_t feature = 0) noexcept {
  return hit_at(r, T(0), -r.direction, feature);
}

/// The distance along the unit direction u at which a ray from o, outside
/// the ball (center c, radius radius), enters it; negative for none.
/// The discriminant is radius² less the squared distance of the center
/// from the ray's line, taken from the perpendicular itself (see the top of
/// this file for why).
template <scalar_type T>
T ball_entry(const vec3<T>& o, const vec3<T>& u, const vec3<T>& c, T radius) noexcept {
  const vec3<T> m = o - c;
  const T b = dot(m, u);
  if (b > T(0)) return T(-1);  // moving away from a ball it is outside of
  const vec3<T> perpendicular = m - u * b;
  const T e = radius * radius - length_squared(perpendicular);
  if (e < T(0)) return T(-1);
  return std::max(T(0), -b - std::sqrt(e));  // ≥ 0 in exact arithmetic: the origin is outside
}

/// Cyrus–Beck clipping of a ray (origin o, unit direction u, in the
/// shape's frame) against convex planes n·x + offset ≤ 0: the distance at
/// which it enters and the index of the plane it enters through (−1 when
/// the origin is inside all of them), or false when it misses.
template <scalar_type T, class PlaneAt>
bool clip_against_planes(const vec3<T>& o, const vec3<T>& u, T max_distance, int count, PlaneAt&& plane_at,
                         T& enter, int& face) noexcept {
  enter = -std::numeric_limits<T>::infinity();
  T leave = max_distance;
  face = -1;
  for (int f = 0; f < count; ++f) {
    vec3<T> n;
    T offset;
    plane_at(f, n, offset);
    const T height = dot(n, o) + offset;  // of the origin above the plane
    const T approach = dot(n, u);
    if (approach == T(0)) {
      if (height > T(0)) return false;  // parallel, outside
      continue;
    }
    // A division rather than a product with 1/approach: a tiny approach
    // then gives ±∞ or a large number, never 0·∞ = NaN.
    const T s = -height / approach;
    if (approach < T(0)) {
      if (s > enter) enter = s, face = f;
    } else if (s < leave) {
      leave = s;
    }
    if (enter > leave) return false;
  }
  return leave >= T(0);  // else the whole shape lies behind the origin
}

}  // namespace detail

// ---- sphere ---------------------------------------------------------------

template <scalar_type T>
ray_hit<T> ray_cast(const ray<T>& r, const sphere<T>& s, const transform<T>& pose, T max_fraction = T(1)) noexcept {
  detail::unit_ray<T> u;
  if (!detail::prepare_ray(r, max_fraction, u)) return {};
  const vec3<T>& c = pose.position;
  if (length_squared(u.origin - c) <= s.radius * s.radius) return detail::hit_inside(u);
  const T d = detail::ball_entry(u.origin, u.direction, c, s.radius);
  if (d < T(0) || d > u.max_distance) return {};
  return detail::hit_at(u, d, normalize_or(u.origin + u.direction * d - c, -u.direction), 0u);
}

// ---- box ------------------------------------------------------------------

template <scalar_type T>
ray_hit<T> ray_cast(const ray<T>& r, const box<T>& b, const transform<T>& pose, T max_fraction = T(1)) noexcept {
  detail::unit_ray<T> u;
  if (!detail::prepare_ray(r, max_fraction, u)) return {};
  const vec3<T> o = inverse_apply(pose, u.origin), d = inverse_apply_direction(pose, u.direction);
  const vec3<T>& h = b.half_extents;
  // The six faces as planes ±x_axis − h_axis ≤ 0: plane 2·axis is the face
  // at −h, 2·axis + 1 the face at +h.
  T enter;
  int face;
  const bool crosses = detail::clip_against_planes(o, d, u.max_distance, 6, [&](int f, vec3<T>& n, T& offset) {
    n = {};
    n[f / 2] = (f & 1) ? T(1) : T(-1);
    offset = -h[f / 2];
  }, enter, face);
  if (!crosses) return {};
  if (face < 0 || enter <= T(0)) return detail::hit_inside(u);
  vec3<T> n{};
  const int axis = face / 2;
  n[axis] = (face & 1) ? T(1) : T(-1);
  std::uint32_t feature = (face & 1) ? 2u : 1u;
  for (int k = 0; k < axis; ++k) feature *= 3;
  return detail::hit_at(u, enter, apply_direction(pose, n), feature);
}

// ---- capsule --------------------------------------------------------------

template <scalar_type T>
ray_hit<T> ray_cast(const ray<T>& r, const capsule<T>& c, const transform<T>& pose, T max_fraction = T(1)) noexcept {
  detail::unit_ray<T> u;
  if (!detail::prepare_ray(r, max_fraction, u)) return {};
  const vec3<T> o = inverse_apply(pose, u.origin), d = inverse_apply_direction(pose, u.direction);
  const T radius = c.radius, h = c.half_height;
  // Inside: within the radius of the core segment.
  const vec3<T> core{T(0), std::clamp(o.y, -h, h), T(0)};
  if (length_squared(o - core) <= radius * radius) return detail::hit_inside(u);

  T best = std::numeric_limits<T>::infinity();
  vec3<T> normal{};
  std::uint32_t feature = 0;
  // The side: the infinite cylinder x² + z² = r², in the xz-plane, with
  // the discriminant again from the line's distance from the axis.
  const T a = d.x * d.x + d.z * d.z;  // the direction's squared length across the axis
  if (a > T(0)) {
    const T closest = -(o.x * d.x + o.z * d.z) / a;  // along the ray, nearest the axis
    const T px = o.x + d.x * closest, pz = o.z + d.z * closest;
    const T e = radius * radius - (px * px + pz * pz);
    if (e >= T(0)) {
      const T s = closest - std::sqrt(e / a);
      const T y = o.y + d.y * s;
      if (s >= T(0) && std::abs(y) <= h) {
        best = s, feature = 2;
        normal = normalize_or(vec3<T>{o.x + d.x * s, T(0), o.z + d.z * s}, -d);
      }
    }
  }
  // The caps: the first entry into either ball.
  for (std::uint32_t k = 0; k < 2; ++k) {
    const vec3<T> center{T(0), k == 0 ? -h : h, T(0)};
    const T s = detail::ball_entry(o, d, center, radius);
    if (s >= T(0) && s < best) best = s, feature = k, normal = normalize_or(o + d * s - center, -d);
  }
  if (!(best <= u.max_distance)) return {};
  return detail::hit_at(u, best, apply_direction(pose, normal), feature);
}

// ---- plane ----------------------------------------------------------------

template <scalar_type T>
ray_hit<T> ray_cast(const ray<T>& r, const plane<T>& p, const transform<T>& pose, T max_fraction = T(1)) noexcept {
  detail::unit_ray<T> u;
  if (!detail::prepare_ray(r, max_fraction, u)) return {};
  const vec3<T> n = apply_direction(pose, p.normal);
  const T height = dot(n, u.origin - pose.position) + p.offset;  // of the origin above the surface
  if (height <= T(0)) return detail::hit_inside(u);
  const T approach = dot(n, u.direction);
  if (!(approach < T(0))) return {};  // parallel or moving up
  const T s = -height / approach;
  if (!(s <= u.max_distance)) return {};
  return detail::hit_at(u, s, n, 0u);
}

// ---- convex hull ----------------------------------------------------------

template <scalar_type T>
ray_hit<T> ray_cast(const ray<T>& r, const convex_hull<T>& hull, const transform<T>& pose,
                    T max_fraction = T(1)) noexcept {
  detail::unit_ray<T> u;
  if (!detail::prepare_ray(r, max_fraction, u)) return {};
  const vec3<T> o = inverse_apply(pose, u.origin), d = inverse_apply_direction(pose, u.direction);
  T enter;
  int face;
  const bool crosses = detail::clip_against_planes(o, d, u.max_distance, int(hull.face_count()),
                                                   [&](int f, vec3<T>& n, T& offset) {
                                                     const auto& pl = hull.plane(std::size_t(f));
                                                     n = pl.normal, offset = pl.offset;
                                                   },
                                                   enter, face);
  if (!crosses) return {};
  if (face < 0 || enter <= T(0)) return detail::hit_inside(u);
  return detail::hit_at(u, enter, apply_direction(pose, hull.plane(std::size_t(face)).normal), std::uint32_t(face));
}

// ---- triangle -------------------------------------------------------------

/// The ray against the triangle a, b, c (world space), both sides; see the
/// top of this file for the normal, the feature and the barycentric weights.
template <scalar_type T>
ray_hit<T> ray_cast_triangle(const ray<T>& r, const vec3<T>& a, const vec3<T>& b, const vec3<T>& c,
                             T max_fraction = T(1)) noexcept {
  detail::unit_ray<T> u;
  if (!detail::prepare_ray(r, max_fraction, u)) return {};
  const vec3<T> e1 = b - a, e2 = c - a;
  const vec3<T> p = cross(u.direction, e2);
  const T det = dot(e1, p);  // = −direction·(e1 × e2): > 0 when the ray meets the front
  // Parallel to the plane, relative to the triangle's size (det is a
  // triple product of the unit direction and the two edges).
  if (!(std::abs(det) > scalar_traits<T>::epsilon * length(e1) * length(e2))) return {};
  const vec3<T> to_origin = u.origin - a;
  const T beta = dot(to_origin, p) / det;
  if (!(beta >= T(0) && beta <= T(1))) return {};
  const vec3<T> q = cross(to_origin, e1);
  const T gamma = dot(u.direction, q) / det;
  if (!(gamma >= T(0) && beta + gamma <= T(1))) return {};
  const T s = dot(e2, q) / det;
  if (!(s >= T(0) && s <= u.max_distance)) return {};
  const vec3<T> front = normalize_or(cross(e1, e2), -u.direction);
  ray_hit<T> h = detail::hit_at(u, s, det > T(0) ? front : -front, det > T(0) ? 0u : 1u);
  h.barycentric = {T(1) - beta - gamma, beta, gamma};
  return h;
}

// ---- any convex shape with a support function ---------------------------

namespace detail {

template <scalar_type T>
struct gjk_ray_cast_result {
  ray_hit<T> hit;
  int iterations = 0;
};

template <class Shape, scalar_type T>
gjk_ray_cast_result<T> run_gjk_ray_cast(const ray<T>& r, const Shape& shape, const transform<T>& pose,
                                        T max_fraction, T grown = T(0)) noexcept {
  gjk_ray_cast_result<T> out;
  unit_ray<T> ur;
  if (!prepare_ray(r, max_fraction, ur)) return out;
  // In double whatever T is, as GJK (gjk.hpp).
  using R = double;
  constexpr R epsilon = tolerances<T>::ray_gjk_tolerance;
  constexpr int max_iterations = 64;
  const vec3<R> o = wide(ur.origin), u = wide(ur.direction);
  const R radius = R(core_radius<T>(shape)) + R(grown);
  const R max_distance = R(ur.max_distance);

  R lambda = 0;         // m along the ray: x = o + u·λ
  vec3<R> x = o;
  vec3<R> plane{};      // the normal of the last support plane x moved onto
  // Any first direction will do: a support plane along it either has x
  // behind it or is a valid plane to move onto.
  vec3<R> v = x - wide(pose.position);
  if (!(length_squared(v) > R(0))) v = -u;
  bool v_from_simplex = false;  // whether v is the simplex's nearest point seen from this x
  simplex<R> s;                 // s.a: the shape's support points; s.w: x less them
  bool stands = false;          // x is on (or in) the shape
  for (int iteration = 1; iteration <= max_iterations && !stands; ++iteration) {
    out.iterations = iteration;
    const vec3<R> p = wide(world_core_support(shape, pose, narrow<T>(v)));
    const R v_length = length(v);
    // x's height above the support plane along v, times |v|.
    const R height = dot(v, x - p) - radius * v_length;
    bool moved = false;
    if (height > R(0)) {
      const R approach = dot(v, u);
      if (!(approach < R(0))) return out;  // in front of the plane and not closing on it: a miss
      lambda -= height / approach;
      if (!(lambda <= max_distance)) return out;
      x = o + u * lambda;
      plane = v;
      moved = true;
      v_from_simplex = false;
    }
    bool repeated = false;
    for (int k = 0; k < s.size; ++k) repeated = repeated || s.a[k] == p;
    // A support point already in the simplex, with x not moved: v is the
    // simplex's nearest point, so v·(x − p) ≥ |v|² > 0 unless v is down to
    // rounding, and x stands on the shape.
    if (repeated && !moved) {
      stands = true;
      break;
    }
    if (!repeated) s.a[s.size] = p, ++s.size;
    for (int k = 0; k < s.size; ++k) s.w[k] = x - s.a[k];
    const vec3<R> next = s.reduce();
    R size2 = R(0);
    for (int k = 0; k < s.size; ++k) size2 = std::max(size2, length_squared(s.w[k]));
    // Around a core, |v| ≈ radius is not small, and its rounding (not the
    // tolerance) limits how closely x can be put at the radius: it steps on
    // to a few ulps of it, in about as many more iterations.
    const R tolerance =
        (radius > R(0) ? R(tolerances<T>::ray_rounded_tolerance) : epsilon) * (std::sqrt(size2) + radius);
    // x stands on the shape: inside the simplex (a tetrahedron round the
    // origin), or within the tolerance of the radius from the core.
    if (s.size == 4 || length(next) <= radius + tolerance) stands = true;
    // At one x, GJK's nearest point only comes closer; when it does not,
    // it is the nearest within rounding, and x has not been moved off it.
    if (!stands && v_from_simplex && !(length_squared(next) < length_squared(v))) stands = true;
    v = next;
    v_from_simplex = true;
    if (length_squared(v) == R(0)) stands = true;
  }
  R size2 = R(0);
  for (int k = 0; k < s.size; ++k) size2 = std::max(size2, length_squared(s.w[k]));
  const R size = std::sqrt(size2) + radius;
  // Out of iterations (a curved surface known only by its support
  // function, crawled over): x is still conservative, in front of the
  // shape; it counts as a hit only if within a looser tolerance.
  if (!stands && !(length(v) <= radius + std::sqrt(epsilon) * size)) return out;
  if (lambda == R(0)) {
    out.hit = hit_inside(ur);
    return out;
  }
  if (radius == R(0) && s.size == 3) {
    // On a polytope's face, GJK stalls once v is down to about 1e4 times
    // its own rounding (ε·size): v·w no longer tells x's side of the plane,
    // so x stays up to that far in front of the face (1e-12 of the size in
    // double). The face's plane through the three support points
    // themselves, with no x in it, is exact to rounding: if it supports the
    // shape, x steps onto it, and its normal is the hit's.
    vec3<R> n = cross(s.a[1] - s.a[0], s.a[2] - s.a[0]);
    if (dot(n, plane) < R(0)) n = -n;
    const R n_length = length(n);
    if (n_length > R(0)) {
      n = n / n_length;
      const vec3<R> p = wide(world_core_support(shape, pose, narrow<T>(n)));
      const R height = dot(n, x - s.a[0]), approach = dot(n, u);
      const R face_tolerance = tolerances<T>::ray_face_tolerance * size;
      if (dot(n, p - s.a[0]) <= face_tolerance && approach < R(0) && std::abs(height) <= length(v) + epsilon * size) {
        lambda = std::clamp(lambda - height / approach, R(0), max_distance);
        plane = n;
      }
    }
  }
  // A rounded shape's normal is x's offset from its core; a polytope's the
  // plane x last moved onto, which at a face is the face's plane.
  const vec3<R> n = radius > R(0) && length_squared(v) > R(0) ? v : plane;
  const vec3<T> normal = normalize_or(narrow<T>(n / length(n)), -ur.direction);
  out.hit = hit_at(ur, T(lambda), normal, 0u);
  return out;
}

}  // namespace detail

/// The ray against any convex shape with a `support(direction)` in its own
/// frame, at pose, by GJK ray casting (see the top of this file).
template <class Shape, scalar_type T>
ray_hit<T> gjk_ray_cast(const ray<T>& r, const Shape& shape, const transform<T>& pose,
                        T max_fraction = T(1)) noexcept {
  return detail::run_gjk_ray_cast(r, shape, pose, max_fraction).hit;
}

/// Where a ball of `radius` whose center moves along the ray first touches
/// the shape: the ray against the shape grown by the radius (its core
/// grown, for GJK's rounded-shape case above), exact to the same
/// tolerance. The hit's point is the ball's center there, the normal the
/// grown surface's. A continuous collision stage sweeps spheres this way.
template <class Shape, scalar_type T>
ray_hit<T> sphere_cast(const ray<T>& r, T radius, const Shape& shape, const transform<T>& pose,
                       T max_fraction = T(1)) noexcept {
  return detail::run_gjk_ray_cast(r, shape, pose, max_fraction, radius).hit;
}
template <scalar_type T>
ray_hit<T> sphere_cast(const ray<T>& r, T radius, const plane<T>& p, const transform<T>& pose,
                       T max_fraction = T(1)) noexcept {
  return ray_cast(r, plane<T>{p.normal, p.offset - radius}, pose, max_fraction);
}

}  // namespace impulse::narrowphase
