// impulse/config.hpp — the default compile-time configuration.
//
// A configuration is a struct of member types and constants that selects the
// policies of a world or particle system. Inherit from default_config and
// override what you need:
//
//   struct my_config : impulse::default_config {
//     using scalar = double;
//   };
//   static_assert(impulse::check_config<my_config>());
//
// Only members whose implementations exist are defaulted here; the others
// (broadphase, solver, shapes, sleeping, ccd) are checked against their
// concepts in core/policy.hpp when a config names them.
#pragma once

#include "core/extern_templates.hpp"
#include "core/policy.hpp"
#include "integrators/symplectic_euler.hpp"

namespace impulse {

struct default_config {
  /// Scalar type of positions, velocities and masses: float or double.
  using scalar = float;
  /// How force-driven motion is integrated: euler, symplectic_euler,
  /// midpoint or rk4 (impulse/integrators.hpp). Symplectic Euler keeps
  /// oscillating systems' energy bounded at one force evaluation per step.
  using integrator = integrators::symplectic_euler;
};

/// default_config in double precision. Like default_config, it has its
/// compiled instantiations under IMPULSE_EXTERN_TEMPLATES
/// (core/extern_templates.hpp).
struct default_double_config : default_config {
  using scalar = double;
};

static_assert(check_config<default_config>());
static_assert(check_config<default_double_config>());

}  // namespace impulse
