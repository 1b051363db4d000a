// impulse/integrators/fwd.hpp — the integrator policies by name.
#pragma once

namespace impulse::integrators {

struct euler;
struct symplectic_euler;
struct midpoint;
struct rk4;

}  // namespace impulse::integrators
