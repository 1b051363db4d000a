// Ray casts: each shape against closed forms (head on, grazing edges and
// corners, parallel to faces, from inside, far from the origin, tiny and
// huge shapes, degenerate rays), thousands of random rays against an
// independent reference (the first root of the shape's signed distance
// along the ray, found by bisection in long double), a hull built from a
// box's corners against the box, and GJK ray casting against every
// analytic cast.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "impulse/core/random.hpp"
#include "impulse/narrowphase/ray_cast.hpp"
#include "impulse/shapes/convex_hull.hpp"

#include "poses.hpp"

namespace narrowphase_ray_cast_tests {

namespace {

using namespace impulse;
using narrowphase::gjk_ray_cast;
using narrowphase::ray_cast;
using narrowphase::ray_cast_triangle;
using test::at;
using test::random_rotation;

/// Closed-form cases: a few roundings of the inputs' size (1 m) in T.
template <class T>
constexpr T tolerance = sizeof(T) == 4 ? T(2e-6) : T(1e-14);

template <class T>
bool finite_hit(const narrowphase::ray_hit<T>& h) {
  return std::isfinite(h.fraction) && is_finite(h.point) && is_finite(h.normal);
}

template <class T>
convex_hull<T> box_hull(const vec3<T>& h) {
  return convex_hull<T>::from_points(test::box_corners(h));
}

// ---- the reference, in long double ----------------------------------------

using L = long double;
struct lvec {
  L x = 0, y = 0, z = 0;
};
lvec operator+(lvec a, lvec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
lvec operator-(lvec a, lvec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
lvec operator*(lvec a, L s) { return {a.x * s, a.y * s, a.z * s}; }
L dot(lvec a, lvec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
lvec cross(lvec a, lvec b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
L norm(lvec a) { return std::sqrt(dot(a, a)); }
template <class T>
lvec wide(const vec3<T>& v) {
  return {L(v.x), L(v.y), L(v.z)};
}

template <class T>
vec3<T> narrow(const lvec& v) {
  return {T(v.x), T(v.y), T(v.z)};
}

/// A world ray seen from a shape's frame, in long double: the origin and
/// the unit direction.
struct local_ray {
  lvec origin, direction;
  L length;  // of the translation
};
template <class T>
local_ray to_local(const ray<T>& r, const transform<T>& pose) {
  const lvec u{L(pose.rotation.x), L(pose.rotation.y), L(pose.rotation.z)};
  const L w = L(pose.rotation.w);
  const auto inverse_rotate = [&](lvec v) {  // by the conjugate: u -> −u
    const lvec t = cross(u * L(-1), v) * L(2);
    return v + t * w + cross(u * L(-1), t);
  };
  const lvec d = wide(r.translation);
  const L length = norm(d);
  return {inverse_rotate(wide(r.origin) - wide(pose.position)), inverse_rotate(d * (L(1) / length)), length};
}

/// The first distance along the ray at which the convex function f (a
/// signed distance, ≤ 0 inside) reaches 0, in [0, max_distance]; nothing
/// when f stays positive. `margin` is set to the minimum of f over the
/// segment, so that a caller can skip grazing rays that no finite
/// precision decides. f is convex along a line, so a ternary search finds
/// its minimum and a bisection before it the entry.
template <class F>
std::optional<L> reference_entry(F f, const local_ray& r, L max_distance, L& minimum) {
  const auto g = [&](L s) { return f(r.origin + r.direction * s); };
  minimum = g(0);
  if (minimum <= 0) return L(0);
  L lo = 0, hi = max_distance;
  for (int k = 0; k < 400 && hi - lo > 0; ++k) {
    const L m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (g(m1) < g(m2)) hi = m2;
    else lo = m1;
  }
  const L lowest = (lo + hi) / 2;
  minimum = g(lowest);
  if (minimum > 0) return std::nullopt;
  L a = 0, b = lowest;
  for (int k = 0; k < 200; ++k) {
    const L m = (a + b) / 2;
    if (g(m) > 0) a = m;
    else b = m;
  }
  return b;
}

L box_distance(lvec p, lvec h) {
  const lvec q{std::abs(p.x) - h.x, std::abs(p.y) - h.y, std::abs(p.z) - h.z};
  const lvec outside{std::max(q.x, L(0)), std::max(q.y, L(0)), std::max(q.z, L(0))};
  return norm(outside) + std::min(std::max(q.x, std::max(q.y, q.z)), L(0));
}
L capsule_distance(lvec p, L radius, L h) {
  const lvec core{0, std::clamp(p.y, -h, h), 0};
  return norm(p - core) - radius;
}

/// What the random tests measure.
struct agreement {
  int compared = 0, skipped = 0, disagreed = 0;
  double worst = 0;         // |Δs|·|cos θ| / scale: the hit's error across the surface
  double worst_normal = 0;  // 1 − n·n_ref
};

template <class T>
void compare_with_reference(agreement& a, const narrowphase::ray_hit<T>& h, std::optional<L> expected, L minimum,
                            L scale, const local_ray& r, L max_distance, const lvec& normal_in_shape_frame,
                            const transform<T>& pose, bool check_normal) {
  // Grazing rays (the segment's nearest approach within rounding of the
  // surface) and hits within rounding of the segment's end are undecided.
  const L undecided = (sizeof(T) == 4 ? L(1e-4) : L(1e-10)) * scale;
  if (std::abs(minimum) < undecided || (expected && std::abs(*expected - max_distance) < undecided)) {
    ++a.skipped;
    return;
  }
  ++a.compared;
  if (h.hit != expected.has_value()) {
    ++a.disagreed;
    return;
  }
  CHECK(finite_hit(h));
  if (!h.hit) return;
  const L s = L(h.fraction) * r.length;
  if (*expected == 0) {  // inside
    CHECK(h.fraction == T(0));
    return;
  }
  const lvec n_world = wide(apply_direction(pose, narrow<T>(normal_in_shape_frame)));
  const L cosine = std::abs(dot(n_world, wide(apply_direction(pose, narrow<T>(r.direction)))));
  a.worst = std::max(a.worst, double(std::abs(s - *expected) * cosine / scale));
  if (check_normal) a.worst_normal = std::max(a.worst_normal, double(1 - dot(wide(h.normal), n_world)));
}

/// A random ray aimed near a point, from up to `spread` away from it,
/// sometimes starting inside.
template <class T>
ray<T> random_ray(lcg32& random, const vec3<T>& near, T size, T spread) {
  const auto in = [&](T r) { return vec3<T>{random.uniform<T>(-r, r), random.uniform<T>(-r, r), random.uniform<T>(-r, r)}; };
  const vec3<T> origin = near + in(spread);
  const vec3<T> aim = near + in(T(1.5) * size);
  return {origin, (aim - origin) * random.uniform<T>(T(0.3), T(2))};
}

/// A ball known only by its support function: GJK ray casting must crawl
/// over its curved surface.
template <class T>
struct support_only_ball {
  T radius;
  vec3<T> support(const vec3<T>& d) const { return normalize_or(d, vec3<T>::unit_x()) * radius; }
  aabb<T> local_aabb() const { return aabb<T>::from_center_half_extents({}, vec3<T>::splat(radius)); }
};

}  // namespace

// ---- closed forms -----------------------------------------------------------

TEST_CASE_TEMPLATE("ray cast: a sphere head on and at an angle and grazed and missed", T, float, double) {
  const sphere<T> ball{T(0.5)};
  const transform<T> pose = at<T>({1, 2, 3});
  // Head on along −x from 3 m: enters at 2.5 m, fraction 2.5/4.
  auto h = ray_cast(ray<T>{{4, 2, 3}, {-4, 0, 0}}, ball, pose);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(0.625).epsilon(tolerance<T>));
  CHECK(length(h.point - vec3<T>{T(1.5), 2, 3}) <= tolerance<T> * 4);
  CHECK(length(h.normal - vec3<T>::unit_x()) <= tolerance<T>);
  // Offset by 0.3 across: enters at 3 − √(0.25 − 0.09) = 2.6 m along the ray.
  h = ray_cast(ray<T>{{4, T(2.3), 3}, {-10, 0, 0}}, ball, pose);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(0.26).epsilon(tolerance<T> * 4));
  CHECK(length(h.normal - vec3<T>{T(0.8), T(0.6), 0}) <= tolerance<T> * 4);
  // Grazing: 0.5 across touches at one point (exact in both types); 0.5 + 1e-3 misses.
  h = ray_cast(ray<T>{{4, T(2.5), 3}, {-10, 0, 0}}, ball, pose);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(0.3).epsilon(T(1e-3)));  // √ of the rounding: the tangent point is ill-posed along the ray
  CHECK(std::abs(h.normal.y - 1) <= T(1e-3));
  CHECK_FALSE(ray_cast(ray<T>{{4, T(2.501), 3}, {-10, 0, 0}}, ball, pose).hit);
  // Pointing away, and too short.
  CHECK_FALSE(ray_cast(ray<T>{{4, 2, 3}, {4, 0, 0}}, ball, pose).hit);
  CHECK_FALSE(ray_cast(ray<T>{{4, 2, 3}, {-2, 0, 0}}, ball, pose).hit);
  // The same ray with a longer reach, through max_fraction.
  h = ray_cast(ray<T>{{4, 2, 3}, {-2, 0, 0}}, ball, pose, T(2));
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(1.25).epsilon(tolerance<T>));
}

TEST_CASE_TEMPLATE("ray cast: a box's faces and the ids and normals of its turned faces", T, float, double) {
  const box<T> b{{T(1), T(0.5), T(0.25)}};
  const quat<T> quarter = quat<T>::from_axis_angle(vec3<T>::unit_z(), T(1.5707963267948966));  // x -> y, y -> −x
  const transform<T> pose = at<T>({10, 0, 0}, quarter);
  // Down onto the turned box: its local +x face (feature 2) faces world +y, at y = 1.
  auto h = ray_cast(ray<T>{{10, 5, 0}, {0, -8, 0}}, b, pose);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(0.5).epsilon(tolerance<T>));
  CHECK(length(h.normal - vec3<T>::unit_y()) <= tolerance<T> * 2);
  CHECK(h.feature == 2u);
  // From −x in the world: its local +y face (feature 6), at x = 9.5.
  h = ray_cast(ray<T>{{0, T(0.2), T(0.1)}, {19, 0, 0}}, b, pose);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(0.5).epsilon(tolerance<T> * 10));
  CHECK(length(h.normal + vec3<T>::unit_x()) <= tolerance<T> * 2);
  CHECK(h.feature == 6u);
  // Along +z from below: the face at local −z, feature 9.
  h = ray_cast(ray<T>{{10, 0, -2}, {0, 0, 4}}, b, pose);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(1.75 / 4).epsilon(tolerance<T> * 10));
  CHECK(h.feature == 9u);
}

TEST_CASE_TEMPLATE("ray cast: grazing a box's edges and corners and running parallel to its faces", T, float, double) {
  const box<T> cube{vec3<T>::splat(T(0.5))};
  const transform<T> pose = at<T>({});
  // Along an edge (y = z = 0.5): the closed box is touched from x = −0.5 on.
  auto h = ray_cast(ray<T>{{-2, T(0.5), T(0.5)}, {4, 0, 0}}, cube, pose);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(0.375).epsilon(tolerance<T>));
  CHECK(h.normal.x == doctest::Approx(-1));
  // Through a corner along the diagonal: enters at the corner (−½, −½, −½).
  h = ray_cast(ray<T>{{-1, -1, -1}, {2, 2, 2}}, cube, pose);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(0.25).epsilon(tolerance<T>));
  CHECK(length(h.point + vec3<T>::splat(T(0.5))) <= tolerance<T> * 4);
  // Past a corner by 1e-4 (outside), and 1e-4 inside it.
  CHECK_FALSE(ray_cast(ray<T>{{-2, T(0.5001), T(0.5001)}, {4, 0, 0}}, cube, pose).hit);
  CHECK(ray_cast(ray<T>{{-2, T(0.4999), T(0.4999)}, {4, 0, 0}}, cube, pose).hit);
  // Parallel to the top face, just above it and just below it.
  CHECK_FALSE(ray_cast(ray<T>{{-2, T(0.5001), 0}, {4, 0, 0}}, cube, pose).hit);
  h = ray_cast(ray<T>{{-2, T(0.4999), 0}, {4, 0, T(0.1)}}, cube, pose);
  REQUIRE(h.hit);
  CHECK(h.feature == 1u);  // the −x face
  // A direction with a denormal component: the slab divides by it, and
  // never multiplies 0 by ∞.
  h = ray_cast(ray<T>{{-2, 0, 0}, {1, std::numeric_limits<T>::denorm_min(), 0}}, cube, pose, T(4));
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(1.5).epsilon(tolerance<T>));
  CHECK(finite_hit(h));
}

TEST_CASE_TEMPLATE("ray cast: a capsule's side and caps exactly", T, float, double) {
  const capsule<T> c{T(0.5), T(1)};  // core from y = −1 to 1
  const transform<T> pose = at<T>({0, 0, 5});
  // The side, from +x at height 0.7: x = 0.5, fraction 1.5/3.
  auto h = ray_cast(ray<T>{{2, T(0.7), 5}, {-3, 0, 0}}, c, pose);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(0.5).epsilon(tolerance<T>));
  CHECK(h.feature == 2u);
  CHECK(length(h.normal - vec3<T>::unit_x()) <= tolerance<T>);
  // Straight down the axis onto the top cap: y = 1.5.
  h = ray_cast(ray<T>{{0, 4, 5}, {0, -5, 0}}, c, pose);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(0.5).epsilon(tolerance<T>));
  CHECK(h.feature == 1u);
  CHECK(length(h.normal - vec3<T>::unit_y()) <= tolerance<T>);
  // From below at x = 0.3: the bottom cap at y = −1 − √(0.25 − 0.09) = −1.4.
  h = ray_cast(ray<T>{{T(0.3), -3, 5}, {0, 4, 0}}, c, pose);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(0.4).epsilon(tolerance<T> * 4));
  CHECK(h.feature == 0u);
  CHECK(length(h.normal - vec3<T>{T(0.6), T(-0.8), 0}) <= tolerance<T> * 4);
  // Slanting down onto the top cap: the line y = x + 0.7 meets the
  // cylinder x = 0.5 at y = 1.2, above the core's end, and passes 0.3/√2
  // from the cap's center (0, 1): the cap's ball decides, checked against
  // a sphere there.
  const ray<T> slant{{2, T(2.7), 5}, {-4, -4, 0}};
  h = ray_cast(slant, c, pose);
  REQUIRE(h.hit);
  const auto ball = ray_cast(slant, sphere<T>{T(0.5)}, at<T>({0, 1, 5}));
  REQUIRE(ball.hit);
  CHECK(h.fraction == doctest::Approx(double(ball.fraction)).epsilon(tolerance<T> * 4));
  CHECK(h.feature == 1u);
  // Parallel to the axis, grazing the side (x = 0.5) and just outside.
  h = ray_cast(ray<T>{{T(0.5), -4, 5}, {0, 8, 0}}, c, pose);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(3.0 / 8).epsilon(T(1e-3)));  // the tangent point: ill-posed along the ray
  CHECK_FALSE(ray_cast(ray<T>{{T(0.5001), -4, 5}, {0, 8, 0}}, c, pose).hit);
  // A capsule with no cylinder is a ball.
  h = ray_cast(ray<T>{{T(0.3), -3, 5}, {0, 4, 0}}, capsule<T>{T(0.5), T(0)}, pose);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(0.65).epsilon(tolerance<T> * 4));
}

TEST_CASE_TEMPLATE("ray cast: a plane is one-sided and solid below", T, float, double) {
  // The plane y = 1, tilted by the pose: normal (0, 1, 0) turned 90° about z is −x.
  const plane<T> ground{vec3<T>::unit_y(), T(-1)};
  auto h = ray_cast(ray<T>{{0, 5, 0}, {1, -8, 0}}, ground, at<T>({}));
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(0.5).epsilon(tolerance<T>));
  CHECK(h.normal == vec3<T>::unit_y());
  CHECK_FALSE(ray_cast(ray<T>{{0, 5, 0}, {1, 8, 0}}, ground, at<T>({})).hit);   // moving up
  CHECK_FALSE(ray_cast(ray<T>{{0, 5, 0}, {1, 0, 0}}, ground, at<T>({})).hit);   // parallel
  h = ray_cast(ray<T>{{0, 0, 0}, {1, 8, 0}}, ground, at<T>({}));                // from below: inside
  REQUIRE(h.hit);
  CHECK(h.fraction == T(0));
  const transform<T> turned = at<T>({2, 0, 0}, quat<T>::from_axis_angle(vec3<T>::unit_z(), T(1.5707963267948966)));
  // Turned: the surface is x = 2 − 1 = 1, solid for x > 1.
  h = ray_cast(ray<T>{{-3, 0, 0}, {8, 0, 0}}, ground, turned);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(0.5).epsilon(tolerance<T> * 4));
  CHECK(length(h.normal + vec3<T>::unit_x()) <= tolerance<T>);
}

TEST_CASE_TEMPLATE("ray cast: a triangle from the front and the back with its barycentric weights", T, float, double) {
  const vec3<T> a{0, 0, 0}, b{2, 0, 0}, c{0, 2, 0};  // counter-clockwise seen from +z: front faces +z
  auto h = ray_cast_triangle(ray<T>{{T(0.5), T(0.25), 3}, {0, 0, -6}}, a, b, c);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(0.5).epsilon(tolerance<T>));
  CHECK(h.feature == 0u);
  CHECK(h.normal == vec3<T>::unit_z());
  CHECK(length(h.barycentric - vec3<T>{T(0.625), T(0.25), T(0.125)}) <= tolerance<T> * 4);
  // From behind: the back, normal −z (towards the origin of the ray).
  h = ray_cast_triangle(ray<T>{{T(0.5), T(0.25), -1}, {0, 0, 4}}, a, b, c);
  REQUIRE(h.hit);
  CHECK(h.feature == 1u);
  CHECK(h.normal == -vec3<T>::unit_z());
  CHECK(h.fraction == doctest::Approx(0.25).epsilon(tolerance<T>));
  // On an edge (x + y = 2) and on a vertex: closed, so hit.
  h = ray_cast_triangle(ray<T>{{1, 1, 1}, {0, 0, -2}}, a, b, c);
  REQUIRE(h.hit);
  CHECK(h.barycentric.x == doctest::Approx(0).epsilon(tolerance<T>));
  CHECK(ray_cast_triangle(ray<T>{{2, 0, 1}, {0, 0, -2}}, a, b, c).hit);
  // Just outside that edge; in the triangle's plane; short of it.
  CHECK_FALSE(ray_cast_triangle(ray<T>{{T(1.001), 1, 1}, {0, 0, -2}}, a, b, c).hit);
  CHECK_FALSE(ray_cast_triangle(ray<T>{{-1, T(0.5), 0}, {4, 0, 0}}, a, b, c).hit);
  CHECK_FALSE(ray_cast_triangle(ray<T>{{T(0.5), T(0.5), 3}, {0, 0, -2}}, a, b, c).hit);
}

// ---- conventions: inside, degenerate rays -----------------------------------

TEST_CASE_TEMPLATE("a ray starting inside a solid hits at fraction 0 with the normal against it", T, float, double) {
  const ray<T> r{{T(0.1), T(0.05), T(-0.1)}, {3, -1, 2}};
  const vec3<T> back = -normalize(r.translation);
  const transform<T> pose = at<T>({}, quat<T>::from_axis_angle(normalize(vec3<T>{1, 2, 3}), T(0.7)));
  const auto check_from = [&](const narrowphase::ray_hit<T>& h, const vec3<T>& origin) {
    REQUIRE(h.hit);
    CHECK(h.fraction == T(0));
    CHECK(h.point == origin);
    CHECK(length(h.normal - back) <= tolerance<T>);
  };
  const auto check = [&](const narrowphase::ray_hit<T>& h) { check_from(h, r.origin); };
  check(ray_cast(r, sphere<T>{T(0.5)}, pose));
  check(ray_cast(r, box<T>{vec3<T>::splat(T(0.5))}, pose));
  check(ray_cast(r, capsule<T>{T(0.3), T(0.5)}, pose));
  check(ray_cast(r, box_hull<T>(vec3<T>::splat(T(0.5))), pose));
  check(ray_cast(r, plane<T>{vec3<T>::unit_y(), T(-1)}, pose));  // solid below y' = 1
  check(gjk_ray_cast(r, sphere<T>{T(0.5)}, pose));
  check(gjk_ray_cast(r, box<T>{vec3<T>::splat(T(0.5))}, pose));
  check(gjk_ray_cast(r, capsule<T>{T(0.3), T(0.5)}, pose));
  check(gjk_ray_cast(r, box_hull<T>(vec3<T>::splat(T(0.5))), pose));
  // On the surface counts as inside (closed solids): a ray leaving a box
  // from its face hits at 0.
  check_from(ray_cast(ray<T>{{T(0.5), 0, 0}, r.translation}, box<T>{vec3<T>::splat(T(0.5))}, at<T>({})), {T(0.5), 0, 0});
}

TEST_CASE_TEMPLATE("degenerate rays miss and never give NaN", T, float, double) {
  const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
  const sphere<T> ball{T(0.5)};
  const box<T> cube{vec3<T>::splat(T(0.5))};
  const capsule<T> pill{T(0.3), T(0.5)};
  const auto hull = box_hull<T>(vec3<T>::splat(T(0.5)));
  const plane<T> ground{vec3<T>::unit_y(), T(0)};
  const transform<T> pose = at<T>({});
  const ray<T> bad[] = {
      {{-2, 0, 0}, {0, 0, 0}},                                     // no length (even inside: origin 0 below)
      {{0, 0, 0}, {0, 0, 0}},
      {{-2, 0, 0}, {T(1e-30), 0, 0}},                              // its square underflows in float
      {{nan, 0, 0}, {1, 0, 0}},
      {{-2, 0, 0}, {nan, 1, 0}},
      {{-2, 0, 0}, {inf, 0, 0}},
      {{-2, 0, 0}, {std::numeric_limits<T>::max(), std::numeric_limits<T>::max(), 0}},  // its length overflows
  };
  for (const ray<T>& r : bad) {
    if (sizeof(T) == 8 && r.translation.x == T(1e-30)) continue;  // a fine ray in double
    CHECK_FALSE(ray_cast(r, ball, pose).hit);
    CHECK_FALSE(ray_cast(r, cube, pose).hit);
    CHECK_FALSE(ray_cast(r, pill, pose).hit);
    CHECK_FALSE(ray_cast(r, hull, pose).hit);
    CHECK_FALSE(ray_cast(r, ground, pose).hit);
    CHECK_FALSE(gjk_ray_cast(r, cube, pose).hit);
    CHECK_FALSE(gjk_ray_cast(r, ball, pose).hit);
    CHECK_FALSE(ray_cast_triangle(r, vec3<T>{0, -1, -1}, vec3<T>{0, 1, -1}, vec3<T>{0, 0, 1}).hit);
  }
  const ray<T> fine{{-2, 0, 0}, {4, 0, 0}};
  CHECK_FALSE(ray_cast(fine, ball, pose, T(-1)).hit);
  CHECK_FALSE(ray_cast(fine, cube, pose, nan).hit);
  CHECK_FALSE(gjk_ray_cast(fine, cube, pose, nan).hit);
  // A ray without end (max_fraction = +∞) is fine, and so is a tiny
  // translation stretched by a large max_fraction.
  auto h = ray_cast(ray<T>{{-2, 0, 0}, {T(0.001), 0, 0}}, cube, pose, inf);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(1500).epsilon(tolerance<T>));
  h = gjk_ray_cast(ray<T>{{-2, 0, 0}, {T(0.001), 0, 0}}, ball, pose, inf);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(1500).epsilon(tolerance<T> * 10));
  CHECK(finite_hit(h));
}

// ---- far, tiny, huge -----------------------------------------------------------

TEST_CASE_TEMPLATE("ray casts far from the origin and against tiny and huge shapes", T, float, double) {
  const vec3<T> far{T(1e4), T(-1e4), T(5e3)};
  const quat<T> turn = quat<T>::from_axis_angle(normalize(vec3<T>{1, 1, 0}), T(0.3));
  // At 1e4 m a float's spacing is 1 mm: positions hold to about that.
  const T far_tolerance = sizeof(T) == 4 ? T(2e-3) : T(1e-10);
  const auto head_on = [&](const auto& shape, T reach) {
    // From 3 m along the turned x axis, straight at the center.
    const vec3<T> axis = rotate(turn, vec3<T>::unit_x());
    const auto h = ray_cast(ray<T>{far + axis * T(3), axis * T(-6)}, shape, at<T>(far, turn));
    REQUIRE(h.hit);
    CHECK(std::abs(h.fraction * 6 - (3 - reach)) <= far_tolerance);
    CHECK(length(h.normal - axis) <= far_tolerance);
    const auto g = gjk_ray_cast(ray<T>{far + axis * T(3), axis * T(-6)}, shape, at<T>(far, turn));
    REQUIRE(g.hit);
    CHECK(std::abs(g.fraction * 6 - (3 - reach)) <= far_tolerance);
  };
  head_on(sphere<T>{T(0.5)}, T(0.5));
  head_on(box<T>{{T(0.5), 1, 2}}, T(0.5));
  head_on(capsule<T>{T(0.25), 1}, T(0.25));
  head_on(box_hull<T>({T(0.5), 1, 2}), T(0.5));

  // 1 mm and 1 km shapes: the error scales with the shape (and the ray's
  // reach), so the relative tolerance is the closed forms' own.
  for (const T size : {T(1e-3), T(1e3)}) {
    const vec3<T> from{size * 3, size * T(0.1), size * T(-0.2)};
    const ray<T> r{from, vec3<T>{-size * 6, 0, 0}};
    const auto ball = ray_cast(r, sphere<T>{size}, at<T>({}));
    REQUIRE(ball.hit);
    CHECK(ball.fraction * 6 == doctest::Approx(3 - std::sqrt(T(1) - T(0.05))).epsilon(tolerance<T> * 4));
    const auto cube = ray_cast(r, box<T>{vec3<T>::splat(size)}, at<T>({}));
    REQUIRE(cube.hit);
    CHECK(cube.fraction * 6 == doctest::Approx(2).epsilon(tolerance<T> * 4));
    const auto pill = gjk_ray_cast(r, capsule<T>{size, size}, at<T>({}));
    REQUIRE(pill.hit);
    CHECK(pill.fraction * 6 == doctest::Approx(3 - std::sqrt(T(1) - T(0.04))).epsilon(tolerance<T> * 4));
    const auto g = gjk_ray_cast(r, box<T>{vec3<T>::splat(size)}, at<T>({}));
    REQUIRE(g.hit);
    CHECK(g.fraction * 6 == doctest::Approx(2).epsilon(tolerance<T> * 10));
  }
}

// ---- random rays against the reference ------------------------------------------

TEST_CASE_TEMPLATE("thousands of random rays agree with the signed-distance reference", T, float, double) {
  // The reference finds the first root of each shape's signed distance
  // along the ray by bisection in long double. Measured worst error of the
  // hit across the surface (|Δs|·|cos θ| over 1 m plus the origin's
  // distance), sphere, box, capsule, hull: 2.0e-7, 2.8e-7, 5.6e-7, 2.2e-7
  // in float and 3.1e-16, 5.0e-16, 6.4e-16, 3.4e-16 in double; normals
  // within 1.2e-6 and 1.9e-15 of the reference (1 − n·n_ref). A handful of
  // grazing rays (at most 3 of 3 000) are left undecided.
  lcg32 random{2024};
  agreement sphere_a, box_a, capsule_a, hull_a;
  const auto hull_shape = box_hull<T>({T(0.7), T(0.3), T(0.45)});
  const box<T> hull_box{{T(0.7), T(0.3), T(0.45)}};
  for (int k = 0; k < 3000; ++k) {
    const transform<T> pose = at<T>({random.uniform<T>(-3, 3), random.uniform<T>(-3, 3), random.uniform<T>(-3, 3)},
                                    random_rotation<T>(random));
    const T size = random.uniform<T>(T(0.1), T(2));
    const ray<T> r = random_ray<T>(random, pose.position, size, T(5) * size);
    const local_ray lr = to_local(r, pose);
    const L reach = lr.length;  // max_fraction 1
    const L scale = 1 + norm(lr.origin);
    L minimum = 0;
    {
      const sphere<T> s{size};
      const auto expected = reference_entry([&](lvec p) { return norm(p) - L(size); }, lr, reach, minimum);
      const auto h = ray_cast(r, s, pose);
      lvec n{};
      if (expected) n = (lr.origin + lr.direction * *expected) * (1 / L(size));
      compare_with_reference(sphere_a, h, expected, minimum, scale, lr, reach, n, pose, true);
    }
    {
      const box<T> b{{size, random.uniform<T>(T(0.1), T(2)), random.uniform<T>(T(0.1), T(2))}};
      const lvec h3 = wide(b.half_extents);
      const auto expected = reference_entry([&](lvec p) { return box_distance(p, h3); }, lr, reach, minimum);
      const auto h = ray_cast(r, b, pose);
      lvec n{};
      bool clear = false;  // of edges: the face is unambiguous
      if (expected) {
        const lvec p = lr.origin + lr.direction * *expected;
        const L q[3] = {std::abs(p.x) - h3.x, std::abs(p.y) - h3.y, std::abs(p.z) - h3.z};
        const int axis = q[0] > q[1] ? (q[0] > q[2] ? 0 : 2) : (q[1] > q[2] ? 1 : 2);
        const L pc[3] = {p.x, p.y, p.z};
        L nn[3] = {0, 0, 0};
        nn[axis] = pc[axis] < 0 ? -1 : 1;
        n = {nn[0], nn[1], nn[2]};
        L second = -1e30L;
        for (int i = 0; i < 3; ++i)
          if (i != axis) second = std::max(second, q[i]);
        clear = second < -L(1e-3);
      }
      compare_with_reference(box_a, h, expected, minimum, scale, lr, reach, n, pose, clear);
    }
    {
      const capsule<T> c{size * T(0.5), random.uniform<T>(T(0), T(2))};
      const auto expected = reference_entry([&](lvec p) { return capsule_distance(p, L(c.radius), L(c.half_height)); },
                                            lr, reach, minimum);
      const auto h = ray_cast(r, c, pose);
      lvec n{};
      if (expected) {
        const lvec p = lr.origin + lr.direction * *expected;
        n = (p - lvec{0, std::clamp(p.y, -L(c.half_height), L(c.half_height)), 0}) * (1 / L(c.radius));
      }
      compare_with_reference(capsule_a, h, expected, minimum, scale, lr, reach, n, pose, true);
    }
    {
      // The hull: max of its face planes (convex, zero on its surface).
      const auto f = [&](lvec p) {
        L d = -1e30L;
        for (const auto& pl : hull_shape.planes()) d = std::max(d, dot(wide(pl.normal), p) + L(pl.offset));
        return d;
      };
      const auto expected = reference_entry(f, lr, reach, minimum);
      const auto h = ray_cast(r, hull_shape, pose);
      lvec n{};
      if (expected) n = wide(hull_shape.plane(h.hit ? h.feature : 0).normal);
      compare_with_reference(hull_a, h, expected, minimum, scale, lr, reach, n, pose, false);
      // And the box it was built from: the same fraction and normal.
      const auto hb = ray_cast(r, hull_box, pose);
      CHECK(hb.hit == h.hit);
      if (hb.hit && h.hit) {
        CHECK(std::abs(hb.fraction - h.fraction) * length(r.translation) <= tolerance<T> * 10 * T(scale));
        if (hb.fraction > 0) CHECK(dot(hb.normal, h.normal) >= T(1) - T(1e-3));  // the same face, bar an edge
      }
    }
  }
  for (const agreement* a : {&sphere_a, &box_a, &capsule_a, &hull_a}) {
    MESSAGE("compared " << a->compared << " skipped " << a->skipped << " disagreed " << a->disagreed << " worst "
                        << a->worst << " worst normal " << a->worst_normal);
    CHECK(a->compared > 2900);
    CHECK(a->disagreed == 0);
    CHECK(a->worst <= (sizeof(T) == 4 ? 2e-6 : 1e-14));
    CHECK(a->worst_normal <= (sizeof(T) == 4 ? 1e-5 : 1e-13));
  }
}

TEST_CASE_TEMPLATE("random rays against random triangles agree with a long double reference", T, float, double) {
  // The reference: the plane's crossing, and signed areas for the
  // barycentric weights, in long double. Measured: the same hits; worst
  // distance error 9.0e-7 (float) and 5.9e-16 (double) of 1 m plus the
  // origin's distance; barycentric weights within 2.3e-6 and 5.4e-15.
  lcg32 random{99};
  int compared = 0, hits = 0, disagreed = 0;
  double worst = 0, worst_weights = 0;
  const auto in = [&](T r) { return vec3<T>{random.uniform<T>(-r, r), random.uniform<T>(-r, r), random.uniform<T>(-r, r)}; };
  for (int k = 0; k < 5000; ++k) {
    const vec3<T> a = in(2), b = in(2), c = in(2);
    const vec3<T> origin = in(5);
    const vec3<T> aim = (a + b + c) / T(3) + in(2);
    const ray<T> r{origin, (aim - origin) * random.uniform<T>(T(0.5), T(3))};
    const lvec la = wide(a), lb = wide(b), lc = wide(c), lo = wide(r.origin), ld = wide(r.translation);
    const lvec n = cross(lb - la, lc - la);
    const L area = norm(n);
    const L denom = dot(n, ld);
    if (area < L(1e-2) || std::abs(denom) < L(1e-2) * area * norm(ld)) continue;  // slivers and grazing
    const L t = dot(n, la - lo) / denom;
    const lvec p = lo + ld * t;
    const L wa = dot(cross(lb - p, lc - p), n) / (area * area), wb = dot(cross(lc - p, la - p), n) / (area * area);
    const L wc = 1 - wa - wb;
    const L undecided = sizeof(T) == 4 ? L(1e-4) : L(1e-10);
    if (std::min({std::abs(wa), std::abs(wb), std::abs(wc), std::abs(t), std::abs(t - 1)}) < undecided) continue;
    const bool expected = t >= 0 && t <= 1 && wa >= 0 && wb >= 0 && wc >= 0;
    const auto h = ray_cast_triangle(r, a, b, c);
    ++compared;
    if (h.hit != expected) {
      ++disagreed;
      continue;
    }
    if (!h.hit) continue;
    ++hits;
    CHECK(finite_hit(h));
    CHECK(h.feature == (denom < 0 ? 0u : 1u));
    CHECK(dot(wide(h.normal), ld) < 0);
    worst = std::max(worst, double(std::abs(L(h.fraction) - t) * norm(ld) / (1 + norm(lo))));
    worst_weights = std::max({worst_weights, double(std::abs(L(h.barycentric.x) - wa)),
                              double(std::abs(L(h.barycentric.y) - wb)), double(std::abs(L(h.barycentric.z) - wc))});
  }
  MESSAGE("compared " << compared << " hits " << hits << " disagreed " << disagreed << " worst " << worst
                      << " worst weights " << worst_weights);
  CHECK(compared > 3000);
  CHECK(hits > 400);
  CHECK(disagreed == 0);
  CHECK(worst <= (sizeof(T) == 4 ? 2e-6 : 1e-14));
  CHECK(worst_weights <= (sizeof(T) == 4 ? 2e-5 : 1e-13));
}

// ---- GJK ray casting against the analytic casts ----------------------------------

TEST_CASE_TEMPLATE("gjk ray casting agrees with every analytic cast on random rays", T, float, double) {
  // Measured worst error of the hit across the surface (|Δs|·|cos θ| over
  // 1 m plus the origin's distance): 5.3e-7 (float, the float analytic
  // casts' own rounding) and 5.2e-15 (double); normals of spheres and
  // capsules within 4.8e-7 and 8.9e-16 (1 − n·n_exact), and a box's or a
  // hull's normal supports the shape at the point (no corner farther above
  // its plane); at most 10 (float) and 11 (double) iterations. Rays that only
  // graze a shape (the reference's nearest approach within 1e-4 or 1e-10
  // of the surface, relative) may go either way.
  lcg32 random{777};
  const auto hull_shape = box_hull<T>({T(0.4), T(0.9), T(0.6)});
  int compared = 0, skipped = 0, disagreed = 0, most_iterations = 0;
  double worst = 0, worst_normal = 0;
  const auto compare = [&](const auto& shape, const transform<T>& pose, const ray<T>& r, const auto& distance,
                           bool rounded, const std::vector<vec3<T>>& corners) {
    const local_ray lr = to_local(r, pose);
    const L scale = 1 + norm(lr.origin);
    L minimum = 0;
    const auto expected = reference_entry(distance, lr, lr.length, minimum);
    const L undecided = (sizeof(T) == 4 ? L(1e-4) : L(1e-10)) * scale;
    if (std::abs(minimum) < undecided || (expected && std::abs(*expected - lr.length) < undecided)) {
      ++skipped;
      return;
    }
    const auto exact = ray_cast(r, shape, pose);
    const auto g = narrowphase::detail::run_gjk_ray_cast(r, shape, pose, T(1));
    most_iterations = std::max(most_iterations, g.iterations);
    ++compared;
    CHECK(finite_hit(g.hit));
    if (exact.hit != g.hit.hit) {
      ++disagreed;
      return;
    }
    if (!exact.hit) return;
    const T cosine = std::abs(dot(exact.normal, normalize(r.translation)));
    worst = std::max(worst, double(std::abs(exact.fraction - g.hit.fraction) * length(r.translation) * cosine / T(scale)));
    if (exact.fraction == T(0)) {
      CHECK(g.hit.fraction == T(0));
      return;
    }
    if (rounded) {
      worst_normal = std::max(worst_normal, double(1 - dot(exact.normal, g.hit.normal)));
    } else {
      // The normal of a polytope's hit supports it at the point.
      T above = 0;
      for (const vec3<T>& corner : corners)
        above = std::max(above, dot(g.hit.normal, apply(pose, corner) - g.hit.point));
      worst_normal = std::max(worst_normal, double(above / T(scale)));
    }
  };
  const std::vector<vec3<T>> none;
  const auto hv = hull_shape.vertices();
  const std::vector<vec3<T>> hull_corners(hv.begin(), hv.end());
  const auto hull_distance = [&](lvec p) {
    L d = -1e30L;
    for (const auto& pl : hull_shape.planes()) d = std::max(d, dot(wide(pl.normal), p) + L(pl.offset));
    return d;
  };
  for (int k = 0; k < 2500; ++k) {
    const transform<T> pose = at<T>({random.uniform<T>(-3, 3), random.uniform<T>(-3, 3), random.uniform<T>(-3, 3)},
                                    random_rotation<T>(random));
    const T size = random.uniform<T>(T(0.1), T(2));
    const ray<T> r = random_ray<T>(random, pose.position, size, T(5) * size);
    compare(sphere<T>{size}, pose, r, [&](lvec p) { return norm(p) - L(size); }, true, none);
    const box<T> b{{size, random.uniform<T>(T(0.1), T(2)), random.uniform<T>(T(0.1), T(2))}};
    std::vector<vec3<T>> corners;
    for (int c = 0; c < 8; ++c) corners.push_back(b.support({(c & 1) ? T(1) : T(-1), (c & 2) ? T(1) : T(-1), (c & 4) ? T(1) : T(-1)}));
    compare(b, pose, r, [&](lvec p) { return box_distance(p, wide(b.half_extents)); }, false, corners);
    const capsule<T> c{size * T(0.5), random.uniform<T>(T(0), T(2))};
    compare(c, pose, r, [&](lvec p) { return capsule_distance(p, L(c.radius), L(c.half_height)); }, true, none);
    compare(hull_shape, pose, r, hull_distance, false, hull_corners);
  }
  MESSAGE("compared " << compared << " skipped " << skipped << " disagreed " << disagreed << " worst " << worst
                      << " worst normal " << worst_normal << " most iterations " << most_iterations);
  CHECK(compared > 9900);
  CHECK(disagreed == 0);
  CHECK(worst <= (sizeof(T) == 4 ? 2e-6 : 1e-13));
  CHECK(worst_normal <= (sizeof(T) == 4 ? 1e-5 : 1e-12));
  CHECK(most_iterations <= 16);
}

TEST_CASE_TEMPLATE("gjk ray casting on a curved surface known only by its support function", T, float, double) {
  // No core and radius: GJK crawls over the curve, converging linearly.
  // Measured worst error across the surface against the sphere's closed
  // form, relative to 1 m plus the origin's distance: 1.7e-7 (float, in up
  // to 42 iterations) and 1.5e-14 (double, some casts at the 64-iteration
  // cap). Rays grazing within 1e-3 (relative) may go either way: a cast
  // out of iterations is a hit within √ε.
  lcg32 random{31};
  int compared = 0, skipped = 0, disagreed = 0, most_iterations = 0;
  double worst = 0;
  for (int k = 0; k < 2000; ++k) {
    const transform<T> pose = at<T>({random.uniform<T>(-3, 3), random.uniform<T>(-3, 3), random.uniform<T>(-3, 3)});
    const T radius = random.uniform<T>(T(0.1), T(2));
    const ray<T> r = random_ray<T>(random, pose.position, radius, T(5) * radius);
    const local_ray lr = to_local(r, pose);
    const L scale = 1 + norm(lr.origin);
    L minimum = 0;
    reference_entry([&](lvec p) { return norm(p) - L(radius); }, lr, lr.length, minimum);
    if (std::abs(minimum) < L(1e-3) * scale) {
      ++skipped;
      continue;
    }
    const auto exact = ray_cast(r, sphere<T>{radius}, pose);
    const auto g = narrowphase::detail::run_gjk_ray_cast(r, support_only_ball<T>{radius}, pose, T(1));
    most_iterations = std::max(most_iterations, g.iterations);
    CHECK(finite_hit(g.hit));
    ++compared;
    if (exact.hit != g.hit.hit) {
      ++disagreed;
      continue;
    }
    if (!exact.hit || exact.fraction == T(0)) continue;
    const T cosine = std::abs(dot(exact.normal, normalize(r.translation)));
    worst = std::max(worst, double(std::abs(exact.fraction - g.hit.fraction) * length(r.translation) * cosine / T(scale)));
  }
  MESSAGE("compared " << compared << " skipped " << skipped << " disagreed " << disagreed << " worst " << worst
                      << " most iterations " << most_iterations);
  CHECK(compared > 1900);
  CHECK(disagreed == 0);
  CHECK(worst <= (sizeof(T) == 4 ? 2e-6 : 1e-12));
}

}  // namespace narrowphase_ray_cast_tests
