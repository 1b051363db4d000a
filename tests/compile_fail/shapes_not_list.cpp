// expect: impulse config: `shapes` must be impulse::shape_list<...>
#include "impulse/config.hpp"

struct sphere_like {
  static constexpr impulse::policy_kind kind = impulse::policy_kind::shape;
};

struct bad_config : impulse::default_config {
  using shapes = sphere_like;  // should be impulse::shape_list<sphere_like>
};

static_assert(impulse::check_config<bad_config>());
