// impulse/integrators/euler.hpp — explicit (forward) Euler.
//
// x1 = x0 + v0·h, v1 = v0 + a(x0, v0)·h. First order; energy of an undamped
// oscillator grows by the factor (1 + ω²h²) every step, so it is the
// baseline the others are measured against, not a method to ship a game with.
#pragma once

#include "ode_state.hpp"

namespace impulse::integrators {

struct euler {
  static constexpr policy_kind kind = policy_kind::integrator;
  static constexpr int order = 1;
  static constexpr int stages = 1;  // evaluations of a(x, v) per step

  template <class S, class H, class Accel>
    requires ode_state<S, H> && acceleration_field<Accel, S>
  static constexpr void step(S& x, S& v, H h, Accel&& accel) {
    const S a0 = accel(x, v);
    x = drift(x, v, h);
    v = v + a0 * h;
  }
};

}  // namespace impulse::integrators
