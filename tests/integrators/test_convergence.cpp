// Measured order of convergence of each integrator on three closed-form
// problems: the slope log2(e(h) / e(h/2)) of the error at t = 2 s.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "impulse/integrators.hpp"
#include "problems.hpp"

namespace integrators_convergence_tests {

namespace {

using namespace impulse::integrators;
using impulse_test::circular_orbit_error;
using impulse_test::oscillator_error;
using impulse_test::projectile_with_drag_error;

// Slope between h = 0.025 and 0.0125 s: the error is C·h^p(1 + O(h)), and at
// these steps the O(h) term moves the measured slope by at most 0.06
// (measured: Euler 1.06 on the oscillator, the largest).
constexpr double order_tolerance = 0.1;
constexpr double t_end = 2.0;

template <class I, class T, class Problem>
double observed_order(Problem error, T h) {
  const double coarse = double(error(h, T(t_end)));
  const double fine = double(error(h / 2, T(t_end)));
  return std::log2(coarse / fine);
}

template <class I, class T>
void check_order_on_all_problems() {
  const T h = T(0.025);
  CAPTURE(I::order);
  CHECK(observed_order<I, T>(&oscillator_error<I, T>, h) ==
        doctest::Approx(I::order).epsilon(order_tolerance / I::order));
  CHECK(observed_order<I, T>(&projectile_with_drag_error<I, T>, h) ==
        doctest::Approx(I::order).epsilon(order_tolerance / I::order));
  CHECK(observed_order<I, T>(&circular_orbit_error<I, T>, h) ==
        doctest::Approx(I::order).epsilon(order_tolerance / I::order));
}

}  // namespace

TEST_CASE_TEMPLATE("explicit Euler converges at first order", T, float, double) {
  check_order_on_all_problems<euler, T>();
}

TEST_CASE_TEMPLATE("symplectic Euler converges at first order", T, float, double) {
  check_order_on_all_problems<symplectic_euler, T>();
}

TEST_CASE_TEMPLATE("the midpoint method converges at second order", T, float, double) {
  check_order_on_all_problems<midpoint, T>();
}

TEST_CASE("RK4 converges at fourth order in double") {
  check_order_on_all_problems<rk4, double>();
}

TEST_CASE("RK4 converges at fourth order in float on the oscillator") {
  // In float, RK4's truncation error meets rounding by h = 0.05 on the drag
  // and orbit problems, leaving no pair of steps to measure. The oscillator
  // keeps one: 3.4e-5 at h = 0.1 and 2.2e-6 at h = 0.05. Rounding over the
  // 40 steps of the finer run is a few 1e-7, up to 10 % of its error, which
  // moves the slope by up to log2(1.1) = 0.14; with the O(h) term (0.06),
  // the tolerance here is 0.2.
  constexpr double float_rk4_tolerance = 0.2;
  CHECK(observed_order<rk4, float>(&oscillator_error<rk4, float>, 0.1f) ==
        doctest::Approx(4).epsilon(float_rk4_tolerance / 4));
}

TEST_CASE("the integrators declare the order and stage count they have") {
  static_assert(euler::order == 1 && euler::stages == 1);
  static_assert(symplectic_euler::order == 1 && symplectic_euler::stages == 1);
  static_assert(midpoint::order == 2 && midpoint::stages == 2);
  static_assert(rk4::order == 4 && rk4::stages == 4);
  static_assert(impulse::integrator_policy<rk4>);
  // stages is the number of acceleration evaluations per step: count them.
  int evaluations = 0;
  double x = 1, v = 0;
  rk4::step(x, v, 0.1, [&](const double& p, const double&) { ++evaluations; return -p; });
  CHECK(evaluations == rk4::stages);
  evaluations = 0;
  midpoint::step(x, v, 0.1, [&](const double& p, const double&) { ++evaluations; return -p; });
  CHECK(evaluations == midpoint::stages);
}

}  // namespace integrators_convergence_tests
