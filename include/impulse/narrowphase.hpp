// impulse/narrowphase.hpp — the narrow phase module: contact manifolds
// between pairs of shapes. So far the closed-form tests between spheres,
// capsules, boxes and planes (narrowphase/analytic.hpp).
#pragma once

#include "narrowphase/analytic.hpp"
#include "narrowphase/manifold.hpp"
