// Shapes: support points are the farthest points of the solid in every
// direction, and world AABBs are the tightest boxes around the posed shape.
#include <doctest/doctest.h>

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "impulse/core/random.hpp"
#include "impulse/math/quat.hpp"
#include "impulse/shapes/box.hpp"
#include "impulse/shapes/capsule.hpp"
#include "impulse/shapes/plane.hpp"
#include "impulse/shapes/sphere.hpp"
#include "impulse/shapes/triangle_mesh.hpp"

#include "../error_code_of.hpp"

namespace shapes_shapes_tests {

namespace {

using impulse::vec3;

template <class T>
vec3<T> random_direction(impulse::lcg32& g) {
  return normalize(vec3<T>{g.uniform<T>(-1, 1), g.uniform<T>(-1, 1), g.uniform<T>(T(-1), T(1))} + vec3<T>{T(1e-3), 0, 0});
}

/// Support along d, checked against the farthest of many surface samples:
/// no sample lies farther, and the support point is on the surface.
template <class T, class Shape, class OnSurface>
void check_support(const Shape& shape, OnSurface&& sample_surface) {
  impulse::lcg32 g{99};
  std::vector<vec3<T>> samples;
  for (int i = 0; i < 2000; ++i) samples.push_back(sample_surface(g));
  T worst = -1;  // largest amount any sample lies beyond the support plane
  for (int k = 0; k < 200; ++k) {
    const vec3<T> d = random_direction<T>(g);
    const vec3<T> s = shape.support(d);
    for (const vec3<T>& p : samples) worst = std::max(worst, dot(p, d) - dot(s, d));
  }
  // A few roundings of unit-sized dot products.
  CHECK(worst <= T(16) * std::numeric_limits<T>::epsilon());
}

TEST_CASE_TEMPLATE("support points are the farthest points of each shape", T, float, double) {
  const impulse::sphere<T> ball{T(0.7)};
  check_support<T>(ball, [&](impulse::lcg32& g) { return random_direction<T>(g) * ball.radius; });
  const impulse::box<T> crate{{T(0.5), T(1), T(1.5)}};
  check_support<T>(crate, [&](impulse::lcg32& g) {  // points inside the box
    return mul(crate.half_extents, vec3<T>{g.uniform<T>(-1, 1), g.uniform<T>(-1, 1), g.uniform<T>(T(-1), T(1))});
  });
  const impulse::capsule<T> pill{T(0.3), T(0.8)};
  check_support<T>(pill, [&](impulse::lcg32& g) {
    const vec3<T> core{0, g.uniform<T>(-pill.half_height, pill.half_height), 0};
    return core + random_direction<T>(g) * pill.radius;
  });
  // The box's support is a corner, and the capsule's is a cap's surface point.
  const vec3<T> corner = crate.support({1, -1, 1});
  CHECK(corner == vec3<T>{T(0.5), T(-1), T(1.5)});
  CHECK(pill.support({0, 1, 0}) == vec3<T>{0, pill.half_height + pill.radius, 0});
  CHECK(length(ball.support({0, 0, 0})) == doctest::Approx(ball.radius));  // zero direction: still on the surface
}

TEST_CASE_TEMPLATE("world AABBs are the tight boxes around posed shapes", T, float, double) {
  impulse::lcg32 g{5};
  const impulse::box<T> crate{{T(0.5), T(1), T(1.5)}};
  const impulse::capsule<T> pill{T(0.3), T(0.8)};
  const impulse::sphere<T> ball{T(0.7)};
  for (int k = 0; k < 50; ++k) {
    const impulse::transform<T> pose{{g.uniform<T>(-5, 5), g.uniform<T>(-5, 5), g.uniform<T>(-5, 5)},
                                     impulse::quat<T>::from_axis_angle(random_direction<T>(g), g.uniform<T>(-3, 3))};
    // The tight bound along each axis is the support along that axis, posed.
    auto check_tight = [&](const auto& shape) {
      const impulse::aabb<T> box = shape.world_aabb(pose);
      for (int axis = 0; axis < 3; ++axis) {
        vec3<T> e{};
        e[axis] = 1;
        const T upper = dot(apply(pose, shape.support(inverse_rotate(pose.rotation, e))), e);
        const T lower = dot(apply(pose, shape.support(inverse_rotate(pose.rotation, -e))), e);
        // A few roundings of coordinates of size ~8 m.
        const T tolerance = T(64) * std::numeric_limits<T>::epsilon() * T(8);
        CHECK(std::abs(box.upper[axis] - upper) <= tolerance);
        CHECK(std::abs(box.lower[axis] - lower) <= tolerance);
      }
    };
    check_tight(crate);
    check_tight(pill);
    check_tight(ball);
  }
}

TEST_CASE_TEMPLATE("planes and triangle meshes refuse degenerate input", T, float, double) {
  using impulse::error_code;
  CHECK(impulse::test::error_code_of([] { (void)impulse::plane<T>::make({0, 0, 0}, 0); }) == error_code::degenerate_shape);
  CHECK(impulse::test::error_code_of([] { (void)impulse::plane<T>::make({0, 2, 0}, 0); }) == error_code::not_normalized);
  const std::vector<vec3<T>> v = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {2, 0, 0}};
  const std::vector<std::uint32_t> ok = {0, 2, 1}, missing = {0, 2, 7}, flat = {0, 1, 3};
  CHECK(impulse::test::error_code_of([&] { (void)impulse::triangle_mesh<T>::make(v, ok); }) == error_code::none);
  CHECK(impulse::test::error_code_of([&] { (void)impulse::triangle_mesh<T>::make(v, missing); }) == error_code::out_of_range);
  CHECK(impulse::test::error_code_of([&] { (void)impulse::triangle_mesh<T>::make(v, flat); }) == error_code::degenerate_shape);
  const auto mesh = impulse::triangle_mesh<T>::make(v, ok);
  CHECK(mesh.triangle_count() == 1);
  CHECK(mesh.local_aabb().upper == vec3<T>{2, 0, 1});
}

}  // namespace

}  // namespace shapes_shapes_tests
