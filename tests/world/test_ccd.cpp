// Continuous collision: fast bodies and bullets are swept over the step and
// stopped short of what they would have passed through.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>

#include "impulse/world.hpp"
#include "scenes.hpp"

namespace world_ccd_tests {

using namespace impulse;

namespace {

using impulse::test::ccd_config;
static_assert(world<ccd_config>::ccd && !world<impulse::test::awake_config>::ccd);

enum class wall_kind { box, mesh };

/// A static wall 200 m square, its near face at x = 5: a box 1 cm thick,
/// or a mesh of two triangles facing −x (a surface, no thickness).
template <class World>
void add_wall(World& w, wall_kind kind = wall_kind::box) {
  body_def<float> d;
  d.type = body_type::static_body;
  if (kind == wall_kind::box) {
    d.pose.position = {5.005f, 0, 0};
    w.create_body(d, box<float>::make({0.005f, 100, 100}));
    return;
  }
  const vec3<float> corners[] = {{5, -100, -100}, {5, -100, 100}, {5, 100, 100}, {5, 100, -100}};
  const std::uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
  w.create_body(d, triangle_mesh<float>::make(corners, triangles));
}

world_settings<float> weightless() {
  world_settings<float> s;
  s.gravity = {0, 0, 0};
  return s;
}

/// The furthest x a ball of radius 0.05 fired at 500 m/s from the origin
/// at `angle` to the wall's normal reaches in 30 steps at 60 Hz (8.3 m a
/// step: its first step ends past the wall).
template <class Config>
float furthest_ball(float angle, wall_kind kind = wall_kind::box) {
  world<Config> w(weightless());
  add_wall(w, kind);
  body_def<float> d;
  d.linear_velocity = vec3<float>{std::cos(angle), std::sin(angle), 0} * 500.0f;
  const body_id ball = w.create_body(d, sphere<float>::make(0.05f));
  float furthest = 0;
  for (int i = 0; i < 30; ++i) {
    w.step(impulse::test::step_dt<float>);
    furthest = std::max(furthest, w.body(ball).position.x);
  }
  return furthest;
}

}  // namespace

TEST_CASE("a ball of radius 5 cm at 500 m/s never passes a 1 cm wall or a mesh wall at any angle of incidence") {
  for (const wall_kind kind : {wall_kind::box, wall_kind::mesh})
    for (const float degrees : {0.0f, 30.0f, 60.0f, 80.0f}) {
      CAPTURE(degrees);
      CAPTURE(kind == wall_kind::mesh);
      const float angle = degrees * std::numbers::pi_v<float> / 180;
      // Its center stays a radius short of the near face (4.95): the sweep
      // stops it 5 mm short, the next step's contact lets it touch.
      CHECK(furthest_ball<ccd_config>(angle, kind) < 4.95f + 0.001f);
      // Without the sweep it is through in the first step.
      CHECK(furthest_ball<impulse::test::awake_config>(angle, kind) > 5.5f);
    }
}

TEST_CASE("a fast ball whose filter leaves out the wall is not swept against it, and passes") {
  // Fired straight at the wall at 500 m/s, the ball's center is past it
  // (x > 5.5) after the first step unless something stops it.
  for (const bool filtered : {false, true}) {
    CAPTURE(filtered);
    world<ccd_config> w(weightless());
    add_wall(w);
    body_def<float> d;
    d.linear_velocity = {500, 0, 0};
    if (filtered) d.filter = {2, ~1u, 0};
    const body_id ball = w.create_body(d, sphere<float>::make(0.05f));
    w.step(impulse::test::step_dt<float>);
    if (filtered) CHECK(w.body(ball).position.x == doctest::Approx(500.0f / 60).epsilon(1e-5));
    else CHECK(w.body(ball).position.x < 4.95f + 0.001f);
  }
}

TEST_CASE("a thin box flying fast and spinning never passes through a thin wall or a mesh wall") {
  for (const wall_kind kind : {wall_kind::box, wall_kind::mesh}) {
    for (const float degrees : {0.0f, 30.0f, 60.0f}) {
      CAPTURE(degrees);
      CAPTURE(kind == wall_kind::mesh);
      const float angle = degrees * std::numbers::pi_v<float> / 180;
      world<ccd_config> w(weightless());
      add_wall(w, kind);
      // A plate 2 cm thick and 0.5 m square, flat side first, at 150 m/s
      // (2.5 m a step) and turning 10 rad/s about z.
      body_def<float> d;
      d.pose.position = {0.5f, 0, 0};
      d.linear_velocity = vec3<float>{std::cos(angle), std::sin(angle), 0} * 150.0f;
      d.angular_velocity = {0, 0, 10};
      const body_id plate = w.create_body(d, box<float>::make({0.01f, 0.25f, 0.25f}));
      float furthest = 0, last = 0;
      for (int i = 0; i < 30; ++i) {
        w.step(impulse::test::step_dt<float>);
        // Its farthest corner's x, from its pose.
        const transform<float> pose = w.shape_pose(plate);
        last = 0;
        for (const float sx : {-1.0f, 1.0f})
          for (const float sy : {-1.0f, 1.0f})
            for (const float sz : {-1.0f, 1.0f})
              last = std::max(last, apply(pose, vec3<float>{0.01f * sx, 0.25f * sy, 0.25f * sz}).x);
        furthest = std::max(furthest, last);
      }
      // The sweep stops it 5 mm short; the next step's contact, met with
      // its points' straight-line approach, stops it at the wall. Its
      // corners, 0.35 m from its center and turning 10 rad/s, leave that
      // line by up to ½·ω²·r·h² = 4.9 mm over the step, which is what can
      // carry one in (1.2 mm at most here).
      CHECK(furthest < 5.0f + 0.0049f);
      // After 30 steps it is no deeper than the slop (0.5 mm) the position
      // pass leaves.
      CHECK(last < 5.0f + 0.0006f);
    }
  }
}

TEST_CASE("a ball stopped short of a wall by its sweep bounces off it at e times its speed the next step") {
  // The sweep stops it 5 mm short and keeps its velocity; the next step's
  // speculative contact meets the impact, with restitution: the rest of
  // the motion is resolved one step late, at the right speed.
  world<ccd_config> w(weightless());
  body_def<float> d;
  d.type = body_type::static_body;
  d.pose.position = {5.005f, 0, 0};
  d.material.restitution = 0.8f;
  w.create_body(d, box<float>::make({0.005f, 100, 100}));
  body_def<float> b;
  b.linear_velocity = {500, 0, 0};
  b.material.restitution = 0.8f;
  const body_id ball = w.create_body(b, sphere<float>::make(0.05f));
  w.step(impulse::test::step_dt<float>);
  CHECK(w.body(ball).position.x == doctest::Approx(4.945f).epsilon(1e-4));
  CHECK(w.body(ball).linear_velocity().x == doctest::Approx(500.0f));
  w.step(impulse::test::step_dt<float>);
  CHECK(w.body(ball).linear_velocity().x == doctest::Approx(-400.0f).epsilon(1e-4));
}

TEST_CASE("a bullet fired at a stack strikes the box in its path instead of passing through it") {
  // Five cubes stacked at x = 10; a 0.1 m ball at 300 m/s (5 m a step)
  // aimed at the second.
  const auto shoot = [](bool bullet) {
    world<ccd_config> w;
    impulse::test::add_ground(w);
    std::vector<body_id> stack;
    for (int k = 0; k < 5; ++k) stack.push_back(impulse::test::add_cube(w, {10, 0.5f + float(k), 0}));
    for (int i = 0; i < 30; ++i) w.step(impulse::test::step_dt<float>);
    body_def<float> d;
    d.pose.position = {0, 1.5f, 0};
    d.linear_velocity = {300, 0, 0};
    d.bullet = bullet;
    d.mass = 1;
    const body_id ball = w.create_body(d, sphere<float>::make(0.1f));
    float struck = 0, ahead = -1;
    for (int i = 0; i < 10; ++i) {
      w.step(impulse::test::step_dt<float>);
      struck = std::max(struck, w.body(stack[1]).linear_velocity().x);
      ahead = std::max(ahead, w.body(ball).position.x - (w.body(stack[1]).position.x + 0.5f));
    }
    return std::pair{struck, ahead};
  };
  const auto [struck, ahead] = shoot(true);
  // The 1 kg box takes the blow (at e = 0 the two share 300 m/s) and the
  // ball never gets past its far face.
  CHECK(struck > 100.0f);
  CHECK(ahead < 0.0f);
  // Not a bullet, it is swept only against static bodies: straight through.
  const auto [missed, through] = shoot(false);
  CHECK(missed < 1.0f);
  CHECK(through > 1.0f);
}

TEST_CASE("a ball rolling fast along the ground is not held back by its sweep") {
  world<ccd_config> w;
  impulse::test::add_ground(w);
  body_def<float> d;
  d.pose.position = {0, 0.05f, 0};
  d.linear_velocity = {30, 0, 0};
  d.angular_velocity = {0, 0, -600};
  const body_id ball = w.create_body(d, sphere<float>::make(0.05f));
  for (int i = 0; i < 60; ++i) w.step(impulse::test::step_dt<float>);
  // Rolling without slipping, it covers 30 m in the second.
  CHECK(w.body(ball).position.x == doctest::Approx(30.0f).epsilon(0.02));
}

TEST_CASE("a bullet meets a fast body where the fast body's own sweep left it, whichever was made first") {
  // A 20 cm cube at 240 m/s (4 m a step) from x = 2.5 at the wall, which
  // its sweep stops at x = 4.895; its reach in the broad phase is capped at
  // 1 m. A 5 cm bullet at 120 m/s straight down the line x = 4.89 from
  // y = 2: it reaches the cube's top near the end of the step, where the
  // cube's sweep left it, and had the cube gone on through the wall it
  // would have passed behind it.
  const auto fire = [](bool cube_first) {
    world<ccd_config> w(weightless());
    add_wall(w);
    body_def<float> cube, shot;
    cube.pose.position = {2.5f, 0, 0};
    cube.linear_velocity = {240, 0, 0};
    shot.pose.position = {4.89f, 2, 0};
    shot.linear_velocity = {0, -120, 0};
    shot.bullet = true;
    const auto make_cube = [&] { return w.create_body(cube, box<float>::make({0.1f, 0.1f, 0.1f})); };
    const auto make_shot = [&] { return w.create_body(shot, sphere<float>::make(0.05f)); };
    body_id c, b;
    if (cube_first) {
      c = make_cube();
      b = make_shot();
    } else {
      b = make_shot();
      c = make_cube();
    }
    w.step(impulse::test::step_dt<float>);
    return std::pair{w.body(c).position, w.body(b).position};
  };
  const auto [cube, shot] = fire(true);
  CHECK(cube.x == doctest::Approx(4.895f).epsilon(1e-5));  // 5 mm (ccd_gap) short of the wall
  // The bullet stops on the cube's top (y = 0.1) before its center gets
  // below it, 2 m short of where its step would have taken it.
  CHECK(shot.y > 0.1f);
  CHECK(shot.y < 0.2f);
  const auto [cube_second, shot_second] = fire(false);
  CHECK(cube_second == cube);
  CHECK(shot_second == shot);
}

TEST_CASE("a fast ball meets a fast kinematic plate coming at it, though the plate's reach in the broad phase is capped") {
  // A ball of radius 5 cm at 300 m/s along +x from x = 0, and a kinematic
  // plate 2 cm thick at 300 m/s along -x from x = 8: they close 10 m in
  // the step, and would have passed through each other at x = 4.
  world<ccd_config> w(weightless());
  body_def<float> d;
  d.linear_velocity = {300, 0, 0};
  const body_id ball = w.create_body(d, sphere<float>::make(0.05f));
  body_def<float> p;
  p.type = body_type::kinematic;
  p.pose.position = {8, 0, 0};
  p.linear_velocity = {-300, 0, 0};
  const body_id plate = w.create_body(p, box<float>::make({0.01f, 1, 1}));
  w.step(impulse::test::step_dt<float>);
  // Stopped where the gap between them closes to ccd_gap (5 mm), the two
  // at the same speed: the ball at (8 − 0.01 − 0.05 − 0.005) / 2.
  CHECK(w.body(ball).position.x == doctest::Approx(3.9675f).epsilon(1e-5));
  CHECK(w.body(plate).position.x == doctest::Approx(3.0f));  // kinematic: it goes on
}

}  // namespace world_ccd_tests
