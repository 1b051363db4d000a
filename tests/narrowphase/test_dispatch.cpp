// Dispatch from the config's shape_list: every listed pair reaches the test
// written for it, static pairs are empty, and a user's shape joins by its
// own collide without the pairs it is not listed with being compiled. (A
// listed pair with no test is a compile error naming it: see
// tests/compile_fail/pair_test_missing.cpp.)
#include <doctest/doctest.h>

#include <vector>

#include "impulse/narrowphase.hpp"
#include "impulse/narrowphase/dispatch.hpp"

#include "poses.hpp"

namespace {

using namespace impulse;
using test::at;

template <class T>
bool same(const contact_manifold<T>& a, const contact_manifold<T>& b) {
  if (a.count != b.count || (!a.empty() && !(a.normal == b.normal))) return false;
  for (int k = 0; k < a.count; ++k) {
    const auto &p = a.points[std::size_t(k)], &q = b.points[std::size_t(k)];
    if (!(p.position == q.position) || p.depth != q.depth || p.feature != q.feature) return false;
  }
  return true;
}

}  // namespace

namespace user {

/// A user's shape: a ball it wants tested only against itself and spheres.
template <class T>
struct lump {
  static constexpr impulse::policy_kind kind = impulse::policy_kind::shape;
  T radius = T(0.5);
};
inline int lump_tests = 0;
template <class T>
impulse::contact_manifold<T> collide(const lump<T>& a, const impulse::transform<T>& pa, const lump<T>& b,
                                     const impulse::transform<T>& pb, T margin) {
  ++lump_tests;
  return impulse::narrowphase::collide(impulse::sphere<T>{a.radius}, pa, impulse::sphere<T>{b.radius}, pb, margin);
}
template <class T>
impulse::contact_manifold<T> collide(const lump<T>& a, const impulse::transform<T>& pa, const impulse::sphere<T>& b,
                                     const impulse::transform<T>& pb, T margin) {
  ++lump_tests;
  return impulse::narrowphase::collide(impulse::sphere<T>{a.radius}, pa, b, pb, margin);
}
template <class T>
impulse::contact_manifold<T> collide(const impulse::sphere<T>& a, const impulse::transform<T>& pa, const lump<T>& b,
                                     const impulse::transform<T>& pb, T margin) {
  return collide(b, pb, a, pa, margin).flipped();
}

}  // namespace user

TEST_CASE_TEMPLATE("every listed pair reaches its own test", T, float, double) {
  using all = shape_list<sphere, box, capsule, convex_hull, plane>;
  using dispatch = narrowphase::dispatcher<all, T>;
  static_assert(dispatch::shape_count == 5);
  static_assert(dispatch::template index_of<box<T>> == 1 && dispatch::template index_of<plane<T>> == 4);
  const sphere<T> ball{T(0.5)};
  const box<T> brick{{T(0.5), T(0.3), T(0.4)}};
  const capsule<T> rod{T(0.2), T(0.5)};
  const convex_hull<T> hull = convex_hull<T>::from_points(test::box_corners<T>({T(0.4), T(0.4), T(0.4)}));
  const plane<T> ground{vec3<T>::unit_y(), T(0)};
  const typename dispatch::shape_ref refs[] = {dispatch::ref(ball), dispatch::ref(brick), dispatch::ref(rod),
                                               dispatch::ref(hull), dispatch::ref(ground)};
  // Each ordered pair at a pose where most pairs touch, through the table
  // and directly: the same manifold, to the bit.
  const transform<T> pa = at<T>({}, quat<T>::from_axis_angle(vec3<T>::unit_z(), T(0.3)));
  const transform<T> pb = at<T>({T(0.2), T(0.45), T(-0.1)}, quat<T>::from_axis_angle(vec3<T>::unit_x(), T(0.5)));
  const auto direct = [&](const auto& a, const auto& b) { return narrowphase::collide(a, pa, b, pb, T(0.01)); };
  const contact_manifold<T> expected[5][5] = {
      {direct(ball, ball), direct(ball, brick), direct(ball, rod), direct(ball, hull), direct(ball, ground)},
      {direct(brick, ball), direct(brick, brick), direct(brick, rod), direct(brick, hull), direct(brick, ground)},
      {direct(rod, ball), direct(rod, brick), direct(rod, rod), direct(rod, hull), direct(rod, ground)},
      {direct(hull, ball), direct(hull, brick), direct(hull, rod), direct(hull, hull), direct(hull, ground)},
      {direct(ground, ball), direct(ground, brick), direct(ground, rod), direct(ground, hull), {}}};
  int touching = 0;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) {
      const contact_manifold<T> m = dispatch::collide(refs[i], pa, refs[j], pb, T(0.01));
      CHECK(same(m, expected[i][j]));
      touching += !m.empty();
    }
  }
  CHECK(touching == 24);  // all but plane against plane
}

TEST_CASE("a user's shape joins by its own collide, and unlisted pairs are never compiled") {
  // lump has tests against itself and spheres only; the list names just
  // those, so lump–box, lump–capsule, … are never asked for.
  using dispatch = narrowphase::dispatcher<shape_list<sphere, user::lump>, double>;
  const sphere<double> ball{0.5};
  const user::lump<double> blob{0.5};
  user::lump_tests = 0;
  const auto m = dispatch::collide(dispatch::ref(blob), at<double>({}), dispatch::ref(ball), at<double>({0.9, 0, 0}));
  REQUIRE(m.count == 1);
  CHECK(m.points[0].depth == doctest::Approx(0.1).epsilon(1e-12));
  CHECK(m.normal.x == doctest::Approx(1).epsilon(1e-12));
  const auto flipped =
      dispatch::collide(dispatch::ref(ball), at<double>({0.9, 0, 0}), dispatch::ref(blob), at<double>({}));
  CHECK(flipped.normal.x == doctest::Approx(-1).epsilon(1e-12));
  CHECK(dispatch::collide(dispatch::ref(blob), at<double>({}), dispatch::ref(blob), at<double>({0, 2, 0})).empty());
  CHECK(user::lump_tests == 3);
  static_assert(!narrowphase::has_pair_test<user::lump<double>, box<double>, double>);
}
