// expect: impulse config: every type in `shapes` must model impulse::shape_type
#include "impulse/config.hpp"

struct sphere_like {
  static constexpr impulse::policy_kind kind = impulse::policy_kind::shape;
};

struct bad_config : impulse::default_config {
  using shapes = impulse::shape_list<sphere_like, int>;
};

static_assert(impulse::check_config<bad_config>());
