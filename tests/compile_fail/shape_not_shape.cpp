// expect: impulse config: every template in `shapes` must, made with float and double, model impulse::shape_type
#include "impulse/config.hpp"

template <class T>
struct sphere_like {
  static constexpr impulse::policy_kind kind = impulse::policy_kind::shape;
  T radius;
};
template <class T>
struct not_a_shape {
  T radius;
};

struct bad_config : impulse::default_config {
  using shapes = impulse::shape_list<sphere_like, not_a_shape>;
};

static_assert(impulse::check_config<bad_config>());
