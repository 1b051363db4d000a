// The world's queries beyond a single ray: every hit along a ray, a convex
// shape swept along a line (shape_cast) and a shape's overlaps, each
// against distances worked out by hand, with filters, and refusing bad
// input.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "../error_code_of.hpp"
#include "impulse/world.hpp"
#include "scenes.hpp"

namespace world_queries_tests {

using namespace impulse;
using impulse::test::error_code_of;
using world_type = world<impulse::test::awake_config>;

namespace {

world_settings<float> weightless() {
  world_settings<float> s;
  s.gravity = {0, 0, 0};
  return s;
}

body_id add_static(world_type& w, vec3<float> at, const auto& shape, collision_filter filter = {},
                   quat<float> turn = quat<float>::identity()) {
  body_def<float> d;
  d.type = body_type::static_body;
  d.pose = {at, turn};
  d.filter = filter;
  return w.create_body(d, shape);
}

/// A cast ends within cast_tolerance (0.5 mm) short of touching, never past:
/// the fraction of a translation of `length` metres is in
/// [exact − 0.5 mm / length, exact], with a float's rounding on top.
void check_fraction(float fraction, float exact, float length) {
  CHECK(fraction <= exact + 1e-5f);
  CHECK(fraction >= exact - 0.0005f / length - 1e-5f);
}

}  // namespace

TEST_CASE("a sphere cast down onto the ground stops where its lowest point meets the top face") {
  world_type w;
  const body_id ground = impulse::test::add_ground(w);
  // Radius 0.5 from y = 5 down 10 m: it touches at y = 0.5, fraction 0.45.
  const auto hit = w.shape_cast(sphere<float>::make(0.5f), {{0, 5, 0}, quat<float>::identity()}, {0, -10, 0});
  REQUIRE(hit);
  CHECK(hit->body == ground);
  check_fraction(hit->fraction, 0.45f, 10);
  CHECK(length(hit->normal - vec3<float>{0, 1, 0}) < 1e-4f);
  CHECK(std::abs(hit->point.y) < 1e-3f);
  CHECK(std::abs(hit->point.x) < 1e-3f);
  // Too short to reach: no hit.
  CHECK_FALSE(w.shape_cast(sphere<float>::make(0.5f), {{0, 5, 0}, quat<float>::identity()}, {0, -4, 0}));
}

TEST_CASE("a box turned 45 degrees cast at a wall stops with its edge on the wall") {
  world_type w(weightless());
  // A wall whose face is the plane x = 5.
  const body_id wall = add_static(w, {5.5f, 0, 0}, box<float>::make({0.5f, 5, 5}));
  // A unit cube turned 45° about y reaches √2/2 = 0.7071 m along x.
  const quat<float> turn = quat<float>::from_axis_angle({0, 1, 0}, std::numbers::pi_v<float> / 4);
  const auto hit = w.shape_cast(box<float>::make({0.5f, 0.5f, 0.5f}), {{0, 0, 0}, turn}, {8, 0, 0});
  REQUIRE(hit);
  CHECK(hit->body == wall);
  check_fraction(hit->fraction, (5 - std::sqrt(0.5f)) / 8, 8);
  CHECK(length(hit->normal - vec3<float>{-1, 0, 0}) < 1e-3f);
  CHECK(std::abs(hit->point.x - 5) < 1e-3f);
  CHECK(std::abs(hit->point.z) < 1e-3f);  // the edge's line, at z = 0
}

TEST_CASE("a capsule cast at a plane body and a sphere at a mesh meet them where the closed forms say") {
  world_type w(weightless());
  // A plane facing +x through x = −3, and a mesh floor of two triangles at y = −2.
  const body_id wall = add_static(w, {-3, 0, 0}, plane<float>::make({1, 0, 0}, 0));
  const vec3<float> corners[] = {{-10, -2, -10}, {-10, -2, 10}, {10, -2, 10}, {10, -2, -10}};
  const std::uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
  const body_id floor = add_static(w, {}, triangle_mesh<float>::make(corners, triangles));
  // A capsule along y (half-height 0.5, radius 0.25) moving −x 10 m: its
  // side meets the plane when its axis is at x = −2.75.
  const auto side = w.shape_cast(capsule<float>::make(0.25f, 0.5f), {{0, 0, 0}, quat<float>::identity()}, {-10, 0, 0});
  REQUIRE(side);
  CHECK(side->body == wall);
  CHECK(side->fraction == doctest::Approx(0.275f).epsilon(1e-5));  // closed form: exact
  CHECK(length(side->normal - vec3<float>{1, 0, 0}) < 1e-6f);
  // A ball of radius 0.3 falling 4 m from y = 0 onto the floor: at y = −1.7.
  const auto down = w.shape_cast(sphere<float>::make(0.3f), {{1, 0, 1}, quat<float>::identity()}, {0, -4, 0});
  REQUIRE(down);
  CHECK(down->body == floor);
  check_fraction(down->fraction, 1.7f / 4, 4);
  CHECK(length(down->normal - vec3<float>{0, 1, 0}) < 1e-3f);
}

TEST_CASE("a shape cast meets the nearest body its filter sees, and one it starts inside at fraction 0") {
  world_type w(weightless());
  const body_id near = add_static(w, {3, 0, 0}, box<float>::make({0.5f, 0.5f, 0.5f}), {2, all_categories, 0});
  const body_id far = add_static(w, {6, 0, 0}, box<float>::make({0.5f, 0.5f, 0.5f}), {4, all_categories, 0});
  const sphere<float> ball = sphere<float>::make(0.25f);
  const transform<float> start{{0, 0, 0}, quat<float>::identity()};
  // Faces at x = 2.5 and 5.5; the ball's front at 0.25: 2.25 and 5.25 of 10.
  const auto first = w.shape_cast(ball, start, {10, 0, 0});
  REQUIRE(first);
  CHECK(first->body == near);
  check_fraction(first->fraction, 0.225f, 10);
  const auto past = w.shape_cast(ball, start, {10, 0, 0}, query_filter{4, 0});
  REQUIRE(past);
  CHECK(past->body == far);
  check_fraction(past->fraction, 0.525f, 10);
  // Starting 0.1 m into the near box's face: a hit at 0, the face's normal.
  const auto inside = w.shape_cast(ball, {{2.35f, 0, 0}, quat<float>::identity()}, {10, 0, 0});
  REQUIRE(inside);
  CHECK(inside->body == near);
  CHECK(inside->fraction == 0);
  CHECK(length(inside->normal - vec3<float>{-1, 0, 0}) < 1e-3f);
  // Bad input is refused.
  CHECK(error_code_of([&] { (void)w.shape_cast(ball, start, {std::nanf(""), 0, 0}); }) == error_code::non_finite);
  CHECK(error_code_of([&] { (void)w.shape_cast(ball, {{0, 0, 0}, {0, 0, 0, 2}}, {1, 0, 0}); }) ==
        error_code::not_normalized);
}

TEST_CASE("ray_cast_all reports every body along the ray, or stops where the callback says") {
  world_type w(weightless());
  std::vector<body_id> balls;
  for (int k = 0; k < 3; ++k) balls.push_back(add_static(w, {2 + 3 * float(k), 0, 0}, sphere<float>::make(0.5f)));
  const ray<float> r{{0, 0, 0}, {10, 0, 0}};
  // Surfaces at x = 1.5, 4.5, 7.5: fractions 0.15, 0.45, 0.75.
  std::vector<float> fractions;
  w.ray_cast_all(r, [&](const world_ray_hit<float>& hit) {
    fractions.push_back(hit.fraction);
    return 1.0f;
  });
  std::ranges::sort(fractions);
  REQUIRE(fractions.size() == 3);
  for (int k = 0; k < 3; ++k) CHECK(fractions[std::size_t(k)] == doctest::Approx(0.15f + 0.3f * float(k)).epsilon(1e-5));
  int calls = 0;
  w.ray_cast_all(r, [&](const world_ray_hit<float>&) {
    ++calls;
    return 0.0f;
  });
  CHECK(calls == 1);
  // Clipping to each hit's own fraction ends on the nearest.
  float nearest = 1;
  w.ray_cast_all(r, [&](const world_ray_hit<float>& hit) {
    nearest = std::min(nearest, hit.fraction);
    return hit.fraction;
  });
  CHECK(nearest == doctest::Approx(0.15f).epsilon(1e-5));
  // The filter hides the middle ball.
  w.set_filter(balls[1], {2, all_categories, 0});
  fractions.clear();
  w.ray_cast_all(r, [&](const world_ray_hit<float>& hit) {
    fractions.push_back(hit.fraction);
    return 1.0f;
  }, query_filter{1, 0});
  CHECK(fractions.size() == 2);
}

TEST_CASE("shape_overlap finds the bodies a shape overlaps or touches, and no sensor unless asked") {
  world_type w(weightless());
  // Unit cubes at x = 0, 1.5 and 3 (faces at ±0.5, 1 and 2, 2.5 and 3.5).
  std::vector<body_id> cubes;
  for (int k = 0; k < 3; ++k) cubes.push_back(add_static(w, {1.5f * float(k), 0, 0}, box<float>::make({0.5f, 0.5f, 0.5f})));
  body_def<float> d;
  d.type = body_type::static_body;
  d.sensor = true;
  d.pose.position = {1, 0, 0};
  const body_id sensor = w.create_body(d, sphere<float>::make(0.2f));
  std::vector<body_id> found;
  // A probe of half-extent 0.6 at x = 1 reaches from 0.4 to 1.6: 0.1 m
  // into each of the first two cubes.
  const box<float> probe = box<float>::make({0.6f, 0.5f, 0.5f});
  const transform<float> at{{1, 0, 0}, quat<float>::identity()};
  w.shape_overlap(probe, at, [&](body_id id) { found.push_back(id); });
  CHECK(found.size() == 2);
  CHECK(std::ranges::find(found, cubes[0]) != found.end());
  CHECK(std::ranges::find(found, cubes[1]) != found.end());
  // One of half-extent 0.5 at x = 2.25 spans 1.75 to 2.75: into the
  // second and the third.
  found.clear();
  const box<float> narrow = box<float>::make({0.5f, 0.5f, 0.5f});
  w.shape_overlap(narrow, {{2.25f, 0, 0}, quat<float>::identity()}, [&](body_id id) { found.push_back(id); });
  CHECK(found.size() == 2);
  CHECK(std::ranges::find(found, cubes[2]) != found.end());
  // Touching counts: at x = 1 it spans 0.5 to 1.5, its face on the
  // first's at x = 0.5, and 0.5 m into the second.
  found.clear();
  w.shape_overlap(narrow, {{1, 0, 0}, quat<float>::identity()}, [&](body_id id) { found.push_back(id); });
  CHECK(found.size() == 2);
  CHECK(std::ranges::find(found, cubes[0]) != found.end());
  query_filter with_sensors;
  with_sensors.sensors = true;
  found.clear();
  w.shape_overlap(probe, at, [&](body_id id) { found.push_back(id); }, with_sensors);
  CHECK(std::ranges::find(found, sensor) != found.end());
  CHECK(error_code_of([&] { w.shape_overlap(probe, {{0, std::nanf(""), 0}, quat<float>::identity()}, [](body_id) {}); }) ==
        error_code::non_finite);
}

}  // namespace world_queries_tests
