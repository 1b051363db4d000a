// expect: impulse config: `scalar` must be float or double
#include "impulse/config.hpp"

struct int_config : impulse::default_config {
  using scalar = int;
};

static_assert(impulse::check_config<int_config>());
