// expect: impulse config: `sleeping` must be `static constexpr bool`
#include "impulse/config.hpp"

struct bad_config : impulse::default_config {
  static constexpr int sleeping = 1;
};

static_assert(impulse::check_config<bad_config>());
