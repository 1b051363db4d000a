// impulse/instantiate.hpp — include in exactly one .cpp file of a program
// built with IMPULSE_EXTERN_TEMPLATES=1: it compiles, there and only there,
// the default configurations' world and particle system (float and
// double), and the narrow phase of the default shapes, the solvers and
// the dynamic BVH in both scalars, that every other translation unit then
// only parses.
// See core/extern_templates.hpp; a program's own configurations use
// IMPULSE_INSTANTIATE_WORLD and its siblings instead.
#pragma once

#include "particles.hpp"
#include "world.hpp"

IMPULSE_INSTANTIATE_NARROW_PHASE(float);
IMPULSE_INSTANTIATE_NARROW_PHASE(double);
IMPULSE_INSTANTIATE_SCALAR_PARTS(float);
IMPULSE_INSTANTIATE_SCALAR_PARTS(double);
IMPULSE_INSTANTIATE_WORLD(impulse::default_config);
IMPULSE_INSTANTIATE_WORLD(impulse::default_double_config);
IMPULSE_INSTANTIATE_PARTICLE_SYSTEM(impulse::default_config, impulse::particles::gravity, impulse::particles::drag,
                                    impulse::particles::point_forces);
IMPULSE_INSTANTIATE_PARTICLE_SYSTEM(impulse::default_double_config, impulse::particles::gravity,
                                    impulse::particles::drag, impulse::particles::point_forces);
