// impulse/dynamics.hpp — the dynamics module: rigid body state and loads.
// (Integration of bodies, springs on bodies, contacts and joints follow.)
#pragma once

#include "dynamics/fwd.hpp"
#include "dynamics/rigid_body.hpp"
