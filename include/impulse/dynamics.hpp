// impulse/dynamics.hpp — the dynamics module: rigid bodies, their motion
// under forces and springs, materials, contact constraints and the contact
// solvers. (Joints follow.)
#pragma once

#include "config.hpp"
#include "dynamics/body_motion.hpp"
#include "dynamics/body_spring.hpp"
#include "dynamics/detail/constraint_parts.hpp"
#include "dynamics/contact_constraint.hpp"
#include "dynamics/detail/contact_rows.hpp"
#include "dynamics/fwd.hpp"
#include "dynamics/detail/island.hpp"
#include "dynamics/joint.hpp"
#include "dynamics/material.hpp"
#include "dynamics/rigid_body.hpp"
#include "dynamics/sequential_impulse.hpp"
#include "dynamics/soft_step.hpp"
#include "dynamics/softness.hpp"
#include "dynamics/solver_settings.hpp"
#include "integrators.hpp"
