// The rigid body state: velocities derived from momenta and the rotated
// inertia, loads at points, impulses that conserve momentum, and bad input
// refused without changing the body.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "impulse/dynamics/rigid_body.hpp"
#include "impulse/shapes/box.hpp"

#include "../error_code_of.hpp"

namespace dynamics_rigid_body_tests {

namespace {

using impulse::body_type;
using impulse::mat3;
using impulse::quat;
using impulse::rigid_body;
using impulse::vec3;

template <class T>
T eps() { return std::numeric_limits<T>::epsilon(); }

template <class T>
rigid_body<T> spun_box() {
  const auto p = mass_properties_of(impulse::box<T>{{T(0.5), T(1), T(1.5)}}, T(2));
  const vec3<T> axis = normalize(vec3<T>{1, 2, 3});
  return rigid_body<T>::dynamic(p, {{1, 2, 3}, quat<T>::from_axis_angle(axis, T(0.7))});
}

TEST_CASE_TEMPLATE("velocities follow from the momenta and the rotated inertia", T, float, double) {
  rigid_body<T> b = spun_box<T>();
  const vec3<T> v{1, -2, T(0.5)}, omega{T(0.3), T(-1.1), T(2)};
  b.set_velocity(v, omega);
  // Round trip through P = m·v and L = R·I·Rᵀ·ω and back through the inverse.
  CHECK(max_component(abs(b.linear_velocity() - v)) <= 4 * eps<T>() * 2);
  CHECK(max_component(abs(b.angular_velocity() - omega)) <= 64 * eps<T>() * 2);
  // The world inertia and its inverse are inverses.
  const mat3<T> product = b.inertia_world() * b.inverse_inertia_world();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) CHECK(std::abs(product(r, c) - (r == c ? T(1) : T(0))) <= 64 * eps<T>());
  // Kinetic energy ½mv² + ½ωᵀIω from the body-frame formula.
  const vec3<T> omega_body = inverse_rotate(b.orientation, omega);
  const T expected = T(0.5) * b.mass * dot(v, v) + T(0.5) * dot(omega_body, b.inertia * omega_body);
  CHECK(b.kinetic_energy() == doctest::Approx(expected).epsilon(100 * eps<T>()));
}

TEST_CASE_TEMPLATE("an impulse at a point changes momentum by the impulse and angular momentum by its moment", T, float, double) {
  rigid_body<T> b = spun_box<T>();
  b.set_velocity({T(0.2), 0, 0}, {0, T(0.5), 0});
  const vec3<T> p0 = b.linear_momentum, l0 = b.angular_momentum;
  const vec3<T> j{T(0.4), T(-1), T(0.25)}, at = b.position + vec3<T>{T(0.5), T(0.3), T(-0.9)};
  const vec3<T> before = b.velocity_at(at);
  b.apply_impulse_at(j, at);
  CHECK(max_component(abs(b.linear_momentum - (p0 + j))) <= 8 * eps<T>());
  CHECK(max_component(abs(b.angular_momentum - (l0 + cross(at - b.position, j)))) <= 16 * eps<T>());
  // The point's velocity changes by K·j with K = 1/m − [r]× I_w⁻¹ [r]×, the
  // effective-mass matrix a contact solver uses.
  const vec3<T> r = at - b.position;
  const vec3<T> expected = j * b.inverse_mass + cross(b.inverse_inertia_world() * cross(r, j), r);
  CHECK(max_component(abs((b.velocity_at(at) - before) - expected)) <= 64 * eps<T>());
  // A force at a point accumulates its moment about the center of mass.
  b.apply_force_at({0, 0, 10}, b.position + vec3<T>{1, 0, 0});
  CHECK(b.torque == vec3<T>{0, -10, 0});
  b.clear_loads();
  CHECK(b.force == vec3<T>{});
}

TEST_CASE_TEMPLATE("static and kinematic bodies are not moved by impulses", T, float, double) {
  rigid_body<T> wall = rigid_body<T>::fixed(body_type::static_body);
  wall.apply_impulse_at({1, 0, 0}, {0, 1, 0});
  CHECK(wall.linear_velocity() == vec3<T>{});
  CHECK(wall.inverse_mass == T(0));
  rigid_body<T> platform = rigid_body<T>::fixed(body_type::kinematic);
  platform.set_velocity({1, 0, 0}, {0, 2, 0});
  platform.apply_impulse_at({0, 100, 0}, {1, 0, 0});
  CHECK(platform.linear_velocity() == vec3<T>{1, 0, 0});
  CHECK(platform.velocity_at({1, 0, 0}) == vec3<T>{1, 0, -2});  // v + ω × r
  CHECK(platform.kinetic_energy() == T(0));
}

TEST_CASE_TEMPLATE("bad mass inertia pose and loads are refused and leave the body unchanged", T, float, double) {
  using impulse::error_code;
  const T nan = std::numeric_limits<T>::quiet_NaN();
  rigid_body<T> b = spun_box<T>();
  const rigid_body<T> before = b;
  impulse::mass_properties<T> p{T(1), {}, mat3<T>::identity()};
  auto set = [&](impulse::mass_properties<T> q) { return impulse::test::error_code_of([&] { b.set_mass_properties(q); }); };
  p.mass = 0;
  CHECK(set(p) == error_code::non_positive_mass);
  p.mass = -2;
  CHECK(set(p) == error_code::non_positive_mass);
  p.mass = nan;
  CHECK(set(p) == error_code::non_finite);
  p.mass = 1;
  p.inertia = mat3<T>::diagonal({1, 1, -1});
  CHECK(set(p) == error_code::degenerate_shape);
  p.inertia = mat3<T>::diagonal({1, 1, 3});  // breaks I_x + I_y ≥ I_z: no solid has it
  CHECK(set(p) == error_code::degenerate_shape);
  p.inertia = mat3<T>::identity();
  p.inertia(0, 1) = T(0.5);  // not symmetric
  CHECK(set(p) == error_code::degenerate_shape);
  p.inertia = mat3<T>::zero();
  CHECK(set(p) == error_code::degenerate_shape);
  CHECK(impulse::test::error_code_of([&] { b.set_pose({{0, nan, 0}, quat<T>::identity()}); }) == error_code::non_finite);
  CHECK(impulse::test::error_code_of([&] { b.set_pose({{}, quat<T>{0, 0, 0, 2}}); }) == error_code::not_normalized);
  CHECK(impulse::test::error_code_of([&] { b.apply_force({nan, 0, 0}); }) == error_code::non_finite);
  CHECK(impulse::test::error_code_of([&] { b.apply_impulse_at({1, 0, 0}, {0, 0, nan}); }) == error_code::non_finite);
  CHECK(impulse::test::error_code_of([&] { b.set_velocity({0, 0, 0}, {nan, 0, 0}); }) == error_code::non_finite);
  CHECK(b.position == before.position);
  CHECK(b.mass == before.mass);
  CHECK(b.inertia == before.inertia);
  CHECK(b.linear_momentum == before.linear_momentum);
  CHECK(b.force == before.force);
  CHECK(impulse::test::error_code_of([] { (void)rigid_body<T>::fixed(body_type::dynamic); }) == error_code::invalid_parameter);
  rigid_body<T> wall = rigid_body<T>::fixed(body_type::static_body);
  CHECK(impulse::test::error_code_of([&] { wall.set_velocity({1, 0, 0}, {}); }) == error_code::invalid_parameter);
}

}  // namespace

}  // namespace dynamics_rigid_body_tests
