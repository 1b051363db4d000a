// Config::particle_masses = false: no inverse-mass column, every particle
// has unit mass. The physics is the same, bit for bit, as a system that
// stores masses of 1 (a product by 1 is exact), and a mass other than 1 is
// refused wherever it could enter.
#include <limits>

#include "../error_code_of.hpp"
#include "particle_test.hpp"

namespace particles_masses_tests {

namespace {

using namespace impulse::particles;
using impulse::vec3;
using impulse::error_code;
using impulse::test::error_code_of;

template <class T, int W, bool Masses>
using mass_config = particle_test::config<T, W, impulse::integrators::rk4, true, Masses>;

/// The particles scene's forces and planes with springs between neighbours,
/// n particles of unit mass, `steps` steps with an emitter refilling what dies.
template <class C>
auto run(std::size_t n, int steps) {
  using T = typename C::scalar;
  particle_system<C, gravity, drag, point_forces, wind, springs> s{n + 64};
  auto& points = s.template force<point_forces>();
  points.add({0, 5, 0}, 20);
  points.add({-5, 8, 3}, -10);
  const T r = T(0.70710678118654752);
  s.add_plane(plane_collider<T>::half_space({0, 1, 0}, 0, T(0.5), T(0.2)));
  s.add_plane(plane_collider<T>::half_space({-r, 0, -r}, 10, T(0.5), T(0.2)));
  impulse::lcg32 random{777};
  for (std::size_t i = 0; i < n; ++i) {
    const vec3<T> x{random.uniform<T>(-8, 8), random.uniform<T>(T(0.5), 15), random.uniform<T>(-8, 8)};
    const vec3<T> v{random.uniform<T>(-5, 5), random.uniform<T>(-5, 5), random.uniform<T>(-5, 5)};
    s.add(x, v, T(1), random.uniform<T>(T(0.1), T(1)));
  }
  for (std::uint32_t i = 0; i + 1 < n; i += 2) s.template force<springs>().add(i, i + 1, T(0.5), T(40), T(0.3));
  emitter<T> source;
  source.rate = 600;
  source.lifetime = T(0.5);
  s.add_emitter(source);
  for (int k = 0; k < steps; ++k) s.step(T(1.0 / 120));
  return s;
}

TEST_CASE_TEMPLATE("without a mass column, unit masses step bit-identically to stored masses of 1", T, float,
                   double) {
  constexpr int W = particle_test::native<T>;
  const auto stored = run<mass_config<T, W, true>>(101, 90);
  const auto unit = run<mass_config<T, W, false>>(101, 90);
  REQUIRE(stored.size() == unit.size());
  REQUIRE(stored.size() > 0);
  bool identical = true;
  for (std::uint32_t i = 0; i < stored.size(); ++i) {
    identical &= stored.position(i) == unit.position(i) && stored.velocity(i) == unit.velocity(i);
    CHECK(unit.mass(i) == T(1));
  }
  CHECK(identical);
  CHECK(stored.template force<springs>().size() == unit.template force<springs>().size());
}

TEST_CASE_TEMPLATE("without a mass column, a mass other than 1 is refused and nothing changes", T, float, double) {
  particle_system<mass_config<T, particle_test::native<T>, false>, gravity, point_forces> s{8};
  s.add({0, 1, 0});
  s.add({1, 1, 0}, {0, 1, 0}, T(1));
  const particle_test::snapshot<T> before(s);
  CHECK(error_code_of([&] { s.add({0, 0, 0}, {}, T(2)); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { s.add({0, 0, 0}, {}, T(0)); }) == error_code::non_positive_mass);
  emitter<T> heavy;
  heavy.mass = T(0.5);
  CHECK(error_code_of([&] { s.add_emitter(heavy); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { (void)s.emit(heavy, 3); }) == error_code::invalid_parameter);
  CHECK(s.emitters().empty());
  CHECK(particle_test::snapshot<T>(s) == before);
  // An emitter made heavy after it was added stops the step before anything moves.
  emitter<T> source;
  source.rate = 120;
  s.add_emitter(source);
  s.emitters()[0].mass = T(3);
  CHECK(error_code_of([&] { s.step(T(0.01)); }) == error_code::invalid_parameter);
  CHECK(particle_test::snapshot<T>(s) == before);
}

}  // namespace

}  // namespace particles_masses_tests
