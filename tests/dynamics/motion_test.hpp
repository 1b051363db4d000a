// tests/dynamics/motion_test.hpp — configs and bodies shared by the rigid
// motion tests: worlds without collision, whose bodies gravity, loads,
// springs and force fields move, every force evaluated at every stage of
// the config's integrator.
#pragma once

#include <cmath>
#include <limits>

#include "impulse/config.hpp"
#include "impulse/dynamics.hpp"
#include "impulse/integrators.hpp"
#include "impulse/world.hpp"

namespace impulse::test {

template <class T, class I>
struct motion_config : default_config {
  using scalar = T;
  using integrator = I;
  static constexpr bool collision = false;
};

/// A world without collision stepped by integrator I.
template <class T, class I>
using motion_world = world<motion_config<T, I>>;

template <class T>
constexpr double epsilon_of = double(std::numeric_limits<T>::epsilon());

/// A dynamic body at `pose` moving at v and spinning at ω (world frame).
/// Its mass is the shape's at material.density unless set.
template <class T>
body_def<T> moving(const transform<T>& pose, const vec3<T>& v = {}, const vec3<T>& omega = {}) {
  body_def<T> def;
  def.pose = pose;
  def.linear_velocity = v;
  def.angular_velocity = omega;
  return def;
}

/// Mass 1 with principal moments (i1, i2, i3) along the body axes, for a
/// shape whose center of mass is its origin (a sphere).
template <class T>
body_def<T> principal(T i1, T i2, T i3) {
  body_def<T> def;
  def.mass = T(1);
  def.inertia = mat3<T>::diagonal({i1, i2, i3});
  return def;
}

/// The one body of a world that has one.
template <class World>
const auto& only_body(const World& w) {
  return w.body(w.body_ids()[0]);
}

/// Angular velocity in body axes: Rᵀ·ω.
template <class T>
vec3<T> body_angular_velocity(const rigid_body<T>& b) {
  return inverse_rotate(b.orientation, b.angular_velocity());
}

}  // namespace impulse::test

// Compiled once for the unit-test executable: tests/world/scenes.hpp says why.
#if IMPULSE_TEST_WORLDS_EXTERN
IMPULSE_DECLARE_WORLD(impulse::test::motion_config<float, impulse::integrators::euler>);
IMPULSE_DECLARE_WORLD(impulse::test::motion_config<float, impulse::integrators::symplectic_euler>);
IMPULSE_DECLARE_WORLD(impulse::test::motion_config<float, impulse::integrators::midpoint>);
IMPULSE_DECLARE_WORLD(impulse::test::motion_config<float, impulse::integrators::rk4>);
IMPULSE_DECLARE_WORLD(impulse::test::motion_config<double, impulse::integrators::euler>);
IMPULSE_DECLARE_WORLD(impulse::test::motion_config<double, impulse::integrators::symplectic_euler>);
IMPULSE_DECLARE_WORLD(impulse::test::motion_config<double, impulse::integrators::midpoint>);
IMPULSE_DECLARE_WORLD(impulse::test::motion_config<double, impulse::integrators::rk4>);
#endif
