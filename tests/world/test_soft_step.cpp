// The soft-step solver (Box2D v3's) on the scenes the sequential-impulse
// solver is held to. It is not the default: it meets the thresholds below
// and misses others, which docs/world.md lists with its figures (its soft
// rows let a 10-box tower sag 3 cm). Its rebounds are measured with the
// default solver's in test_landing.cpp.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "../error_code_of.hpp"
#include "scenes.hpp"

namespace world_soft_step_tests {

using namespace impulse;

namespace {

using impulse::test::soft_config;
using soft_world = world<soft_config>;

}  // namespace

TEST_CASE("soft step: a box on a 30 degree incline at friction 0.5 slides at g(sin - 0.5 cos) within 0.5 percent") {
  soft_world w;
  const float angle = 3.14159265f / 6;
  const quat<float> turn = quat<float>::from_axis_angle({0, 0, 1}, angle);
  body_def<float> ramp;
  ramp.type = body_type::static_body;
  ramp.pose.rotation = turn;
  ramp.material.friction = 0.5f;
  w.create_body(ramp, box<float>::make({15, 0.5f, 5}));
  const body_id cube = impulse::test::add_cube(w, rotate(turn, vec3<float>{5, 1, 0}), 1.0f, 0.5f, turn);
  impulse::test::run(w, 60);
  const float v1 = length(w.body(cube).linear_velocity());
  impulse::test::run(w, 60);
  const float v2 = length(w.body(cube).linear_velocity());
  const double analytic = 9.81 * (std::sin(double(angle)) - 0.5 * std::cos(double(angle)));
  CHECK(std::abs((v2 - v1) / analytic - 1) < 0.005);
}

TEST_CASE("soft step: a 10-box tower stands for 20 s with its top within 1 cm of the axis") {
  soft_world w;
  impulse::test::add_ground(w);
  std::vector<body_id> tower;
  for (int k = 0; k < 10; ++k) tower.push_back(impulse::test::add_cube(w, {0, 0.5f + float(k), 0}));
  float drift = 0;
  for (int i = 0; i < 1200; ++i) {
    w.step(impulse::test::step_dt<float>);
    const vec3<float> top = w.body(tower.back()).position;
    drift = std::max(drift, std::hypot(top.x, top.z));
  }
  CHECK(drift < 0.01f);
  // Soft rows rest deeper than rigid ones, but a tower does not keep sinking.
  CHECK(w.body(tower.back()).position.y > 9.4f);
  CHECK(length(w.body(tower.back()).linear_velocity()) < 1e-3f);
}

TEST_CASE("soft step: the 20-row pyramid stands for 20 s without spreading more than 2 cm across") {
  soft_world w;
  impulse::test::add_ground(w);
  const std::vector<body_id> boxes = impulse::test::add_pyramid(w, 20);
  const auto start = impulse::test::positions(w, boxes);
  impulse::test::run(w, impulse::test::long_run(1200));
  const vec3<float> worst = impulse::test::largest_displacement(w, boxes, start);
  CHECK(worst.x < 0.02f);
  CHECK(worst.z < 0.02f);
  CHECK(w.body(boxes.back()).position.y > 19.0f);
}

TEST_CASE("soft step: a 100 kg box on a 1 kg box stands for 10 s without sliding 1 cm") {
  soft_world w;
  impulse::test::add_ground(w);
  impulse::test::add_cube(w, {0, 0.5f, 0}, 1);
  const body_id heavy = impulse::test::add_cube(w, {0, 1.5f, 0}, 100);
  float slid = 0;
  for (int i = 0; i < 600; ++i) {
    w.step(impulse::test::step_dt<float>);
    slid = std::max(slid, std::hypot(w.body(heavy).position.x, w.body(heavy).position.z));
  }
  CHECK(slid < 0.01f);
  CHECK(w.body(heavy).position.y > 1.45f);
}

TEST_CASE("soft step's own settings are checked: no substep, a negative stiffness or a NaN damping is refused, the "
          "world's settings kept") {
  soft_world w;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  soft_world::settings_type bad;
  bad.solver.substeps = 0;
  CHECK(impulse::test::error_code_of([&] { w.set_settings(bad); }) == error_code::invalid_parameter);
  bad = {};
  bad.solver.contact_hertz = -30;
  CHECK(impulse::test::error_code_of([&] { w.set_settings(bad); }) == error_code::invalid_parameter);
  bad = {};
  bad.solver.joint_damping_ratio = nan;
  CHECK(impulse::test::error_code_of([&] { w.set_settings(bad); }) == error_code::invalid_parameter);
  CHECK(w.settings().solver.substeps == 4);
  CHECK(w.settings().solver.contact_hertz == 30);
  CHECK(std::isfinite(w.settings().solver.joint_damping_ratio));
}

}  // namespace world_soft_step_tests
