// Gyroscopic motion at 60 Hz, default settings: a heavy top on a ball joint
// precesses at the rate of its closed-form steady precession, and a box
// spun about its intermediate axis keeps its energy and angular momentum
// over 10⁴ steps, with either solver and every integrator. The world turns
// a body with its angular momentum held by the split free turn
// (free_rotation.hpp), exact for a symmetric body.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "impulse/integrators/euler.hpp"
#include "impulse/integrators/midpoint.hpp"
#include "impulse/integrators/rk4.hpp"
#include "scenes.hpp"

namespace world_gyroscopic_tests {

using namespace impulse;

namespace {

using impulse::test::soft_config;
struct euler_config : impulse::test::awake_double_config {
  using integrator = integrators::euler;
};
struct midpoint_config : impulse::test::awake_double_config {
  using integrator = integrators::midpoint;
};

/// The heavy top: a disc of 1 kg and radius 0.3 m (moments ¼ and ½ of
/// m·r²) whose center is 0.1 m up its axis from a ball joint at the
/// origin, tilted 0.5 rad from the vertical, started in steady precession
/// with `spin` rad/s about its axis. Lagrange's top precesses steadily at
/// Ω when m·g·l = Ω·(I₃·ω₃ − I₁·Ω·cos θ), I₁ about the pivot and
/// ω₃ = spin + Ω·cos θ (Goldstein, Classical Mechanics, §5.7): the slow
/// root of (I₁ − I₃)·cos θ·Ω² − I₃·spin·Ω + m·g·l = 0.
struct top {
  double precession_ratio;  ///< measured over analytic rate of precession
  double tilt_error;        ///< rad, the most the axis left its tilt
};

template <class World>
top run_top(double spin, double seconds, const typename World::settings_type& settings = {}) {
  using T = typename World::scalar;
  constexpr double m = 1, r = 0.3, l = 0.1, theta = 0.5, g = 9.81;
  constexpr double i1 = 0.25 * m * r * r, i3 = 0.5 * m * r * r, i1_pivot = i1 + m * l * l;
  World w(settings);
  body_def<T> pivot;
  pivot.type = body_type::static_body;
  const body_id anchor = w.create_body(pivot, sphere<T>::make(T(0.01)));
  body_def<T> d;
  d.mass = T(m);
  d.inertia = mat3<T>::diagonal({T(i1), T(i3), T(i1)});  // axis: the body's y
  const vec3<double> axis{std::sin(theta), std::cos(theta), 0};
  d.pose.position = vec3<T>{T(axis.x * l), T(axis.y * l), 0};
  d.pose.rotation = quat<T>{0, 0, T(std::sin(-theta / 2)), T(std::cos(-theta / 2))};
  const double mgl = m * g * l, k = (i1_pivot - i3) * std::cos(theta);
  const double rate = 2 * mgl / (i3 * spin + std::sqrt(i3 * i3 * spin * spin - 4 * k * mgl));
  d.angular_velocity = vec3<T>{T(axis.x * spin), T(axis.y * spin + rate), 0};
  d.linear_velocity = cross(d.angular_velocity, d.pose.position);
  const body_id disc = w.create_body(d, sphere<T>::make(T(0.05)));
  w.create_joint(joint_def<T>::ball(anchor, disc, {}));
  double last = std::atan2(-axis.z, axis.x), turned = 0, tilt_error = 0;
  const int steps = int(std::lround(seconds * 60));
  for (int i = 0; i < steps; ++i) {
    w.step(impulse::test::step_dt<T>);
    const vec3<T> now = rotate(w.body(disc).orientation, vec3<T>{0, 1, 0});
    const double azimuth = std::atan2(-double(now.z), double(now.x));
    turned += std::remainder(azimuth - last, 2 * std::numbers::pi);
    last = azimuth;
    tilt_error = std::max(tilt_error, std::abs(std::acos(std::clamp(double(now.y), -1.0, 1.0)) - theta));
  }
  return {turned / seconds / rate, tilt_error};
}

}  // namespace

TEST_CASE("a heavy top precesses at its analytic rate within 0.5 %: sequential_impulse from 20 to 300 rad/s") {
  // Measured (float, 2 s, the default 4 parts): 1.0020 at 20 rad/s, 1.0006
  // to 1.0010 from 50 to 300. With ω held for the step instead, the top
  // precessed 8.6 times too fast at 20 rad/s and fell over.
  for (const double spin : {20.0, 50.0, 100.0, 150.0, 200.0, 300.0}) {
    const top t = run_top<world<impulse::test::awake_config>>(spin, 2);
    CAPTURE(spin);
    CHECK(std::abs(t.precession_ratio - 1) < 0.005);
    CHECK(t.tilt_error < 0.01);
  }
}

TEST_CASE("a heavy top precesses at its analytic rate within 1 %: sequential_impulse in one part, from 20 to 150 rad/s") {
  // Measured: 1.0084, 1.0039, 1.0023, 1.0045. Past about 160 rad/s the
  // nutation of the jointed disc (I₃·ω₃/I₁ ≈ 415 rad/s at 300) turns more
  // than π a step, and a joint solved once a step no longer holds it: the
  // parts are what hold it.
  world<impulse::test::awake_config>::settings_type s;
  s.solver.substeps = 1;
  s.solver.velocity_iterations = 20;
  for (const double spin : {20.0, 50.0, 100.0, 150.0}) {
    const top t = run_top<world<impulse::test::awake_config>>(spin, 2, s);
    CAPTURE(spin);
    CHECK(std::abs(t.precession_ratio - 1) < 0.01);
    CHECK(t.tilt_error < 0.01);
  }
}

TEST_CASE("a heavy top precesses at its analytic rate within 0.5 %: soft_step from 20 to 300 rad/s") {
  // soft_step turns the disc substep by substep, so its joint holds at
  // 1.25 rad a substep. Measured: 1.0018 at 20 rad/s to 1.0002 at 300. With
  // ω held through each substep and Catto's implicit gyroscopic step once a
  // step, it precessed 2 % fast at 20 rad/s and 89 % at 300.
  for (const double spin : {20.0, 50.0, 100.0, 150.0, 200.0, 300.0}) {
    const top t = run_top<world<soft_config>>(spin, 2);
    CAPTURE(spin);
    CHECK(std::abs(t.precession_ratio - 1) < 0.005);
    CHECK(t.tilt_error < 0.01);
  }
}

TEST_CASE_TEMPLATE("a box spun about its intermediate axis keeps its energy within 1e-4 and its angular momentum within "
                   "1e-9 over 10⁴ steps, from 2 to 100 rad/s",
                   Config, impulse::test::awake_double_config, euler_config, midpoint_config, soft_config) {
  // The Dzhanibekov box (half-extents 0.2, 0.5, 1) flips over and over.
  // With ω held for the step it gained 259 % and ended spinning on its
  // minor axis; soft_step's implicit gyroscopic step lost 77 % of it. Each
  // integrator policy turns it the same way (explicit Euler and midpoint
  // as symplectic Euler); RK4 takes the fourth-order turn (the next test).
  using T = typename Config::scalar;
  for (const double spin : {2.0, 10.0, 30.0, 100.0}) {
    typename world<Config>::settings_type settings;
    settings.gravity = {0, 0, 0};
    world<Config> w(settings);
    body_def<T> d;
    d.angular_velocity = vec3<T>{T(0.005 * spin), T(spin), T(0.005 * spin)};
    const body_id b = w.create_body(d, box<T>::make({T(0.2), T(0.5), T(1)}));
    const vec3<T> l0 = w.body(b).angular_momentum;
    const double e0 = double(w.kinetic_energy());
    double energy = 0, momentum = 0;
    for (int i = 0; i < impulse::test::long_run(10000); ++i) {
      w.step(impulse::test::step_dt<T>);
      energy = std::max(energy, std::abs(double(w.kinetic_energy()) / e0 - 1));
      momentum = std::max(momentum, double(length(w.body(b).angular_momentum - l0) / length(l0)));
    }
    CAPTURE(spin);
    CHECK(energy < 1e-4);
    CHECK(momentum < 1e-9);
  }
}

TEST_CASE_TEMPLATE("in float at the default settings the flipping box keeps its energy within 1e-4 and its angular "
                   "momentum exactly, sleeping off and on",
                   Config, impulse::test::awake_config, impulse::test::sleeping_config) {
  typename world<Config>::settings_type settings;
  settings.gravity = {0, 0, 0};
  world<Config> w(settings);
  body_def<float> d;
  d.angular_velocity = {0.05f, 10, 0.05f};
  const body_id b = w.create_body(d, box<float>::make({0.2f, 0.5f, 1}));
  const vec3<float> l0 = w.body(b).angular_momentum;
  const double e0 = double(w.kinetic_energy());
  double energy = 0;
  for (int i = 0; i < impulse::test::long_run(10000); ++i) {
    w.step(impulse::test::step_dt<float>);
    energy = std::max(energy, std::abs(double(w.kinetic_energy()) / e0 - 1));
  }
  CHECK(energy < 1e-4);
  CHECK(w.body(b).angular_momentum == l0);
}

TEST_CASE("under RK4 the flipping box's energy error falls with the step at fourth order") {
  // At 4 rad/s the turn takes one piece a step, and its error is well
  // above rounding: halving the step divides the energy's largest error
  // over 4 s by 2⁴.
  struct rk4_config : impulse::test::awake_double_config {
    using integrator = integrators::rk4;
  };
  const auto energy_error = [](double dt) {
    world<rk4_config>::settings_type settings;
    settings.gravity = {0, 0, 0};
    world<rk4_config> w(settings);
    body_def<double> d;
    d.angular_velocity = {0.02, 4, 0.02};
    w.create_body(d, box<double>::make({0.2, 0.5, 1.0}));
    const double e0 = w.kinetic_energy();
    double worst = 0;
    for (int i = 0; i < int(std::lround(4 / dt)); ++i) {
      w.step(dt);
      worst = std::max(worst, std::abs(w.kinetic_energy() / e0 - 1));
    }
    return worst;
  };
  const double coarse = energy_error(1.0 / 60), fine = energy_error(1.0 / 120);
  MESSAGE("largest energy error over 4 s: " << coarse << " at 1/60 s, " << fine << " at 1/120 s");
  CHECK(coarse / fine > 12);
  CHECK(coarse / fine < 20);
}

TEST_CASE("a body whose inertia is given off its principal axes turns as the same body given on them") {
  // The same solid twice: once with its principal moments along its own
  // axes, once with its tensor written in a frame turned by t and the body
  // turned by t⁻¹ to match, so both have the same tensor in the world.
  // Spun alike, their world tensors must agree as they tumble: the second
  // turns through the principal axes that Jacobi rotations found. Spun
  // about the major axis with a wobble, which is stable, so the rounding
  // of the two paths grows only linearly (about the intermediate axis it
  // grows exponentially, and the bound would measure the build's rounding).
  const quat<double> t = normalize(quat<double>{0.2, -0.4, 0.7, 0.5});
  const mat3<double> moments = mat3<double>::diagonal({1.25, 1.04, 0.29});
  const auto tumble = [&](bool off_axes) {
    world<impulse::test::awake_double_config>::settings_type settings;
    settings.gravity = {0, 0, 0};
    world<impulse::test::awake_double_config> w(settings);
    body_def<double> d;
    d.mass = 1;
    d.inertia = off_axes ? to_mat3(t) * moments * transpose(to_mat3(t)) : moments;
    d.pose.rotation = off_axes ? conjugate(t) : quat<double>::identity();
    d.angular_velocity = {10, 3, 3};
    const body_id b = w.create_body(d, sphere<double>::make(0.5));
    for (int i = 0; i < 600; ++i) w.step(1.0 / 60);
    return w.body(b).inertia_world();
  };
  const mat3<double> on = tumble(false), off = tumble(true);
  double worst = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(on(r, c) - off(r, c)));
  MESSAGE("largest difference of the world tensors: " << worst);
  CHECK(worst < 1e-11);
  CHECK(std::abs(on(0, 1)) > 0.01);  // it did tumble: the tensor is no longer diagonal
}

}  // namespace world_gyroscopic_tests
