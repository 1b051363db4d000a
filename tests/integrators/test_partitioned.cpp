// The partitioned form x' = g(x, p), p' = f(x, p) that rigid bodies use:
// each method keeps its order when the position rate is not simply p, and
// the second-order form is the same computation.
#include <doctest/doctest.h>

#include <cmath>

#include "impulse/integrators.hpp"

namespace integrators_partitioned_tests {

namespace {

using namespace impulse::integrators;

// A particle whose mass depends on where it is, m(x) = 1 + x², in a linear
// spring: x' = p / (1 + x²), p' = −x. The position rate depends on both x
// and p, which the second-order form cannot express.
struct variable_mass_oscillator {
  int evaluations = 0;
  double position_rate(double x, double p) {
    ++evaluations;
    return p / (1.0 + x * x);
  }
  double momentum_rate(double x, double) { return -x; }
};

template <class I>
double error_at_t2(double h) {
  // Reference: RK4 at h / 64, whose error (~C·(h/64)^4) is far below the
  // coarse errors compared here.
  double x = 1.0, p = 0.0, xr = 1.0, pr = 0.0;
  variable_mass_oscillator system;
  for (int i = 0, n = int(std::lround(2.0 / h)); i < n; ++i) I::advance(x, p, h, system);
  for (int i = 0, n = int(std::lround(2.0 / (h / 64))); i < n; ++i) rk4::advance(xr, pr, h / 64, system);
  return std::hypot(x - xr, p - pr);
}

// As in test_convergence.cpp: between h = 0.025 and 0.0125 the O(h) term of
// the error moves the slope by well under 0.1.
constexpr double order_tolerance = 0.1;

template <class I>
double observed_order() {
  return std::log2(error_at_t2<I>(0.025) / error_at_t2<I>(0.0125));
}

}  // namespace

TEST_CASE("each method keeps its order when the position rate depends on position and momentum") {
  CHECK(observed_order<euler>() == doctest::Approx(1).epsilon(order_tolerance));
  CHECK(observed_order<symplectic_euler>() == doctest::Approx(1).epsilon(order_tolerance));
  CHECK(observed_order<midpoint>() == doctest::Approx(2).epsilon(order_tolerance / 2));
  CHECK(observed_order<rk4>() == doctest::Approx(4).epsilon(order_tolerance / 4));
}

TEST_CASE("each method evaluates the position rate once per stage") {
  const auto evaluations = [](auto method) {
    double x = 1.0, p = 0.5;
    variable_mass_oscillator system;
    decltype(method)::advance(x, p, 0.01, system);
    return system.evaluations;
  };
  CHECK(evaluations(euler{}) == euler::stages);
  CHECK(evaluations(symplectic_euler{}) == symplectic_euler::stages);
  CHECK(evaluations(midpoint{}) == midpoint::stages);
  CHECK(evaluations(rk4{}) == rk4::stages);
}

TEST_CASE("the second-order form is the partitioned form with p = v") {
  // Damped oscillator a = −4x − 0.3v: step() and advance() with g = v must
  // give bit-identical results for every method.
  const auto accel = [](double x, double v) { return -4.0 * x - 0.3 * v; };
  struct as_system {
    double position_rate(double, double v) const { return v; }
    double momentum_rate(double x, double v) const { return -4.0 * x - 0.3 * v; }
  };
  const auto compare = [&](auto method) {
    using I = decltype(method);
    double x1 = 1.0, v1 = 0.2, x2 = 1.0, v2 = 0.2;
    for (int i = 0; i < 100; ++i) {
      I::step(x1, v1, 0.01, accel);
      I::advance(x2, v2, 0.01, as_system{});
    }
    CHECK(x1 == x2);
    CHECK(v1 == v2);
  };
  compare(euler{});
  compare(symplectic_euler{});
  compare(midpoint{});
  compare(rk4{});
}

}  // namespace integrators_partitioned_tests
