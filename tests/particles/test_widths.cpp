// The same physics source compiled for every batch width gives the same
// particles: the scalar fallback (W = 1), the SSE width and the native width
// step the particles scene to the same state within rounding.
#include <cmath>

#include "particle_test.hpp"

namespace particles_widths_tests {

namespace {

using namespace impulse::particles;
using impulse::vec3;

/// The standard particles scene (docs/standard_scenes.md) with n particles
/// (not a multiple of any width, so the last batch is partly padding),
/// stepped `steps` times.
template <class C>
auto run_scene(int n, int steps) {
  using T = typename C::scalar;
  particle_system<C, gravity, drag, point_forces, wind> s{std::size_t(n)};
  auto& points = s.template force<point_forces>();
  points.add({0, 5, 0}, 20);
  points.add({-5, 8, 3}, -10);
  points.add({5, 3, -4}, 15);
  const T r = T(std::sqrt(0.5));
  s.add_plane(plane_collider<T>::half_space({0, 1, 0}, 0, T(0.5), T(0.2)));
  s.add_plane(plane_collider<T>::half_space({1, 0, 0}, 10, T(0.5), T(0.2)));
  s.add_plane(plane_collider<T>::half_space({-r, 0, -r}, 10, T(0.5), T(0.2)));
  s.add_plane(plane_collider<T>::rectangle({0, 2, 0}, {0, 1, 0}, {1, 0, 0}, 3, 3, T(0.5), T(0.2)));
  impulse::lcg32 random{12345};
  for (int i = 0; i < n; ++i) {
    const vec3<T> x{random.uniform<T>(-8, 8), random.uniform<T>(T(0.5), 15), random.uniform<T>(-8, 8)};
    const vec3<T> v{random.uniform<T>(-5, 5), random.uniform<T>(-5, 5), random.uniform<T>(-5, 5)};
    s.add(x, v, random.uniform<T>(T(0.5), 2), random.uniform<T>(T(0.05), T(0.5)));
  }
  for (int k = 0; k < steps; ++k) s.step(T(1.0 / 120));
  return s;
}

template <class T, class I>
void check_widths_agree() {
  using namespace particle_test;
  const int n = 37, steps = 30;
  auto reference = run_scene<config<T, 1, I>>(n, steps);
  auto sse = run_scene<config<T, 4, I>>(n, steps);
  auto wide = run_scene<config<T, native<T>, I>>(n, steps);
  REQUIRE(reference.size() == sse.size());
  REQUIRE(reference.size() == wide.size());
  REQUIRE(reference.size() < std::size_t(n));  // some died, and were swapped out in the same order
  // Lane for lane the vector code does what the scalar code does, except the
  // softened inverse-square force: float vector lanes use the estimate of
  // 1/√ (within 5e-7 of the force, point_forces::root) where W = 1 divides
  // by a square root. Over 30 steps of O(10) positions and O(100)
  // accelerations that leaves differences of a few hundred roundings;
  // double is exact in both.
  const T tolerance = T(sizeof(T) == 4 ? 2000 : 64) * epsilon<T> * 10;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    CAPTURE(i);
    CHECK(max_component(abs(reference.position(std::uint32_t(i)) - sse.position(std::uint32_t(i)))) <= tolerance);
    CHECK(max_component(abs(reference.position(std::uint32_t(i)) - wide.position(std::uint32_t(i)))) <= tolerance);
    CHECK(max_component(abs(sse.velocity(std::uint32_t(i)) - wide.velocity(std::uint32_t(i)))) <= tolerance * 10);
  }
}

TEST_CASE_TEMPLATE("every batch width steps the particles scene to the same state", T, float, double) {
  namespace in = impulse::integrators;
  SUBCASE("euler") { check_widths_agree<T, in::euler>(); }
  SUBCASE("symplectic euler") { check_widths_agree<T, in::symplectic_euler>(); }
  SUBCASE("midpoint") { check_widths_agree<T, in::midpoint>(); }
  SUBCASE("rk4") { check_widths_agree<T, in::rk4>(); }
}

}  // namespace

}  // namespace particles_widths_tests
