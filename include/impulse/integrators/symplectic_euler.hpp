// impulse/integrators/symplectic_euler.hpp — semi-implicit (symplectic) Euler.
//
// v1 = v0 + a(x0, v0)·h, then x1 = x0 + v1·h: the velocity update is used at
// once by the position update. Still first order, but for forces that depend
// on position only it is symplectic, so an oscillator's energy oscillates
// within O(h) of its true value forever instead of drifting. The usual
// default of game engines (Box2D, Bullet, Jolt) for that reason.
#pragma once

#include "ode_state.hpp"

namespace impulse::integrators {

struct symplectic_euler {
  static constexpr policy_kind kind = policy_kind::integrator;
  static constexpr int order = 1;
  static constexpr int stages = 1;

  template <class S, class H, class Accel>
    requires ode_state<S, H> && acceleration_field<Accel, S>
  static constexpr void step(S& x, S& v, H h, Accel&& accel) {
    v = v + accel(x, v) * h;
    x = drift(x, v, h);
  }
};

}  // namespace impulse::integrators
