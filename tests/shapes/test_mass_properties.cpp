// Mass properties: the closed forms of sphere, box and capsule against
// independent integrations, the polyhedron integrals against the closed
// forms, and the parallel-axis theorem on compounds.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "impulse/math/quat.hpp"
#include "impulse/shapes/box.hpp"
#include "impulse/shapes/capsule.hpp"
#include "impulse/shapes/convex_hull.hpp"
#include "impulse/shapes/mass_properties.hpp"
#include "impulse/shapes/sphere.hpp"

#include "../error_code_of.hpp"

namespace shapes_mass_properties_tests {

namespace {

using impulse::mat3;
using impulse::vec3;
constexpr double pi = 3.14159265358979323846;

template <class T>
T epsilon() { return std::numeric_limits<T>::epsilon(); }

template <class T>
T relative_difference(const mat3<T>& a, const mat3<T>& b) {
  T largest = 0, diff = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      largest = std::max(largest, std::abs(b(r, c)));
      diff = std::max(diff, std::abs(a(r, c) - b(r, c)));
    }
  return diff / largest;
}

/// The 8 corners and 12 outward triangles of a box of half extents h at c.
template <class T>
void box_mesh(const vec3<T>& h, const vec3<T>& c, std::vector<vec3<T>>& v, std::vector<std::uint32_t>& t) {
  v.clear();
  for (int i = 0; i < 8; ++i)
    v.push_back(c + vec3<T>{(i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z});
  t = {0, 2, 1, 1, 2, 3,   4, 5, 6, 5, 7, 6,   0, 1, 4, 1, 5, 4,
       2, 6, 3, 3, 6, 7,   0, 4, 2, 2, 4, 6,   1, 3, 5, 3, 7, 5};
}

/// An icosahedron subdivided `levels` times and pushed onto the sphere of radius r.
template <class T>
void sphere_mesh(int levels, T r, std::vector<vec3<T>>& v, std::vector<std::uint32_t>& t) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<vec3<double>> p = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                 {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  std::vector<std::uint32_t> f = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,
                                  11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8,
                                  3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
  for (auto& q : p) q = normalize(q);
  for (int l = 0; l < levels; ++l) {
    std::vector<std::uint32_t> next;
    for (std::size_t i = 0; i < f.size(); i += 3) {
      std::uint32_t m[3];
      for (int k = 0; k < 3; ++k) {
        p.push_back(normalize(p[f[i + k]] + p[f[i + (k + 1) % 3]]));  // shared edges duplicate points: harmless here
        m[k] = std::uint32_t(p.size() - 1);
      }
      next.insert(next.end(), {f[i], m[0], m[2], m[0], f[i + 1], m[1], m[2], m[1], f[i + 2], m[0], m[1], m[2]});
    }
    f = next;
  }
  v.clear();
  for (const auto& q : p) v.push_back({T(q.x * r), T(q.y * r), T(q.z * r)});
  t = f;
}

TEST_CASE_TEMPLATE("a hull of a box's corners has the box's mass properties", T, float, double) {
  const impulse::box<T> b{{T(0.5), T(1.25), T(2)}};
  std::vector<vec3<T>> v;
  std::vector<std::uint32_t> t;
  box_mesh(b.half_extents, {}, v, t);
  const auto exact = mass_properties_of(b, T(3));
  const auto mesh = impulse::polyhedron_mass_properties<T>(v, t, T(3));
  // The integrals run in double; what is left is rounding the inputs to T.
  CHECK(std::abs(mesh.mass - exact.mass) <= T(1e-6) * exact.mass);
  CHECK(relative_difference(mesh.inertia, exact.inertia) <= T(1e-6));
  CHECK(max_component(abs(mesh.center)) <= T(1e-6));
}

TEST_CASE_TEMPLATE("the convex hull of a box's corners has the box's mass properties", T, float, double) {
  const impulse::box<T> b{{T(0.5), T(1.25), T(2)}};
  std::vector<vec3<T>> v;
  std::vector<std::uint32_t> t;
  box_mesh(b.half_extents, vec3<T>{T(3), T(-1), T(7)}, v, t);
  v.push_back(vec3<T>{T(3), T(-1), T(7)});  // an inside point, dropped by the hull
  const auto hull = impulse::convex_hull<T>::from_points(v);
  REQUIRE(hull.face_count() == 6);
  const auto exact = mass_properties_of(b, T(3));
  const auto solid = mass_properties_of(hull, T(3));
  CHECK(std::abs(solid.mass - exact.mass) <= T(1e-6) * exact.mass);
  CHECK(relative_difference(solid.inertia, exact.inertia) <= T(1e-6));
  CHECK(max_component(abs(solid.center - vec3<T>{T(3), T(-1), T(7)})) <= T(1e-6) * T(8));
}

TEST_CASE_TEMPLATE("a finer tessellated sphere converges to the sphere's mass properties at second order", T, float, double) {
  const impulse::sphere<T> s{T(0.75)};
  const auto exact = mass_properties_of(s, T(2));
  double previous = 0;
  for (int level = 1; level <= 5; ++level) {
    std::vector<vec3<T>> v;
    std::vector<std::uint32_t> t;
    sphere_mesh(level, s.radius, v, t);
    const auto mesh = impulse::polyhedron_mass_properties<T>(v, t, T(2));
    const double error = std::abs(double(mesh.inertia(0, 0)) - double(exact.inertia(0, 0))) / double(exact.inertia(0, 0));
    CAPTURE(level);
    CAPTURE(error);
    // Inscribed facets of edge ~e miss a sliver of depth ~e²: halving the
    // edge quarters the error (ratio between 3 and 5 allows for the
    // icosphere's uneven facets).
    if (level > 1) CHECK(previous / error == doctest::Approx(4).epsilon(0.25));
    previous = error;
  }
  CHECK(previous < 1e-3);  // 20 480 facets
}

TEST_CASE_TEMPLATE("a polyhedron far from the origin has the same inertia about its center of mass", T, float, double) {
  std::vector<vec3<T>> v;
  std::vector<std::uint32_t> t;
  sphere_mesh(2, T(1), v, t);
  const auto here = impulse::polyhedron_mass_properties<T>(v, t, T(1));
  const vec3<T> far{T(1e4), T(-2e4), T(3e4)};
  for (auto& p : v) p = p + far;
  const auto there = impulse::polyhedron_mass_properties<T>(v, t, T(1));
  // Integrated about the mean vertex: only the input rounding at 3e4 (ε·3e4
  // relative to a unit body) is left.
  const T tolerance = T(10) * epsilon<T>() * T(3e4);
  CHECK(relative_difference(there.inertia, here.inertia) <= tolerance);
  CHECK(max_component(abs(there.center - (here.center + far))) <= tolerance);
}

TEST_CASE("the capsule's closed form matches an independent slice-by-slice integration") {
  // Disks of radius ρ(y) stacked along y: dm = πρ²dy, axial dI = dm·ρ²/2,
  // transverse dI = dm·(ρ²/4 + y²). ρ² is a polynomial on each of the three
  // pieces, so Simpson's rule on each converges fast.
  const double r = 0.3, h = 0.7, density = 2.5;
  auto integrate = [&](double a, double b, auto&& f) {
    const int n = 2000;
    double sum = f(a) + f(b);
    for (int i = 1; i < n; ++i) sum += f(a + (b - a) * i / n) * (i % 2 ? 4 : 2);
    return sum * (b - a) / (3 * n);
  };
  auto rho2 = [&](double y) { const double e = std::abs(y) - h; return e <= 0 ? r * r : r * r - e * e; };
  double mass = 0, axial = 0, across = 0;
  for (auto [a, b] : {std::pair{-h - r, -h}, std::pair{-h, h}, std::pair{h, h + r}}) {
    mass += integrate(a, b, [&](double y) { return pi * rho2(y); });
    axial += integrate(a, b, [&](double y) { return pi * rho2(y) * rho2(y) / 2; });
    across += integrate(a, b, [&](double y) { return pi * rho2(y) * (rho2(y) / 4 + y * y); });
  }
  const auto c = mass_properties_of(impulse::capsule<double>{r, h}, density);
  CHECK(c.mass == doctest::Approx(mass * density).epsilon(1e-10));
  CHECK(c.inertia(1, 1) == doctest::Approx(axial * density).epsilon(1e-10));
  CHECK(c.inertia(0, 0) == doctest::Approx(across * density).epsilon(1e-10));
  CHECK(c.inertia(2, 2) == c.inertia(0, 0));
  // And with no core segment it is the sphere.
  const auto ball = mass_properties_of(impulse::capsule<double>{r, 0}, density);
  const auto sphere = mass_properties_of(impulse::sphere<double>{r}, density);
  CHECK(ball.mass == doctest::Approx(sphere.mass).epsilon(1e-15));
  CHECK(ball.inertia(0, 0) == doctest::Approx(sphere.inertia(0, 0)).epsilon(1e-15));
}

TEST_CASE_TEMPLATE("two half boxes combined by the parallel-axis theorem make the whole box", T, float, double) {
  const impulse::box<T> half{{T(0.5), T(0.75), T(1)}}, whole{{T(1), T(0.75), T(1)}};
  const auto part = mass_properties_of(half, T(7));
  const mat3<T> identity = mat3<T>::identity();
  const auto left = impulse::transformed(part, identity, vec3<T>{T(-0.5), 0, 0});
  const auto right = impulse::transformed(part, identity, vec3<T>{T(0.5), 0, 0});
  const auto sum = impulse::combine(left, right);
  const auto exact = mass_properties_of(whole, T(7));
  CHECK(std::abs(sum.mass - exact.mass) <= 4 * epsilon<T>() * exact.mass);
  CHECK(relative_difference(sum.inertia, exact.inertia) <= 16 * epsilon<T>());
  CHECK(max_component(abs(sum.center)) <= 4 * epsilon<T>());
  // A quarter turn about z swaps the x and y moments.
  const mat3<T> quarter = impulse::to_mat3(impulse::quat<T>::from_axis_angle(vec3<T>::unit_z(), T(pi / 2)));
  const auto turned = impulse::transformed(exact, quarter, vec3<T>{});
  CHECK(turned.inertia(0, 0) == doctest::Approx(exact.inertia(1, 1)).epsilon(1e-5));
  CHECK(turned.inertia(1, 1) == doctest::Approx(exact.inertia(0, 0)).epsilon(1e-5));
}

TEST_CASE_TEMPLATE("bad densities and dimensions are refused with a clear error", T, float, double) {
  const T nan = std::numeric_limits<T>::quiet_NaN();
  using impulse::error_code;
  CHECK(impulse::test::error_code_of([] { (void)mass_properties_of(impulse::sphere<T>{1}, T(0)); }) == error_code::non_positive_mass);
  CHECK(impulse::test::error_code_of([] { (void)mass_properties_of(impulse::box<T>{}, T(-1)); }) == error_code::non_positive_mass);
  CHECK(impulse::test::error_code_of([&] { (void)mass_properties_of(impulse::box<T>{}, nan); }) == error_code::non_finite);
  CHECK(impulse::test::error_code_of([] { (void)impulse::sphere<T>::make(0); }) == error_code::degenerate_shape);
  CHECK(impulse::test::error_code_of([] { (void)impulse::box<T>::make({1, 0, 1}); }) == error_code::degenerate_shape);
  CHECK(impulse::test::error_code_of([&] { (void)impulse::box<T>::make({1, nan, 1}); }) == error_code::non_finite);
  CHECK(impulse::test::error_code_of([] { (void)impulse::capsule<T>::make(0, 1); }) == error_code::degenerate_shape);
  CHECK(impulse::test::error_code_of([] { (void)impulse::capsule<T>::make(1, -1); }) == error_code::degenerate_shape);
  // A flat "polyhedron" encloses nothing.
  std::vector<vec3<T>> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  std::vector<std::uint32_t> t = {0, 1, 2, 2, 1, 3, 0, 2, 1, 2, 3, 1};
  CHECK(impulse::test::error_code_of([&] { (void)impulse::polyhedron_mass_properties<T>(v, t, T(1)); }) == error_code::degenerate_shape);
  t[0] = 9;
  CHECK(impulse::test::error_code_of([&] { (void)impulse::polyhedron_mass_properties<T>(v, t, T(1)); }) == error_code::out_of_range);
}

}  // namespace

}  // namespace shapes_mass_properties_tests
