// GJK distance: exact distances between boxes (polytopes end exactly),
// spheres and capsules against their closed forms, closest points on both
// surfaces, overlap, a hull against the box it was built from, far from the
// origin, and 10 000 random separated pairs against the analytic tests.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <vector>

#include "impulse/core/random.hpp"
#include "impulse/narrowphase.hpp"

#include "poses.hpp"
#include "impulse/shapes/convex_hull.hpp"

namespace narrowphase_gjk_tests {

namespace {

using namespace impulse;
using narrowphase::gjk_distance;
using test::at;
using test::random_rotation;

/// Distances from GJK: ε/2 relative from its termination (1e-6 in float,
/// 1e-12 in double), plus rounding of the shapes' own size.
template <class T>
constexpr T tolerance = sizeof(T) == 4 ? T(1e-5) : T(1e-10);

}  // namespace

TEST_CASE_TEMPLATE("gjk: boxes apart face to face and corner to corner, exactly", T, float, double) {
  const box<T> cube{vec3<T>::splat(T(0.5))};
  auto r = gjk_distance(cube, at<T>({}), cube, at<T>({T(1.3), T(0.2), T(-0.1)}));
  CHECK_FALSE(r.overlapping);
  CHECK(r.distance == doctest::Approx(0.3).epsilon(tolerance<T>));
  CHECK(length(r.on_b - r.on_a) == doctest::Approx(0.3).epsilon(tolerance<T>));
  CHECK(r.on_a.x == doctest::Approx(0.5).epsilon(tolerance<T>));
  CHECK(r.on_b.x == doctest::Approx(0.8).epsilon(tolerance<T>));
  // Corner to corner: gaps 0.3, 0.4 and 0.2 along the axes.
  r = gjk_distance(cube, at<T>({}), cube, at<T>({T(1.3), T(1.4), T(1.2)}));
  CHECK(r.distance == doctest::Approx(std::sqrt(0.29)).epsilon(tolerance<T>));
  CHECK(length(r.on_a - vec3<T>::splat(T(0.5))) <= tolerance<T>);
  // Overlapping, and touching exactly.
  CHECK(gjk_distance(cube, at<T>({}), cube, at<T>({T(0.9), 0, 0})).overlapping);
  r = gjk_distance(cube, at<T>({}), cube, at<T>({1, T(0.3), 0}));
  CHECK(r.distance <= tolerance<T>);
  // Turned: a box on its edge above another, 0.25 above its top face.
  const T reach = T(0.5) * std::sqrt(T(2));
  r = gjk_distance(cube, at<T>({}), cube, at<T>({0, T(0.75) + reach, 0}, quat<T>::from_axis_angle(vec3<T>::unit_z(), T(0.785398163397448))));
  CHECK(r.distance == doctest::Approx(0.25).epsilon(tolerance<T> * 10));
  CHECK(r.iterations <= 64);
}

TEST_CASE_TEMPLATE("gjk: spheres and capsules against their closed forms", T, float, double) {
  const sphere<T> ball{T(0.4)};
  const vec3<T> d = normalize(vec3<T>{1, -2, 2}) * T(1.7);
  auto r = gjk_distance(ball, at<T>({}), sphere<T>{T(0.6)}, at<T>(d));
  CHECK(r.distance == doctest::Approx(0.7).epsilon(tolerance<T> * 10));
  CHECK(length(r.on_a) == doctest::Approx(0.4).epsilon(tolerance<T> * 10));
  CHECK(length(r.on_b - d) == doctest::Approx(0.6).epsilon(tolerance<T> * 10));
  // Crossing capsules (along x and along z), cores 1 apart: 0.5 between them.
  const capsule<T> c{T(0.25), T(1)};
  const quat<T> along_x = quat<T>::from_axis_angle(vec3<T>::unit_z(), T(1.5707963267948966));
  const quat<T> along_z = quat<T>::from_axis_angle(vec3<T>::unit_x(), T(1.5707963267948966));
  r = gjk_distance(c, at<T>({}, along_x), c, at<T>({T(0.2), 1, T(-0.3)}, along_z));
  CHECK(r.distance == doctest::Approx(0.5).epsilon(tolerance<T> * 10));
  CHECK(length(r.on_a - vec3<T>{T(0.2), T(0.25), 0}) <= tolerance<T> * 100);
  // A sphere against a box corner.
  r = gjk_distance(ball, at<T>({T(1.5), T(1.5), T(1.5)}), box<T>{vec3<T>::splat(T(0.5))}, at<T>({}));
  CHECK(r.distance == doctest::Approx(std::sqrt(T(3)) - T(0.4)).epsilon(tolerance<T> * 10));
}

TEST_CASE_TEMPLATE("gjk: a hull built from a box's corners is that box", T, float, double) {
  std::vector<vec3<T>> corners;
  for (int k = 0; k < 8; ++k)
    corners.push_back({(k & 1) ? T(0.5) : T(-0.5), (k & 2) ? T(0.5) : T(-0.5), (k & 4) ? T(0.5) : T(-0.5)});
  const auto hull = convex_hull<T>::from_points(corners);
  const box<T> cube{vec3<T>::splat(T(0.5))};
  lcg32 random{17};
  for (int k = 0; k < 200; ++k) {
    const transform<T> pa = at<T>({}, random_rotation<T>(random));
    const transform<T> pb = at<T>({random.uniform<T>(-3, 3), random.uniform<T>(-3, 3), random.uniform<T>(T(-3), T(3))},
                                  random_rotation<T>(random));
    const auto with_hull = gjk_distance(hull, pa, cube, pb), with_box = gjk_distance(cube, pa, cube, pb);
    CHECK(with_hull.overlapping == with_box.overlapping);
    CHECK(std::abs(with_hull.distance - with_box.distance) <= tolerance<T> * 10);
  }
}

TEST_CASE_TEMPLATE("gjk: 10 000 random separated pairs agree with the analytic tests", T, float, double) {
  // The analytic tests, given a margin wider than the gap, report the
  // separation as a negative depth: an independent closed form for sphere
  // against sphere, box and capsule, and capsule against capsule.
  lcg32 random{4242};
  const auto place = [&](T spread) {
    return at<T>({random.uniform<T>(-spread, spread), random.uniform<T>(-spread, spread), random.uniform<T>(-spread, spread)},
                 random_rotation<T>(random));
  };
  int compared = 0, worst_iterations = 0;
  T worst = 0;
  const auto compare = [&](const auto& a, const transform<T>& pa, const auto& b, const transform<T>& pb) {
    const auto exact = narrowphase::collide(a, pa, b, pb, T(100));
    const auto r = gjk_distance(a, pa, b, pb);
    REQUIRE(exact.count >= 1);
    const T expected = -exact.points[0].depth;
    if (expected <= T(1e-3)) return;  // overlapping or nearly: not this test's business
    ++compared;
    worst = std::max(worst, std::abs(r.distance - expected) / (T(1) + expected));
    worst_iterations = std::max(worst_iterations, r.iterations);
    CHECK(std::abs(length(r.on_b - r.on_a) - r.distance) <= tolerance<T> * 10 * (1 + r.distance));
  };
  for (int k = 0; k < 2500; ++k) {
    const sphere<T> s{random.uniform<T>(T(0.05), T(1))};
    const box<T> b{{random.uniform<T>(T(0.05), T(1)), random.uniform<T>(T(0.05), T(1)), random.uniform<T>(T(0.05), T(1))}};
    const capsule<T> c{random.uniform<T>(T(0.05), T(0.5)), random.uniform<T>(T(0), T(1))};
    const capsule<T> c2{random.uniform<T>(T(0.05), T(0.5)), random.uniform<T>(T(0), T(1))};
    compare(s, place(3), sphere<T>{T(0.3)}, place(3));
    compare(s, place(3), b, place(3));
    compare(s, place(3), c, place(3));
    compare(c, place(3), c2, place(3));
  }
  MESSAGE("compared " << compared << ", worst relative error " << worst << ", most iterations " << worst_iterations);
  CHECK(compared > 5000);
  // Spheres and capsules are point and segment cores grown by radii, so
  // these end in a few iterations (measured: 7.9e-7 in float, 1.3e-15 in
  // double, relative to 1 m plus the distance).
  CHECK(worst <= (sizeof(T) == 4 ? T(1e-5) : T(1e-12)));
  CHECK(worst_iterations <= 64);
}

/// A ball known only by its support function: GJK meets its curved
/// surface itself, not a point core grown by a radius.
template <class T>
struct support_only_ball {
  T radius;
  vec3<T> support(const vec3<T>& d) const { return normalize_or(d, vec3<T>::unit_x()) * radius; }
};

TEST_CASE_TEMPLATE("gjk on a curved surface: a ball known only by its support function", T, float, double) {
  // GJK's points crowd into slivers on a curved surface; it must neither
  // cycle nor take a sliver for an overlap, and its distance must hold to
  // its tolerance (measured: 1.2e-6 in float, 4e-11 in double, relative to
  // 1 m plus the distance; up to 57 iterations).
  lcg32 random{4242};
  const auto place = [&](T spread) {
    return at<T>({random.uniform<T>(-spread, spread), random.uniform<T>(-spread, spread), random.uniform<T>(-spread, spread)},
                 random_rotation<T>(random));
  };
  T worst = 0;
  int compared = 0, most_iterations = 0;
  for (int k = 0; k < 3000; ++k) {
    const T r = random.uniform<T>(T(0.05), T(1));
    const box<T> b{{random.uniform<T>(T(0.05), T(1)), random.uniform<T>(T(0.05), T(1)), random.uniform<T>(T(0.05), T(1))}};
    const capsule<T> c{random.uniform<T>(T(0.05), T(0.5)), random.uniform<T>(T(0), T(1))};
    const transform<T> p1 = place(3), p2 = place(3), p3 = place(3), p4 = place(3);
    const auto check = [&](const auto& other, const transform<T>& po, const transform<T>& pb) {
      const auto exact = narrowphase::collide(sphere<T>{r}, pb, other, po, T(100));
      const T expected = -exact.points[0].depth;
      if (expected <= T(1e-3)) return;
      const auto g = gjk_distance(support_only_ball<T>{r}, pb, other, po);
      ++compared;
      worst = std::max(worst, std::abs(g.distance - expected) / (T(1) + expected));
      most_iterations = std::max(most_iterations, g.iterations);
    };
    check(b, p1, p2);
    check(c, p3, p4);
  }
  MESSAGE("compared " << compared << ", worst " << worst << ", most iterations " << most_iterations);
  CHECK(compared > 4000);
  CHECK(worst <= (sizeof(T) == 4 ? T(1e-5) : T(1e-9)));
  CHECK(most_iterations <= 64);
}

TEST_CASE_TEMPLATE("gjk far from the origin and between shapes of very different size", T, float, double) {
  const box<T> cube{vec3<T>::splat(T(0.5))};
  const vec3<T> far{T(1e4), T(-1e4), T(5e3)};
  const auto r = gjk_distance(cube, at<T>(far), cube, at<T>(far + vec3<T>{T(1.3), 0, 0}));
  // Within two float spacings at 1e4 (1 mm each), exact in double.
  CHECK(std::abs(r.distance - T(0.3)) <= (sizeof(T) == 4 ? T(2e-3) : T(1e-9)));
  const box<T> pebble{vec3<T>::splat(T(0.001))}, rock{vec3<T>::splat(T(1))};
  const auto s = gjk_distance(pebble, at<T>({0, T(1.5), 0}), rock, at<T>({}));
  CHECK(s.distance == doctest::Approx(0.499).epsilon(tolerance<T> * 10));
}

}  // namespace narrowphase_gjk_tests
