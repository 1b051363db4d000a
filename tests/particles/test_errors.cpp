// Bad input to a particle system is refused with a clear error and changes
// nothing: NaN or infinite state, zero or negative mass, a zero-length or
// non-unit plane normal, a full system, a bad step or force parameter.
#include <limits>

#include "../error_code_of.hpp"
#include "particle_test.hpp"

namespace particles_errors_tests {

namespace {

using namespace impulse::particles;
using impulse::error_code;
using impulse::vec3;

using impulse::test::error_code_of;

template <class System>
auto make_system() {
  using T = typename System::scalar;
  System s{3};
  s.add_plane(plane_collider<T>::half_space({0, 1, 0}, 0, T(0.5), T(0.2)));
  s.add({1, 2, 3}, {0, 1, 0});
  s.add({-1, 2, 0}, {1, 0, 0}, 2);
  s.step(T(0.01));
  return s;
}

TEST_CASE_TEMPLATE("bad particle input is refused and leaves the system as it was", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  using system = particle_system<C, gravity, drag, point_forces, springs>;
  system s = make_system<system>();
  const particle_test::snapshot<T> before(s);
  const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();

  CHECK(error_code_of([&] { s.add({nan, 0, 0}); }) == error_code::non_finite);
  CHECK(error_code_of([&] { s.add({0, 0, 0}, {0, inf, 0}); }) == error_code::non_finite);
  CHECK(error_code_of([&] { s.add({0, 0, 0}, {}, 0); }) == error_code::non_positive_mass);
  CHECK(error_code_of([&] { s.add({0, 0, 0}, {}, -1); }) == error_code::non_positive_mass);
  CHECK(error_code_of([&] { s.add({0, 0, 0}, {}, nan); }) == error_code::non_finite);
  CHECK(error_code_of([&] { s.add({0, 0, 0}, {}, 1, 0); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { s.set_position(0, {0, nan, 0}); }) == error_code::non_finite);
  CHECK(error_code_of([&] { s.set_velocity(1, {inf, 0, 0}); }) == error_code::non_finite);
  CHECK(error_code_of([&] { s.set_mass(1, 0); }) == error_code::non_positive_mass);
  CHECK(error_code_of([&] { s.set_mass(7, 1); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { s.kill(2); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { (void)s.position(2); }) == error_code::out_of_range);
  CHECK(s.size() == 2);
  CHECK(particle_test::snapshot<T>(s) == before);
}

TEST_CASE_TEMPLATE("adding to a full system is refused and emission counts what it dropped", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  particle_system<C> s{3};
  for (int i = 0; i < 3; ++i) s.add({T(i), 0, 0});
  const particle_test::snapshot<T> before(s);
  CHECK(error_code_of([&] { s.add({0, 0, 0}); }) == error_code::capacity_exceeded);
  emitter<T> source;
  CHECK(s.emit(source, 5) == 0);
  CHECK(source.dropped == 5);
  CHECK(particle_test::snapshot<T>(s) == before);
  CHECK(error_code_of([] { particle_system<C> empty{0}; }) == error_code::invalid_parameter);
}

TEST_CASE_TEMPLATE("bad planes are refused when added and when changed before a step", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  using system = particle_system<C, gravity>;
  system s = make_system<system>();
  const particle_test::snapshot<T> before(s);
  CHECK(error_code_of([&] { s.add_plane(plane_collider<T>::half_space({0, 0, 0}, 0, 0, 0)); }) == error_code::degenerate_shape);
  CHECK(error_code_of([&] { s.add_plane(plane_collider<T>::half_space({0, 2, 0}, 0, 0, 0)); }) == error_code::not_normalized);
  CHECK(error_code_of([&] { s.add_plane(plane_collider<T>::half_space({0, 1, 0}, 0, T(1.5), 0)); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { s.add_plane(plane_collider<T>::rectangle({0, 0, 0}, {0, 1, 0}, {0, 1, 0}, 1, 1, 0, 0)); }) == error_code::not_normalized);
  CHECK(error_code_of([&] { s.add_plane(plane_collider<T>::rectangle({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, 0, 1, 0, 0)); }) == error_code::degenerate_shape);
  CHECK(s.planes().size() == 1);
  // A plane edited in place is checked before the next step moves anything.
  s.planes()[0].normal = {0, 0, 0};
  CHECK(error_code_of([&] { s.step(T(0.01)); }) == error_code::degenerate_shape);
  CHECK(particle_test::snapshot<T>(s) == before);
}

TEST_CASE_TEMPLATE("a bad time step or force parameter stops the step before anything moves", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  using system = particle_system<C, gravity, drag, point_forces, wind, springs>;
  system s = make_system<system>();
  const particle_test::snapshot<T> before(s);
  const T nan = std::numeric_limits<T>::quiet_NaN();
  CHECK(error_code_of([&] { s.step(0); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { s.step(-T(0.01)); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { s.step(nan); }) == error_code::invalid_parameter);

  s.template force<gravity>().acceleration.y = nan;
  CHECK(error_code_of([&] { s.step(T(0.01)); }) == error_code::non_finite);
  s.template force<gravity>().acceleration.y = T(-9.81);

  s.template force<drag>().coefficient = -1;
  CHECK(error_code_of([&] { s.step(T(0.01)); }) == error_code::invalid_parameter);
  s.template force<drag>().coefficient = T(0.1);

  auto& points = s.template force<point_forces>();
  CHECK(error_code_of([&] { points.add({0, nan, 0}, 1); }) == error_code::non_finite);
  points.add({0, 5, 0}, 1);
  points.points[0].strength = nan;
  CHECK(error_code_of([&] { s.step(T(0.01)); }) == error_code::non_finite);
  points.points[0].strength = 1;
  points.softening = 0;
  CHECK(error_code_of([&] { s.step(T(0.01)); }) == error_code::invalid_parameter);
  points.softening = T(0.05);
  for (int i = 1; i < 8; ++i) points.add({0, 0, 0}, 1);
  CHECK(error_code_of([&] { points.add({0, 0, 0}, 1); }) == error_code::capacity_exceeded);

  s.template force<wind>().variation = 2;
  CHECK(error_code_of([&] { s.step(T(0.01)); }) == error_code::invalid_parameter);
  s.template force<wind>().variation = T(0.3);

  auto& springs_list = s.template force<springs>();
  CHECK(error_code_of([&] { springs_list.add(0, 0, 1, 1); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { springs_list.add(0, 1, 1, -1); }) == error_code::invalid_parameter);
  springs_list.add(0, 5, 1, 10);  // particle 5 does not exist
  CHECK(error_code_of([&] { s.step(T(0.01)); }) == error_code::out_of_range);
  // A spring set to a bad value is refused and kept as it was.
  CHECK(error_code_of([&] { springs_list.set(0, {0, 1, T(1), std::numeric_limits<T>::quiet_NaN(), T(0)}); }) ==
        error_code::non_finite);
  CHECK(error_code_of([&] { springs_list.set(0, {1, 1, T(1), T(10), T(0)}); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { springs_list.set(1, {0, 1, T(1), T(10), T(0)}); }) == error_code::out_of_range);
  CHECK(springs_list[0].b == 5);
  CHECK(springs_list[0].stiffness == T(10));
  springs_list.clear();

  emitter<T> bad;
  bad.mass = 0;
  CHECK(error_code_of([&] { s.add_emitter(bad); }) == error_code::non_positive_mass);
  CHECK(particle_test::snapshot<T>(s) == before);
  s.step(T(0.01));  // and with everything fixed, it steps
  CHECK(!(particle_test::snapshot<T>(s) == before));
}

}  // namespace

}  // namespace particles_errors_tests
