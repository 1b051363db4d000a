// Dispatch from the config's shape_list: every listed pair reaches the test
// written for it, static pairs are empty, and a user's shape joins by its
// own collide without the pairs it is not listed with being compiled. (A
// listed pair with no test is a compile error naming it: see
// tests/compile_fail/pair_test_missing.cpp.)
#include <doctest/doctest.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "impulse/narrowphase.hpp"
#include "impulse/narrowphase/dispatch.hpp"

#include "poses.hpp"

namespace narrowphase_dispatch_tests {

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
  using all = shape_list<sphere, box, capsule, convex_hull, plane, triangle_mesh>;
  using dispatch = narrowphase::dispatcher<all, T>;
  static_assert(dispatch::shape_count == 6);
  static_assert(dispatch::template index_of<box<T>> == 1 && dispatch::template index_of<triangle_mesh<T>> == 5);
  const sphere<T> ball{T(0.5)};
  const box<T> brick{{T(0.5), T(0.3), T(0.4)}};
  const capsule<T> rod{T(0.2), T(0.5)};
  const convex_hull<T> hull = convex_hull<T>::from_points(test::box_corners<T>({T(0.4), T(0.4), T(0.4)}));
  const plane<T> ground{vec3<T>::unit_y(), T(0)};
  // A floor of two triangles, 4 m across, facing +y.
  const std::vector<vec3<T>> corners{{-2, 0, -2}, {2, 0, -2}, {2, 0, 2}, {-2, 0, 2}};
  const std::vector<std::uint32_t> triangles{0, 2, 1, 0, 3, 2};
  const triangle_mesh<T> floor = triangle_mesh<T>::make(corners, triangles);
  const typename dispatch::shape_ref refs[] = {dispatch::ref(ball), dispatch::ref(brick), dispatch::ref(rod),
                                               dispatch::ref(hull), dispatch::ref(ground), dispatch::ref(floor)};
  // Each ordered pair through the table and directly: the same manifolds,
  // to the bit. At these poses every pair touches but the static ones and
  // a shape at pa under the floor at pb: the mesh is one-sided, and the
  // shape's center is behind it.
  const transform<T> pa = at<T>({}, quat<T>::from_axis_angle(vec3<T>::unit_z(), T(0.3)));
  const transform<T> pb = at<T>({T(0.2), T(0.45), T(-0.1)}, quat<T>::from_axis_angle(vec3<T>::unit_x(), T(0.5)));
  const T margin = T(0.01);
  using manifolds = std::vector<contact_manifold<T>>;
  const auto one = [](const contact_manifold<T>& m) { return m.empty() ? manifolds{} : manifolds{m}; };
  const auto direct = [&](const auto& a, const auto& b) -> manifolds {
    if constexpr (requires { narrowphase::collide(a, pa, b, pb, margin); }) {
      return one(narrowphase::collide(a, pa, b, pb, margin));
    } else {
      std::array<contact_manifold<T>, 4> out;
      const std::size_t n = narrowphase::collide(a, pa, b, pb, margin, std::span<contact_manifold<T>>(out));
      return manifolds(out.begin(), out.begin() + std::ptrdiff_t(n));
    }
  };
  const auto row = [&](const auto& a) {
    return std::array<manifolds, 6>{direct(a, ball), direct(a, brick), direct(a, rod),
                                    direct(a, hull), direct(a, ground), direct(a, floor)};
  };
  std::array<std::array<manifolds, 6>, 6> expected{row(ball), row(brick), row(rod), row(hull), {}, {}};
  expected[4] = {direct(ground, ball), direct(ground, brick), direct(ground, rod), direct(ground, hull), {}, {}};
  expected[5] = {direct(floor, ball), direct(floor, brick), direct(floor, rod), direct(floor, hull), {}, {}};
  int touching = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    for (std::size_t j = 0; j < 6; ++j) {
      std::array<contact_manifold<T>, 4> out;
      const std::size_t n = dispatch::collide(refs[i], pa, refs[j], pb, margin, out);
      REQUIRE(n == expected[i][j].size());
      for (std::size_t k = 0; k < n; ++k) CHECK(same(out[k], expected[i][j][k]));
      touching += n > 0;
      if (i < 4) CHECK((n > 0) == (j != 5));
    }
  }
  CHECK(touching == 28);
}

TEST_CASE("a user's shape joins by its own collide, and unlisted pairs are never compiled") {
  // lump has tests against itself and spheres only; the list names just
  // those, so lump–box, lump–capsule, … are never asked for.
  using dispatch = narrowphase::dispatcher<shape_list<sphere, user::lump>, double>;
  const sphere<double> ball{0.5};
  const user::lump<double> blob{0.5};
  user::lump_tests = 0;
  std::array<contact_manifold<double>, 1> out;
  REQUIRE(dispatch::collide(dispatch::ref(blob), at<double>({}), dispatch::ref(ball), at<double>({0.9, 0, 0}), 0.0, out) == 1);
  CHECK(out[0].points[0].depth == doctest::Approx(0.1).epsilon(1e-12));
  CHECK(out[0].normal.x == doctest::Approx(1).epsilon(1e-12));
  REQUIRE(dispatch::collide(dispatch::ref(ball), at<double>({0.9, 0, 0}), dispatch::ref(blob), at<double>({}), 0.0, out) == 1);
  CHECK(out[0].normal.x == doctest::Approx(-1).epsilon(1e-12));
  CHECK(dispatch::collide(dispatch::ref(blob), at<double>({}), dispatch::ref(blob), at<double>({0, 2, 0}), 0.0, out) == 0);
  CHECK(user::lump_tests == 3);
  static_assert(!narrowphase::has_pair_test<user::lump<double>, box<double>, double>);
}

}  // namespace narrowphase_dispatch_tests
