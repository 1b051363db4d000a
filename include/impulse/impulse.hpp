// impulse/impulse.hpp — everything in impulse. Each module also has its own
// umbrella header (impulse/math.hpp, ...) for users who need less.
#pragma once

#include "broadphase.hpp"
#include "config.hpp"
#include "core.hpp"
#include "dynamics.hpp"
#include "integrators.hpp"
#include "math.hpp"
#include "narrowphase.hpp"
#include "particles.hpp"
#include "shapes.hpp"
#include "world.hpp"
