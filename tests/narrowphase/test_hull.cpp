// Convex hulls against planes and spheres: a hull built from a box's
// corners must give the box's answers, a tetrahedron rests on a face or a
// vertex, and ids hold.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "impulse/core/random.hpp"
#include "impulse/narrowphase.hpp"
#include "impulse/shapes/convex_hull.hpp"

#include "poses.hpp"

namespace narrowphase_hull_tests {

namespace {

using namespace impulse;
using narrowphase::collide;
using test::at;
using test::random_rotation;

template <class T>
constexpr T tolerance = test::contact_tolerance<T>;

template <class T>
convex_hull<T> cube_hull(T half) {
  return convex_hull<T>::from_points(test::box_corners(vec3<T>::splat(half)));
}

}  // namespace

TEST_CASE_TEMPLATE("a hull on a plane: a cube on a face, a tetrahedron on a face and on a vertex", T, float, double) {
  const plane<T> ground{vec3<T>::unit_y(), T(0)};
  const auto cube = cube_hull<T>(T(0.5));
  auto m = collide(cube, at<T>({T(2), T(0.49), T(-1)}), ground, at<T>({}));
  REQUIRE(m.count == 4);
  CHECK(length(m.normal + vec3<T>::unit_y()) <= tolerance<T>);
  std::set<std::uint32_t> ids;
  for (const auto& p : m.contacts()) {
    CHECK(p.depth == doctest::Approx(0.01).epsilon(tolerance<T> * 1000));
    ids.insert(p.feature);
  }
  CHECK(ids.size() == 4);
  // The same four ids 1 mm higher and shifted.
  const auto again = collide(cube, at<T>({T(2.3), T(0.491), T(-1)}), ground, at<T>({}));
  std::set<std::uint32_t> ids_again;
  for (const auto& p : again.contacts()) ids_again.insert(p.feature);
  CHECK(ids_again == ids);

  // A regular tetrahedron with a face down (y = 0 for three vertices) and
  // the fourth vertex up: sunk 1 cm, the three base vertices.
  const T s = T(1);
  const std::vector<vec3<T>> tetra{{s, 0, 0}, {-s / 2, 0, s * std::sqrt(T(3)) / 2}, {-s / 2, 0, -s * std::sqrt(T(3)) / 2}, {0, s * std::sqrt(T(2)), 0}};
  const auto t = convex_hull<T>::from_points(tetra);
  m = collide(t, at<T>({0, T(-0.01), 0}), ground, at<T>({}));
  REQUIRE(m.count == 3);
  for (const auto& p : m.contacts()) CHECK(p.depth == doctest::Approx(0.01).epsilon(tolerance<T> * 1000));
  // Upside down: on its apex.
  m = collide(t, at<T>({0, s * std::sqrt(T(2)) - T(0.01), 0}, quat<T>::from_axis_angle(vec3<T>::unit_x(), T(3.14159265358979))),
              ground, at<T>({}));
  REQUIRE(m.count == 1);
  CHECK(m.points[0].depth == doctest::Approx(0.01).epsilon(tolerance<T> * 1000));
  // The swapped pair.
  CHECK(length(collide(ground, at<T>({}), cube, at<T>({0, T(0.49), 0})).normal - vec3<T>::unit_y()) <= tolerance<T>);
}

TEST_CASE_TEMPLATE("a sphere against a cube hull gives the box's answers", T, float, double) {
  // 5000 random spheres and poses, touching or within a margin of 0.2:
  // the same count, depth and normal as sphere against box.
  const auto hull = cube_hull<T>(T(0.5));
  const box<T> b{vec3<T>::splat(T(0.5))};
  lcg32 random{77};
  int compared = 0, inside = 0;
  T worst_depth = 0, worst_normal = 0;
  for (int k = 0; k < 5000; ++k) {
    const sphere<T> s{random.uniform<T>(T(0.05), T(1))};
    const transform<T> ps = at<T>({random.uniform<T>(T(-1.5), T(1.5)), random.uniform<T>(T(-1.5), T(1.5)), random.uniform<T>(T(-1.5), T(1.5))});
    const transform<T> pb = at<T>({}, random_rotation<T>(random));
    const auto with_box = collide(s, ps, b, pb, T(0.2));
    const auto with_hull = collide(s, ps, hull, pb, T(0.2));
    REQUIRE(with_box.count == with_hull.count);
    if (with_box.empty()) continue;
    ++compared;
    if (with_box.points[0].depth > s.radius) ++inside;
    worst_depth = std::max(worst_depth, std::abs(with_box.points[0].depth - with_hull.points[0].depth));
    worst_normal = std::max(worst_normal, length(with_box.normal - with_hull.normal));
  }
  MESSAGE("compared " << compared << " (center inside: " << inside << "), worst depth " << worst_depth << ", normal " << worst_normal);
  CHECK(compared > 1500);
  CHECK(inside > 100);
  CHECK(worst_depth <= tolerance<T> * 10);
  CHECK(worst_normal <= (sizeof(T) == 4 ? T(1e-5) : T(1e-11)));  // measured 3.2e-7 and 9.9e-13
  // The swapped pair.
  const auto m = collide(hull, at<T>({}), sphere<T>{T(0.5)}, at<T>({T(0.9), 0, 0}));
  REQUIRE(m.count == 1);
  CHECK(length(m.normal - vec3<T>::unit_x()) <= tolerance<T>);
  CHECK(m.points[0].depth == doctest::Approx(0.1).epsilon(tolerance<T> * 100));
}

}  // namespace narrowphase_hull_tests
