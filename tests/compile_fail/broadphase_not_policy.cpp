// expect: impulse config: `broadphase` does not model impulse::broadphase_policy
// A solver named where a broad phase belongs.
#include "impulse/config.hpp"

struct some_solver {
  static constexpr impulse::policy_kind kind = impulse::policy_kind::solver;
};

struct bad_config : impulse::default_config {
  using broadphase = some_solver;
};

static_assert(impulse::check_config<bad_config>());
