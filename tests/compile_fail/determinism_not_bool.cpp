// expect: impulse config: `cross_platform_determinism` must be `static constexpr bool`
#include "impulse/config.hpp"

struct bad_config : impulse::default_config {
  static constexpr int cross_platform_determinism = 1;
};

static_assert(impulse::check_config<bad_config>());
