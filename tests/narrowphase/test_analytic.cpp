// Analytic pair tests: every pair against closed-form answers (separated,
// touching, overlapping, contained), at a rotated and moved pose so that the
// frames are exercised, in float and double; feature ids that hold while
// the same features touch; and the manifold reduction.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "impulse/narrowphase.hpp"

namespace narrowphase_analytic_tests {

namespace {

using namespace impulse;
using narrowphase::collide;

/// Relative-to-size tolerance per scalar type: 1 m bodies, exact formulas.
template <class T>
constexpr T tolerance = sizeof(T) == 4 ? T(2e-5) : T(1e-12);

template <class T>
bool near(const vec3<T>& a, const vec3<T>& b) {
  return length(a - b) <= tolerance<T> * (T(1) + length(a));
}

/// A pose far from trivial: turned about a skew axis and moved.
template <class T>
transform<T> skew_pose() {
  return {{T(3), T(-2), T(5)}, quat<T>::from_axis_angle(normalize(vec3<T>{T(1), T(2), T(3)}), T(0.7))};
}

template <class T>
bool finite(const contact_manifold<T>& m) {
  bool ok = is_finite(m.normal) && std::abs(length(m.normal) - T(1)) <= tolerance<T>;
  for (const auto& p : m.contacts()) ok = ok && is_finite(p.position) && std::isfinite(p.depth);
  return ok;
}

}  // namespace

TEST_CASE_TEMPLATE("sphere against sphere: separated, within the margin, touching, overlapping, concentric", T, float,
                   double) {
  const sphere<T> s{T(0.5)};
  const transform<T> at_origin = transform<T>::identity();
  const vec3<T> n = normalize(vec3<T>{1, 2, 2});
  const auto at = [](const vec3<T>& p) { return transform<T>{p, quat<T>::identity()}; };

  CHECK(collide(s, at_origin, s, at(n * T(1.5))).empty());
  const auto within = collide(s, at_origin, s, at(n * T(1.5)), T(0.6));
  REQUIRE(within.count == 1);
  CHECK(within.points[0].depth == doctest::Approx(-0.5).epsilon(tolerance<T>));

  const auto touching = collide(s, at_origin, s, at(n));
  REQUIRE(touching.count == 1);
  CHECK(std::abs(touching.points[0].depth) <= tolerance<T>);

  // 0.8 apart along n: 0.2 deep, the point midway between the surfaces.
  const auto overlapping = collide(s, at_origin, s, at(n * T(0.8)));
  REQUIRE(overlapping.count == 1);
  CHECK(near(overlapping.normal, n));
  CHECK(overlapping.points[0].depth == doctest::Approx(0.2).epsilon(tolerance<T> * 10));
  CHECK(near(overlapping.points[0].position, n * T(0.4)));

  // Concentric: every direction is right; the result is +y, deep 2r.
  const auto concentric = collide(s, at_origin, s, at_origin);
  REQUIRE(concentric.count == 1);
  CHECK(finite(concentric));
  CHECK(concentric.normal == vec3<T>::unit_y());
  CHECK(concentric.points[0].depth == doctest::Approx(1.0));
}

TEST_CASE_TEMPLATE("sphere against a turned plane: depth along its normal and the normal from the sphere into it", T,
                   float, double) {
  const plane<T> ground{vec3<T>::unit_y(), T(0)};
  const transform<T> pose = skew_pose<T>();
  const vec3<T> n = apply_direction(pose, vec3<T>::unit_y());
  const vec3<T> on_surface = apply(pose, vec3<T>{T(0.3), T(0), T(-0.7)});
  const sphere<T> s{T(0.5)};
  const auto ball = [&](T height) { return transform<T>{on_surface + n * height, quat<T>::identity()}; };

  CHECK(collide(s, ball(T(0.6)), ground, pose).empty());
  const auto resting = collide(s, ball(T(0.4)), ground, pose);
  REQUIRE(resting.count == 1);
  CHECK(near(resting.normal, -n));
  CHECK(resting.points[0].depth == doctest::Approx(0.1).epsilon(tolerance<T> * 100));
  CHECK(near(resting.points[0].position, on_surface - n * T(0.05)));
  // Below the surface altogether: deeper than the diameter.
  const auto sunk = collide(s, ball(T(-2)), ground, pose);
  REQUIRE(sunk.count == 1);
  CHECK(sunk.points[0].depth == doctest::Approx(2.5).epsilon(tolerance<T> * 10));
  // The swapped pair is the same contact seen from the plane.
  const auto swapped = collide(ground, pose, s, ball(T(0.4)));
  CHECK(near(swapped.normal, n));
  CHECK(swapped.points[0].depth == resting.points[0].depth);
}

TEST_CASE_TEMPLATE("sphere against a box: face, edge, corner, inside, and ids that hold across a face", T, float,
                   double) {
  const box<T> b{{T(1), T(2), T(3)}};
  const transform<T> pose = skew_pose<T>();
  const auto ball_at = [&](const vec3<T>& local) { return transform<T>{apply(pose, local), quat<T>::identity()}; };
  const auto world_dir = [&](const vec3<T>& local) { return apply_direction(pose, normalize(local)); };

  // Face +x, 0.3 from it: radius 0.5 is 0.2 deep; the normal points into the box.
  auto m = collide(sphere<T>{T(0.5)}, ball_at({T(1.3), T(0.5), T(0.2)}), b, pose);
  REQUIRE(m.count == 1);
  CHECK(near(m.normal, world_dir({-1, 0, 0})));
  CHECK(m.points[0].depth == doctest::Approx(0.2).epsilon(tolerance<T> * 100));
  CHECK(near(m.points[0].position, apply(pose, vec3<T>{T(0.9), T(0.5), T(0.2)})));
  CHECK(m.points[0].feature == 2u);
  // Rolling across that face keeps the id.
  for (T y : {T(-1.5), T(0), T(1.9)})
    CHECK(collide(sphere<T>{T(0.5)}, ball_at({T(1.3), y, T(-2)}), b, pose).points[0].feature == 2u);

  // Edge (+x, +y): 0.5 from it, radius 0.6.
  m = collide(sphere<T>{T(0.6)}, ball_at({T(1.3), T(2.4), T(0)}), b, pose);
  REQUIRE(m.count == 1);
  CHECK(near(m.normal, world_dir({-0.6, -0.8, 0})));
  CHECK(m.points[0].depth == doctest::Approx(0.1).epsilon(tolerance<T> * 100));
  CHECK(m.points[0].feature == 2u + 3u * 2u);

  // Corner (+x, +y, +z): 0.3 from it, radius 0.4.
  m = collide(sphere<T>{T(0.4)}, ball_at({T(1.2), T(2.2), T(3.1)}), b, pose);
  REQUIRE(m.count == 1);
  CHECK(near(m.normal, world_dir({-0.2, -0.2, -0.1})));
  CHECK(m.points[0].depth == doctest::Approx(0.1).epsilon(tolerance<T> * 100));
  CHECK(m.points[0].feature == 2u + 3u * 2u + 9u * 2u);

  // Center inside, 0.1 below face +x: out through it, as deep as r + 0.1.
  m = collide(sphere<T>{T(0.5)}, ball_at({T(0.9), T(0.3), T(-1)}), b, pose);
  REQUIRE(m.count == 1);
  CHECK(near(m.normal, world_dir({-1, 0, 0})));
  CHECK(m.points[0].depth == doctest::Approx(0.6).epsilon(tolerance<T> * 100));
  CHECK(m.points[0].feature == 2u);
  // Center inside nearest face −z.
  m = collide(sphere<T>{T(0.5)}, ball_at({T(0), T(0), T(-2.8)}), b, pose);
  CHECK(near(m.normal, world_dir({0, 0, 1})));
  CHECK(m.points[0].feature == 9u * 1u);

  // Apart by more than the margin; within it.
  CHECK(collide(sphere<T>{T(0.5)}, ball_at({T(1.7), T(0), T(0)}), b, pose).empty());
  m = collide(sphere<T>{T(0.5)}, ball_at({T(1.7), T(0), T(0)}), b, pose, T(0.3));
  REQUIRE(m.count == 1);
  CHECK(m.points[0].depth == doctest::Approx(-0.2).epsilon(tolerance<T> * 100));
  // The swapped pair.
  const auto swapped = collide(b, pose, sphere<T>{T(0.5)}, ball_at({T(1.3), T(0.5), T(0.2)}));
  CHECK(near(swapped.normal, world_dir({1, 0, 0})));
}

TEST_CASE_TEMPLATE("box on a plane: four corners resting, two on an edge, one on a corner, four of eight sunk", T,
                   float, double) {
  const plane<T> ground{vec3<T>::unit_y(), T(0)};
  const transform<T> level = transform<T>::identity();
  const box<T> b{vec3<T>::splat(T(0.5))};

  // Resting 1 cm deep: the four bottom corners (ids with the +y bit clear),
  // the same four at every height and sideways shift.
  for (const T x : {T(0), T(0.3), T(-7)}) {
    const auto m = collide(b, transform<T>{{x, T(0.49), T(1)}, quat<T>::identity()}, ground, level);
    REQUIRE(m.count == 4);
    CHECK(near(m.normal, vec3<T>{0, -1, 0}));
    std::vector<std::uint32_t> ids;
    for (const auto& p : m.contacts()) {
      ids.push_back(p.feature);
      CHECK(p.depth == doctest::Approx(0.01).epsilon(tolerance<T> * 1000));
      CHECK(p.position.y == doctest::Approx(-0.005).epsilon(tolerance<T> * 1000));
    }
    std::sort(ids.begin(), ids.end());
    CHECK(ids == std::vector<std::uint32_t>{0, 1, 4, 5});
  }
  // On an edge: turned 45° about z, the lowest edge 1 cm deep.
  const T half_diagonal = T(0.5) * std::sqrt(T(2));
  auto m = collide(b, transform<T>{{0, half_diagonal - T(0.01), 0}, quat<T>::from_axis_angle(vec3<T>::unit_z(), T(0.785398163397448))},
                   ground, level);
  REQUIRE(m.count == 2);
  for (const auto& p : m.contacts()) CHECK(p.depth == doctest::Approx(0.01).epsilon(tolerance<T> * 1000));
  // On a corner: turned so that a body diagonal is vertical.
  const quat<T> corner_down = quat<T>::from_axis_angle(normalize(vec3<T>{1, 0, -1}), std::acos(T(1) / std::sqrt(T(3))));
  const T half_body_diagonal = T(0.5) * std::sqrt(T(3));
  m = collide(b, transform<T>{{0, half_body_diagonal - T(0.01), 0}, corner_down}, ground, level);
  REQUIRE(m.count == 1);
  CHECK(m.points[0].depth == doctest::Approx(0.01).epsilon(tolerance<T> * 1000));
  // Entirely below the surface: eight candidates, four kept, the deepest
  // among them, spanning the bottom face.
  m = collide(b, transform<T>{{0, -3, 0}, quat<T>::from_axis_angle(vec3<T>::unit_x(), T(0.1))}, ground, level);
  REQUIRE(m.count == 4);
  T deepest = 0;
  for (const auto& p : m.contacts()) deepest = std::max(deepest, p.depth);
  CHECK(deepest == doctest::Approx(3 + T(0.5) * (std::cos(T(0.1)) + std::sin(T(0.1)))).epsilon(tolerance<T> * 100));
  CHECK(finite(m));
}

TEST_CASE_TEMPLATE("capsules: lying on a plane, crossing, lying along each other, end to end, coincident", T, float,
                   double) {
  const plane<T> ground{vec3<T>::unit_y(), T(0)};
  const capsule<T> c{T(0.25), T(0.5)};
  const quat<T> along_x = quat<T>::from_axis_angle(vec3<T>::unit_z(), T(1.5707963267948966));
  const quat<T> along_z = quat<T>::from_axis_angle(vec3<T>::unit_x(), T(1.5707963267948966));

  // Lying on the ground, 1 cm deep: both cap centers.
  auto m = collide(c, transform<T>{{0, T(0.24), 0}, along_x}, ground, transform<T>::identity());
  REQUIRE(m.count == 2);
  for (const auto& p : m.contacts()) {
    CHECK(p.depth == doctest::Approx(0.01).epsilon(tolerance<T> * 1000));
    CHECK(std::abs(std::abs(p.position.x) - T(0.5)) <= tolerance<T> * 10);
  }
  CHECK(m.points[0].feature != m.points[1].feature);

  // Crossing at right angles, cores 0.45 apart: 0.05 deep, one point.
  m = collide(c, transform<T>{{}, along_x}, c, transform<T>{{0, T(0.45), 0}, along_z});
  REQUIRE(m.count == 1);
  CHECK(near(m.normal, vec3<T>::unit_y()));
  CHECK(m.points[0].depth == doctest::Approx(0.05).epsilon(tolerance<T> * 100));
  CHECK(near(m.points[0].position, vec3<T>{0, T(0.225), 0}));

  // One lying along the other, shifted by half: two points at the ends of
  // the overlap, x = 0 and x = 0.5.
  m = collide(c, transform<T>{{}, along_x}, c, transform<T>{{T(0.5), T(0.45), 0}, along_x});
  REQUIRE(m.count == 2);
  CHECK(near(m.normal, vec3<T>::unit_y()));
  std::vector<T> xs;
  for (const auto& p : m.contacts()) {
    xs.push_back(p.position.x);
    CHECK(p.depth == doctest::Approx(0.05).epsilon(tolerance<T> * 100));
  }
  std::sort(xs.begin(), xs.end());
  CHECK(std::abs(xs[0]) <= tolerance<T> * 10);
  CHECK(xs[1] == doctest::Approx(0.5).epsilon(tolerance<T> * 10));

  // End to end on one line, cores 0.4 apart.
  m = collide(c, transform<T>{{}, along_x}, c, transform<T>{{T(1.4), 0, 0}, along_x});
  REQUIRE(m.count == 1);
  CHECK(near(m.normal, vec3<T>::unit_x()));
  CHECK(m.points[0].depth == doctest::Approx(0.1).epsilon(tolerance<T> * 100));

  // Coincident: no direction between the cores; finite, 2r deep.
  m = collide(c, transform<T>{{}, along_x}, c, transform<T>{{}, along_x});
  REQUIRE(m.count >= 1);
  CHECK(finite(m));
  for (const auto& p : m.contacts()) CHECK(p.depth == doctest::Approx(0.5));

  // Sphere against capsule, and the swapped pair.
  m = collide(sphere<T>{T(0.4)}, transform<T>{{T(0.3), T(0.6), 0}, quat<T>::identity()}, c, transform<T>{{}, along_x});
  REQUIRE(m.count == 1);
  CHECK(near(m.normal, vec3<T>{0, -1, 0}));
  CHECK(m.points[0].depth == doctest::Approx(0.05).epsilon(tolerance<T> * 100));
  const auto swapped =
      collide(c, transform<T>{{}, along_x}, sphere<T>{T(0.4)}, transform<T>{{T(0.3), T(0.6), 0}, quat<T>::identity()});
  CHECK(near(swapped.normal, vec3<T>::unit_y()));
}

TEST_CASE_TEMPLATE("reduce_to_four keeps the deepest and spans the candidates", T, float, double) {
  const vec3<T> up = vec3<T>::unit_y();
  contact_manifold<T> m;
  // A regular octagon of radius 1 at depth 0.1, one vertex deeper.
  std::vector<contact_point<T>> octagon;
  for (int k = 0; k < 8; ++k) {
    const T angle = T(0.785398163397448) * T(k);
    octagon.push_back({{std::cos(angle), 0, std::sin(angle)}, k == 3 ? T(0.3) : T(0.1), std::uint32_t(k)});
  }
  reduce_to_four(std::span<const contact_point<T>>(octagon), up, m);
  REQUIRE(m.count == 4);
  CHECK(m.points[0].feature == 3u);  // the deepest first
  // The kept four: a square inscribed in the octagon (area 2 of its 2.83),
  // the largest quadrilateral on its vertices.
  std::vector<std::uint32_t> ids;
  for (const auto& p : m.contacts()) ids.push_back(p.feature);
  std::sort(ids.begin(), ids.end());
  CHECK(ids == std::vector<std::uint32_t>{1, 3, 5, 7});

  // Points on one line: the deepest and the two ends.
  std::vector<contact_point<T>> line;
  for (int k = 0; k < 6; ++k) line.push_back({{T(k), 0, 0}, T(0.1), std::uint32_t(k)});
  line[2].depth = T(0.2);
  reduce_to_four(std::span<const contact_point<T>>(line), up, m);
  REQUIRE(m.count == 3);
  CHECK(m.points[0].feature == 2u);
  CHECK(m.points[1].feature == 5u);
  CHECK(m.points[2].feature == 0u);

  // The same line with each point a rounding off it (1e-7 of its length
  // across): still a line, not a triangle of noise.
  for (int k = 0; k < 6; ++k) line[std::size_t(k)].position.z = T(k % 2 ? 1e-7 : -1e-7) * T(5);
  reduce_to_four(std::span<const contact_point<T>>(line), up, m);
  REQUIRE(m.count == 3);
  CHECK(m.points[0].feature == 2u);
  CHECK(m.points[1].feature == 5u);
  CHECK(m.points[2].feature == 0u);

  // Four or fewer pass through unchanged.
  reduce_to_four(std::span<const contact_point<T>>(octagon.data(), 3), up, m);
  CHECK(m.count == 3);
}

}  // namespace narrowphase_analytic_tests
