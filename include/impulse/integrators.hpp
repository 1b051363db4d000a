// impulse/integrators.hpp — the integrator policies: euler, symplectic_euler,
// midpoint, rk4, over any state modelling integrators::ode_state.
#pragma once

#include "integrators/euler.hpp"
#include "integrators/fwd.hpp"
#include "integrators/midpoint.hpp"
#include "integrators/ode_state.hpp"
#include "integrators/rk4.hpp"
#include "integrators/symplectic_euler.hpp"
