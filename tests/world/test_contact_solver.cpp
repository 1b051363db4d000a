// The contact solver against analytic answers: a bounce, a slide, a
// Newton's cradle; and the hard cases with their thresholds,
// measured in float with the default solver and sleeping off.
#include <doctest/doctest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "scenes.hpp"

namespace world_contact_solver_tests {

using namespace impulse;

namespace {

template <class T>
struct awake_world_of;
template <>
struct awake_world_of<float> {
  using type = world<test::awake_config>;
};
template <>
struct awake_world_of<double> {
  using type = world<test::awake_double_config>;
};
template <class T>
using awake_world = typename awake_world_of<T>::type;

/// `bounce`: the first peak of a ball of radius 0.5 dropped from center
/// height 10 with restitution 0.8 on the standard ground.
template <class T>
T first_rebound_peak() {
  awake_world<T> w;
  test::add_ground(w);
  body_def<T> d;
  d.pose.position = {0, 10, 0};
  d.mass = 1;
  d.material.restitution = T(0.8);
  const body_id ball = w.create_body(d, sphere<T>::make(T(0.5)));
  bool rising = false;
  T peak = 0;
  for (int i = 0; i < 600; ++i) {
    w.step(test::step_dt<T>);
    const T v = w.body(ball).linear_velocity().y, y = w.body(ball).position.y;
    if (v > 0) rising = true;
    if (rising) peak = std::max(peak, y);
    if (rising && v < 0) break;
  }
  return peak;
}

/// `incline`: a cube resting 5 m up a static 30° slope (a box of
/// half-extents (15, 0.5, 5) turned about z), both of friction mu; the
/// speed along the slope at 1 s and 2 s and the distance moved at 5 s.
template <class T>
struct slide {
  T speed_1s = 0, speed_2s = 0, moved_5s = 0;
};
template <class T>
slide<T> incline(T mu) {
  awake_world<T> w;
  const T angle = T(3.14159265358979323846) / T(6);
  const quat<T> turn = quat<T>::from_axis_angle({0, 0, 1}, angle);
  body_def<T> ramp;
  ramp.type = body_type::static_body;
  ramp.pose.rotation = turn;
  ramp.material.friction = mu;
  w.create_body(ramp, box<T>::make({15, T(0.5), 5}));
  const body_id cube = test::add_cube(w, rotate(turn, vec3<T>{5, 1, 0}), T(1), mu, turn);
  const vec3<T> start = w.body(cube).position;
  slide<T> s;
  for (int i = 1; i <= 300; ++i) {
    w.step(test::step_dt<T>);
    if (i == 60) s.speed_1s = length(w.body(cube).linear_velocity());
    if (i == 120) s.speed_2s = length(w.body(cube).linear_velocity());
  }
  s.moved_5s = length(w.body(cube).position - start);
  return s;
}

}  // namespace

TEST_CASE_TEMPLATE("a ball dropped from 10 m with restitution 0.8 rebounds to 6.58 within 0.25 percent", T, float,
                   double) {
  // Analytic: it falls 9.5 m to touch, and rises 0.8² of that: 0.5 + 0.64·9.5.
  // Jolt rebounds 0.28 % high and Bullet 0.38 % low on this scene.
  constexpr double analytic = 0.5 + 0.64 * 9.5, tolerance = 0.0025;
  const T peak = first_rebound_peak<T>();
  CHECK(std::abs(double(peak) / analytic - 1) < tolerance);
}

TEST_CASE_TEMPLATE("a box on a 30 degree incline at friction 0.5 slides at g(sin - 0.5 cos) within 0.5 percent", T,
                   float, double) {
  const double angle = 3.14159265358979323846 / 6, analytic = 9.81 * (std::sin(angle) - 0.5 * std::cos(angle));
  const slide<T> s = incline<T>(T(0.5));
  const double acceleration = double(s.speed_2s - s.speed_1s);  // over 1 s
  CHECK(std::abs(acceleration / analytic - 1) < 0.005);
}

TEST_CASE("a box on a 30 degree incline at friction 0.7 stays put: drift under 0.05 mm in 5 s") {
  // tan 30° = 0.577 < 0.7: static friction holds it. Jolt drifts 0.05 mm, ODE 7.3 mm.
  const slide<float> s = incline<float>(0.7f);
  CHECK(s.moved_5s < 5e-5f);
}

TEST_CASE("a Newton's cradle of five spheres with restitution 1 hands the first ball's speed to the last") {
  // Four balls touching in a row, the fifth arriving at 1 m/s, no gravity:
  // the impact must run down the row (at least 90 % of the speed reaches
  // the last ball) and leave the first at rest.
  world_settings<float> settings;
  settings.gravity = {0, 0, 0};
  world<test::awake_config> w(settings);
  std::vector<body_id> balls;
  for (int i = 0; i < 5; ++i) {
    body_def<float> d;
    d.pose.position = {i == 0 ? -1.0f : float(i), 0, 0};
    d.mass = 1;
    d.material.restitution = 1;
    d.material.friction = 0;
    if (i == 0) d.linear_velocity = {1, 0, 0};
    balls.push_back(w.create_body(d, sphere<float>::make(0.5f)));
  }
  test::run(w, 120);
  CHECK(w.body(balls[4]).linear_velocity().x >= 0.9f);
  CHECK(std::abs(w.body(balls[0]).linear_velocity().x) < 0.1f);
  // Momentum is conserved by every impulse: 1 kg·m/s in all.
  vec3<float> momentum{};
  for (const body_id b : balls) momentum += w.body(b).linear_momentum;
  CHECK(std::abs(momentum.x - 1.0f) < 1e-5f);
}

TEST_CASE("a 10-box tower stands for 20 s: top drift and height lost each under 1 cm") {
  world<test::awake_config> w;
  test::add_ground(w);
  std::vector<body_id> tower;
  for (int k = 0; k < 10; ++k) tower.push_back(test::add_cube(w, {0, 0.5f + float(k), 0}));
  float drift = 0, lost = 0;  // the worst over the 20 s, not only at the end
  for (int i = 0; i < 1200; ++i) {
    w.step(test::step_dt<float>);
    const vec3<float> top = w.body(tower.back()).position;
    drift = std::max(drift, std::hypot(top.x, top.z));
    lost = std::max(lost, 9.5f - top.y);
  }
  // Jolt loses 19 cm of a 10-stack to its slop; Bullet's, with its one
  // friction direction per point, walks off and falls at about 15 s.
  CHECK(drift < 0.01f);
  CHECK(lost < 0.01f);
}

TEST_CASE("the 10-box tower keeps its top within 0.1 mm for 80 s at 6 to 30 iterations") {
  // The margin under the default 20: pressed to solver_settings::rest_depth
  // rather than to zero, the tower no longer sways on rounding noise (it
  // fell within 80 s at 16, 20 or 26 iterations, by build, before).
  for (const int iterations : {6, 10, 16, 20, 26, 30}) {
    CAPTURE(iterations);
    world_settings<float> settings;
    settings.solver.velocity_iterations = iterations;
    world<test::awake_config> w(settings);
    test::add_ground(w);
    std::vector<body_id> tower;
    for (int k = 0; k < 10; ++k) tower.push_back(test::add_cube(w, {0, 0.5f + float(k), 0}));
    float drift = 0;
    for (int i = 0; i < test::long_run(80 * 60); ++i) {
      w.step(test::step_dt<float>);
      const vec3<float> top = w.body(tower.back()).position;
      drift = std::max(drift, std::hypot(top.x, top.z));
    }
    CHECK(drift < 1e-4f);
  }
}

TEST_CASE("a 100 kg box resting on a 1 kg box stands for 10 s without sinking or sliding 1 cm") {
  // Bullet and ODE both let the heavy box sink and slide off within 10 s.
  world<test::awake_config> w;
  test::add_ground(w);
  const body_id light = test::add_cube(w, {0, 0.5f, 0}, 1);
  const body_id heavy = test::add_cube(w, {0, 1.5f, 0}, 100);
  float sunk = 0, slid = 0;
  for (int i = 0; i < 600; ++i) {
    w.step(test::step_dt<float>);
    const vec3<float> p = w.body(heavy).position;
    sunk = std::max(sunk, 1.5f - p.y);
    slid = std::max(slid, std::hypot(p.x, p.z));
  }
  CHECK(sunk < 0.01f);
  CHECK(slid < 0.01f);
  CHECK(w.body(light).position.y > 0.49f);
}

TEST_CASE("a slab carrying 100 boxes holds them all though it has more contacts than the solver has colors") {
  // The slab is in 100 contacts with the boxes (and one with the ground);
  // the coloring gives 64 of them a color and leaves the rest to be
  // solved one by one after the batches (constraint_graph.hpp). Both
  // paths must hold their boxes alike.
  world<test::awake_config> w;
  test::add_ground(w);
  body_def<float> slab_def;
  slab_def.pose.position = {0, 0.25f, 0};
  slab_def.mass = 100;
  const body_id slab = w.create_body(slab_def, box<float>::make({7, 0.25f, 7}));
  std::vector<body_id> boxes;
  for (int i = 0; i < 10; ++i)
    for (int k = 0; k < 10; ++k)
      boxes.push_back(test::add_cube(w, {(float(i) - 4.5f) * 1.2f, 1.0f, (float(k) - 4.5f) * 1.2f}));
  const auto start = test::positions(w, boxes);
  test::run(w, 300);
  const vec3<float> moved = test::largest_displacement(w, boxes, start);
  CHECK(moved.x < 0.001f);
  CHECK(moved.y < 0.001f);
  CHECK(moved.z < 0.001f);
  CHECK(std::abs(w.body(slab).position.y - 0.25f) < 0.001f);
}

namespace {

/// The 20-row pyramid after 20 s with its ground at `origin`: the largest
/// displacement of any box on each axis, and the top box's height.
template <class Config>
std::pair<vec3<typename Config::scalar>, typename Config::scalar> pyramid_after_20s(
    vec3<typename Config::scalar> origin) {
  world<Config> w;
  test::add_ground(w, typename Config::scalar(0.6), origin);
  const std::vector<body_id> boxes = test::add_pyramid(w, 20, origin);
  const auto start = test::positions(w, boxes);
  test::run(w, test::long_run(1200));
  return {test::largest_displacement(w, boxes, start), w.body(boxes.back()).position.y - origin.y};
}

}  // namespace

TEST_CASE("the 20-row pyramid stands for 20 s with sleeping off at the origin and 1e4 m from it in float") {
  // Every box within 2 cm of where it started on each axis (Jolt 2.9 cm,
  // Bullet 97 cm out of plane, ODE 191 cm), the top box above y = 19. At
  // x = 1e4 a float resolves 1 mm, every contact offset carries that
  // rounding, and the pyramid must drift there as it does at the origin,
  // within 1 cm.
  const auto [near, near_top] = pyramid_after_20s<test::awake_config>({});
  const auto [far, far_top] = pyramid_after_20s<test::awake_config>({1e4f, 0, 0});
  CHECK(near.x < 0.02f);
  CHECK(near.y < 0.02f);
  CHECK(near.z < 0.02f);
  CHECK(near_top > 19.0f);
  CHECK(max_component(abs(far - near)) < 0.01f);
  CHECK(far_top > 19.0f);
}

TEST_CASE("the pyramid 1e6 m from the origin in double drifts as it does at the origin, within 1 cm") {
  const auto [near, near_top] = pyramid_after_20s<test::awake_double_config>({});
  const auto [far, far_top] = pyramid_after_20s<test::awake_double_config>({1e6, 0, 0});
  CHECK(max_component(abs(far - near)) < 0.01);
  CHECK(far_top > 19.0);
}

// Debug and sanitizer builds run the piles for a quarter of their 10 s
// (test::long_run): the fall and the first impacts, where the contacts are
// made, with no box sinking. Whether the pile settles is the optimised
// builds' to show.
TEST_CASE("the pile settles with sleeping off: kinetic energy under 1e-4 J per box after 10 s, none below y = 0.45") {
  world<test::awake_config> w;
  test::add_ground(w);
  const std::vector<body_id> pile = test::add_pile(w);
  test::run(w, test::long_run(600));
  if (test::long_run(600) == 600) CHECK(w.kinetic_energy() / 1000.0f < 1e-4f);
  for (const body_id b : pile) REQUIRE(w.body(b).position.y >= 0.45f);
}

TEST_CASE("the pile settles with sleeping on: every box asleep within 10 s, none below y = 0.45") {
  world<test::sleeping_config> w;
  test::add_ground(w);
  const std::vector<body_id> pile = test::add_pile(w);
  test::run(w, test::long_run(600));
  if (test::long_run(600) == 600) CHECK(w.awake_body_count() == 0);
  for (const body_id b : pile) REQUIRE(w.body(b).position.y >= 0.45f);
}

}  // namespace world_contact_solver_tests
