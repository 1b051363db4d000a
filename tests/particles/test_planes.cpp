// Plane colliders: the bounce and the friction loss they promise, and the
// guarantee that no particle ends a step behind a plane at any speed.
#include <cmath>

#include "particle_test.hpp"

namespace particles_planes_tests {

namespace {

using namespace impulse::particles;
using impulse::vec3;
using particle_test::epsilon;

TEST_CASE_TEMPLATE("a particle hitting a plane leaves with restitution times its normal speed", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  // No forces: the particle crosses the floor within one step and is caught.
  particle_system<C> s{8};
  const T e = T(0.6), mu = T(0.25);
  s.add_plane(plane_collider<T>::half_space({0, 1, 0}, 0, e, mu));
  s.add({0, T(0.05), 0}, {2, -3, 0});
  s.step(T(0.1));
  const vec3<T> v = s.velocity(0);
  // One multiply each: exact to a rounding or two.
  CHECK(std::abs(v.y - e * 3) <= 2 * epsilon<T> * 3);
  CHECK(std::abs(v.x - (1 - mu) * 2) <= 2 * epsilon<T> * 2);
  CHECK(s.position(0).y == T(0));
}

TEST_CASE_TEMPLATE("a ball dropped from 1 m rebounds to restitution squared of its height", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  const T e = T(0.5), h = 1, g = T(9.81), dt = T(1e-3);
  particle_system<C, gravity> s{1, gravity<T>{{0, -g, 0}}};
  s.add_plane(plane_collider<T>::half_space({0, 1, 0}, 0, e, 0));
  s.add({0, h, 0});
  bool bounced = false;
  T apex = 0;
  for (int k = 0; k < 1500; ++k) {
    s.step(dt);
    const T y = s.position(0).y, vy = s.velocity(0).y;
    if (!bounced && vy > 0) bounced = true;
    if (bounced) apex = std::max(apex, y);
  }
  REQUIRE(bounced);
  // The bounce is caught at the end of the step that crosses the floor, with
  // up to g·dt more speed than at impact: relative error 2g·dt/v_impact in
  // the height. The integrator's apex is off by up to one step of travel, u·dt.
  const T v_impact = std::sqrt(2 * g * h), u = e * v_impact;
  const T tolerance = e * e * h * (2 * g * dt / v_impact) + u * dt;
  CHECK(std::abs(apex - e * e * h) <= tolerance);
}

TEST_CASE_TEMPLATE("a particle sliding on a floor loses the friction fraction of its speed each step", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  const T mu = T(0.2);
  particle_system<C, gravity> s{1};
  s.add_plane(plane_collider<T>::half_space({0, 1, 0}, 0, 0, mu));
  s.add({0, 0, 0}, {5, 0, 0});
  // Gravity presses it into the floor every step, so every step is a contact.
  for (int k = 0; k < 10; ++k) s.step(T(1.0 / 60));
  const T expected = 5 * std::pow(1 - mu, T(10));
  CHECK(std::abs(s.velocity(0).x - expected) <= 20 * epsilon<T> * 5);
  CHECK(s.velocity(0).y == T(0));
}

TEST_CASE_TEMPLATE("no particle ends a step behind a plane even when it travels farther than the planes' spacing", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  // A slab 0 ≤ y ≤ 1 closed by a 45° wedge in x: particles at up to 600 m/s
  // cross the whole box many times over in each 1/60 s step.
  particle_system<C> s{200};
  const T r = T(std::sqrt(0.5));
  s.add_plane(plane_collider<T>::half_space({0, 1, 0}, 0, T(0.9), T(0.1)));
  s.add_plane(plane_collider<T>::half_space({0, -1, 0}, 1, T(0.9), T(0.1)));
  s.add_plane(plane_collider<T>::half_space({1, 0, 0}, 2, T(0.9), T(0.1)));
  s.add_plane(plane_collider<T>::half_space({-r, 0, -r}, 2, T(0.9), T(0.1)));
  impulse::lcg32 random{7};
  for (int i = 0; i < 200; ++i) {
    const vec3<T> v{random.uniform<T>(-600, 600), random.uniform<T>(-600, 600), random.uniform<T>(-600, 600)};
    s.add({0, T(0.5), 0}, v);
  }
  double worst = 0;
  for (int k = 0; k < 200; ++k) {
    s.step(T(1.0 / 60));
    worst = std::fmax(worst, particle_test::worst_penetration_in_roundings(s));
  }
  CHECK(worst <= 1.0);
}

TEST_CASE_TEMPLATE("a finite board stops a fast particle from either side and lets others pass its edge", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  particle_system<C> s{4};
  // A 2 m × 2 m board at y = 0, tilted 30° about z.
  const T c = T(std::cos(0.5235987755982988)), sn = T(std::sin(0.5235987755982988));
  const vec3<T> n{-sn, c, 0}, u{c, sn, 0};
  s.add_plane(plane_collider<T>::rectangle({0, 0, 0}, n, u, 1, 1, T(0.5), 0));
  s.add({0, 1, 0}, {0, -1000, 0});   // from above, 16 m in one step
  s.add({0, -1, 0}, {0, 1000, 0});   // from below
  s.add({3, 1, 0}, {0, -1000, 0});   // beside the board
  s.step(T(1.0 / 60));
  CHECK(dot(n, s.position(0)) > 0);
  CHECK(dot(n, s.position(1)) < 0);
  CHECK(s.position(2).y < -10);
  // Reflected with restitution along the normal of the side it came from.
  CHECK(std::abs(dot(n, s.velocity(0)) - T(0.5) * 1000 * c) <= 8 * epsilon<T> * 1000);
  CHECK(std::abs(dot(n, s.velocity(1)) + T(0.5) * 1000 * c) <= 8 * epsilon<T> * 1000);
}

TEST_CASE_TEMPLATE("a particle comes to rest on a finite board under gravity", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  particle_system<C, gravity> s{1};
  s.add_plane(plane_collider<T>::rectangle({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, 1, 1, T(0.3), T(0.5)));
  s.add({T(0.2), 2, T(-0.3)});
  for (int k = 0; k < 600; ++k) {
    s.step(T(1.0 / 120));
    REQUIRE(s.position(0).y >= 0);  // never through, not even by rounding
  }
  // Settled within one step's fall of the surface.
  CHECK(s.position(0).y <= T(9.81) / (120 * 120));
  CHECK(std::abs(s.velocity(0).y) <= T(9.81) / 120);
}

TEST_CASE_TEMPLATE("the particles scene keeps every particle inside its three planes", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  particle_system<C, gravity, drag, point_forces> s{500};
  auto& points = s.template force<point_forces>();
  points.add({0, 5, 0}, 20);
  points.add({-5, 8, 3}, 10);
  points.add({5, 3, -4}, 15);
  const T r = T(std::sqrt(0.5));
  s.add_plane(plane_collider<T>::half_space({0, 1, 0}, 0, T(0.5), T(0.2)));
  s.add_plane(plane_collider<T>::half_space({1, 0, 0}, 10, T(0.5), T(0.2)));
  s.add_plane(plane_collider<T>::half_space({-r, 0, -r}, 10, T(0.5), T(0.2)));
  impulse::lcg32 random{12345};
  for (int i = 0; i < 500; ++i) {
    const vec3<T> x{random.uniform<T>(-8, 8), random.uniform<T>(T(0.5), 15), random.uniform<T>(-8, 8)};
    const vec3<T> v{random.uniform<T>(-5, 5), random.uniform<T>(-5, 5), random.uniform<T>(-5, 5)};
    s.add(x, v);
  }
  double worst = 0;
  for (int k = 0; k < 240; ++k) {
    s.step(T(1.0 / 120));
    worst = std::fmax(worst, particle_test::worst_penetration_in_roundings(s));
  }
  CHECK(worst <= 1.0);
}

}  // namespace

}  // namespace particles_planes_tests
