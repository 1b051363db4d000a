// impulse/dynamics.hpp — the dynamics module: rigid bodies, their motion
// under forces and springs. (Contacts and joints follow.)
#pragma once

#include "config.hpp"
#include "dynamics/body_motion.hpp"
#include "dynamics/body_spring.hpp"
#include "dynamics/fwd.hpp"
#include "dynamics/rigid_body.hpp"
#include "dynamics/rigid_body_system.hpp"
#include "integrators.hpp"
