// Fast landings and fast passes against the contacts that reach ahead with
// speed (solver_settings::max_speculative_distance): a body landing at
// 2–20 m/s is met on the step it arrives and never sinks past where it
// rests; a ball landing with spin rolls off at the speed the impulse
// theory gives; a ball passing an edge clear of it is not touched by it;
// a ball met ahead of the ground rebounds to e² of its height at each
// bounce. Both solvers, sleeping off, default settings.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "../error_code_of.hpp"
#include "scenes.hpp"

namespace world_landing_tests {

using namespace impulse;

namespace {

using impulse::test::soft_config;

/// How deep (m, below resting height 0.5) a ball or cube of half-size 0.5
/// gets, deepest over 3 s and at the end, dropped at `speed` from 6 steps'
/// flight above the standard ground.
template <class World>
std::pair<float, float> landing_depths(bool cube, float speed) {
  World w;
  impulse::test::add_ground(w);
  body_def<float> d;
  d.mass = 1;
  d.pose.position = {0, 0.5f + speed * 0.1f + 0.013f, 0};
  d.linear_velocity = {0, -speed, 0};
  const body_id b = cube ? w.create_body(d, box<float>::make({0.5f, 0.5f, 0.5f}))
                         : w.create_body(d, sphere<float>::make(0.5f));
  float deepest = 0;
  for (int i = 0; i < 180; ++i) {
    w.step(impulse::test::step_dt<float>);
    deepest = std::max(deepest, 0.5f - w.body(b).position.y);
  }
  return {deepest, 0.5f - w.body(b).position.y};
}

}  // namespace

TEST_CASE_TEMPLATE("a ball or a box landing at 2 to 20 m/s sinks no deeper than it rests", World,
                   world<impulse::test::awake_config>, world<soft_config>) {
  // At 60 Hz these cross 3.3 to 33 cm a step. Contacts found only 2 cm
  // ahead (speculative_distance) let one land 5.7 cm deep at 5 m/s; now
  // a pair is tested as far ahead as it can close in the step, and the
  // landing is met on the step it arrives. sequential_impulse rests
  // 3 µm in (rest_depth), soft_step at its slop, 0.5 mm, plus what its
  // soft rows give under the weight (0.07 mm).
  const float slop = typename World::settings_type{}.solver.linear_slop;
  for (const bool cube : {false, true})
    for (const float speed : {2.0f, 5.0f, 10.0f, 20.0f}) {
      CAPTURE(cube);
      CAPTURE(speed);
      const auto [deepest, rest] = landing_depths<World>(cube, speed);
      CHECK(deepest <= rest + 1e-5f);
      CHECK(rest < slop + 0.0001f);
    }
}

TEST_CASE_TEMPLATE("a ball landing with spin at 2 to 20 m/s rolls off at the speed the impulse theory gives, within 0.5 percent",
                   World, world<impulse::test::awake_config>, world<soft_config>) {
  // A ball of radius 0.5 (I = 2/5·m·r²) moving at 3 m/s and spinning at
  // 10 rad/s (backspin) lands at friction 0.5 and restitution 0. The
  // ground's impulses pass through the point of contact, so the angular
  // momentum about it is kept: m·r·v − I·ω = (I + m·r²)·v_roll, v_roll =
  // (3 − 0.4·0.5·10) / 1.4 = 0.714 m/s. Friction acting at the middle of
  // the gap of a contact met ahead, not at the ball's surface, turned it
  // through a lever up to 17 cm too long (1.7 % fast at 20 m/s).
  for (const float fall : {2.0f, 5.0f, 10.0f, 20.0f}) {
    CAPTURE(fall);
    World w;
    impulse::test::add_ground(w, 0.5f);
    body_def<float> d;
    d.mass = 1;
    d.material.friction = 0.5f;
    d.pose.position = {0, 0.5f + fall / 60 + 0.001f, 0};
    d.linear_velocity = {3, -fall, 0};
    d.angular_velocity = {0, 0, 10};
    const body_id ball = w.create_body(d, sphere<float>::make(0.5f));
    impulse::test::run(w, 240);
    const float rolling = (3.0f - 0.4f * 0.5f * 10.0f) / 1.4f;
    CHECK(std::abs(w.body(ball).linear_velocity().x / rolling - 1) < 0.005f);
    CHECK(std::abs(w.body(ball).linear_velocity().x + 0.5f * w.body(ball).angular_velocity().z) < 0.001f);
  }
}

TEST_CASE_TEMPLATE("a ball passing 5 cm clear of a box's edge at 5, 20 and 50 m/s is not touched by it", World,
                   world<impulse::test::awake_config>, world<soft_config>) {
  // Weightless, it flies along x past the top edge of a static unit box.
  // Its contact with the box is found up to a step's flight ahead (0.8 m
  // at 50 m/s), with a normal from the edge that leans against its motion;
  // kept without the sweep that shows the two never come within 2 cm, it
  // would stop the ball there (a ghost collision).
  for (const float speed : {5.0f, 20.0f, 50.0f}) {
    CAPTURE(speed);
    typename World::settings_type settings;
    settings.gravity = {0, 0, 0};
    World w(settings);
    body_def<float> wall;
    wall.type = body_type::static_body;
    w.create_body(wall, box<float>::make({0.5f, 0.5f, 0.5f}));
    body_def<float> d;
    d.pose.position = {-3, 0.5f + 0.25f + 0.05f, 0};
    d.linear_velocity = {speed, 0, 0};
    const body_id ball = w.create_body(d, sphere<float>::make(0.25f));
    impulse::test::run(w, 60);
    CHECK(w.body(ball).linear_velocity() == vec3<float>{speed, 0, 0});
    CHECK(w.body(ball).position.y == doctest::Approx(0.8f).epsilon(1e-6));
  }
}

TEST_CASE_TEMPLATE("a ball's rebounds from 10 m follow e squared at each bounce, and elastic ones keep its height",
                   World, world<impulse::test::awake_config>, world<soft_config>) {
  // Peaks 0.5 + e^(2k)·9.5. The contact that meets the ball is found up to
  // a step's flight ahead (22 cm at 13.6 m/s); the ball parts from there at
  // the speed the impact's e·v has left at that height, or it would climb
  // (1 − e²)·g too high (1 % at the second rebound of e = 0.8). Elastic, it
  // climbs back to 10 m at every bounce: soft_step gained 1.8 % of the
  // height at each, from the approach speed taken for its substeps.
  for (const float e : {0.8f, 1.0f}) {
    CAPTURE(e);
    World w;
    impulse::test::add_ground(w);
    body_def<float> d;
    d.pose.position = {0, 10, 0};
    d.mass = 1;
    d.material.restitution = e;
    const body_id ball = w.create_body(d, sphere<float>::make(0.5f));
    int bounces = 0;
    float peak = 0;
    bool rising = false;
    for (int i = 0; i < 60 * 30 && bounces < 3; ++i) {
      w.step(impulse::test::step_dt<float>);
      if (w.body(ball).linear_velocity().y > 0) {
        rising = true;
        peak = std::max(peak, w.body(ball).position.y);
      } else if (rising) {
        rising = false;
        ++bounces;
        CAPTURE(bounces);
        const float expected = 0.5f + std::pow(e, 2.0f * float(bounces)) * 9.5f;
        CHECK(std::abs((peak - 0.5f) / (expected - 0.5f) - 1) < 0.001f);
        peak = 0;
      }
    }
    CHECK(bounces == 3);
  }
}

TEST_CASE("a reach ahead that is negative or not finite is refused and the world keeps its settings") {
  world<impulse::test::awake_config> w;
  for (const float bad : {-1.0f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    CAPTURE(bad);
    auto settings = w.settings();
    settings.solver.max_speculative_distance = bad;
    CHECK(impulse::test::error_code_of([&] { w.set_settings(settings); }) == error_code::invalid_parameter);
    CHECK(w.settings().solver.max_speculative_distance == 1.0f);
  }
}

}  // namespace world_landing_tests
