// A world without collision as a container and a stepper: stable ids, body
// types, loads held over a step, a user force field, bad input refused at
// the call without changing anything, and a body whose step overflows held
// while the others step on.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "impulse/shapes/box.hpp"
#include "impulse/shapes/mass_properties.hpp"
#include "impulse/shapes/sphere.hpp"

#include "../error_code_of.hpp"
#include "motion_test.hpp"

namespace dynamics_body_system_tests {

namespace {

using namespace impulse;
using namespace impulse::integrators;
using impulse::test::epsilon_of;
using impulse::test::error_code_of;
using impulse::test::motion_world;
using impulse::test::moving;

template <class T>
const sphere<T> ball_shape{T(0.5)};

/// A ball of radius 0.5 m and density 100 kg/m³ (52 kg) at `at`, moving at v.
template <class T>
body_def<T> ball(vec3<T> at, vec3<T> v = {}) {
  body_def<T> def = moving<T>({at, quat<T>::identity()}, v);
  def.material.density = T(100);
  return def;
}

// Every byte of every body and spring, the time and the gravity: what
// "unchanged" means.
template <class World>
std::vector<unsigned char> snapshot(const World& w) {
  std::vector<unsigned char> bytes;
  const auto append = [&](const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    bytes.insert(bytes.end(), c, c + n);
  };
  for (const body_id id : w.body_ids()) {
    const auto& b = w.body(id);
    append(&id, sizeof id);
    append(&b, sizeof b);
  }
  for (const spring_id id : w.spring_ids()) {
    const auto& s = w.spring(id);
    append(&id, sizeof id);
    append(&s, sizeof s);
  }
  const auto t = w.time();
  const auto g = w.settings().gravity;
  append(&t, sizeof t);
  append(&g, sizeof g);
  return bytes;
}

}  // namespace

TEST_CASE_TEMPLATE("ids stay valid while other bodies come and go and stale ids are refused", T, float, double) {
  motion_world<T, rk4> w;
  const body_id a = w.create_body(ball<T>({0, 0, 0}), ball_shape<T>);
  const body_id b = w.create_body(ball<T>({1, 0, 0}), ball_shape<T>);
  const body_id c = w.create_body(ball<T>({2, 0, 0}), ball_shape<T>);
  const spring_id ab = w.create_spring(body_spring<T>::between(a, {}, b, {}, T(10), T(0), T(1)));
  const spring_id bc = w.create_spring(body_spring<T>::between(b, {}, c, {}, T(10), T(0), T(1)));
  w.destroy_body(a);  // takes its spring with it; c moves into a's storage slot
  CHECK_FALSE(w.contains(a));
  CHECK(w.body_count() == 2);
  CHECK_FALSE(w.contains(ab));
  CHECK(w.spring_count() == 1);
  CHECK(w.contains(bc));
  CHECK(w.body(c).position.x == T(2));
  CHECK(w.body(b).position.x == T(1));
  const body_id d = w.create_body(ball<T>({3, 0, 0}), ball_shape<T>);  // reuses a's slot with a new generation
  CHECK(d.index == a.index);
  CHECK_FALSE(d == a);
  CHECK(w.body(d).position.x == T(3));

  // A stale id names nothing: every call given one is refused, and the
  // world is left as it was.
  const std::vector<unsigned char> before = snapshot(w);
  CHECK(error_code_of([&] { (void)w.body(a); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { w.destroy_body(a); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { w.apply_force(a, {1, 0, 0}); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { w.set_velocity(a, {1, 0, 0}, {}); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { w.create_spring(body_spring<T>::between(a, {}, b, {}, T(1), T(0))); }) ==
        error_code::out_of_range);
  CHECK(error_code_of([&] { (void)w.spring(ab); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { w.destroy_spring(ab); }) == error_code::out_of_range);
  CHECK(snapshot(w) == before);

  // body_ids() lists the live bodies, each once.
  std::vector<body_id> live(w.body_ids().begin(), w.body_ids().end());
  CHECK(live.size() == 3);
  for (const body_id id : {b, c, d}) CHECK(std::count(live.begin(), live.end(), id) == 1);
}

TEST_CASE_TEMPLATE("static bodies stay put and kinematic bodies follow their set velocity exactly", T, float,
                   double) {
  motion_world<T, rk4> w;
  body_def<T> ground_def;
  ground_def.type = body_type::static_body;
  ground_def.pose.position = {0, -1, 0};
  const body_id ground = w.create_body(ground_def, box<T>{{T(5), T(0.5), T(5)}});
  body_def<T> platform = moving<T>(transform<T>::identity(), {1, 0, T(0.5)}, {0, 2, 0});
  platform.type = body_type::kinematic;
  const body_id moving_id = w.create_body(platform, box<T>{{T(1), T(0.1), T(1)}});
  const int steps = 120;
  for (int i = 0; i < steps; ++i) w.step(T(1.0 / 60));
  CHECK(w.body(ground).position == vec3<T>{0, -1, 0});
  CHECK(w.body(ground).orientation == quat<T>::identity());
  // 2 s at (1, 0, 0.5) m/s and 2 rad/s about y: the position to the
  // rounding of 120 additions, the angle to that of 120 exact rotations.
  const vec3<T> at = w.body(moving_id).position;
  CHECK(std::abs(double(at.x) - 2) < steps * epsilon_of<T> * 2);
  CHECK(std::abs(double(at.z) - 1) < steps * epsilon_of<T> * 2);
  const quat<T> expected = quat<T>::from_axis_angle({0, 1, 0}, T(4));
  CHECK(double(angle_between(w.body(moving_id).orientation, expected)) < steps * 4 * epsilon_of<T> * 4);
}

TEST_CASE_TEMPLATE("a force applied before a step acts through the whole step and is then cleared", T, float,
                   double) {
  // A constant force from rest: x = ½·(F/m)·t², exact for methods of order
  // two or more, so midpoint and RK4 land on it to rounding after one step.
  const auto check = [](auto w) {
    w.set_gravity({});
    const body_id id = w.create_body(ball<T>({0, 0, 0}), ball_shape<T>);
    const T m = w.body(id).mass, dt = T(0.1);
    w.apply_force(id, {3, 0, 0});
    w.apply_torque(id, {0, 0, 2});
    w.step(dt);
    const rigid_body<T>& b = w.body(id);
    CHECK(double(b.position.x) == doctest::Approx(0.5 * 3 / double(m) * 0.01).epsilon(8 * epsilon_of<T>));
    CHECK(double(b.linear_momentum.x) == doctest::Approx(0.3).epsilon(8 * epsilon_of<T>));
    CHECK(double(b.angular_momentum.z) == doctest::Approx(0.2).epsilon(8 * epsilon_of<T>));
    CHECK(b.force == vec3<T>{});
    CHECK(b.torque == vec3<T>{});
    w.step(dt);  // no new load: momentum unchanged
    CHECK(double(w.body(id).linear_momentum.x) == doctest::Approx(0.3).epsilon(8 * epsilon_of<T>));
  };
  check(motion_world<T, midpoint>{});
  check(motion_world<T, rk4>{});
}

TEST_CASE_TEMPLATE("gravity accelerates dynamic bodies at g whatever their mass", T, float, double) {
  motion_world<T, rk4> w;
  const body_id light = w.create_body(ball<T>({0, 0, 0}), ball_shape<T>);
  body_def<T> heavy_def = ball<T>({2, 0, 0});
  heavy_def.material.density = T(7000);
  const body_id heavy = w.create_body(heavy_def, ball_shape<T>);
  for (int i = 0; i < 60; ++i) w.step(T(1.0 / 60));
  // y = −½·g·t² at t = 1 s, exact for RK4 up to the rounding of 60 steps.
  for (body_id id : {light, heavy}) {
    CHECK(double(w.body(id).position.y) == doctest::Approx(-0.5 * 9.81).epsilon(60 * 4 * epsilon_of<T>));
    CHECK(double(w.body(id).linear_velocity().y) == doctest::Approx(-9.81).epsilon(60 * 4 * epsilon_of<T>));
  }
}

TEST_CASE_TEMPLATE("a force field is called at every stage on the stage state", T, float, double) {
  // Linear drag F = −c·v on a body coasting at v₀: v(t) = v₀·e^(−c·t/m).
  // RK4 reaches it with a fourth-order error, which it could not if the
  // field were read from the stored state only; and it is called 4 times
  // per body per step.
  motion_world<T, rk4> w;
  w.set_gravity({});
  const body_id id = w.create_body(ball<T>({0, 0, 0}, {2, 0, 0}), ball_shape<T>);
  const T m = w.body(id).mass, c = m;  // time constant 1 s
  int calls = 0;
  const auto drag = [&](body_id which, const body_kinematics<T>& k) {
    ++calls;
    CHECK(which == id);
    return wrench<T>{k.linear_velocity * -c, {}};
  };
  for (int i = 0; i < 60; ++i) w.step(T(1.0 / 60), drag);
  CHECK(calls == 60 * rk4::stages);
  // RK4's error for y' = −y at h = 1/60 over 1 s: about h⁴/120 ≈ 6.4e-10
  // relative; float adds the rounding of 60 steps.
  const double tolerance = std::is_same_v<T, double> ? 1e-9 : 60 * 4 * epsilon_of<T>;
  CHECK(double(w.body(id).linear_velocity().x) == doctest::Approx(2 * std::exp(-1.0)).epsilon(tolerance));
}

TEST_CASE_TEMPLATE("bad bodies, springs, loads and steps are refused at the call and leave the world unchanged", T,
                   float, double) {
  const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
  motion_world<T, rk4> w;
  const body_id a = w.create_body(ball<T>({0, 0, 0}), ball_shape<T>);
  const body_id b = w.create_body(ball<T>({1, 0, 0}), ball_shape<T>);
  body_def<T> wall_def;
  wall_def.type = body_type::static_body;
  wall_def.pose.position = {0, 0, 3};
  const body_id wall = w.create_body(wall_def, ball_shape<T>);
  w.create_spring(body_spring<T>::between(a, {}, b, {}, T(10), T(1), T(1)));
  w.step(T(1.0 / 60));
  const std::vector<unsigned char> before = snapshot(w);
  const auto refused = [&](auto&& call) {
    const error_code code = error_code_of(call);
    CHECK(snapshot(w) == before);
    return code;
  };

  // Bodies.
  body_def<T> bad = ball<T>({0, 0, 0});
  bad.pose.position.y = nan;
  CHECK(refused([&] { w.create_body(bad, ball_shape<T>); }) == error_code::non_finite);
  bad = ball<T>({0, 0, 0});
  bad.angular_velocity.z = inf;
  CHECK(refused([&] { w.create_body(bad, ball_shape<T>); }) == error_code::non_finite);
  bad = ball<T>({0, 0, 0});
  bad.pose.rotation = {0, 0, 0, 2};
  CHECK(refused([&] { w.create_body(bad, ball_shape<T>); }) == error_code::not_normalized);
  bad = ball<T>({0, 0, 0});
  bad.material.density = 0;  // with no mass given, the mass is the density's
  CHECK(refused([&] { w.create_body(bad, ball_shape<T>); }) == error_code::non_positive_mass);
  bad = ball<T>({0, 0, 0});
  bad.mass = -1;  // the world's code for a mass that is not finite and >= 0
  CHECK(refused([&] { w.create_body(bad, ball_shape<T>); }) == error_code::non_finite);
  const mat3<T> ball_inertia = mass_properties_of(ball_shape<T>, T(100)).inertia;
  bad = ball<T>({0, 0, 0});
  bad.inertia = ball_inertia;
  bad.inertia(0, 0) = 0;  // not positive definite
  CHECK(refused([&] { w.create_body(bad, ball_shape<T>); }) == error_code::degenerate_shape);
  bad.inertia = ball_inertia;
  bad.inertia(0, 1) = T(1);  // not symmetric
  CHECK(refused([&] { w.create_body(bad, ball_shape<T>); }) == error_code::degenerate_shape);
  bad.inertia = ball_inertia;
  bad.inertia(2, 2) = T(100);  // breaks I₁ + I₂ ≥ I₃: no real solid has it
  CHECK(refused([&] { w.create_body(bad, ball_shape<T>); }) == error_code::degenerate_shape);
  CHECK(refused([&] { (void)mass_properties_of(sphere<T>{T(0.5)}, T(0)); }) == error_code::non_positive_mass);
  CHECK(refused([&] { (void)mass_properties_of(sphere<T>{T(0.5)}, T(-1)); }) == error_code::non_positive_mass);
  // The world's limits: a body past max_coordinate or faster than the
  // speed limits.
  bad = ball<T>({2 * w.settings().max_coordinate, 0, 0});
  CHECK(refused([&] { w.create_body(bad, ball_shape<T>); }) == error_code::invalid_parameter);
  bad = ball<T>({0, 0, 0}, {2 * w.settings().max_linear_speed, 0, 0});
  CHECK(refused([&] { w.create_body(bad, ball_shape<T>); }) == error_code::invalid_parameter);

  // Springs.
  CHECK(refused([&] { w.create_spring(body_spring<T>::between(a, {}, a, {}, T(1), T(0))); }) ==
        error_code::invalid_parameter);
  CHECK(refused([&] { w.create_spring(body_spring<T>::between(a, {}, body_id{77, 0}, {}, T(1), T(0))); }) ==
        error_code::out_of_range);
  CHECK(refused([&] { w.create_spring(body_spring<T>::to_anchor(wall, {}, {}, T(1), T(0))); }) ==
        error_code::invalid_parameter);  // moves nothing: no end on a dynamic body
  CHECK(refused([&] { w.create_spring(body_spring<T>::to_anchor(a, {}, {}, T(-1), T(0))); }) ==
        error_code::invalid_parameter);
  CHECK(refused([&] { w.create_spring(body_spring<T>::to_anchor(a, {}, {}, T(1), T(-1))); }) ==
        error_code::invalid_parameter);
  CHECK(refused([&] { w.create_spring(body_spring<T>::to_anchor(a, {}, {nan, 0, 0}, T(1), T(0))); }) ==
        error_code::non_finite);

  // State, loads and gravity: a body's state is changed through the
  // world's calls only, and each refuses what a step could not take.
  CHECK(refused([&] { w.set_velocity(b, {nan, 0, 0}, {}); }) == error_code::non_finite);
  CHECK(refused([&] { w.set_velocity(b, {}, {0, 0, 2 * w.settings().max_angular_speed}); }) ==
        error_code::invalid_parameter);
  CHECK(refused([&] { w.set_pose(b, {{nan, 0, 0}, quat<T>::identity()}); }) == error_code::non_finite);
  CHECK(refused([&] { w.apply_force(b, {0, inf, 0}); }) == error_code::non_finite);
  CHECK(refused([&] { w.apply_torque(b, {0, 0, nan}); }) == error_code::non_finite);
  CHECK(refused([&] { w.apply_force(wall, {1, 0, 0}); }) == error_code::invalid_parameter);
  CHECK(refused([&] { w.set_gravity({0, nan, 0}); }) == error_code::non_finite);

  // Steps.
  CHECK(refused([&] { w.step(T(0)); }) == error_code::invalid_parameter);
  CHECK(refused([&] { w.step(-T(1)); }) == error_code::invalid_parameter);
  CHECK(refused([&] { w.step(nan); }) == error_code::invalid_parameter);
  CHECK(refused([&] { w.step(2 * w.max_dt); }) == error_code::invalid_parameter);
  CHECK(snapshot(w) == before);
}

TEST_CASE("a body driven non-finite by a valid spring is held and named and the others keep their step") {
  // A spring of stiffness 1e300 N/m stretched by 1 m gives a force of 1e300 N
  // and, within the step, a state past the largest double: valid input,
  // non-finite result. The body is held where it was with no velocity.
  motion_world<double, rk4> w;
  w.set_gravity({});
  const body_id calm = w.create_body(ball<double>({5, 0, 0}, {1, 0, 0}), ball_shape<double>);
  const body_id wild = w.create_body(ball<double>({0, 0, 0}, {0, 0.5, 0}), ball_shape<double>);
  const spring_id spring = w.create_spring(body_spring<double>::to_anchor(wild, {}, {1, 0, 0}, 1e300, 0));
  const rigid_body<double> wild_before = w.body(wild);
  try {
    w.step(0.1);
    FAIL("the step should report the body that became non-finite");
  } catch (const invalid_argument& e) {
    CHECK(e.code() == error_code::non_finite);
    CHECK(e.object() == wild.index);
  }
  const rigid_body<double>& held = w.body(wild);
  CHECK(held.position == wild_before.position);
  CHECK(held.orientation == wild_before.orientation);
  CHECK(held.linear_momentum == vec3<double>{});
  CHECK(held.angular_momentum == vec3<double>{});
  REQUIRE(w.held_bodies().size() == 1);
  CHECK(w.held_bodies()[0] == wild);
  CHECK(w.body(calm).position.x == doctest::Approx(5.1));
  CHECK(w.time() == doctest::Approx(0.1));

  // Without the spring the held body stays at rest and the world steps on.
  w.destroy_spring(spring);
  w.step(0.1);
  CHECK(w.held_bodies().empty());
  CHECK(w.body(wild).position == wild_before.position);
  CHECK(w.body(calm).position.x == doctest::Approx(5.2));
}

}  // namespace dynamics_body_system_tests
