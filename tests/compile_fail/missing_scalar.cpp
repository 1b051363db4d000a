// expect: impulse config: missing member type `scalar`
// A config written from scratch that forgets the scalar type.
#include "impulse/config.hpp"

struct bare_config {
  static constexpr bool sleeping = true;
};

static_assert(impulse::check_config<bare_config>());
