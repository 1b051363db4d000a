// Ageing, death and recycling: particles die when their age reaches their
// lifetime, emitters refill the freed slots, and a continuous snowfall runs
// in the memory it was created with. Removal keeps the columns dense and
// springs attached to the particles that moved.
#include <cmath>

#include "particle_test.hpp"

namespace particles_lifetime_tests {

namespace {

using namespace impulse::particles;
using impulse::vec3;

TEST_CASE_TEMPLATE("a particle dies on the step its age reaches its lifetime", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  particle_system<C> s{4};
  const T dt = T(0.125);  // exact in binary: ages are exact sums
  s.add({0, 0, 0}, {}, 1, T(0.5));
  s.add({1, 0, 0}, {}, 1, T(0.75));
  s.add({2, 0, 0});  // infinite lifetime
  s.step(dt);
  CHECK(s.age(0) == dt);
  for (int k = 1; k < 4; ++k) s.step(dt);
  // At age 0.5 the first died; the last particle took its index.
  REQUIRE(s.size() == 2);
  CHECK(s.position(0).x == 2);
  CHECK(s.position(1).x == 1);
  s.step(dt);
  s.step(dt);
  REQUIRE(s.size() == 1);
  CHECK(s.position(0).x == 2);
  CHECK(s.age(0) == 6 * dt);
}

TEST_CASE_TEMPLATE("an emitter adds rate times dt particles per step, carrying fractions over", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  particle_system<C, gravity> s{1000};
  emitter<T> source;
  source.rate = 30;  // at dt = 1/120: one particle every fourth step
  source.lifetime = 100;
  source.position = {0, 10, 0};
  source.half_extents = {1, 0, 1};
  source.velocity = {0, 2, 0};
  source.velocity_spread = {T(0.5), T(0.5), T(0.5)};
  s.add_emitter(source);
  for (int k = 0; k < 120; ++k) s.step(T(1.0 / 120));
  // 30 in one second, give or take the last fraction's rounding.
  CHECK(s.size() >= 29);
  CHECK(s.size() <= 30);
  // Each drawn inside the emitter's box and velocity range (then moved).
  const auto v = s.velocities();
  for (std::size_t i = 0; i < s.size(); ++i) {
    CHECK(std::abs(v.x[i]) <= T(0.5));
    CHECK(std::abs(v.z[i]) <= T(0.5));
  }
  CHECK(s.emitters()[0].dropped == 0);
}

TEST_CASE_TEMPLATE("continuous snowfall settles at rate times lifetime particles in constant memory", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  particle_system<C, gravity, drag, wind> s{220};
  s.add_plane(plane_collider<T>::half_space({0, 1, 0}, 0, 0, 1));
  emitter<T> snow;
  snow.position = {0, 20, 0};
  snow.half_extents = {10, 0, 10};
  snow.rate = 50;
  snow.lifetime = 4;
  snow.lifetime_spread = T(0.4);
  s.add_emitter(snow);
  const T* storage = s.positions().x.data();
  std::size_t largest = 0;
  for (int k = 0; k < 60 * 16; ++k) {  // 16 s: four lifetimes
    s.step(T(1.0 / 60));
    if (k > 60 * 6) largest = std::max(largest, s.size());
  }
  // Steady state r·L = 200, within the ±10 % lifetime spread.
  CHECK(s.size() >= 180);
  CHECK(largest <= 220);
  CHECK(s.emitters()[0].dropped == 0);
  CHECK(s.positions().x.data() == storage);  // never reallocated
  // Flakes that landed stay on the ground (restitution 0, friction 1).
  for (std::size_t i = 0; i < s.size(); ++i) CHECK(s.positions().y[i] >= 0);
}

TEST_CASE_TEMPLATE("wind carries each particle toward its own fixed gust velocity", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  wind<T> w;
  w.velocity = {4, 0, 0};
  w.coefficient = 2;
  w.variation = T(0.25);
  particle_system<C, wind> s{64, w};
  for (int i = 0; i < 64; ++i) s.add({0, 0, T(i)});
  // Terminal velocity w·(1 + σ·r_i), approached as e^(−k·t): after 10 s it is there.
  for (int k = 0; k < 1200; ++k) s.step(T(1.0 / 120));
  T slowest = 1e9, fastest = 0;
  const auto v = s.velocities();
  for (std::size_t i = 0; i < s.size(); ++i) {
    slowest = std::min(slowest, v.x[i]);
    fastest = std::max(fastest, v.x[i]);
    CHECK(std::abs(v.y[i]) <= particle_test::epsilon<T>);
  }
  CHECK(slowest >= 4 * T(0.75) - T(1e-4));
  CHECK(fastest <= 4 * T(1.25) + T(1e-4));
  CHECK(fastest - slowest >= 4 * T(0.25));  // the 64 gusts spread over most of the range
}

TEST_CASE_TEMPLATE("killing a particle moves the last one into its place and its springs follow", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  particle_system<C, springs> s{8};
  for (int i = 0; i < 5; ++i) s.add({T(i), 0, 0});
  const auto& list = s.template force<springs>();
  s.template force<springs>().add(0, 1, 1, 10);
  s.template force<springs>().add(1, 4, 3, 10);
  s.template force<springs>().add(3, 4, 1, 10);
  s.kill(1);  // 4 moves to 1; the two springs on old 1 go
  REQUIRE(s.size() == 4);
  CHECK(s.position(1).x == 4);
  REQUIRE(list.size() == 1);
  CHECK(list[0].a == 3);
  CHECK(list[0].b == 1);
}

}  // namespace

}  // namespace particles_lifetime_tests
