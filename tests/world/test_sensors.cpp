// Sensors: bodies that report what their shapes overlap and make no
// contacts. Entry and exit are checked against the step at which the
// overlap begins and ends by the bodies' own positions, and the bodies
// passing through against free fall.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "../dynamics/motion_test.hpp"
#include "../error_code_of.hpp"
#include "impulse/world.hpp"
#include "scenes.hpp"

namespace world_sensors_tests {

using namespace impulse;
using impulse::test::error_code_of;
using impulse::test::step_dt;

namespace {

constexpr float g = 9.81f;

/// A static sensor box of the given half-extents at `at`.
template <class World>
body_id add_sensor(World& w, vec3<float> at, vec3<float> half, collision_filter filter = {},
                   body_type type = body_type::static_body) {
  body_def<float> d;
  d.type = type;
  d.pose.position = at;
  d.sensor = true;
  d.filter = filter;
  return w.create_body(d, box<float>::make(half));
}

template <class World>
body_id add_ball(World& w, vec3<float> at, float radius, collision_filter filter = {}) {
  body_def<float> d;
  d.pose.position = at;
  d.filter = filter;
  return w.create_body(d, sphere<float>::make(radius));
}

bool has(std::span<const sensor_event> events, body_id sensor, body_id visitor) {
  return std::ranges::find(events, sensor_event{sensor, visitor}) != events.end();
}

template <class World>
bool inside(const World& w, body_id sensor, body_id visitor) {
  const std::span<const body_id> in = w.sensor_overlaps(sensor);
  return std::ranges::find(in, visitor) != in.end();
}

}  // namespace

TEST_CASE("a ball falling through a sensor is reported in the step it enters and the step it leaves, and falls freely") {
  impulse::test::with_sleeping_off_and_on([](auto& w) {
    // The sensor spans y from 4.5 to 5.5; the ball of radius 0.25 is in
    // it from when its center is below 5.75 until it is below 4.25.
    const body_id sensor = add_sensor(w, {0, 5, 0}, {1, 0.5f, 1});
    const body_id ball = add_ball(w, {0, 8, 0}, 0.25f);
    int begins = 0, ends = 0;
    for (int i = 1; i <= 90; ++i) {
      const float before = w.body(ball).position.y;
      w.step(step_dt<float>);
      const float y = w.body(ball).position.y;
      CAPTURE(i);
      CAPTURE(y);
      const bool in_now = y <= 5.75f && y >= 4.25f;
      const bool in_before = before <= 5.75f && before >= 4.25f;
      CHECK(inside(w, sensor, ball) == in_now);
      CHECK(has(w.sensor_begin_events(), sensor, ball) == (in_now && !in_before));
      CHECK(has(w.sensor_end_events(), sensor, ball) == (!in_now && in_before));
      begins += int(w.sensor_begin_events().size());
      ends += int(w.sensor_end_events().size());
      // Nothing held it: each step added g·dt to its fall.
      CHECK(std::abs(w.body(ball).linear_velocity().y + g * float(i) * step_dt<float>) < 1e-4f * float(i));
    }
    CHECK(begins == 1);
    CHECK(ends == 1);
    CHECK(w.body(ball).position.y < 0);
    CHECK(w.touching_pair_count() == 0);
  });
}

TEST_CASE("a sensor sees every body type, asleep or awake, but no other sensor and none its filter leaves out") {
  world<impulse::test::sleeping_config> w;
  const body_id ground = impulse::test::add_ground(w);
  // A sensor 4 m wide reaching 0.5 m into the ground.
  const body_id sensor = add_sensor(w, {0, 0.5f, 0}, {2, 1, 2}, collision_filter{2, ~8u, 0});
  const body_id cube = impulse::test::add_cube(w, {0, 0.5f, 0});
  body_def<float> kd;
  kd.type = body_type::kinematic;
  kd.pose.position = {1.2f, 1, 1.5f};
  const body_id platform = w.create_body(kd, box<float>::make({0.2f, 0.2f, 0.2f}));
  const body_id other_sensor = add_sensor(w, {0.8f, 1, 0}, {0.5f, 0.5f, 0.5f});
  const body_id hidden = impulse::test::add_cube(w, {-1.5f, 0.5f, 0});
  w.set_filter(hidden, collision_filter{8, all_categories, 0});  // its category is out of the sensor's mask
  const body_id outside = impulse::test::add_cube(w, {5, 0.5f, 0});
  impulse::test::run(w, 180);
  REQUIRE_FALSE(w.is_awake(cube));  // asleep, and still seen
  const std::span<const body_id> in = w.sensor_overlaps(sensor);
  CHECK(in.size() == 3);
  CHECK(inside(w, sensor, ground));
  CHECK(inside(w, sensor, cube));
  CHECK(inside(w, sensor, platform));
  CHECK_FALSE(inside(w, sensor, other_sensor));
  CHECK_FALSE(inside(w, sensor, hidden));
  CHECK_FALSE(inside(w, sensor, outside));
  CHECK(std::ranges::is_sorted(in, {}, &body_id::index));
  // The other sensor (x from 0.3 to 1.3, y from 0.5 to 1.5, z within
  // ±0.5) reaches 0.2 m into the cube; the platform (z from 1.3) and the
  // ground (below y = 0) are clear of it.
  CHECK(w.sensor_overlaps(other_sensor).size() == 1);
  CHECK(inside(w, other_sensor, cube));
  // The sensors held nothing up: the cube rests on the ground alone, and
  // the touching pairs are the three cubes' with the ground.
  CHECK(std::abs(w.body(cube).position.y - 0.5f) < 0.01f);
  CHECK(w.touching_pair_count() == 3);  // cube, hidden and outside on the ground
  CHECK(w.is_sensor(sensor));
  CHECK_FALSE(w.is_sensor(cube));
  CHECK(error_code_of([&] { (void)w.sensor_overlaps(cube); }) == error_code::invalid_parameter);
}

TEST_CASE("destroying a body inside a sensor, or the sensor, ends the overlap at once") {
  world<impulse::test::awake_config> w;
  impulse::test::add_ground(w);
  const body_id sensor = add_sensor(w, {0, 1, 0}, {2, 1, 2});
  const body_id a = impulse::test::add_cube(w, {-1, 0.5f, 0});
  const body_id b = impulse::test::add_cube(w, {1, 0.5f, 0});
  w.step(step_dt<float>);
  CHECK(has(w.sensor_begin_events(), sensor, a));
  CHECK(has(w.sensor_begin_events(), sensor, b));
  impulse::test::run(w, 10);
  CHECK(w.sensor_begin_events().empty());
  w.destroy_body(a);
  CHECK(w.sensor_end_events().size() == 1);
  CHECK(has(w.sensor_end_events(), sensor, a));
  CHECK(w.sensor_overlaps(sensor).size() == 2);  // b and the ground
  w.step(step_dt<float>);
  CHECK(w.sensor_end_events().empty());  // not reported twice
  w.destroy_body(sensor);
  CHECK(w.sensor_end_events().size() == 2);
  CHECK(has(w.sensor_end_events(), sensor, b));
  w.step(step_dt<float>);
  CHECK(std::abs(w.body(b).position.y - 0.5f) < 0.01f);
  CHECK(error_code_of([&] { (void)w.sensor_overlaps(sensor); }) == error_code::out_of_range);
}

TEST_CASE("a dynamic sensor falls through the ground and the bodies it passes, reporting them") {
  world<impulse::test::awake_config> w;
  const body_id ground = impulse::test::add_ground(w);
  const body_id cube = impulse::test::add_cube(w, {0, 0.5f, 0});
  const body_id probe = add_sensor(w, {0, 3, 0}, {0.2f, 0.2f, 0.2f}, {}, body_type::dynamic);
  bool met_cube = false, met_ground = false;
  for (int i = 1; i <= 60; ++i) {
    w.step(step_dt<float>);
    met_cube = met_cube || has(w.sensor_begin_events(), probe, cube);
    met_ground = met_ground || has(w.sensor_begin_events(), probe, ground);
  }
  CHECK(met_cube);
  CHECK(met_ground);
  // It fell freely through both: 1 s of g.
  CHECK(std::abs(w.body(probe).linear_velocity().y + g) < 1e-3f);
  CHECK(std::abs(w.body(cube).position.y - 0.5f) < 0.01f);  // and moved nothing
}

TEST_CASE("queries pass through sensors unless their filter asks for them") {
  world<impulse::test::awake_config> w;
  const body_id sensor = add_sensor(w, {0, 5, 0}, {1, 0.5f, 1});
  const body_id ground = impulse::test::add_ground(w);
  const ray<float> down{{0, 10, 0}, {0, -20, 0}};
  // The ground's top at y = 0: fraction 0.5; the sensor's top at 5.5: 0.225.
  const auto hit = w.ray_cast(down);
  REQUIRE(hit);
  CHECK(hit->body == ground);
  CHECK(hit->fraction == doctest::Approx(0.5f).epsilon(1e-5));
  query_filter with_sensors;
  with_sensors.sensors = true;
  const auto sensed = w.ray_cast(down, 1, with_sensors);
  REQUIRE(sensed);
  CHECK(sensed->body == sensor);
  CHECK(sensed->fraction == doctest::Approx(0.225f).epsilon(1e-5));
  int seen = 0;
  w.overlap(aabb<float>{{-1, 4, -1}, {1, 6, 1}}, [&](body_id) { ++seen; });
  CHECK(seen == 0);
  w.overlap(aabb<float>{{-1, 4, -1}, {1, 6, 1}}, [&](body_id) { ++seen; }, with_sensors);
  CHECK(seen == 1);
}

TEST_CASE("a world without collision refuses a sensor and stays unchanged") {
  impulse::test::motion_world<float, integrators::symplectic_euler> w;
  body_def<float> d;
  d.sensor = true;
  CHECK(error_code_of([&] { w.create_body(d, sphere<float>::make(1)); }) == error_code::invalid_parameter);
  CHECK(w.body_count() == 0);
}

}  // namespace world_sensors_tests
