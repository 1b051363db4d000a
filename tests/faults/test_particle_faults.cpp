// Inputs that once made a particle system allocate without bound or compute
// with undefined behaviour are refused, and leave the system as it was: a
// capacity past max_capacity (checked before any column is allocated), an
// emitter rate past max_rate (whose count converted out of size_t's range),
// a mass too small to invert (an infinite inverse mass, NaN after a step with
// drag). emitter::due and the snapshot raster keep every float-to-integer
// conversion in range for any finite input, and an aligned_array never
// wraps its byte size.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <new>

#include "../error_code_of.hpp"
#include "../particles/particle_test.hpp"
#include "impulse/core/aligned_array.hpp"
#include "impulse/io/picture.hpp"

namespace faults_particle_faults_tests {

namespace {

using namespace impulse::particles;
using impulse::error_code;
using impulse::test::error_code_of;

/// A small system with particles, a plane and an emitter, stepped once.
template <class System>
System make_system() {
  using T = typename System::scalar;
  System s{8};
  s.add_plane(plane_collider<T>::half_space({0, 1, 0}, 0, T(0.5), T(0.2)));
  s.add({1, 2, 3}, {0, 1, 0});
  s.add({-1, 2, 0}, {1, 0, 0}, 2);
  emitter<T> source;
  source.rate = 30;  // one particle every fourth step of 1/120 s
  s.add_emitter(source);
  s.step(T(1) / 120);
  return s;
}

}  // namespace

TEST_CASE_TEMPLATE("a capacity past max_capacity is refused before any column is allocated", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  using system = particle_system<C, gravity, drag>;
  static_assert(system::max_capacity == std::size_t(1) << 26);
  system s = make_system<system>();
  const particle_test::snapshot<T> before(s);
  const std::size_t size = s.size();
  // 1e9 would have allocated and zeroed 40 GB (float) before any check.
  CHECK(error_code_of([&] { s = system{1'000'000'000}; }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { s = system{system::max_capacity + 1}; }) == error_code::invalid_parameter);
  // 2^62 particles' columns would take more bytes than size_t counts: had
  // they been allocated before the check, the byte count would have wrapped
  // to a small block and the zeroing run past it.
  CHECK(error_code_of([&] { s = system{std::size_t(1) << 62}; }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { s = system{0}; }) == error_code::invalid_parameter);
  // The system the refused ones would have replaced is as it was.
  CHECK(s.capacity() == 8);
  CHECK(s.size() == size);
  CHECK(particle_test::snapshot<T>(s) == before);
}

TEST_CASE_TEMPLATE("an emitter rate past max_rate is refused when added, emitted from or stepped, and changes nothing",
                   C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  using system = particle_system<C, gravity, drag>;
  system s = make_system<system>();
  const particle_test::snapshot<T> before(s);
  const std::size_t size = s.size();
  const double time = s.time();

  emitter<T> fast;
  fast.rate = T(1e30);  // rate·dt converted to size_t was undefined behaviour
  CHECK(error_code_of([&] { s.add_emitter(fast); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { s.emit(fast, 1); }) == error_code::invalid_parameter);
  CHECK(s.emitters().size() == 1);

  // An emitter changed in place is checked before the step moves anything.
  s.emitters()[0].rate = T(1e30);
  CHECK(error_code_of([&] { s.step(T(1) / 120); }) == error_code::invalid_parameter);
  s.emitters()[0].rate = emitter<T>::max_rate * 2;
  CHECK(error_code_of([&] { s.step(T(1) / 120); }) == error_code::invalid_parameter);
  s.emitters()[0].rate = 30;
  s.emitters()[0].owed = T(-3);  // owed must stay in [0, 1)
  CHECK(error_code_of([&] { s.step(T(1) / 120); }) == error_code::invalid_parameter);
  CHECK(s.size() == size);
  CHECK(s.time() == time);
  CHECK(particle_test::snapshot<T>(s) == before);

  // At max_rate a step's emission fills the system and the rest is counted as dropped.
  s.emitters()[0].owed = 0;
  s.emitters()[0].rate = emitter<T>::max_rate;
  s.step(T(1) / 120);
  CHECK(s.size() == s.capacity());
  CHECK(s.emitters()[0].dropped > 8'000'000);
  for (std::size_t i = 0; i < s.size(); ++i) CHECK(impulse::is_finite(s.position(std::uint32_t(i))));
}

TEST_CASE_TEMPLATE("emitter::due saturates at max_due rather than convert a count past size_t", T, float, double) {
  emitter<T> e;
  e.rate = emitter<T>::max_rate;
  CHECK(e.due(T(1e30)) == emitter<T>::max_due);  // 1e39 particles: past size_t, and past float
  CHECK(e.owed == 0);
  e.rate = std::numeric_limits<T>::max();
  CHECK(e.due(T(10)) == emitter<T>::max_due);  // rate·dt is infinite
  e.rate = 0;
  e.owed = T(-5);  // below zero, nothing is due
  CHECK(e.due(T(1)) == 0);
  // Within range the fraction still carries: 30 a second at 1/120 s is one
  // particle every fourth step.
  e.rate = 30;
  e.owed = 0;
  std::size_t total = 0;
  for (int step = 0; step < 12; ++step) total += e.due(T(1) / 120);
  CHECK(total == 3);
}

TEST_CASE_TEMPLATE("a mass too small to invert is refused by add, set_mass and emitters, and changes nothing", C,
                   PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  using system = particle_system<C, gravity, drag>;
  system s = make_system<system>();
  const particle_test::snapshot<T> before(s);
  const std::size_t size = s.size();
  // The smallest denormal (1.4e-45 for float: what 1e-45 becomes) has an
  // infinite inverse; half the smallest normal a finite one, but it is
  // denormal and refused too.
  for (const T tiny : {std::numeric_limits<T>::denorm_min(), min_particle_mass<T> / 2}) {
    CAPTURE(tiny);
    CHECK(error_code_of([&] { s.add({0, 1, 0}, {}, tiny); }) == error_code::invalid_parameter);
    CHECK(error_code_of([&] { s.set_mass(0, tiny); }) == error_code::invalid_parameter);
    emitter<T> light;
    light.mass = tiny;
    CHECK(error_code_of([&] { s.add_emitter(light); }) == error_code::invalid_parameter);
    CHECK(error_code_of([&] { s.emit(light, 1); }) == error_code::invalid_parameter);
    s.emitters()[0].mass = tiny;
    CHECK(error_code_of([&] { s.step(T(1) / 120); }) == error_code::invalid_parameter);
    s.emitters()[0].mass = 1;
  }
  CHECK(s.size() == size);
  CHECK(s.emitters().size() == 1);
  CHECK(particle_test::snapshot<T>(s) == before);

  // The smallest mass allowed has a finite inverse, and a particle at rest
  // with it under drag steps to finite values (zero force times its inverse
  // mass is zero, not the NaN that zero times infinity was).
  const std::uint32_t light = s.add({0, 5, 0}, {}, min_particle_mass<T>);
  CHECK(std::isfinite(s.inverse_masses()[light]));
  s.step(T(1) / 120);
  CHECK(impulse::is_finite(s.position(light)));
  CHECK(impulse::is_finite(s.velocity(light)));
}

TEST_CASE("the snapshot raster clamps a triangle's pixel bounds before converting them to int") {
  // A box around the camera, cut at the near plane, gives corners 1e13
  // pixels off screen; converting those to int was undefined behaviour (and
  // at -O3 left the screen undrawn). The triangle covers every pixel.
  impulse::io::detail::raster r(8, 6);
  const std::array<std::uint8_t, 3> color{1, 2, 3};
  r.fill({{{-1e13, -1e13, 1}, {1e13, -1e13, 1}, {0, 1e13, 1}}}, color);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 8; ++x) CHECK(r.picture.at(x, y) == color);
}

TEST_CASE("an aligned_array whose byte size would wrap refuses rather than allocate a small block") {
  using impulse::aligned_array;
  CHECK_THROWS_AS(aligned_array<double>(std::size_t(-1) / 4), std::bad_array_new_length);
  const aligned_array<double> small(3);
  CHECK(small.size() == 3);
}

}  // namespace faults_particle_faults_tests
