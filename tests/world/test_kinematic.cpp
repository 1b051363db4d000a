// Kinematic bodies as platforms: they move as told, by velocity or by a
// target pose each step, and carry what rests on them by friction,
// including the ω × r of a turning one.
#include <doctest/doctest.h>

#include <cmath>

#include "../error_code_of.hpp"
#include "impulse/world.hpp"
#include "scenes.hpp"

namespace world_kinematic_tests {

using namespace impulse;
using impulse::test::error_code_of;

namespace {

struct platform_scene {
  world<impulse::test::sleeping_config> w;
  body_id platform, rider;

  /// A 8 × 0.5 × 8 m kinematic slab with its top at y = 0.25, and a cube
  /// resting on it 2 m from its center, both of the given friction.
  explicit platform_scene(float friction) {
    body_def<float> d;
    d.type = body_type::kinematic;
    d.material.friction = friction;
    platform = w.create_body(d, box<float>::make({4, 0.25f, 4}));
    rider = impulse::test::add_cube(w, {2, 0.75f, 0}, 1, friction);
    for (int i = 0; i < 60; ++i) w.step(impulse::test::step_dt<float>);  // settle
  }
};

/// Where a point of the platform at p is after the platform turned by
/// angle about y.
vec3<float> turned(const vec3<float>& p, float angle) {
  return rotate(quat<float>::from_axis_angle({0, 1, 0}, angle), p);
}

}  // namespace

TEST_CASE("a box on a turning platform turns with it without sliding when friction suffices") {
  // ω = 1 rad/s at r = 2 m needs ω²·r = 2 m/s² of friction; μ = 0.6
  // gives up to 5.9 m/s².
  // The platform spins up at 1 rad/s² (2 m/s² more at the box) over the
  // first second, then turns steadily for five.
  platform_scene s(0.6f);
  const vec3<float> start = s.w.body(s.rider).position;
  for (int i = 1; i <= 360; ++i) {
    s.w.set_velocity(s.platform, {}, {0, std::min(float(i) / 60, 1.0f), 0});
    s.w.step(impulse::test::step_dt<float>);
  }
  const quat<float> turn = s.w.body(s.platform).orientation;
  const float angle = 2 * std::atan2(turn.y, turn.w);
  // Carried along the arc: within 1 cm of the platform point it started
  // on (a slip of 1 cm in 6 s is 1.7 mm/s), and turned as much.
  CHECK(length(s.w.body(s.rider).position - turned(start, angle)) < 0.01f);
  const quat<float> q = s.w.body(s.rider).orientation;
  CHECK(std::abs(std::remainder(2 * std::atan2(q.y, q.w) - angle, 2 * std::numbers::pi_v<float>)) < 0.01f);
  CHECK(s.w.is_awake(s.rider));

  // With μ = 0.1 (0.98 m/s²) the same turn throws it outward.
  platform_scene slippery(0.1f);
  slippery.w.set_velocity(slippery.platform, {}, {0, 1, 0});
  for (int i = 0; i < 120; ++i) slippery.w.step(impulse::test::step_dt<float>);
  const vec3<float> p = slippery.w.body(slippery.rider).position;
  CHECK(std::hypot(p.x, p.z) > 2.2f);
}

TEST_CASE("a platform moved by a target pose each step follows its path exactly and carries its rider") {
  // The platform swings out and back over 4 s along x and z, turning
  // through half a radian and back, from rest and smoothly (at most
  // 1.2 m/s² and 0.62 rad/s², within what μ = 0.6 holds); the rider keeps
  // its place on it.
  platform_scene s(0.6f);
  const vec3<float> offset = s.w.body(s.rider).position;  // from the platform's center
  const float dt = impulse::test::step_dt<float>;
  transform<float> pose{};
  float worst = 0;
  for (int i = 1; i <= 240; ++i) {
    const float t = float(i) * dt, swing = 1 - std::cos(2 * std::numbers::pi_v<float> * t / 4);
    pose = {{0.5f * swing, 0, 0.25f * swing}, quat<float>::from_axis_angle({0, 1, 0}, 0.25f * swing)};
    s.w.set_target_pose(s.platform, pose, dt);
    s.w.step(dt);
    REQUIRE(length(s.w.shape_pose(s.platform).position - pose.position) < 1e-5f);
    worst = std::max(worst, length(s.w.body(s.rider).position - apply(pose, offset)));
  }
  CHECK(worst < 0.005f);
  // No new target: it stops after the step it arrived in.
  s.w.step(dt);
  s.w.step(dt);
  CHECK(s.w.body(s.platform).linear_velocity() == vec3<float>{});
  CHECK(length(s.w.shape_pose(s.platform).position - pose.position) < 1e-5f);

  CHECK(error_code_of([&] { s.w.set_target_pose(s.rider, pose, dt); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { s.w.set_target_pose(s.platform, pose, 0); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] {
          s.w.set_target_pose(s.platform, {{0, std::numeric_limits<float>::quiet_NaN(), 0}, {}}, dt);
        }) == error_code::non_finite);
}

TEST_CASE("a box asleep on a platform wakes when the platform starts to move") {
  platform_scene s(0.6f);
  for (int i = 0; i < 120 && s.w.is_awake(s.rider); ++i) s.w.step(impulse::test::step_dt<float>);
  REQUIRE_FALSE(s.w.is_awake(s.rider));
  s.w.set_velocity(s.platform, {0.5f, 0, 0}, {});
  s.w.step(impulse::test::step_dt<float>);
  CHECK(s.w.is_awake(s.rider));
  for (int i = 0; i < 60; ++i) s.w.step(impulse::test::step_dt<float>);
  CHECK(s.w.body(s.rider).linear_velocity().x == doctest::Approx(0.5f).epsilon(0.01));
}

}  // namespace world_kinematic_tests
