// The forces, checked through the particle kernel itself: the measured
// convergence order of each integrator on closed-form problems (projectile
// with linear drag, circular orbit about a softened attractor, and a spring
// oscillator through the staged springs path), and the inverse-square law of
// a point force with its run-time switches.
#include <cmath>

#include "particle_test.hpp"

namespace {

using namespace impulse::particles;
using impulse::vec3;
namespace in = impulse::integrators;

template <class I>
using config = particle_test::config<double, particle_test::native<double>, I>;

/// v' = g − k v: x(t) = x0 + v∞ t + (v0 − v∞)(1 − e^{−kt})/k, v∞ = g/k.
template <class I>
double projectile_error(double h) {
  const double k = 0.7, t_end = 2;
  const vec3<double> g{0, -9.81, 0}, x0{0, 1, 0}, v0{3, 5, -2};
  particle_system<config<I>, gravity, drag> s{1, gravity<double>{g}, drag<double>{k}};
  s.add(x0, v0);
  for (long i = 0; i < std::lround(t_end / h); ++i) s.step(h);
  const vec3<double> v_inf = g / k;
  const vec3<double> exact = x0 + v_inf * t_end + (v0 - v_inf) * ((1 - std::exp(-k * t_end)) / k);
  return impulse::length(s.position(0) - exact);
}

/// A softened attractor of strength s still holds a circular orbit of any
/// radius r, at angular rate ω² = s/(r² + ε)^{3/2}.
template <class I>
double orbit_error(double h) {
  const double strength = 4, softening = 0.05, r = 2, t_end = 2;
  const double omega = std::sqrt(strength / std::pow(r * r + softening, 1.5));
  particle_system<config<I>, point_forces> s{1};
  s.template force<point_forces>().softening = softening;
  s.template force<point_forces>().add({0, 0, 0}, strength);
  s.add({r, 0, 0}, {0, omega * r, 0});
  for (long i = 0; i < std::lround(t_end / h); ++i) s.step(h);
  const double angle = omega * t_end;
  return impulse::length(s.position(0) - vec3<double>{r * std::cos(angle), r * std::sin(angle), 0});
}

/// Two unit masses on a spring k, released stretched by a: the separation is
/// L + a·cos ωt, ω² = 2k.
template <class I>
double spring_error(double h) {
  const double k = 2, a = 0.3, t_end = 2, omega = std::sqrt(2 * k);
  particle_system<config<I>, springs> s{2};
  s.add({0, 0, 0});
  s.add({1 + a, 0, 0});
  s.template force<springs>().add(0, 1, 1, k);
  for (long i = 0; i < std::lround(t_end / h); ++i) s.step(h);
  return std::abs((s.position(1).x - s.position(0).x) - (1 + a * std::cos(omega * t_end)));
}

template <class I, class F>
void check_order(F&& error, double h) {
  const double coarse = error(h), fine = error(h / 2);
  const double order = std::log2(coarse / fine);
  CAPTURE(coarse);
  CAPTURE(fine);
  // The slope between two step sizes carries the next term of the error
  // series, O(h) relative to the leading one: 0.15 covers it at these h.
  CHECK(order == doctest::Approx(I::order).epsilon(0.15 / I::order));
}

TEST_CASE_TEMPLATE("each integrator converges at its order through the particle kernel", I, in::euler,
                   in::symplectic_euler, in::midpoint, in::rk4) {
  // RK4 reaches double rounding fast; it is measured at larger steps.
  const double h = I::order == 4 ? 0.05 : 0.00625;
  SUBCASE("projectile with linear drag") { check_order<I>(projectile_error<I>, h); }
  SUBCASE("circular orbit about a softened attractor") { check_order<I>(orbit_error<I>, h); }
  SUBCASE("spring oscillator through the staged springs pass") { check_order<I>(spring_error<I>, h); }
}

TEST_CASE_TEMPLATE("a point force pulls with the softened inverse-square law and can be re-signed or switched off", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  const T strength = 30, softening = T(0.05), dt = T(1e-3);
  particle_system<C, point_forces> s{4};
  auto& points = s.template force<point_forces>();
  points.softening = softening;
  points.add({0, 0, 0}, strength);
  for (T r : {T(0.1), T(1), T(10)}) s.add({r, 0, 0}, {}, 2);  // mass 2
  // One symplectic Euler step from rest: v = a·dt = s·r/(r² + ε)^{3/2}/m·dt.
  s.step(dt);
  const T radii[3] = {T(0.1), T(1), T(10)};
  for (std::uint32_t i = 0; i < 3; ++i) {
    const T r = radii[i];
    const T expected = -strength * r / std::pow(r * r + softening, T(1.5)) / 2 * dt;
    CAPTURE(r);
    // The float kernel's rsqrt is good to 3 ulp; cubed, 10 ulp.
    CHECK(std::abs(s.velocity(i).x - expected) <= 16 * particle_test::epsilon<T> * std::abs(expected));
  }
  // Re-signed: a repeller pushes outward with the same magnitude.
  const T before = s.velocity(2).x;
  points.points[0].strength = -strength;
  s.step(dt);
  CHECK(s.velocity(2).x - before > 0);
  // Switched off: no force at all.
  points.points[0].enabled = false;
  const vec3<T> v = s.velocity(2);
  s.step(dt);
  CHECK(s.velocity(2).x == v.x);
}

}  // namespace
