// Long-run energy behaviour on the undamped oscillator x'' = -ω² x, with
// E = v² + ω² x² (twice the energy per unit mass).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "impulse/integrators.hpp"

namespace integrators_energy_tests {

namespace {

constexpr int steps = 100000;
constexpr double omega = 1.0;  // rad/s
constexpr double h = 0.01;     // s; ωh = 0.01

template <class T>
T energy(T x, T v) {
  return v * v + T(omega * omega) * x * x;
}

}  // namespace

TEST_CASE_TEMPLATE("explicit Euler multiplies the energy by 1 + w2h2 every step", T, float, double) {
  // x1 = x + h v, v1 = v - ω²h x  =>  E1 = (1 + ω²h²) E exactly.
  T x = 1, v = 0;
  const T e0 = energy(x, v);
  for (int i = 0; i < steps; ++i)
    impulse::integrators::euler::step(x, v, T(h), [](const T& p, const T&) { return -T(omega * omega) * p; });
  const double growth = std::pow(1.0 + omega * omega * h * h, steps);  // e^10 ≈ 22 000
  // Each step rounds a few times; over N steps the relative error is at most ~4Nε.
  const double rounding = 4.0 * steps * std::numeric_limits<T>::epsilon();
  CHECK(double(energy(x, v) / e0) == doctest::Approx(growth).epsilon(rounding));
  CHECK(double(energy(x, v) / e0) > 2e4);  // the drift the test exists to show
}

TEST_CASE_TEMPLATE("symplectic Euler keeps the oscillator energy bounded for 1e5 steps", T, float, double) {
  // The map v1 = v - ω²h x, x1 = x + h v1 conserves exactly
  //   I = v² + ω² x² - ω² h x v,
  // and |ω² h x v| <= (ωh/2) E, so E stays within I / (1 ± ωh/2) forever.
  T x = 1, v = 0;
  const double i0 = energy(x, v);
  const double bound = (omega * h / 2) / (1 - omega * h / 2);
  const double rounding = 4.0 * steps * std::numeric_limits<T>::epsilon();
  double worst_energy = 0, worst_invariant = 0;
  for (int i = 0; i < steps; ++i) {
    impulse::integrators::symplectic_euler::step(x, v, T(h), [](const T& p, const T&) {
      return -T(omega * omega) * p;
    });
    const double e = energy(x, v);
    const double invariant = e - omega * omega * h * double(x) * double(v);
    worst_energy = std::fmax(worst_energy, std::abs(e / i0 - 1));
    worst_invariant = std::fmax(worst_invariant, std::abs(invariant / i0 - 1));
  }
  CHECK(worst_energy <= bound + rounding);
  CHECK(worst_energy >= 0.9 * bound);  // the bound is reached, not vacuous
  CHECK(worst_invariant <= rounding);
}

TEST_CASE("RK4 loses energy slowly and monotonically on the oscillator") {
  // RK4's amplification factor for ωh = 0.01 is 1 - (ωh)^6/72 per step in
  // modulus squared (to leading order), so E(N)/E(0) = 1 - N (ωh)^6 / 72.
  double x = 1, v = 0;
  for (int i = 0; i < steps; ++i)
    impulse::integrators::rk4::step(x, v, h, [](const double& p, const double&) { return -omega * omega * p; });
  const double expected_loss = steps * std::pow(omega * h, 6) / 72;  // 1.4e-9
  CHECK(1 - energy(x, v) == doctest::Approx(expected_loss).epsilon(0.01));
}

}  // namespace integrators_energy_tests
