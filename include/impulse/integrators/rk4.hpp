// impulse/integrators/rk4.hpp — classical fourth-order Runge–Kutta.
//
// The four-slope method applied to (x, p)' = (g(x, p), f(x, p)). Fourth
// order, four evaluations of the rates per step. The final position is one
// drift along the weighted mean of the four position rates.
#pragma once

#include <type_traits>

#include "ode_state.hpp"

namespace impulse::integrators {

struct rk4 {
  static constexpr policy_kind kind = policy_kind::integrator;
  static constexpr int order = 4;
  static constexpr int stages = 4;

  template <class X, class P, class H, class System>
    requires ode_state<P, H> && mechanical_system<System, X, P>
  [[gnu::always_inline]] static constexpr void advance(X& x, P& p, H h, System&& system) {
    const H half = h * H(0.5);
    // The stages' rates are summed as they come, k1 + 2·k2 + 2·k3 + k4,
    // so at most one stage's state and rates are alive beside the sums:
    // summed at the end, the particle kernel kept all eight rates and spilled
    // them to the stack (it ran at 0.69 times a hand-written kernel's speed
    // in float). Stage states are named, so a rate returned by reference
    // (the second-order adapter returns p itself) outlives its use.
    const auto& k1x = system.position_rate(x, p);
    const P k1p = system.momentum_rate(x, p);
    std::remove_cvref_t<decltype(k1x)> sum_x = k1x;
    const X x2 = drift(x, k1x, half);
    const P p2 = p + k1p * half;
    P sum_p = k1p;
    const auto& k2x = system.position_rate(x2, p2);
    const P k2p = system.momentum_rate(x2, p2);
    sum_x = sum_x + k2x * H(2);
    sum_p = sum_p + k2p * H(2);
    const X x3 = drift(x, k2x, half);
    const P p3 = p + k2p * half;
    const auto& k3x = system.position_rate(x3, p3);
    const P k3p = system.momentum_rate(x3, p3);
    sum_x = sum_x + k3x * H(2);
    sum_p = sum_p + k3p * H(2);
    const X x4 = drift(x, k3x, h);
    const P p4 = p + k3p * h;
    const auto& k4x = system.position_rate(x4, p4);
    const P k4p = system.momentum_rate(x4, p4);
    const H sixth = h / H(6);
    x = drift(x, sum_x + k4x, sixth);
    p = p + (sum_p + k4p) * sixth;
  }

  template <class S, class H, class Accel>
    requires ode_state<S, H> && acceleration_field<Accel, S>
  [[gnu::always_inline]] static constexpr void step(S& x, S& v, H h, Accel&& accel) {
    advance(x, v, h, second_order_system<Accel>{accel});
  }
};

}  // namespace impulse::integrators
