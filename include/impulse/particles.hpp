// impulse/particles.hpp — the particle module: particle_system, its forces
// (gravity, drag, point_forces, wind, springs), plane colliders and emitters.
// A particles-only program includes this and never parses rigid-body code.
#pragma once

#include "config.hpp"
#include "integrators.hpp"
#include "particles/drag.hpp"
#include "particles/emitter.hpp"
#include "particles/force.hpp"
#include "particles/fwd.hpp"
#include "particles/gravity.hpp"
#include "particles/particle_system.hpp"
#include "particles/plane_collider.hpp"
#include "particles/point_forces.hpp"
#include "particles/springs.hpp"
#include "particles/wind.hpp"

#if IMPULSE_EXTERN_TEMPLATES
// The default configurations' system with the forces of the README's example
// (core/extern_templates.hpp).
IMPULSE_DECLARE_PARTICLE_SYSTEM(impulse::default_config, impulse::particles::gravity, impulse::particles::drag,
                                impulse::particles::point_forces);
IMPULSE_DECLARE_PARTICLE_SYSTEM(impulse::default_double_config, impulse::particles::gravity,
                                impulse::particles::drag, impulse::particles::point_forces);
#endif
