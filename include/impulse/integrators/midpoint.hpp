// impulse/integrators/midpoint.hpp — explicit midpoint method (RK2).
//
// Half an Euler step to the midpoint, then a full step with the slopes found
// there. Second order, two evaluations of a(x, v) per step.
#pragma once

#include "ode_state.hpp"

namespace impulse::integrators {

struct midpoint {
  static constexpr policy_kind kind = policy_kind::integrator;
  static constexpr int order = 2;
  static constexpr int stages = 2;

  template <class S, class H, class Accel>
    requires ode_state<S, H> && acceleration_field<Accel, S>
  static constexpr void step(S& x, S& v, H h, Accel&& accel) {
    const H half = h * H(0.5);
    const S a0 = accel(x, v);
    const S v_mid = v + a0 * half;
    const S a_mid = accel(drift(x, v, half), v_mid);
    x = drift(x, v_mid, h);
    v = v + a_mid * h;
  }
};

}  // namespace impulse::integrators
