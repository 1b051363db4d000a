// impulse/dynamics/softness.hpp — a constraint row made into a stiff,
// damped spring that the solver treats implicitly.
//
// Catto, "Soft Step" (2024) and Box2D v3's b2MakeSoft: a row whose error C
// should behave as a spring of frequency f and damping ratio ζ over a step
// h is solved as J·v + bias_rate·C = 0 with its effective mass scaled by
// mass_scale and its accumulated impulse leaking by impulse_scale. With
// ω = 2πf, a₁ = 2ζ + hω, a₂ = hω·a₁, a₃ = 1/(1 + a₂):
//
//   bias_rate = ω / a₁,  mass_scale = a₂·a₃,  impulse_scale = a₃.
//
// This is the implicit Euler step of the spring–damper, so any stiffness
// is stable at any step; the spring is only as stiff as the step resolves.
#pragma once

#include <numbers>

#include "../core/policy.hpp"

namespace impulse {

template <scalar_type T>
struct softness {
  T bias_rate = T(0);      ///< 1/s: velocity asked per metre (or radian) of error
  T mass_scale = T(1);     ///< of the row's effective mass
  T impulse_scale = T(0);  ///< of the accumulated impulse, taken off each update

  /// A rigid row: the error is left to the position pass.
  static constexpr softness rigid() noexcept { return {}; }
};

/// The softness of a spring of `hertz` and damping ratio `zeta` over a
/// step h.
template <scalar_type T>
[[nodiscard]] softness<T> soften(T hertz, T zeta, T h) noexcept {
  const T omega = T(2) * std::numbers::pi_v<T> * hertz;
  const T a1 = T(2) * zeta + h * omega, a2 = h * omega * a1, a3 = T(1) / (T(1) + a2);
  return {omega / a1, a2 * a3, a3};
}

/// The softness of a spring of stiffness k (N/m, or N·m/rad) and damping c
/// (N·s/m) on a row of effective mass m over a step h: soften() with
/// ω² = k/m and 2ζω = c/m, which gives
///
///   bias_rate = k/(c + h·k),  a₂ = h·(c + h·k)/m,
///
/// and the implicit Euler step of m·ẍ = −k·x − c·ẋ exactly: one update from
/// rest gives v₁ = (m·v₀ − h·k·x₀)/(m + h·c + h²·k). A row with k = c = 0
/// does nothing and must be skipped; one no body can move (m = 0) takes no
/// impulse.
template <scalar_type T>
[[nodiscard]] softness<T> soften_absolute(T k, T c, T m, T h) noexcept {
  const T kc = c + h * k;
  if (!(m > T(0)) || !(kc > T(0))) return {T(0), T(0), T(1)};
  const T a2 = h * kc / m, a3 = T(1) / (T(1) + a2);
  return {k / kc, a2 * a3, a3};
}

}  // namespace impulse
