// The pre-solve and post-solve hooks: a one-way platform, a conveyor belt,
// restitution and friction set per contact, impulses reported against the
// weight they carry, and a hook that misbehaves leaving the world whole.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "../error_code_of.hpp"
#include "impulse/world.hpp"
#include "scenes.hpp"

namespace world_contact_hooks_tests {

using namespace impulse;
using impulse::test::error_code_of;
using impulse::test::step_dt;
using world_type = world<impulse::test::awake_config>;

namespace {

constexpr float g = 9.81f;

/// A one-way platform: its contacts count only while the other body's
/// center is above the platform's top by that body's radius, less 5 cm.
struct one_way {
  const world_type* w = nullptr;
  body_id platform;
  float top = 0, radius = 0;
  static void call(body_id a, body_id b, const contact_manifold<float>&, contact_settings<float>& s, void* context) {
    const auto& self = *static_cast<const one_way*>(context);
    if (a != self.platform && b != self.platform) return;
    const body_id other = a == self.platform ? b : a;
    s.enabled = self.w->body(other).position.y > self.top + self.radius - 0.05f;
  }
};

/// A belt that carries what lies on it at `speed` along x.
struct conveyor {
  body_id belt;
  float speed = 0;
  static void call(body_id a, body_id b, const contact_manifold<float>&, contact_settings<float>& s, void* context) {
    const auto& self = *static_cast<const conveyor*>(context);
    if (a == self.belt) s.surface_velocity = {self.speed, 0, 0};
    else if (b == self.belt) s.surface_velocity = {-self.speed, 0, 0};
  }
};

body_id add_static_box(world_type& w, vec3<float> at, vec3<float> half) {
  body_def<float> d;
  d.type = body_type::static_body;
  d.pose.position = at;
  return w.create_body(d, box<float>::make(half));
}

body_id add_ball(world_type& w, vec3<float> at, vec3<float> velocity = {}) {
  body_def<float> d;
  d.pose.position = at;
  d.linear_velocity = velocity;
  return w.create_body(d, sphere<float>::make(0.25f));
}

}  // namespace

TEST_CASE("a ball thrown up through a one-way platform flies as if it were not there, then lands on it") {
  // The platform spans y from 1.9 to 2.1; the ball (radius 0.25) leaves
  // y = 0.5 at 8 m/s: it would peak at 0.5 + 8²/(2g) = 3.76 m.
  world_type w;
  one_way rule{&w, {}, 2.1f, 0.25f};
  rule.platform = add_static_box(w, {0, 2, 0}, {2, 0.1f, 2});
  w.set_pre_solve({&one_way::call, &rule});
  const body_id ball = add_ball(w, {0, 0.5f, 0}, {0, 8, 0});
  // The same throw in an empty world.
  world_type free;
  const body_id free_ball = add_ball(free, {0, 0.5f, 0}, {0, 8, 0});
  float peak = 0;
  int step = 0;
  for (; step < 60 && w.body(ball).linear_velocity().y > -2; ++step) {
    w.step(step_dt<float>);
    free.step(step_dt<float>);
    peak = std::max(peak, w.body(ball).position.y);
    // Through the platform and up to where it starts to fall back on it,
    // its flight is the free one, to the bit.
    CHECK(w.body(ball).position.y == free.body(free_ball).position.y);
  }
  CHECK(peak == doctest::Approx(3.76f).epsilon(0.02));
  impulse::test::run(w, 180);
  // Resting on the top: y = 2.1 + 0.25.
  CHECK(std::abs(w.body(ball).position.y - 2.35f) < 0.01f);
  CHECK(length(w.body(ball).linear_velocity()) < 0.01f);

  // Without the hook the same throw strikes the platform from below.
  world_type blocked;
  add_static_box(blocked, {0, 2, 0}, {2, 0.1f, 2});
  const body_id struck = add_ball(blocked, {0, 0.5f, 0}, {0, 8, 0});
  float highest = 0;
  for (int i = 0; i < 60; ++i) {
    blocked.step(step_dt<float>);
    highest = std::max(highest, blocked.body(struck).position.y);
  }
  CHECK(highest < 1.9f - 0.25f + 0.01f);
}

TEST_CASE("a box on a conveyor belt speeds up at mu*g to the belt's speed, with the belt as either body, in both solvers with sleeping off and on") {
  const auto check = [](auto& w, bool belt_first) {
    // Friction 0.6 on both (combined 0.6): μ·g = 5.886 m/s², so the box
    // reaches 2 m/s at t = 0.340 s, having moved 0.340 m, then keeps it.
    body_id belt, cube;
    if (belt_first) {
      belt = impulse::test::add_ground(w);
      cube = impulse::test::add_cube(w, {0, 0.5f, 0});
    } else {
      cube = impulse::test::add_cube(w, {0, 0.5f, 0});
      belt = impulse::test::add_ground(w);
    }
    conveyor c{belt, 2};
    w.set_pre_solve({&conveyor::call, &c});
    const float mu_g = 0.6f * g;
    impulse::test::run(w, 12);  // 0.2 s: still slipping
    CHECK(w.body(cube).linear_velocity().x == doctest::Approx(mu_g * 0.2f).epsilon(0.03));
    impulse::test::run(w, 108);  // 2 s in all
    CHECK(w.body(cube).linear_velocity().x == doctest::Approx(2.0f).epsilon(0.005));
    const float t_slip = 2 / mu_g;
    const float expected = 0.5f * mu_g * t_slip * t_slip + 2 * (2 - t_slip);
    CHECK(w.body(cube).position.x == doctest::Approx(expected).epsilon(0.02));
    CHECK(std::abs(w.body(cube).position.y - 0.5f) < 0.01f);  // and it stays on the belt, not tipped
  };
  for (const bool belt_first : {true, false}) {
    CAPTURE(belt_first);
    world_type w;
    check(w, belt_first);
    world<impulse::test::soft_config> soft;
    check(soft, belt_first);
    world<impulse::test::sleeping_config> sleepy;  // the box never rests on the belt long enough to sleep
    check(sleepy, belt_first);
  }
}

TEST_CASE("a pre-solve hook's restitution and friction replace the pair's own") {
  // A ball of restitution 0 dropped from 2 m above its rest height: with
  // the hook's 0.8 it rebounds to e²·2 = 1.28 m.
  struct bouncy {
    static void call(body_id, body_id, const contact_manifold<float>&, contact_settings<float>& s, void*) {
      s.restitution = 0.8f;
    }
  };
  world_type w;
  impulse::test::add_ground(w);
  const body_id ball = add_ball(w, {0, 2.25f, 0});
  w.set_pre_solve({&bouncy::call, nullptr});
  float low = 10, rebound = 0;
  for (int i = 0; i < 120; ++i) {
    w.step(step_dt<float>);
    const float y = w.body(ball).position.y;
    low = std::min(low, y);
    if (low < 0.3f) rebound = std::max(rebound, y - 0.25f);
  }
  CHECK(rebound == doctest::Approx(1.28f).epsilon(0.02));

  // A box on a 30° incline of friction 0.6 stays; with the hook's
  // friction 0 it slides down at g·sin 30° = 4.905 m/s².
  struct slippery {
    static void call(body_id, body_id, const contact_manifold<float>&, contact_settings<float>& s, void*) {
      s.friction = 0;
    }
  };
  world_type slope;
  const quat<float> tilt = quat<float>::from_axis_angle({0, 0, 1}, 0.5235988f);
  body_def<float> ramp;
  ramp.type = body_type::static_body;
  ramp.pose = {{0, 0, 0}, tilt};
  slope.create_body(ramp, box<float>::make({20, 0.5f, 5}));
  const body_id cube = impulse::test::add_cube(slope, rotate(tilt, vec3<float>{0, 1, 0}), 1, 0.6f, tilt);
  impulse::test::run(slope, 30);
  CHECK(length(slope.body(cube).linear_velocity()) < 0.01f);
  slope.set_pre_solve({&slippery::call, nullptr});
  const vec3<float> v0 = slope.body(cube).linear_velocity();
  impulse::test::run(slope, 30);
  CHECK(length(slope.body(cube).linear_velocity() - v0) == doctest::Approx(g * 0.5f * 0.5f).epsilon(0.01));
}

TEST_CASE("the post-solve hook reports impulses that carry a resting box's weight, and a switched-off contact none") {
  struct tally {
    int calls = 0;
    float normal = 0;
    static void call(body_id, body_id, const contact_manifold<float>& m, const manifold_impulse<float>& impulse,
                     void* context) {
      auto& self = *static_cast<tally*>(context);
      ++self.calls;
      for (int p = 0; p < m.count; ++p) self.normal += impulse.normal[std::size_t(p)];
    }
  };
  world_type w;
  impulse::test::add_ground(w);
  impulse::test::add_cube(w, {0, 0.5f, 0}, 2);
  impulse::test::run(w, 60);
  tally t;
  w.set_post_solve({&tally::call, &t});
  w.step(step_dt<float>);
  CHECK(t.calls == 1);
  CHECK(t.calls == int(w.last_step_counts().solved_manifolds));
  // m·g·dt = 2 · 9.81 / 60 N·s.
  CHECK(t.normal == doctest::Approx(2 * g / 60).epsilon(0.005));

  // Switched off, the contact is not solved: the box falls into the ground.
  struct off {
    static void call(body_id, body_id, const contact_manifold<float>&, contact_settings<float>& s, void*) {
      s.enabled = false;
    }
  };
  w.set_pre_solve({&off::call, nullptr});
  t = {};
  w.step(step_dt<float>);
  CHECK(t.calls == 0);
  CHECK(w.last_step_counts().solved_manifolds == 0);
  w.set_pre_solve({});
  w.set_post_solve({});
  CHECK(!w.pre_solve().call);
}

TEST_CASE("a hook that gives bad settings or throws leaves a whole step, then the step says so") {
  struct bad {
    static void call(body_id, body_id, const contact_manifold<float>&, contact_settings<float>& s, void*) {
      s.friction = std::nanf("");
    }
  };
  world_type w;
  impulse::test::add_ground(w);
  const body_id cube = impulse::test::add_cube(w, {0, 0.5f, 0});
  impulse::test::run(w, 30);
  w.set_pre_solve({&bad::call, nullptr});
  const float before = float(w.time());
  CHECK(error_code_of([&] { w.step(step_dt<float>); }) == error_code::invalid_parameter);
  CHECK(float(w.time()) == doctest::Approx(before + step_dt<float>));  // the step completed
  CHECK(std::abs(w.body(cube).position.y - 0.5f) < 0.01f);              // on its own friction

  // A hook that tries to change the world is refused; the refusal comes
  // out of step() once the step is done.
  struct meddler {
    world_type* w = nullptr;
    body_id victim;
    int calls = 0;
    static void call(body_id, body_id, const contact_manifold<float>&, contact_settings<float>&, void* context) {
      auto& self = *static_cast<meddler*>(context);
      ++self.calls;
      self.w->destroy_body(self.victim);
    }
  };
  meddler m{&w, cube};
  impulse::test::add_cube(w, {3, 0.5f, 0});
  impulse::test::run(w, 0);
  w.set_pre_solve({&meddler::call, &m});
  CHECK(error_code_of([&] { w.step(step_dt<float>); }) == error_code::invalid_parameter);
  CHECK(m.calls == 1);  // no hook again in that step
  CHECK(w.contains(cube));
  w.set_pre_solve({});
  impulse::test::run(w, 10);
  CHECK(std::abs(w.body(cube).position.y - 0.5f) < 0.01f);
}

}  // namespace world_contact_hooks_tests
