// expect: impulse config: `ccd` must be `static constexpr bool`
#include "impulse/config.hpp"

struct bad_config : impulse::default_config {
  static constexpr double ccd = 0.0;
};

static_assert(impulse::check_config<bad_config>());
