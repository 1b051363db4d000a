// spin — a body turning at a constant angular velocity, integrated step by
// step with the exact exponential map, checked against the closed form.
//
// The orientation after time t at constant ω is exp(ω t / 2) * q0; stepping
// with impulse::integrate reproduces it up to rounding, and |q| stays 1.
#include <cmath>
#include <cstdio>

#include "impulse/math.hpp"

int main() {
  using T = double;
  const impulse::vec3<T> omega{0.5, -2.0, 3.0};  // rad/s
  const T dt = 1.0 / 60.0;                        // s
  const int steps = 60 * 60;                      // one simulated minute

  const impulse::quat<T> start = impulse::quat<T>::from_axis_angle(
      impulse::normalize(impulse::vec3<T>{1, 1, 0}), 0.3);
  impulse::quat<T> q = start;
  T worst_norm_error = 0;
  for (int i = 0; i < steps; ++i) {
    q = impulse::integrate(q, omega, dt);
    worst_norm_error = std::fmax(worst_norm_error, std::abs(impulse::length(q) - T(1)));
  }

  const T speed = impulse::length(omega);
  const T turned = speed * dt * steps;
  const impulse::quat<T> exact =
      impulse::quat<T>::from_axis_angle(omega / speed, turned) * start;
  const impulse::vec3<T> tip = impulse::rotate(q, impulse::vec3<T>::unit_x());

  std::printf("spin: %d steps of %.4f s at |omega| = %.4f rad/s\n", steps, dt, speed);
  std::printf("  turned %.2f rad (%.1f revolutions)\n", turned, turned / (2 * 3.14159265358979));
  std::printf("  body x axis now points at (%.6f, %.6f, %.6f)\n", tip.x, tip.y, tip.z);
  std::printf("  angle to the closed-form orientation: %.3g rad\n", impulse::angle_between(q, exact));
  std::printf("  largest | |q| - 1 | over the run:     %.3g\n", worst_norm_error);
  return impulse::angle_between(q, exact) < 1e-9 ? 0 : 1;
}
