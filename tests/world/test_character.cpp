// The character controller (impulse/character.hpp): walking, walls,
// slopes, steps, falling and jumping, carried by moving and turning
// platforms, pushing bodies with a capped force, and crouching; each
// against where geometry and the character's own integration put it.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "../error_code_of.hpp"
#include "impulse/character.hpp"
#include "scenes.hpp"

namespace world_character_tests {

using namespace impulse;
using impulse::test::error_code_of;
using impulse::test::step_dt;
using world_type = world<impulse::test::awake_config>;
using hero_type = character<impulse::test::awake_config>;

namespace {

constexpr float g = 9.81f;
constexpr float dt = 1.0f / 60;
constexpr float skin = 0.01f;  // character_def's default
constexpr float radius = 0.3f;

body_id add_block(world_type& w, vec3<float> at, vec3<float> half, body_type type = body_type::static_body,
                  float friction = 0.6f) {
  body_def<float> d;
  d.type = type;
  d.pose.position = at;
  d.material.friction = friction;
  return w.create_body(d, box<float>::make(half));
}

/// Steps the world and then moves the character, n times.
void walk(world_type& w, hero_type& hero, vec3<float> velocity, int n) {
  for (int i = 0; i < n; ++i) {
    w.step(dt);
    hero.move(velocity, dt);
  }
}

/// A ramp rising at `angle` from x = 1: the surface y = (x − 1)·tan(angle)
/// for x in [1, 11], as two triangles.
body_id add_ramp(world_type& w, float angle) {
  const float top = 10 * std::tan(angle);
  const vec3<float> corners[] = {{1, 0, -5}, {1, 0, 5}, {11, top, 5}, {11, top, -5}};
  const std::uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
  body_def<float> d;
  d.type = body_type::static_body;
  return w.create_body(d, triangle_mesh<float>::make(corners, triangles));
}

}  // namespace

TEST_CASE("a character walks the flat ground at its speed, its feet a skin above it") {
  world_type w;
  impulse::test::add_ground(w);
  hero_type hero(w, {}, {0, skin, 0});
  walk(w, hero, {2, 0, 0}, 120);
  CHECK(hero.feet().x == doctest::Approx(4.0f).epsilon(1e-4));
  CHECK(std::abs(hero.feet().z) < 1e-5f);
  CHECK(std::abs(hero.feet().y - skin) < 0.001f);
  CHECK(hero.on_ground());
  CHECK(length(hero.ground()->normal - vec3<float>{0, 1, 0}) < 1e-3f);
  CHECK(length(hero.velocity() - vec3<float>{2, 0, 0}) < 1e-3f);
}

TEST_CASE("a character stops at a wall a radius and a skin short, and slides along it at the speed's part along it") {
  world_type w;
  impulse::test::add_ground(w);
  add_block(w, {3.5f, 2, 0}, {0.5f, 2, 20});  // its face at x = 3
  hero_type hero(w, {}, {0, skin, 0});
  walk(w, hero, {2, 0, 0}, 180);
  CHECK(std::abs(hero.feet().x - (3 - radius - skin)) < 0.001f);
  // At 45° to the wall, √2 m/s along it: 2.83 m in 2 s.
  const float z0 = hero.feet().z;
  walk(w, hero, {std::sqrt(2.0f), 0, std::sqrt(2.0f)}, 120);
  CHECK(hero.feet().z - z0 == doctest::Approx(2 * std::sqrt(2.0f)).epsilon(0.005));
  CHECK(std::abs(hero.feet().x - (3 - radius - skin)) < 0.001f);
}

TEST_CASE("a character falls as its own steps of gravity say, lands, and jumps to v squared over 2g") {
  world_type w;
  impulse::test::add_ground(w);
  hero_type hero(w, {}, {0, 3, 0});
  // Each move adds g·dt to the fall, then moves by it: after n moves the
  // feet have fallen g·dt²·n(n+1)/2.
  walk(w, hero, {}, 20);
  CHECK(hero.feet().y == doctest::Approx(3 - g * dt * dt * 210).epsilon(1e-5));
  CHECK_FALSE(hero.on_ground());
  walk(w, hero, {}, 60);
  CHECK(hero.on_ground());
  CHECK(std::abs(hero.feet().y - skin) < 0.001f);
  CHECK(hero.vertical_speed() == 0);
  // A jump at 5 m/s rises 5²/(2g) = 1.274 m, less the steps' rounding (½·5·dt).
  hero.jump(5);
  float apex = 0;
  for (int i = 0; i < 90; ++i) {
    w.step(dt);
    hero.move({}, dt);
    apex = std::max(apex, hero.feet().y - skin);
  }
  CHECK(apex == doctest::Approx(25 / (2 * g)).epsilon(0.04));
  CHECK(hero.on_ground());
}

TEST_CASE("a character walks up a 30 degree slope on it, and is held below a 60 degree one") {
  for (const float degrees : {30.0f, 60.0f}) {
    CAPTURE(degrees);
    const float angle = degrees * std::numbers::pi_v<float> / 180;
    world_type w;
    impulse::test::add_ground(w);
    add_ramp(w, angle);
    hero_type hero(w, {}, {0, skin, 0});
    walk(w, hero, {1, 0, 0}, 240);
    if (degrees < 45) {
      // On the slope, its lower cap's center r/cos(angle) above the
      // surface: the feet (x − 1)·tan(angle) + r/cos(angle) − r up, and a
      // skin along the normal.
      const float x = hero.feet().x;
      CHECK(x > 3);
      const float expected = (x - 1) * std::tan(angle) + radius / std::cos(angle) - radius;
      CHECK(std::abs(hero.feet().y - expected) < 0.02f);
      CHECK(hero.on_ground());
    } else {
      CHECK(hero.feet().y < 0.3f + 0.05f);  // no higher than a step
      CHECK(hero.feet().x < 1.5f);
    }
  }
}

TEST_CASE("a character climbs stairs of 0.2 m and is stopped by a step of 0.5 m") {
  for (const float rise : {0.2f, 0.5f}) {
    CAPTURE(rise);
    world_type w;
    impulse::test::add_ground(w);
    // Five steps 0.5 m deep from x = 1.
    for (int k = 0; k < 5; ++k)
      add_block(w, {1.25f + 0.5f * float(k), rise * float(k + 1) / 2, 0}, {0.25f, rise * float(k + 1) / 2, 2});
    hero_type hero(w, {}, {0, skin, 0});
    // Until its axis is over the middle of the top step (x from 3 to 3.5),
    // or 5 s.
    for (int i = 0; i < 300 && hero.feet().x < 3.25f; ++i) walk(w, hero, {1, 0, 0}, 1);
    if (rise < 0.3f) {
      CHECK(hero.feet().x >= 3.25f);
      CHECK(std::abs(hero.feet().y - (5 * rise + skin)) < 0.001f);  // on the top step, a skin above it
      CHECK(hero.on_ground());
    } else {
      CHECK(hero.feet().x < 1 - radius);
      CHECK(std::abs(hero.feet().y - skin) < 0.001f);
    }
  }
}

TEST_CASE("a character on a turning platform is carried round a circle, and on a moving one along with it") {
  world_type w;
  const body_id platform = add_block(w, {0, 0, 0}, {4, 0.25f, 4}, body_type::kinematic);
  hero_type hero(w, {}, {2, 0.25f + skin, 0});
  w.set_velocity(platform, {}, {0, 1, 0});
  walk(w, hero, {}, 90);
  // Carried by the platform's change of pose: still 2 m from its axis (no
  // spiral), a step behind its turn (the first move found the ground).
  const vec3<float> feet = hero.feet();
  CHECK(std::sqrt(feet.x * feet.x + feet.z * feet.z) == doctest::Approx(2.0f).epsilon(1e-4));
  const quat<float> q = w.body(platform).orientation;
  const float turned = 2 * std::atan2(q.y, q.w);
  const float at = std::atan2(-feet.z, feet.x);
  CHECK(std::abs(at - (turned - dt)) < 1e-3f);
  CHECK(length(hero.ground()->velocity) == doctest::Approx(2.0f).epsilon(1e-3));  // ω·r
  // A platform sliding at 1 m/s along z carries it 1 m in a second.
  w.set_velocity(platform, {0, 0, 1}, {});
  walk(w, hero, {}, 2);
  const vec3<float> before = hero.feet();
  walk(w, hero, {}, 60);
  CHECK(length(hero.feet() - before - vec3<float>{0, 0, 1}) < 1e-3f);
}

TEST_CASE("a character pushes a box with at most push_force, and cannot shift one that friction holds harder") {
  // A 5 kg box on ice is pushed for a second at most 200 N·s / 5 kg = 40 m/s
  // faster: its momentum is at most 200 N·s.
  world_type w;
  impulse::test::add_ground(w, 0);
  body_def<float> d;
  d.pose.position = {1.5f, 0.5f, 0};
  d.mass = 5;
  d.material.friction = 0;
  const body_id light = w.create_body(d, box<float>::make({0.5f, 0.5f, 0.5f}));
  hero_type hero(w, {}, {0, skin, 0});
  walk(w, hero, {1, 0, 0}, 60);
  const float p = w.body(light).linear_momentum.x;
  CHECK(p > 0);
  CHECK(p <= 200 * 1.0f * 1.0001f);
  CHECK(w.body(light).position.x > 1.5f);

  // 50 kg on friction 0.6: μ·m·g = 294 N holds it against 200 N.
  world_type held;
  impulse::test::add_ground(held);
  const body_id heavy = impulse::test::add_cube(held, {1.5f, 0.5f, 0}, 50);
  impulse::test::run(held, 30);
  hero_type pusher(held, {}, {0, skin, 0});
  walk(held, pusher, {1, 0, 0}, 120);
  CHECK(std::abs(held.body(heavy).position.x - 1.5f) < 1e-3f);
  CHECK(std::abs(pusher.feet().x - (1 - radius - skin)) < 0.002f);
}

TEST_CASE("a character wakes a box that fell asleep and pushes it") {
  // With sleeping on, a box left at rest sleeps; the character's push
  // (a force at the contact) must wake it, or a game's crates freeze once
  // they settle. Friction 0.2 on both: 200 N against μ·m·g = 9.8 N moves it.
  world<impulse::test::sleeping_config> w;
  impulse::test::add_ground(w, 0.2f);
  const body_id crate = impulse::test::add_cube(w, {1.5f, 0.5f, 0}, 5, 0.2f);
  impulse::test::run(w, 120);
  REQUIRE_FALSE(w.is_awake(crate));
  character<impulse::test::sleeping_config> hero(w, {}, {0, skin, 0});
  for (int i = 0; i < 60; ++i) {
    w.step(dt);
    hero.move({1, 0, 0}, dt);
  }
  CHECK(w.is_awake(crate));
  // The character meets the crate's face x = 1 when its feet reach
  // 1 − radius − skin = 0.69, at 0.69 s, and walks on for 0.31 s: the
  // crate is pushed on by about that, and stays ahead of the character
  // (its face no nearer than the capsule's front, less a centimetre).
  CHECK(w.body(crate).position.x > 1.5f + 0.25f);
  CHECK(w.body(crate).position.x - 0.5f > hero.feet().x + radius - 0.01f);
}

TEST_CASE("a character crouches under a low ceiling and stands up only where there is room") {
  world_type w;
  impulse::test::add_ground(w);
  add_block(w, {3, 1.9f, 0}, {1, 0.5f, 3});  // a slab over x from 2 to 4, its underside at y = 1.4
  hero_type hero(w, {}, {0, skin, 0});
  walk(w, hero, {1, 0, 0}, 180);
  CHECK(hero.feet().x < 2 - radius);  // standing, it does not fit
  hero.crouch();
  CHECK(hero.crouching());
  walk(w, hero, {1, 0, 0}, 60);
  CHECK(hero.feet().x > 2.5f);
  CHECK_FALSE(hero.stand());  // no room under the slab
  CHECK(hero.height() == doctest::Approx(1.0f));
  walk(w, hero, {1, 0, 0}, 150);
  CHECK(hero.feet().x > 4 + radius);
  CHECK(hero.stand());
  CHECK(hero.height() == doctest::Approx(1.8f));
}

TEST_CASE("a character refuses a bad definition, velocity or time step") {
  world_type w;
  character_def<float> bad;
  bad.height = 0.5f;  // less than two radii
  CHECK(error_code_of([&] { hero_type h(w, bad, {}); }) == error_code::invalid_parameter);
  bad = {};
  bad.skin = std::nanf("");
  CHECK(error_code_of([&] { hero_type h(w, bad, {}); }) == error_code::non_finite);
  hero_type hero(w, {}, {});
  CHECK(error_code_of([&] { hero.move({std::nanf(""), 0, 0}, dt); }) == error_code::non_finite);
  CHECK(error_code_of([&] { hero.move({1, 0, 0}, 0); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { hero.jump(-1); }) == error_code::invalid_parameter);
  CHECK(hero.feet() == vec3<float>{});
}

}  // namespace world_character_tests
