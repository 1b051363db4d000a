// The rigid body set as a container and a stepper: stable ids, body types,
// loads held over a step, a user force field, and bad input refused without
// changing anything.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "impulse/shapes/box.hpp"
#include "impulse/shapes/mass_properties.hpp"
#include "impulse/shapes/sphere.hpp"

#include "../error_code_of.hpp"
#include "motion_test.hpp"

namespace {

using namespace impulse;
using namespace impulse::integrators;
using impulse::test::body_system;
using impulse::test::epsilon_of;
using impulse::test::error_code_of;

template <class T>
rigid_body<T> ball(vec3<T> at) {
  return rigid_body<T>::dynamic(mass_properties_of(sphere<T>{T(0.5)}, T(100)), {at, quat<T>::identity()});
}

}  // namespace

TEST_CASE_TEMPLATE("ids stay valid while other bodies come and go and stale ids are refused", T, float, double) {
  body_system<T, rk4> system;
  const body_id a = system.add_body(ball<T>({0, 0, 0}));
  const body_id b = system.add_body(ball<T>({1, 0, 0}));
  const body_id c = system.add_body(ball<T>({2, 0, 0}));
  system.add_spring(body_spring<T>::between(a, {}, b, {}, T(10), T(0), T(1)));
  const spring_id bc = system.add_spring(body_spring<T>::between(b, {}, c, {}, T(10), T(0), T(1)));
  system.remove_body(a);  // takes its spring with it; c moves into a's storage slot
  CHECK_FALSE(system.contains(a));
  CHECK(system.body_count() == 2);
  CHECK(system.spring_count() == 1);
  CHECK(system.contains(bc));
  CHECK(system.body(c).position.x == T(2));
  CHECK(system.body(b).position.x == T(1));
  const body_id d = system.add_body(ball<T>({3, 0, 0}));  // reuses a's slot with a new generation
  CHECK(d.index == a.index);
  CHECK_FALSE(d == a);
  CHECK(error_code_of([&] { (void)system.body(a); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { system.remove_body(a); }) == error_code::out_of_range);
  CHECK(system.body(d).position.x == T(3));
  for (std::size_t i = 0; i < system.body_count(); ++i)
    CHECK(&system.body(system.body_ids()[i]) == &system.bodies()[i]);
}

TEST_CASE_TEMPLATE("static bodies stay put and kinematic bodies follow their set velocity exactly", T, float,
                   double) {
  body_system<T, rk4> system;
  const body_id ground = system.add_body(rigid_body<T>::fixed(body_type::static_body, {{0, -1, 0}, quat<T>::identity()}));
  rigid_body<T> platform = rigid_body<T>::fixed(body_type::kinematic);
  platform.set_velocity({1, 0, T(0.5)}, {0, 2, 0});
  const body_id moving = system.add_body(platform);
  const int steps = 120;
  for (int i = 0; i < steps; ++i) system.step(T(1.0 / 60));
  CHECK(system.body(ground).position == vec3<T>{0, -1, 0});
  CHECK(system.body(ground).orientation == quat<T>::identity());
  // 2 s at (1, 0, 0.5) m/s and 2 rad/s about y: the position to the
  // rounding of 120 additions, the angle to that of 120 exact rotations.
  const vec3<T> at = system.body(moving).position;
  CHECK(std::abs(double(at.x) - 2) < steps * epsilon_of<T> * 2);
  CHECK(std::abs(double(at.z) - 1) < steps * epsilon_of<T> * 2);
  const quat<T> expected = quat<T>::from_axis_angle({0, 1, 0}, T(4));
  CHECK(double(angle_between(system.body(moving).orientation, expected)) < steps * 4 * epsilon_of<T> * 4);
}

TEST_CASE_TEMPLATE("a force applied before a step acts through the whole step and is then cleared", T, float,
                   double) {
  // A constant force from rest: x = ½·(F/m)·t², exact for methods of order
  // two or more, so midpoint and RK4 land on it to rounding after one step.
  const auto check = [](auto system) {
    system.gravity = {};
    const body_id id = system.add_body(ball<T>({0, 0, 0}));
    const T m = system.body(id).mass, dt = T(0.1);
    system.body(id).apply_force({3, 0, 0});
    system.body(id).apply_torque({0, 0, 2});
    system.step(dt);
    const rigid_body<T>& b = system.body(id);
    CHECK(double(b.position.x) == doctest::Approx(0.5 * 3 / double(m) * 0.01).epsilon(8 * epsilon_of<T>));
    CHECK(double(b.linear_momentum.x) == doctest::Approx(0.3).epsilon(8 * epsilon_of<T>));
    CHECK(double(b.angular_momentum.z) == doctest::Approx(0.2).epsilon(8 * epsilon_of<T>));
    CHECK(b.force == vec3<T>{});
    CHECK(b.torque == vec3<T>{});
    system.step(dt);  // no new load: momentum unchanged
    CHECK(double(system.body(id).linear_momentum.x) == doctest::Approx(0.3).epsilon(8 * epsilon_of<T>));
  };
  check(body_system<T, midpoint>{});
  check(body_system<T, rk4>{});
}

TEST_CASE_TEMPLATE("gravity accelerates dynamic bodies at g whatever their mass", T, float, double) {
  body_system<T, rk4> system;
  const body_id light = system.add_body(ball<T>({0, 0, 0}));
  rigid_body<T> heavy_body = ball<T>({2, 0, 0});
  heavy_body.set_mass_properties(mass_properties_of(sphere<T>{T(0.5)}, T(7000)));
  const body_id heavy = system.add_body(heavy_body);
  for (int i = 0; i < 60; ++i) system.step(T(1.0 / 60));
  // y = −½·g·t² at t = 1 s, exact for RK4 up to the rounding of 60 steps.
  for (body_id id : {light, heavy}) {
    CHECK(double(system.body(id).position.y) == doctest::Approx(-0.5 * 9.81).epsilon(60 * 4 * epsilon_of<T>));
    CHECK(double(system.body(id).linear_velocity().y) == doctest::Approx(-9.81).epsilon(60 * 4 * epsilon_of<T>));
  }
}

TEST_CASE_TEMPLATE("a force field is called at every stage on the stage state", T, float, double) {
  // Linear drag F = −c·v on a body coasting at v₀: v(t) = v₀·e^(−c·t/m).
  // RK4 reaches it with a fourth-order error, which it could not if the
  // field were read from the stored state only; and it is called 4 times
  // per body per step.
  body_system<T, rk4> system;
  system.gravity = {};
  rigid_body<T> b = ball<T>({0, 0, 0});
  b.set_velocity({2, 0, 0}, {});
  const body_id id = system.add_body(b);
  const T m = system.body(id).mass, c = m;  // time constant 1 s
  int calls = 0;
  const auto drag = [&](body_id which, const body_kinematics<T>& k) {
    ++calls;
    CHECK(which == id);
    return wrench<T>{k.linear_velocity * -c, {}};
  };
  for (int i = 0; i < 60; ++i) system.step(T(1.0 / 60), drag);
  CHECK(calls == 60 * rk4::stages);
  // RK4's error for y' = −y at h = 1/60 over 1 s: about h⁴/120 ≈ 6.4e-10
  // relative; float adds the rounding of 60 steps.
  const double tolerance = std::is_same_v<T, double> ? 1e-9 : 60 * 4 * epsilon_of<T>;
  CHECK(double(system.body(id).linear_velocity().x) == doctest::Approx(2 * std::exp(-1.0)).epsilon(tolerance));
}

namespace {

// Every byte of every body and spring, and the time: what "unchanged" means.
template <class System>
std::vector<unsigned char> snapshot(const System& system) {
  std::vector<unsigned char> bytes;
  const auto append = [&](const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    bytes.insert(bytes.end(), c, c + n);
  };
  for (const auto& b : system.bodies()) append(&b, sizeof b);
  for (const auto& s : system.springs()) append(&s, sizeof s);
  const auto t = system.time();
  append(&t, sizeof t);
  return bytes;
}

}  // namespace

TEST_CASE_TEMPLATE("bad bodies, springs and steps are refused and leave the set unchanged", T, float, double) {
  const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
  body_system<T, rk4> system;
  const body_id a = system.add_body(ball<T>({0, 0, 0}));
  const body_id b = system.add_body(ball<T>({1, 0, 0}));
  system.add_spring(body_spring<T>::between(a, {}, b, {}, T(10), T(1), T(1)));
  system.step(T(1.0 / 60));
  const std::vector<unsigned char> before = snapshot(system);
  const auto refused = [&](auto&& call) {
    const error_code code = error_code_of(call);
    CHECK(snapshot(system) == before);
    return code;
  };

  // Bodies.
  rigid_body<T> bad = ball<T>({0, 0, 0});
  bad.position.y = nan;
  CHECK(refused([&] { system.add_body(bad); }) == error_code::non_finite);
  bad = ball<T>({0, 0, 0});
  bad.angular_momentum.z = inf;
  CHECK(refused([&] { system.add_body(bad); }) == error_code::non_finite);
  bad = ball<T>({0, 0, 0});
  bad.orientation = {0, 0, 0, 2};
  CHECK(refused([&] { system.add_body(bad); }) == error_code::not_normalized);
  bad = ball<T>({0, 0, 0});
  bad.mass = 0;
  CHECK(refused([&] { system.add_body(bad); }) == error_code::non_positive_mass);
  bad.mass = -1;
  CHECK(refused([&] { system.add_body(bad); }) == error_code::non_positive_mass);
  bad = ball<T>({0, 0, 0});
  bad.inertia(0, 0) = 0;  // not positive definite
  CHECK(refused([&] { system.add_body(bad); }) == error_code::degenerate_shape);
  bad = ball<T>({0, 0, 0});
  bad.inertia(0, 1) = T(1);  // not symmetric
  CHECK(refused([&] { system.add_body(bad); }) == error_code::degenerate_shape);
  bad = ball<T>({0, 0, 0});
  bad.inertia(2, 2) = T(100);  // breaks I₁ + I₂ ≥ I₃: no real solid has it
  CHECK(refused([&] { system.add_body(bad); }) == error_code::degenerate_shape);
  CHECK(refused([&] { (void)mass_properties_of(sphere<T>{T(0.5)}, T(0)); }) == error_code::non_positive_mass);
  CHECK(refused([&] { (void)mass_properties_of(sphere<T>{T(0.5)}, T(-1)); }) == error_code::non_positive_mass);

  // Springs.
  CHECK(refused([&] { system.add_spring(body_spring<T>::between(a, {}, a, {}, T(1), T(0))); }) ==
        error_code::invalid_parameter);
  CHECK(refused([&] { system.add_spring(body_spring<T>::between(a, {}, body_id{77, 0}, {}, T(1), T(0))); }) ==
        error_code::out_of_range);
  CHECK(refused([&] { system.add_spring(body_spring<T>::to_anchor(a, {}, {}, T(-1), T(0))); }) ==
        error_code::invalid_parameter);
  CHECK(refused([&] { system.add_spring(body_spring<T>::to_anchor(a, {}, {}, T(1), T(-1))); }) ==
        error_code::invalid_parameter);
  CHECK(refused([&] { system.add_spring(body_spring<T>::to_anchor(a, {}, {nan, 0, 0}, T(1), T(0))); }) ==
        error_code::non_finite);

  // Steps, including state edited in place since the last step.
  CHECK(refused([&] { system.step(T(0)); }) == error_code::invalid_parameter);
  CHECK(refused([&] { system.step(-T(1)); }) == error_code::invalid_parameter);
  CHECK(refused([&] { system.step(nan); }) == error_code::invalid_parameter);
  const auto edited = [&](auto edit, auto undo) {
    edit();
    const std::vector<unsigned char> edited_state = snapshot(system);
    const error_code code = error_code_of([&] { system.step(T(1.0 / 60)); });
    CHECK(snapshot(system) == edited_state);
    undo();
    return code;
  };
  CHECK(edited([&] { system.body(b).position.x = nan; }, [&] { system.body(b).position.x = 1; }) ==
        error_code::non_finite);
  CHECK(edited([&] { system.body(b).apply_force({1, 0, 0}), system.body(b).force.y = inf; },
               [&] { system.body(b).clear_loads(); }) == error_code::non_finite);
  CHECK(edited([&] { system.body(a).mass = 0; }, [&] { system.body(a).mass = system.body(b).mass; }) ==
        error_code::non_positive_mass);
  CHECK(edited([&] { system.gravity.y = nan; }, [&] { system.gravity.y = T(-9.81); }) == error_code::non_finite);
  CHECK(snapshot(system) == before);
}

TEST_CASE("a body driven non-finite by a valid spring is put back and named and the others keep their step") {
  // A spring of stiffness 1e300 N/m stretched by 1 m gives a force of 1e300 N
  // and, after the step, a momentum past the largest double: valid input,
  // non-finite result.
  body_system<double, rk4> system;
  system.gravity = {};
  const body_id calm = system.add_body(ball<double>({5, 0, 0}));
  system.body(calm).set_velocity({1, 0, 0}, {});
  const body_id wild = system.add_body(ball<double>({0, 0, 0}));
  system.add_spring(body_spring<double>::to_anchor(wild, {}, {1, 0, 0}, 1e300, 0));
  const rigid_body<double> wild_before = system.body(wild);
  try {
    system.step(0.1);
    FAIL("the step should report the body that became non-finite");
  } catch (const invalid_argument& e) {
    CHECK(e.code() == error_code::non_finite);
    CHECK(e.object() == wild.index);
  }
  CHECK(std::memcmp(&system.body(wild), &wild_before, sizeof wild_before) == 0);
  CHECK(system.body(calm).position.x == doctest::Approx(5.1));
  CHECK(system.time() == doctest::Approx(0.1));
}
