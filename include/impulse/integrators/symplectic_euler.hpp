// impulse/integrators/symplectic_euler.hpp — semi-implicit (symplectic) Euler.
//
// p1 = p0 + f(x0, p0)·h, then x1 = x0 + g(x0, p1)·h: the new momentum is
// used at once by the position update. Still first order, but for forces
// that depend on position only it is symplectic, so an oscillator's energy
// oscillates within O(h) of its true value forever instead of drifting. The
// usual default of game engines (Box2D, Bullet, Jolt) for that reason; for a
// rigid body it is the "update L, then turn q with the new ω" of those
// engines, with ω = I_w(q0)⁻¹·L1.
#pragma once

#include "ode_state.hpp"

namespace impulse::integrators {

struct symplectic_euler {
  static constexpr policy_kind kind = policy_kind::integrator;
  static constexpr int order = 1;
  static constexpr int stages = 1;

  template <class X, class P, class H, class System>
    requires ode_state<P, H> && mechanical_system<System, X, P>
  [[gnu::always_inline]] static constexpr void advance(X& x, P& p, H h, System&& system) {
    p = p + system.momentum_rate(x, p) * h;
    x = drift(x, system.position_rate(x, p), h);
  }

  template <class S, class H, class Accel>
    requires ode_state<S, H> && acceleration_field<Accel, S>
  [[gnu::always_inline]] static constexpr void step(S& x, S& v, H h, Accel&& accel) {
    advance(x, v, h, second_order_system<Accel>{accel});
  }
};

}  // namespace impulse::integrators
