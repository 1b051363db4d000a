// expect: impulse config: `integrator` does not model impulse::integrator_policy
// A type that states its order but not its stage count is not an integrator.
#include "impulse/config.hpp"

struct half_an_integrator {
  static constexpr impulse::policy_kind kind = impulse::policy_kind::integrator;
  static constexpr int order = 4;
};

struct bad_config : impulse::default_config {
  using integrator = half_an_integrator;
};

static_assert(impulse::check_config<bad_config>());
