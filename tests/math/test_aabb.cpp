// Tests of impulse/math/aabb.hpp. Boxes with corners on small integers and
// halves make every bound exact, so containment and overlap are checked at
// exactly touching faces.
#include <impulse/math/aabb.hpp>

#include <array>
#include <cmath>
#include <limits>

#include "tolerances.hpp"

namespace math_aabb_tests {

using namespace impulse;
using namespace impulse::test;

namespace {

template <class T>
constexpr T pi = T(3.14159265358979323846);

template <class T>
aabb<T> unit_cube() {
  return {vec3<T>::zero(), vec3<T>::splat(1)};
}

/// The eight corners of b.
template <class T>
std::array<vec3<T>, 8> corners(const aabb<T>& b) {
  std::array<vec3<T>, 8> c;
  for (int i = 0; i < 8; ++i) {
    c[i] = {(i & 1) ? b.upper.x : b.lower.x, (i & 2) ? b.upper.y : b.lower.y, (i & 4) ? b.upper.z : b.lower.z};
  }
  return c;
}

}  // namespace

TEST_CASE_TEMPLATE("the empty box is not valid and is the identity of merge", T, float, double) {
  const aabb<T> empty = aabb<T>::empty();
  const aabb<T> b{{-1, 2, 0}, {3, 4, T(0.5)}};
  CHECK_FALSE(is_valid(empty));
  CHECK(is_valid(b));
  CHECK(merge(empty, b) == b);
  CHECK(merge(b, empty) == b);
  CHECK(merge(empty, empty) == empty);
  CHECK_FALSE(contains(empty, vec3<T>::zero()));
  CHECK_FALSE(overlaps(empty, b));
}

TEST_CASE_TEMPLATE("center and half extents recover the box they built", T, float, double) {
  const vec3<T> c{1, -2, T(0.5)};
  const vec3<T> h{T(0.5), 2, 3};
  const aabb<T> b = aabb<T>::from_center_half_extents(c, h);
  CHECK(b.lower == vec3<T>{T(0.5), -4, T(-2.5)});
  CHECK(b.upper == vec3<T>{T(1.5), 0, T(3.5)});
  CHECK(center(b) == c);
  CHECK(half_extents(b) == h);
}

TEST_CASE_TEMPLATE("a box contains its interior and its boundary but no outside point", T, float, double) {
  const aabb<T> b = unit_cube<T>();
  CHECK(contains(b, vec3<T>::splat(T(0.5))));
  for (const vec3<T>& corner : corners(b)) CHECK(contains(b, corner));
  CHECK(contains(b, vec3<T>{1, T(0.5), T(0.5)}));  // on a face
  for (int axis = 0; axis < 3; ++axis) {
    vec3<T> below = vec3<T>::splat(T(0.5));
    vec3<T> above = vec3<T>::splat(T(0.5));
    below[axis] = std::nextafter(T(0), T(-1));
    above[axis] = std::nextafter(T(1), T(2));
    CHECK_FALSE(contains(b, below));
    CHECK_FALSE(contains(b, above));
  }
}

TEST_CASE_TEMPLATE("a box contains the boxes inside it including those touching its faces", T, float, double) {
  const aabb<T> outer = unit_cube<T>();
  CHECK(contains(outer, outer));
  CHECK(contains(outer, aabb<T>{vec3<T>::splat(T(0.25)), vec3<T>::splat(T(0.75))}));
  CHECK(contains(outer, aabb<T>{{0, T(0.25), T(0.25)}, {T(0.5), 1, T(0.75)}}));
  CHECK_FALSE(contains(outer, aabb<T>{{T(0.5), T(0.5), T(0.5)}, {T(1.5), 1, 1}}));
  CHECK_FALSE(contains(outer, aabb<T>{vec3<T>::splat(-1), vec3<T>::splat(2)}));
}

TEST_CASE_TEMPLATE("boxes that touch at a face or an edge or a corner overlap", T, float, double) {
  const aabb<T> a = unit_cube<T>();
  for (int axis = 0; axis < 3; ++axis) {
    aabb<T> b = a;
    b.lower[axis] = 1;
    b.upper[axis] = 2;
    CHECK(overlaps(a, b));
    CHECK(overlaps(b, a));
  }
  CHECK(overlaps(a, aabb<T>{vec3<T>::splat(1), vec3<T>::splat(2)}));
  CHECK(overlaps(a, aabb<T>{vec3<T>::splat(T(0.5)), vec3<T>::splat(T(0.6))}));
  CHECK(overlaps(a, aabb<T>{vec3<T>::splat(-1), vec3<T>::splat(2)}));
}

TEST_CASE_TEMPLATE("boxes separated along a single axis do not overlap", T, float, double) {
  const aabb<T> a = unit_cube<T>();
  for (int axis = 0; axis < 3; ++axis) {
    aabb<T> above = a;  // overlapping on the other two axes
    above.lower[axis] = std::nextafter(T(1), T(2));
    above.upper[axis] = 2;
    aabb<T> below = a;
    below.lower[axis] = -2;
    below.upper[axis] = std::nextafter(T(0), T(-1));
    CHECK_FALSE(overlaps(a, above));
    CHECK_FALSE(overlaps(above, a));
    CHECK_FALSE(overlaps(a, below));
    CHECK_FALSE(overlaps(below, a));
  }
}

TEST_CASE_TEMPLATE("merging two boxes gives the smallest box containing both", T, float, double) {
  const aabb<T> a{{0, 0, 0}, {1, 2, 3}};
  const aabb<T> b{{-1, 1, 1}, {T(0.5), 4, 2}};
  const aabb<T> m = merge(a, b);
  CHECK(m == aabb<T>{{-1, 0, 0}, {1, 4, 3}});
  CHECK(contains(m, a));
  CHECK(contains(m, b));
  CHECK(merge(b, a) == m);
}

TEST_CASE_TEMPLATE("merging points into the empty box gives their bounds", T, float, double) {
  const vec3<T> points[] = {{1, -2, 3}, {-4, 5, 0}, {2, 2, -1}};
  aabb<T> b = aabb<T>::empty();
  for (const vec3<T>& p : points) b = merge(b, p);
  CHECK(b == aabb<T>{{-4, -2, -1}, {2, 5, 3}});
  CHECK(merge(aabb<T>::empty(), points[0]) == aabb<T>{points[0], points[0]});
  CHECK(is_valid(merge(aabb<T>::empty(), points[0])));
}

TEST_CASE_TEMPLATE("expand moves every face out by the margin", T, float, double) {
  const aabb<T> b{{0, 1, 2}, {1, 2, 4}};
  CHECK(expand(b, T(0.5)) == aabb<T>{{T(-0.5), T(0.5), T(1.5)}, {T(1.5), T(2.5), T(4.5)}});
  CHECK(expand(b, T(0)) == b);
}

TEST_CASE_TEMPLATE("a unit cube has surface area 6 and volume 1", T, float, double) {
  CHECK(surface_area(unit_cube<T>()) == 6);
  CHECK(volume(unit_cube<T>()) == 1);
}

TEST_CASE_TEMPLATE("a 1 by 2 by 3 box has surface area 22 and volume 6", T, float, double) {
  const aabb<T> b{{-1, 5, T(0.5)}, {0, 7, T(3.5)}};
  CHECK(surface_area(b) == 22);
  CHECK(volume(b) == 6);
}

TEST_CASE_TEMPLATE("a box rotated 45 degrees about z has world half extents of the diagonal", T, float, double) {
  // A world half extent sums two products of a rounded cos 45° and h, and the
  // expected value is rounded too: four roundings of a number near 2, where
  // an ulp is 2 epsilon. The center lies near 32, where an ulp is 32 epsilon.
  const T half_extent_rounding = 4 * 2 * epsilon<T>;
  const T center_rounding = 2 * 32 * epsilon<T>;
  const vec3<T> h{1, 2, 3};
  const vec3<T> c{5, -1, 2};
  const transform<T> t{{10, 20, 30}, quat<T>::from_axis_angle(vec3<T>::unit_z(), pi<T> / 4)};
  const aabb<T> world = transform_aabb(aabb<T>::from_center_half_extents(c, h), t);
  const T r = std::sqrt(T(0.5));
  const vec3<T> expected_half{(h.x + h.y) * r, (h.x + h.y) * r, h.z};
  const vec3<T> expected_center = vec3<T>{(c.x - c.y) * r, (c.x + c.y) * r, c.z} + t.position;
  CHECK(max_abs_diff(half_extents(world), expected_half) <= half_extent_rounding);
  CHECK(max_abs_diff(center(world), expected_center) <= center_rounding);
}

TEST_CASE_TEMPLATE("transform_aabb with no rotation translates the box", T, float, double) {
  const aabb<T> b{{-1, 0, 2}, {1, 4, 3}};
  const transform<T> t{{10, -20, T(0.5)}, quat<T>::identity()};
  CHECK(transform_aabb(b, t) == aabb<T>{{9, -20, T(2.5)}, {11, -16, T(3.5)}});
}

TEST_CASE_TEMPLATE("a rotated box has every corner inside its world box and a corner on each face", T, float, double) {
  // Corners are placed by rotating once, the box by |R|·h: both are a few
  // roundings of numbers of size up to 20 m (box size plus offset).
  const T corner_rounding = 20 * rotation_rounding<T>;
  lcg rng;
  T worst_outside = 0;
  T worst_face_gap = 0;
  for (int i = 0; i < 1000; ++i) {
    const aabb<T> body = aabb<T>::from_center_half_extents(rng.vector<T>(-5, 5), rng.vector<T>(0.1, 5));
    const transform<T> t{rng.vector<T>(-10, 10), rng.rotation<T>()};
    const aabb<T> world = transform_aabb(body, t);
    vec3<T> nearest_lower = vec3<T>::splat(std::numeric_limits<T>::max());
    vec3<T> nearest_upper = vec3<T>::splat(std::numeric_limits<T>::max());
    for (const vec3<T>& corner : corners(body)) {
      const vec3<T> p = apply(t, corner);
      worst_outside = std::fmax(worst_outside, max_component(max(world.lower - p, p - world.upper)));
      nearest_lower = min(nearest_lower, p - world.lower);
      nearest_upper = min(nearest_upper, world.upper - p);
    }
    worst_face_gap = std::fmax(worst_face_gap, max_component(max(abs(nearest_lower), abs(nearest_upper))));
  }
  CHECK(worst_outside <= corner_rounding);
  CHECK(worst_face_gap <= corner_rounding);
}

}  // namespace math_aabb_tests
