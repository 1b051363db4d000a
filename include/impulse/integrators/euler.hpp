// impulse/integrators/euler.hpp — explicit (forward) Euler.
//
// x1 = x0 + g(x0, p0)·h, p1 = p0 + f(x0, p0)·h: both from the start of the
// step. First order; energy of an undamped oscillator grows by the factor
// (1 + ω²h²) every step, so it is the baseline the others are measured
// against, not a method to ship a game with.
#pragma once

#include "ode_state.hpp"

namespace impulse::integrators {

struct euler {
  static constexpr policy_kind kind = policy_kind::integrator;
  static constexpr int order = 1;
  static constexpr int stages = 1;  // evaluations of the rates per step

  template <class X, class P, class H, class System>
    requires ode_state<P, H> && mechanical_system<System, X, P>
  [[gnu::always_inline]] static constexpr void advance(X& x, P& p, H h, System&& system) {
    const auto& dx = system.position_rate(x, p);
    const P dp = system.momentum_rate(x, p);
    x = drift(x, dx, h);
    p = p + dp * h;
  }

  template <class S, class H, class Accel>
    requires ode_state<S, H> && acceleration_field<Accel, S>
  [[gnu::always_inline]] static constexpr void step(S& x, S& v, H h, Accel&& accel) {
    advance(x, v, h, second_order_system<Accel>{accel});
  }
};

}  // namespace impulse::integrators
