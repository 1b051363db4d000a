// impulse/integrators/midpoint.hpp — explicit midpoint method (RK2).
//
// Half an Euler step to the midpoint, then a full step with the rates found
// there. Second order, two evaluations of the rates per step.
#pragma once

#include "ode_state.hpp"

namespace impulse::integrators {

struct midpoint {
  static constexpr policy_kind kind = policy_kind::integrator;
  static constexpr int order = 2;
  static constexpr int stages = 2;

  template <class X, class P, class H, class System>
    requires ode_state<P, H> && mechanical_system<System, X, P>
  [[gnu::always_inline]] static constexpr void advance(X& x, P& p, H h, System&& system) {
    const H half = h * H(0.5);
    const auto& dx0 = system.position_rate(x, p);
    const X x_mid = drift(x, dx0, half);
    const P p_mid = p + system.momentum_rate(x, p) * half;
    const auto& dx_mid = system.position_rate(x_mid, p_mid);
    const P dp_mid = system.momentum_rate(x_mid, p_mid);
    x = drift(x, dx_mid, h);
    p = p + dp_mid * h;
  }

  template <class S, class H, class Accel>
    requires ode_state<S, H> && acceleration_field<Accel, S>
  [[gnu::always_inline]] static constexpr void step(S& x, S& v, H h, Accel&& accel) {
    advance(x, v, h, second_order_system<Accel>{accel});
  }
};

}  // namespace impulse::integrators
