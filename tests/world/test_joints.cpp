// Joints measured against what mechanics says they should do: a pendulum's
// period, a motor's speed, limits under load, a spring's frequency, a
// slider's free fall, a joint breaking at its threshold; each with both
// solvers, and bad joints refused.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "../error_code_of.hpp"
#include "impulse/world.hpp"
#include "scenes.hpp"

namespace world_joints_tests {

using namespace impulse;
using impulse::test::error_code_of;

namespace {

using impulse::test::soft_config;

template <class World>
body_id add_pivot(World& w, vec3<typename World::scalar> at) {
  using T = typename World::scalar;
  body_def<T> d;
  d.type = body_type::static_body;
  d.pose.position = at;
  return w.create_body(d, sphere<T>::make(T(0.05)));
}

template <class World>
body_id add_ball(World& w, vec3<typename World::scalar> at, typename World::scalar radius = 0.1,
                 typename World::scalar mass = 1) {
  using T = typename World::scalar;
  body_def<T> d;
  d.pose.position = at;
  d.mass = mass;
  return w.create_body(d, sphere<T>::make(radius));
}

/// A bar of half-extents (half_length, 0.05, 0.05) along x from `from`.
template <class World>
body_id add_bar(World& w, vec3<typename World::scalar> from, typename World::scalar half_length,
                typename World::scalar mass = 1) {
  using T = typename World::scalar;
  body_def<T> d;
  d.pose.position = from + vec3<T>{half_length, 0, 0};
  d.mass = mass;
  return w.create_body(d, box<T>::make({half_length, T(0.05), T(0.05)}));
}

}  // namespace

TEST_CASE_TEMPLATE("a hinge pendulum swings at the small-angle period of a physical pendulum", World,
                   world<impulse::test::awake_config>, world<impulse::test::awake_double_config>, world<soft_config>) {
  using T = typename World::scalar;
  // A ball of radius 0.1 on a 1 m arm, let go 0.05 rad from the vertical:
  // T = 2π·√(I_pivot / (m·g·L)), I_pivot = m·(L² + 2/5·r²). The amplitude's
  // own lengthening, (1 + θ²/16), is 0.016 %.
  const T length = 1, radius = T(0.1), start = T(0.05);
  World w;
  const body_id pivot = add_pivot(w, {0, 10, 0});
  const body_id bob = add_ball(w, {length * std::sin(start), 10 - length * std::cos(start), 0}, radius);
  const joint_id hinge = w.create_joint(joint_def<T>::hinge(pivot, bob, {0, 10, 0}, {0, 0, 1}));
  const double analytic =
      2 * std::numbers::pi * std::sqrt((length * length + 0.4 * radius * radius) / (9.81 * length));

  // The period from the first and last of the bob's crossings of x = 0.
  double first = 0, last = 0, before = double(w.body(bob).position.x);
  int crossings = 0;
  T widest = 0;
  for (int i = 0; i < 1200; ++i) {
    w.step(impulse::test::step_dt<T>);
    const double x = double(w.body(bob).position.x);
    if ((before < 0) != (x < 0)) {
      const double t = double(w.time()) - double(impulse::test::step_dt<T>) * x / (x - before);
      if (crossings++ == 0) first = t;
      last = t;
    }
    before = x;
    widest = std::max(widest, w.joint_separation(hinge));
  }
  REQUIRE(crossings >= 10);
  const double period = 2 * (last - first) / (crossings - 1);
  CHECK(std::abs(period / analytic - 1) < 0.01);
  CHECK(widest < T(1e-3));  // the pivot holds
}

namespace {

/// The test chain: 20 links of 0.5 m (boxes of half-extents 0.05, 0.25,
/// 0.05), 10 kg and 1 kg in turn from the top, joined end to end by ball
/// joints and hung from a static body at y = 20; hanging down, or held out
/// along x. Returns the largest gap any joint opened over `steps`.
template <class World>
typename World::scalar chain_gap(bool held_out, int steps, bool exact = true) {
  using T = typename World::scalar;
  World w;
  auto settings = w.settings();
  settings.solver.exact_joint_trees = exact;
  w.set_settings(settings);
  body_id above = add_pivot(w, {0, 20, 0});
  std::vector<joint_id> joints;
  vec3<T> anchor{0, 20, 0};
  const vec3<T> link = held_out ? vec3<T>{T(0.5), 0, 0} : vec3<T>{0, T(-0.5), 0};
  for (int i = 0; i < 20; ++i) {
    body_def<T> d;
    d.mass = i % 2 == 0 ? T(10) : T(1);
    d.pose.position = anchor + link * T(0.5);
    if (held_out) d.pose.rotation = quat<T>::from_axis_angle({0, 0, 1}, std::numbers::pi_v<T> / 2);
    const body_id b = w.create_body(d, box<T>::make({T(0.05), T(0.25), T(0.05)}));
    joints.push_back(w.create_joint(joint_def<T>::ball(above, b, anchor)));
    anchor += link;
    above = b;
  }
  T widest = 0;
  for (int i = 0; i < steps; ++i) {
    w.step(impulse::test::step_dt<T>);
    for (const joint_id j : joints) widest = std::max(widest, w.joint_separation(j));
  }
  return widest;
}

}  // namespace

TEST_CASE_TEMPLATE("a chain of 20 ball joints at 10 to 1 between neighbours stays within 1 mm hanging and swinging",
                   World, world<impulse::test::awake_config>, world<soft_config>) {
  using T = typename World::scalar;
  // The bound: 1 mm. Each link's joints solved one at a time (Gauss–
  // Seidel, 20 iterations) opened the hanging chain 13 mm; its tree solved
  // exactly (joint_tree.hpp) keeps it within 0.01 mm, and let go from
  // horizontal, the whip of its tail within 0.013 mm (sequential_impulse
  // and soft_step alike, float).
  constexpr T bound = T(0.001);
  CHECK(chain_gap<World>(false, 600) < bound);
  CHECK(chain_gap<World>(true, 600) < bound);
  // And it is the exact solve that holds it: one joint at a time, the
  // hanging chain opens more than 2 mm in its first 12 steps (2.3 mm in
  // sequential_impulse's 4 parts, 13 mm in one part of 20 sweeps).
  CHECK(chain_gap<World>(false, 12, false) > T(0.002));
}

TEST_CASE_TEMPLATE("a hinge motor brings a loaded arm to its target speed and holds it", World,
                   world<impulse::test::awake_config>, world<soft_config>) {
  using T = typename World::scalar;
  // A 1 kg bar 1 m long, hinged at one end about z, driven at 2 rad/s: its
  // weight's torque about the pivot, up to m·g·0.5 = 4.9 N·m, changes
  // sign as it turns; the motor's 20 N·m holds the speed throughout.
  World w;
  const body_id pivot = add_pivot(w, {0, 10, 0});
  const body_id bar = add_bar(w, {0, 10, 0}, T(0.5));
  joint_def<T> d = joint_def<T>::hinge(pivot, bar, {0, 10, 0}, {0, 0, 1});
  d.enable_motor = true;
  d.motor_speed = 2;
  d.max_motor_force = 20;
  const joint_id hinge = w.create_joint(d);
  for (int i = 0; i < 30; ++i) w.step(impulse::test::step_dt<T>);
  T slowest = 100, fastest = 0;
  for (int i = 0; i < 300; ++i) {
    w.step(impulse::test::step_dt<T>);
    const T spin = w.body(bar).angular_velocity().z;
    slowest = std::min(slowest, spin), fastest = std::max(fastest, spin);
  }
  CHECK(slowest > T(2 * 0.99));
  CHECK(fastest < T(2 * 1.01));
  CHECK(w.joint_separation(hinge) < T(1e-3));
}

TEST_CASE_TEMPLATE("a hinge motor too weak for its load applies its whole torque and no more", World,
                   world<impulse::test::awake_config>, world<soft_config>) {
  using T = typename World::scalar;
  // The bar hangs straight down; the motor, asked for 2 rad/s with at
  // most 2 N·m, is never reached, so it pushes with a constant 2 N·m: the
  // bar swings up to where that torque's work equals the rise of its
  // center, τ·θ = m·g·(L/2)·(1 − cos θ), θ = 0.8688 rad, and back.
  World w;
  const body_id pivot = add_pivot(w, {0, 10, 0});
  body_def<T> d;
  d.pose.position = {0, T(9.5), 0};
  d.mass = 1;
  const body_id bar = w.create_body(d, box<T>::make({T(0.05), T(0.5), T(0.05)}));
  joint_def<T> motor = joint_def<T>::hinge(pivot, bar, {0, 10, 0}, {0, 0, 1});
  motor.enable_motor = true;
  motor.motor_speed = 2;
  motor.max_motor_force = 2;
  const joint_id hinge = w.create_joint(motor);
  double theta = 0.8;  // Newton on m·g·L/2·(1 − cos θ) − τ·θ = 0
  for (int i = 0; i < 20; ++i)
    theta -= (9.81 * 0.5 * (1 - std::cos(theta)) - 2 * theta) / (9.81 * 0.5 * std::sin(theta) - 2);
  T highest = 0, strongest = 0;
  for (int i = 0; i < 180; ++i) {
    w.step(impulse::test::step_dt<T>);
    highest = std::max(highest, w.joint_position(hinge));
    strongest = std::max(strongest, std::abs(w.joint_torque(hinge).z));
  }
  CHECK(std::abs(double(highest) / theta - 1) < 0.01);
  CHECK(strongest < T(2 * 1.001));
}

TEST_CASE_TEMPLATE("hinge limits hold a loaded arm at the limit and let it swing within", World,
                   world<impulse::test::awake_config>, world<soft_config>) {
  using T = typename World::scalar;
  // A horizontal 1 m bar of 5 kg would fall; the lower limit −0.2 rad
  // stops it there and holds it, 24.5 N·m on it.
  World w;
  const body_id pivot = add_pivot(w, {0, 10, 0});
  const body_id bar = add_bar(w, {0, 10, 0}, T(0.5), 5);
  joint_def<T> d = joint_def<T>::hinge(pivot, bar, {0, 10, 0}, {0, 0, 1});
  d.enable_limit = true;
  d.lower = T(-0.2);
  d.upper = T(0.3);
  const joint_id hinge = w.create_joint(d);
  T lowest = 0;
  for (int i = 0; i < 300; ++i) {
    w.step(impulse::test::step_dt<T>);
    lowest = std::min(lowest, w.joint_position(hinge));
  }
  // The limit is reached at 1.4 rad/s; 0.01 rad past it is 1 cm at the end.
  CHECK(lowest > T(-0.2 - 0.01));
  CHECK(std::abs(w.joint_position(hinge) - T(-0.2)) < T(0.005));
  CHECK(length(w.body(bar).linear_velocity()) < T(0.01));
  // Its weight's torque about the pivot, m·g·(L/2)·cos 0.2.
  CHECK(std::abs(w.joint_torque(hinge).z - T(5 * 9.81 * 0.5) * std::cos(T(0.2))) < T(0.01 * 24.5));

  // Pushed up hard, it stops at the upper limit.
  w.apply_impulse_at(bar, {0, 20, 0}, w.body(bar).position);
  T highest = -1;
  for (int i = 0; i < 60; ++i) {
    w.step(impulse::test::step_dt<T>);
    highest = std::max(highest, w.joint_position(hinge));
  }
  CHECK(highest < T(0.3 + 0.01));
  CHECK(highest > T(0.29));
}

TEST_CASE_TEMPLATE("a body on a vertical slider falls at g along it and does not leave the line", World,
                   world<impulse::test::awake_config>, world<soft_config>) {
  using T = typename World::scalar;
  World w;
  const body_id pivot = add_pivot(w, {0, 10, 0});
  // The slider's anchor is off the body's center, and the body is spun:
  // the slider keeps it from turning and from leaving the line.
  const body_id block = impulse::test::add_cube(w, {0.3, 10, 0});
  const joint_id slider = w.create_joint(joint_def<T>::slider(pivot, block, {0, 10, 0}, {0, 1, 0}));
  w.set_velocity(block, {0, 0, 0}, {0, 3, 1});
  for (int i = 0; i < 60; ++i) w.step(impulse::test::step_dt<T>);
  // The free fall of symplectic Euler over n steps (soft_step: substeps)
  // of h: y = −g·h²·n(n+1)/2.
  T n = T(60);
  if constexpr (World::solver_type::moves_bodies) n *= T(w.settings().solver.substeps);
  const T fallen = T(-9.81) / (n * n) * n * (n + 1) / T(2);
  CHECK(std::abs(w.joint_position(slider) - fallen) < T(2e-3));
  const vec3<T> at = w.body(block).position;
  CHECK(std::abs(at.x - T(0.3)) < T(1e-3));
  CHECK(std::abs(at.z) < T(1e-3));
  CHECK(length(w.body(block).angular_velocity()) < T(0.01));
}

TEST_CASE_TEMPLATE("a slider limit and motor: the block is driven up at the motor speed and held at the limit", World,
                   world<impulse::test::awake_config>, world<soft_config>) {
  using T = typename World::scalar;
  World w;
  const body_id pivot = add_pivot(w, {0, 10, 0});
  const body_id block = impulse::test::add_cube(w, {0, 10, 0}, 2);
  joint_def<T> d = joint_def<T>::slider(pivot, block, {0, 10, 0}, {0, 1, 0});
  d.enable_motor = true;
  d.motor_speed = T(0.5);
  d.max_motor_force = 100;
  d.enable_limit = true;
  d.lower = -1;
  d.upper = T(0.5);
  const joint_id slider = w.create_joint(d);
  for (int i = 0; i < 30; ++i) w.step(impulse::test::step_dt<T>);
  CHECK(std::abs(w.body(block).linear_velocity().y - T(0.5)) < T(0.005));
  for (int i = 0; i < 90; ++i) w.step(impulse::test::step_dt<T>);
  CHECK(std::abs(w.joint_position(slider) - T(0.5)) < T(2e-3));
  CHECK(std::abs(w.body(block).linear_velocity().y) < T(0.01));
  // Motor off: it falls to the lower limit and stays, the limit holding
  // its weight.
  w.set_joint_motor(slider, false, 0, 0);
  for (int i = 0; i < 120; ++i) w.step(impulse::test::step_dt<T>);
  CHECK(std::abs(w.joint_position(slider) + 1) < T(2e-3));
  CHECK(std::abs(w.joint_force(slider).y - T(2) * T(9.81)) < T(0.05) * T(19.62));
}

TEST_CASE_TEMPLATE("a welded cantilever holds its pose and a distance spring oscillates at its frequency", World,
                   world<impulse::test::awake_config>, world<soft_config>) {
  using T = typename World::scalar;
  World w;
  const body_id wall = add_pivot(w, {0, 10, 0});
  const body_id beam = add_bar(w, {0, 10, 0}, T(1), 2);
  const joint_id weld = w.create_joint(joint_def<T>::fixed(wall, beam, {0, 10, 0}));
  // A 1 kg ball on a 2 Hz spring under a static point, undamped: it
  // hangs m·g/k = 6.2 cm below the rest length and oscillates about there
  // at 2 Hz. The soft row is implicit Euler: its damping loses amplitude
  // but keeps the frequency within a percent at 2 Hz and 60 Hz steps.
  const body_id hook = add_pivot(w, {5, 10, 0});
  const body_id ball = add_ball(w, {5, 9, 0});
  joint_def<T> spring = joint_def<T>::distance(hook, ball, {5, 10, 0}, {5, 9, 0});
  spring.spring_hertz = 2;
  w.create_joint(spring);
  double before = double(w.body(ball).position.y), last = 0, first = 0;
  const double center = 9 - 9.81 / std::pow(2 * std::numbers::pi * 2, 2);
  int crossings = 0;
  T sag = 0, turn = 0;
  for (int i = 0; i < 240; ++i) {
    w.step(impulse::test::step_dt<T>);
    const double y = double(w.body(ball).position.y) - center;
    if ((before - center < 0) != (y < 0)) {
      const double t = double(w.time()) - double(impulse::test::step_dt<T>) * y / (y - (before - center));
      if (crossings++ == 0) first = t;
      last = t;
    }
    before = double(w.body(ball).position.y);
    sag = std::max(sag, T(10) - w.body(beam).position.y);
    turn = std::max(turn, std::abs(w.body(beam).orientation.z) * 2);
  }
  // A 2 kg beam 2 m long held at one end carries 19.6 N·m; the weld
  // holds it within a millimetre and a milliradian.
  CHECK(sag < T(1e-3));
  CHECK(turn < T(1e-3));
  CHECK(w.joint_separation(weld) < T(1e-3));
  REQUIRE(crossings >= 6);
  const double frequency = (crossings - 1) / (2 * (last - first));
  CHECK(std::abs(frequency / 2 - 1) < 0.02);
}

TEST_CASE_TEMPLATE("a breakable joint holds below its threshold for 10 s and breaks in the first step above it", World,
                   world<impulse::test::awake_config>, world<soft_config>) {
  using T = typename World::scalar;
  const T weight = T(9.81) * 2;
  {
    World w;
    const body_id pivot = add_pivot(w, {0, 10, 0});
    const body_id load = add_ball(w, {0, 9, 0}, T(0.1), 2);
    joint_def<T> d = joint_def<T>::ball(pivot, load, {0, 10, 0});
    d.break_force = weight * T(1.01);
    const joint_id j = w.create_joint(d);
    for (int i = 0; i < 600; ++i) {
      w.step(impulse::test::step_dt<T>);
      REQUIRE(w.joint_broken_events().empty());
    }
    CHECK_FALSE(w.is_broken(j));
    CHECK(std::abs(w.joint_force(j).y - weight) < T(1e-3) * weight);
  }
  {
    // A pull added to the weight grows by 1 N a step from the first: the
    // joint must break at the end of the first step whose load passes
    // 1.5 times the weight, 9.81 N more: step 10 (the pull is 10 N there).
    World w;
    const body_id pivot = add_pivot(w, {0, 10, 0});
    const body_id load = add_ball(w, {0, 9, 0}, T(0.1), 2);
    joint_def<T> d = joint_def<T>::ball(pivot, load, {0, 10, 0});
    d.break_force = weight * T(1.5);
    const joint_id j = w.create_joint(d);
    int broke = 0;
    for (int i = 1; i <= 20 && broke == 0; ++i) {
      w.apply_force(load, {0, -T(i), 0});
      w.step(impulse::test::step_dt<T>);
      if (!w.joint_broken_events().empty()) {
        broke = i;
        const joint_broken_event<T>& e = w.joint_broken_events()[0];
        CHECK(e.joint == j);
        CHECK(e.a == pivot);
        CHECK(e.b == load);
        CHECK(e.time == doctest::Approx(double(w.time())));
        CHECK(e.force > d.break_force);
      }
    }
    CHECK(broke == 10);
    CHECK(w.is_broken(j));
    // Broken, it holds nothing: the load falls freely.
    const T y = w.body(load).position.y;
    for (int i = 0; i < 30; ++i) w.step(impulse::test::step_dt<T>);
    CHECK(w.body(load).position.y < y - T(0.5));
    CHECK(w.joint_broken_events().empty());
  }
}

TEST_CASE("joined bodies do not collide unless the joint says so, and do again once it is destroyed") {
  using T = float;
  world<impulse::test::awake_config> w;
  impulse::test::add_ground(w);
  // Two cubes overlapping by 0.2 m, hinged at the overlap.
  const body_id a = impulse::test::add_cube(w, {0, 3, 0});
  const body_id b = impulse::test::add_cube(w, {0.8f, 3, 0});
  w.step(impulse::test::step_dt<T>);
  REQUIRE(w.touching_pair_count() == 1);
  const joint_id j = w.create_joint(joint_def<T>::hinge(a, b, {0.4f, 3, 0}, {0, 0, 1}));
  CHECK(w.contact_end_events().size() == 1);  // their contact ended at once
  for (int i = 0; i < 5; ++i) {
    w.step(impulse::test::step_dt<T>);
    CHECK(w.touching_pair_count() == 0);
  }
  w.destroy_joint(j);
  w.step(impulse::test::step_dt<T>);
  CHECK(w.touching_pair_count() == 1);

  joint_def<T> touching = joint_def<T>::ball(a, b, {0.4f, 3, 0});
  touching.collide_connected = true;
  w.create_joint(touching);
  w.step(impulse::test::step_dt<T>);
  CHECK(w.touching_pair_count() == 1);
}

TEST_CASE("bad joints are refused with a clear error and leave the world unchanged") {
  using T = float;
  world<impulse::test::awake_config> w;
  const body_id ground = impulse::test::add_ground(w);
  const body_id a = impulse::test::add_cube(w, {0, 3, 0});
  const body_id b = impulse::test::add_cube(w, {2, 3, 0});
  const body_id gone = impulse::test::add_cube(w, {4, 3, 0});
  w.destroy_body(gone);
  const T nan = std::numeric_limits<T>::quiet_NaN();
  CHECK(error_code_of([&] { w.create_joint(joint_def<T>::ball(a, a, {0, 3, 0})); }) ==
        error_code::invalid_parameter);
  CHECK(error_code_of([&] { w.create_joint(joint_def<T>::ball(a, gone, {0, 3, 0})); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { w.create_joint(joint_def<T>::ball(a, b, {nan, 3, 0})); }) == error_code::non_finite);
  CHECK(error_code_of([&] { w.create_joint(joint_def<T>::hinge(a, b, {1, 3, 0}, {0, 0, 0})); }) ==
        error_code::invalid_parameter);
  CHECK(error_code_of([&] { w.create_joint(joint_def<T>::slider(a, b, {1, 3, 0}, {0, nan, 0})); }) ==
        error_code::non_finite);
  joint_def<T> reversed = joint_def<T>::hinge(a, b, {1, 3, 0}, {0, 0, 1});
  reversed.enable_limit = true;
  reversed.lower = 1, reversed.upper = -1;
  CHECK(error_code_of([&] { w.create_joint(reversed); }) == error_code::invalid_parameter);
  joint_def<T> weak = joint_def<T>::ball(a, b, {1, 3, 0});
  weak.break_force = 0;
  CHECK(error_code_of([&] { w.create_joint(weak); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { w.create_joint(joint_def<T>::ball(ground, ground, {0, 0, 0})); }) ==
        error_code::invalid_parameter);
  CHECK(w.joint_count() == 0);

  // A stale joint id, and a joint whose body is destroyed, go with it.
  const joint_id j = w.create_joint(joint_def<T>::ball(a, b, {1, 3, 0}));
  CHECK(error_code_of([&] { w.set_joint_limits(j, true, 1, -1); }) == error_code::invalid_parameter);
  CHECK_FALSE(w.joint(j).enable_limit);
  w.destroy_body(b);
  CHECK_FALSE(w.contains(j));
  CHECK(error_code_of([&] { (void)w.joint_position(j); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { w.destroy_joint(j); }) == error_code::out_of_range);
}

TEST_CASE("a snapshot restores joints with their impulses, and the same state steps to the same bits") {
  using T = float;
  world<impulse::test::awake_config> w;
  const body_id pivot = add_pivot(w, {0, 10, 0});
  const body_id arm = add_bar(w, {0, 10, 0}, T(0.5));
  const body_id tip = add_ball(w, {1, 10, 0});
  w.create_joint(joint_def<T>::hinge(pivot, arm, {0, 10, 0}, {0, 0, 1}));
  w.create_joint(joint_def<T>::ball(arm, tip, {1, 10, 0}));
  for (int i = 0; i < 30; ++i) w.step(impulse::test::step_dt<T>);
  const auto saved = w.snapshot();
  for (int i = 0; i < 60; ++i) w.step(impulse::test::step_dt<T>);
  const vec3<T> there = w.body(tip).position;
  w.restore(saved);
  for (int i = 0; i < 60; ++i) w.step(impulse::test::step_dt<T>);
  CHECK(w.body(tip).position == there);
}

TEST_CASE("a jointed pair sleeps as one island and wakes together") {
  using T = float;
  world<impulse::test::sleeping_config> w;
  impulse::test::add_ground(w);
  const body_id a = impulse::test::add_cube(w, {0, 0.5f, 0});
  const body_id b = impulse::test::add_cube(w, {0, 0.5f, 3});
  // A rod between their tops: resting on the ground, both sleep.
  w.create_joint(joint_def<T>::distance(a, b, {0, 1, 0}, {0, 1, 3}));
  int steps = 0;
  while ((w.is_awake(a) || w.is_awake(b)) && steps < 600) w.step(impulse::test::step_dt<T>), ++steps;
  CHECK_FALSE(w.is_awake(a));
  CHECK_FALSE(w.is_awake(b));
  w.apply_impulse_at(a, {0, 0, 1}, w.body(a).position);
  w.step(impulse::test::step_dt<T>);
  CHECK(w.is_awake(b));
}

}  // namespace world_joints_tests
