// The world's springs and force fields (world/world_forces.hpp): a spring is
// a soft distance row of its stiffness and damping, solved with the
// contacts and joints; its step is the implicit Euler step of the spring,
// which these tests check exactly (period and decay), then against statics
// and conservation, and beside contacts. A force field is a load per awake
// body per step.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "../error_code_of.hpp"
#include "scenes.hpp"

namespace world_springs_tests {

using namespace impulse;
using impulse::test::error_code_of;

namespace {

using awake_world = world<impulse::test::awake_config>;
using awake_double_world = world<impulse::test::awake_double_config>;

template <class World>
typename World::settings_type weightless() {
  typename World::settings_type s;
  s.gravity = {0, 0, 0};
  return s;
}

/// A dynamic box of half-extent `half` and mass `mass` at `at`.
template <class World>
body_id add_box(World& w, vec3<typename World::scalar> at, typename World::scalar mass,
                typename World::scalar half = 0.25) {
  using T = typename World::scalar;
  body_def<T> d;
  d.pose.position = at;
  d.mass = mass;
  return w.create_body(d, box<T>::make({half, half, half}));
}

}  // namespace

TEST_CASE("an undamped spring to an anchor swings with implicit Euler's period and decay: 2*pi*h/atan(h*w) and "
          "(1 + h^2 w^2)^(-1/2) a part") {
  // 1 kg, k = 100 N/m: w = 10 rad/s. The soft row gives
  // v1 = (v0 − h·w²·x0)/(1 + h²w²), then x1 = x0 + h·v1, h a part of the
  // step (the solver's 4 by default; 1/240 s, h·w = 1/24): per part the
  // state turns by atan(h·w) and shrinks by (1 + h²w²)^(−1/2), the
  // implicit Euler step of the oscillator (softness.hpp).
  awake_double_world w(weightless<awake_double_world>());
  const body_id b = add_box(w, {1.5, 0, 0}, 1.0);
  w.create_spring(body_spring<double>::to_anchor(b, {}, {0, 0, 0}, 100.0, 0.0, 1.0));
  const int parts = w.settings().solver.substeps;
  const double dt = 1.0 / 60, h = dt / parts, omega = 10;
  std::vector<double> x;
  for (int i = 0; i < 120; ++i) {
    w.step(dt);
    x.push_back(w.body(b).position.x - 1);
  }
  // The amplitude: x² + (v/ω_d)² is not conserved by the scheme, but the
  // state's norm in its eigenbasis shrinks by the eigenvalue's modulus; over
  // a whole number of half turns the peaks shrink by it exactly.
  std::vector<std::pair<int, double>> peaks;
  for (std::size_t i = 1; i + 1 < x.size(); ++i)
    if (std::abs(x[i]) >= std::abs(x[i - 1]) && std::abs(x[i]) >= std::abs(x[i + 1])) peaks.push_back({int(i), std::abs(x[i])});
  REQUIRE(peaks.size() >= 4);
  const double turn = parts * std::atan(h * omega);  // per step
  const double half_period_steps = std::numbers::pi / turn;  // 18.86 steps
  const int n = peaks.back().first - peaks.front().first;
  const double half_turns = double(peaks.size() - 1);
  CHECK(double(n) / half_turns == doctest::Approx(half_period_steps).epsilon(0.01));  // peaks fall on whole steps
  const double decay = std::pow(1 + h * h * omega * omega, -0.5 * double(n * parts));
  CHECK(peaks.back().second / peaks.front().second == doctest::Approx(decay).epsilon(0.005));  // sampled peaks: up to half a step off
  CHECK(w.body(b).position.y == 0.0);
}

TEST_CASE("a box hanging from a damped spring settles where k*x = m*g, and the spring's tension is its weight") {
  awake_world w;
  const body_id b = add_box(w, {0, 8.5f, 0}, 2.0f);
  // From the box's top face to an anchor 1 m (the rest length) above it.
  const spring_id s = w.create_spring(body_spring<float>::to_anchor(b, {0, 0.25f, 0}, {0, 9.75f, 0}, 400.0f, 40.0f, 1.0f));
  impulse::test::run(w, 600);
  const float stretch = 2.0f * 9.81f / 400.0f;  // 4.9 cm
  CHECK(w.body(b).position.y == doctest::Approx(8.5f - stretch).epsilon(2e-5));
  CHECK(w.spring_tension(s) == doctest::Approx(2.0f * 9.81f).epsilon(1e-3));
  CHECK(length(w.body(b).linear_velocity()) < 1e-4f);
}

TEST_CASE("a spring of 1e6 N/m on a 1 kg box at 60 Hz takes the implicit step, is stable and settles at m*g/k") {
  // An explicit step of this spring diverges (h·w = 4.2 at a part of
  // 1/240 s); the soft row is the implicit step, stable at any stiffness:
  // from a stretch x and speed v, a part of h ends at speed
  // v' = (v + h·(k·x − m·g)/m)/(1 + h²·k/m) and stretch x − h·v', and each
  // part shrinks the motion by (1 + h²·w²)^(−1/2) = 0.23.
  awake_world w;
  const body_id b = add_box(w, {0, 4, 0}, 1.0f);
  w.create_spring(body_spring<float>::to_anchor(b, {}, {0, 5.2f, 0}, 1e6f, 0.0f, 1.0f));
  const float dt = impulse::test::step_dt<float>;
  const int parts = w.settings().solver.substeps;
  const double h = double(dt) / parts;
  double v = 0, x = 0.2;
  for (int k = 0; k < parts; ++k) {
    v = (v + h * (1e6 * x - 9.81)) / (1 + h * h * 1e6);
    x -= h * v;
  }
  w.step(dt);
  CHECK(w.body(b).linear_velocity().y == doctest::Approx(v).epsilon(1e-3));
  impulse::test::run(w, 60);
  CHECK(length(w.body(b).linear_velocity()) < 1e-3f);
  CHECK(w.body(b).position.y == doctest::Approx(4.2f - 9.81f / 1e6f).epsilon(1e-5));
}

TEST_CASE("a spring of zero stiffness and damping pulls with nothing: the body falls as it would alone") {
  awake_double_world w;
  const body_id held = add_box(w, {0, 10, 0}, 1.0);
  const body_id free = add_box(w, {5, 10, 0}, 1.0);
  const spring_id s = w.create_spring(body_spring<double>::to_anchor(held, {}, {0, 10.5, 0}, 0.0, 0.0, 0.5));
  impulse::test::run(w, 60);
  CHECK(w.body(held).position.y == w.body(free).position.y);  // bit for bit: nothing acted on it but gravity
  CHECK(w.body(held).position.y < 6);
  CHECK(w.spring_tension(s) == 0.0);
}

TEST_CASE("a spring between two bodies conserves their momentum to rounding") {
  awake_double_world w(weightless<awake_double_world>());
  const body_id a = add_box(w, {0, 0, 0}, 1.0);
  const body_id b = add_box(w, {2, 0, 0}, 3.0);
  w.create_spring(body_spring<double>::between(a, {0, 0, 0}, b, {0, 0, 0}, 50.0, 2.0, 1.0));
  w.set_velocity(a, {1, 0, 0}, {});
  const auto momentum = [&] { return w.body(a).linear_momentum + w.body(b).linear_momentum; };
  const vec3<double> start = momentum();
  for (int i = 0; i < 600; ++i) {
    w.step(1.0 / 60);
    REQUIRE(length(momentum() - start) < 1e-12);
  }
  // It has pulled them to its rest length by now (damped): 1 m apart.
  CHECK(length(w.body(b).position - w.body(a).position) == doctest::Approx(1.0).epsilon(1e-3));
}

TEST_CASE("a cube hanging from springs at its four top corners still collides: a box dropped on it rests on it") {
  // The springs do not keep the cube level against a load off its middle
  // (a ball on it would roll off: the tilt it makes grows), so the load is
  // a box, dropped square on the middle.
  awake_world w;
  const float k = 300, c = 30;
  const body_id cube = add_box(w, {0, 5, 0}, 1.0f, 0.5f);
  for (const float x : {-0.5f, 0.5f})
    for (const float z : {-0.5f, 0.5f})
      w.create_spring(body_spring<float>::to_anchor(cube, {x, 0.5f, z}, {x, 7, z}, k, c, 1.5f));
  const body_id load = add_box(w, {0, 7, 0}, 1.0f);
  impulse::test::run(w, 900);
  // Four springs of k share the two bodies' weight: the cube hangs
  // 2·m·g/(4k) below their rest, its top face at 7 − 1.5 − that.
  const float top = 7 - 1.5f - 2 * 9.81f / (4 * k);
  CHECK(w.body(cube).position.y == doctest::Approx(top - 0.5f).epsilon(2e-4));
  CHECK(w.body(load).position.y == doctest::Approx(top + 0.25f).epsilon(2e-4));  // on the top face
  CHECK(std::abs(w.body(load).position.x) < 1e-3f);
}

TEST_CASE("springs join islands: bodies on a spring sleep together, and waking one wakes the other") {
  world<impulse::test::sleeping_config> w;
  impulse::test::add_ground(w);
  const body_id a = impulse::test::add_cube(w, {0, 0.5f, 0});
  const body_id b = impulse::test::add_cube(w, {3, 0.5f, 0});
  w.create_spring(body_spring<float>::between(a, {}, b, {}, 10.0f, 1.0f, 3.0f));
  impulse::test::run(w, 120);
  REQUIRE(w.awake_body_count() == 0);
  w.wake(a);
  CHECK(w.is_awake(b));
  w.step(impulse::test::step_dt<float>);
  CHECK(w.last_step_counts().solved_springs == 1);
}

TEST_CASE("bad springs are refused and leave the world as it was; destroying a body removes its springs") {
  awake_world w;
  const body_id a = impulse::test::add_cube(w, {0, 5, 0});
  const body_id b = impulse::test::add_cube(w, {2, 5, 0});
  body_def<float> fixed;
  fixed.type = body_type::static_body;
  const body_id ground = w.create_body(fixed, box<float>::make({1, 1, 1}));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  CHECK(error_code_of([&] { w.create_spring(body_spring<float>::between(a, {}, body_id{7, 0}, {}, 1, 0, 0)); }) ==
        error_code::out_of_range);
  CHECK(error_code_of([&] { w.create_spring(body_spring<float>::between(a, {}, a, {1, 0, 0}, 1, 0, 0)); }) ==
        error_code::invalid_parameter);
  CHECK(error_code_of([&] { w.create_spring(body_spring<float>::to_anchor(ground, {}, {0, 9, 0}, 1, 0, 0)); }) ==
        error_code::invalid_parameter);
  CHECK(error_code_of([&] { w.create_spring(body_spring<float>::between(a, {}, b, {}, -1, 0, 0)); }) ==
        error_code::invalid_parameter);
  CHECK(error_code_of([&] { w.create_spring(body_spring<float>::between(a, {nan, 0, 0}, b, {}, 1, 0, 0)); }) ==
        error_code::non_finite);
  CHECK(w.spring_count() == 0);
  const spring_id s = w.create_spring(body_spring<float>::between(a, {}, b, {}, 10, 1, 2));
  w.create_spring(body_spring<float>::to_anchor(b, {}, {2, 9, 0}, 10, 1, 2));
  CHECK(w.spring(s).stiffness == 10);
  w.destroy_body(b);
  CHECK(w.spring_count() == 0);
  CHECK_FALSE(w.contains(s));
  CHECK(error_code_of([&] { (void)w.spring_tension(s); }) == error_code::out_of_range);
}

TEST_CASE("a force field acts on the awake bodies for one step: one that cancels gravity holds them still, a torque "
          "spins a box up at tau/I") {
  awake_double_world w;
  const body_id floating = add_box(w, {0, 5, 0}, 2.0);
  const body_id spun = add_box(w, {5, 5, 0}, 1.0);
  const double inertia = 1.0 * (0.5 * 0.5 + 0.5 * 0.5) / 12;  // box of side 0.5
  const double torque = 0.1;
  const auto field = [&](body_id id, const body_kinematics<double>&) {
    wrench<double> out;
    out.force = vec3<double>{0, 9.81, 0} * w.body(id).mass;
    if (id == spun) out.torque = {0, torque, 0};
    return out;
  };
  for (int i = 0; i < 60; ++i) w.step(1.0 / 60, field);
  CHECK(length(w.body(floating).linear_velocity()) < 1e-12);
  CHECK(w.body(floating).position.y == doctest::Approx(5.0).epsilon(1e-12));
  CHECK(w.body(spun).angular_velocity().y == doctest::Approx(torque / inertia * 1.0).epsilon(1e-9));
  // Without the field, gravity acts again.
  w.step(1.0 / 60);
  CHECK(w.body(floating).linear_velocity().y == doctest::Approx(-9.81 / 60).epsilon(1e-9));
}

TEST_CASE("a force field that gives a body a force that is not finite, or makes a body, is refused before any body moves") {
  awake_world w;
  const body_id a = impulse::test::add_cube(w, {0, 5, 0});
  const body_id b = impulse::test::add_cube(w, {3, 5, 0});
  const auto bad = [&](body_id id, const body_kinematics<float>&) {
    wrench<float> out;
    if (id == b) out.force = {std::numeric_limits<float>::infinity(), 0, 0};
    return out;
  };
  CHECK(error_code_of([&] { w.step(impulse::test::step_dt<float>, bad); }) == error_code::non_finite);
  CHECK(w.step_count() == 0);
  CHECK(w.body(a).force == vec3<float>{});
  // Nor may a field change what the step walks: a body made inside it is refused.
  const auto greedy = [&](body_id, const body_kinematics<float>&) {
    (void)impulse::test::add_cube(w, {9, 9, 9});
    return wrench<float>{};
  };
  CHECK(error_code_of([&] { w.step(impulse::test::step_dt<float>, greedy); }) == error_code::invalid_parameter);
  CHECK(w.body_count() == 2);
  w.step(impulse::test::step_dt<float>);  // the world steps on as before
  CHECK(w.body(a).position.y < 5);
}

}  // namespace world_springs_tests
