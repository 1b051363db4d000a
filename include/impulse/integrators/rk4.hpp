// impulse/integrators/rk4.hpp — classical fourth-order Runge–Kutta.
//
// The four-slope method applied to (x, v)' = (v, a(x, v)). Fourth order,
// four evaluations of a(x, v) per step. For x the slopes are velocities, so
// the final position is one drift along their weighted mean.
#pragma once

#include "ode_state.hpp"

namespace impulse::integrators {

struct rk4 {
  static constexpr policy_kind kind = policy_kind::integrator;
  static constexpr int order = 4;
  static constexpr int stages = 4;

  template <class S, class H, class Accel>
    requires ode_state<S, H> && acceleration_field<Accel, S>
  static constexpr void step(S& x, S& v, H h, Accel&& accel) {
    const H half = h * H(0.5);
    const S k1v = accel(x, v);                        // k1x = v
    const S k2x = v + k1v * half;
    const S k2v = accel(drift(x, v, half), k2x);
    const S k3x = v + k2v * half;
    const S k3v = accel(drift(x, k2x, half), k3x);
    const S k4x = v + k3v * h;
    const S k4v = accel(drift(x, k3x, h), k4x);
    const H sixth = h / H(6);
    x = drift(x, v + (k2x + k3x) * H(2) + k4x, sixth);  // (k1x + 2k2x + 2k3x + k4x)·h/6
    v = v + (k1v + (k2v + k3v) * H(2) + k4v) * sixth;
  }
};

}  // namespace impulse::integrators
