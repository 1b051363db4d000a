// Closest point on a triangle by Voronoi regions: one point in each of the
// seven regions with its exact answer, 10 000 random points against an
// independent reference, and degenerate triangles.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "impulse/core/random.hpp"
#include "impulse/narrowphase/triangle.hpp"

namespace narrowphase_triangle_tests {

namespace {

using namespace impulse;
using narrowphase::closest_point_on_triangle;
using narrowphase::triangle_region;

template <class T>
constexpr T tolerance = sizeof(T) == 4 ? T(1e-5) : T(1e-12);

/// The closest point computed another way: the projection onto the plane
/// if it falls inside (solved by Cramer's rule), else the nearest of the
/// three edges.
template <class T>
vec3<T> reference(const vec3<T>& p, const vec3<T>& a, const vec3<T>& b, const vec3<T>& c) {
  const vec3<T> ab = b - a, ac = c - a, ap = p - a;
  const T d00 = dot(ab, ab), d01 = dot(ab, ac), d11 = dot(ac, ac), d20 = dot(ap, ab), d21 = dot(ap, ac);
  const T det = d00 * d11 - d01 * d01;
  if (det > T(0)) {
    const T v = (d11 * d20 - d01 * d21) / det, w = (d00 * d21 - d01 * d20) / det;
    if (v >= T(0) && w >= T(0) && v + w <= T(1)) return a + ab * v + ac * w;
  }
  vec3<T> best = narrowphase::detail::closest_point_on_segment(a, b, p);
  for (const vec3<T>& q : {narrowphase::detail::closest_point_on_segment(b, c, p),
                           narrowphase::detail::closest_point_on_segment(c, a, p)})
    if (length_squared(q - p) < length_squared(best - p)) best = q;
  return best;
}

}  // namespace

TEST_CASE_TEMPLATE("closest point on a triangle in each of its seven regions", T, float, double) {
  const vec3<T> a{0, 0, 0}, b{2, 0, 0}, c{0, 2, 0};
  struct expected {
    vec3<T> p, point;
    triangle_region region;
  };
  const expected cases[] = {
      {{-1, -1, 3}, a, triangle_region::vertex_a},
      {{3, T(-0.5), 1}, b, triangle_region::vertex_b},
      {{T(-0.5), 3, -1}, c, triangle_region::vertex_c},
      {{1, -1, 2}, {1, 0, 0}, triangle_region::edge_ab},
      {{-1, 1, T(0.5)}, {0, 1, 0}, triangle_region::edge_ca},
      {{2, 2, 1}, {1, 1, 0}, triangle_region::edge_bc},
      {{T(0.5), T(0.5), -3}, {T(0.5), T(0.5), 0}, triangle_region::face},
  };
  for (const expected& e : cases) {
    const auto r = closest_point_on_triangle(e.p, a, b, c);
    CHECK(r.region == e.region);
    CHECK(length(r.point - e.point) <= tolerance<T>);
    CHECK(length(a * r.barycentric.x + b * r.barycentric.y + c * r.barycentric.z - r.point) <= tolerance<T>);
  }
  const auto face = closest_point_on_triangle(vec3<T>{T(0.5), T(0.5), -3}, a, b, c);
  CHECK(length(face.barycentric - vec3<T>{T(0.5), T(0.25), T(0.25)}) <= tolerance<T>);
}

TEST_CASE_TEMPLATE("closest point on random triangles agrees with an independent reference", T, float, double) {
  lcg32 random{5};
  const auto point = [&](T spread) {
    return vec3<T>{random.uniform<T>(-spread, spread), random.uniform<T>(-spread, spread), random.uniform<T>(-spread, spread)};
  };
  int regions_seen[7] = {};
  for (int k = 0; k < 10000; ++k) {
    const vec3<T> a = point(1), b = point(1), c = point(1), p = point(3);
    const auto r = closest_point_on_triangle(p, a, b, c);
    const vec3<T> q = reference(p, a, b, c);
    CHECK(std::abs(length(r.point - p) - length(q - p)) <= T(10) * tolerance<T> * (T(1) + length(q - p)));
    const vec3<T>& w = r.barycentric;
    CHECK(std::min({w.x, w.y, w.z}) >= T(0));
    CHECK(std::abs(w.x + w.y + w.z - T(1)) <= T(10) * tolerance<T>);
    ++regions_seen[int(r.region)];
  }
  for (const int seen : regions_seen) CHECK(seen > 100);
}

TEST_CASE_TEMPLATE("degenerate triangles: corners on a line, or all at one point", T, float, double) {
  // On a line: the nearest point of the segment from 0 to 2 along x.
  const vec3<T> a{0, 0, 0}, b{1, 0, 0}, c{2, 0, 0};
  auto r = closest_point_on_triangle(vec3<T>{T(1.5), 1, 0}, a, b, c);
  CHECK(length(r.point - vec3<T>{T(1.5), 0, 0}) <= tolerance<T>);
  CHECK(is_finite(r.barycentric));
  CHECK((r.region == triangle_region::edge_bc || r.region == triangle_region::edge_ca));
  // All at one point.
  r = closest_point_on_triangle(vec3<T>{1, 2, 3}, a, a, a);
  CHECK(r.point == a);
  CHECK(is_finite(r.barycentric));
  // Two corners together.
  r = closest_point_on_triangle(vec3<T>{T(0.5), 1, 0}, a, a, b);
  CHECK(length(r.point - vec3<T>{T(0.5), 0, 0}) <= tolerance<T>);
}

}  // namespace narrowphase_triangle_tests
