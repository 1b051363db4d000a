// expect: impulse config: `solver` does not model impulse::solver_policy
#include "impulse/config.hpp"

struct bad_config : impulse::default_config {
  using solver = float;
};

static_assert(impulse::check_config<bad_config>());
