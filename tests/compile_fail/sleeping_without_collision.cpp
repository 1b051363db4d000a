// expect: impulse world: a world without collision neither sleeps nor sweeps
// Sleeping needs contacts to say when a body is at rest; a config that asks
// for it with collision off is named at the world.
#include "impulse/world.hpp"

struct bad_config : impulse::default_config {
  static constexpr bool collision = false;
  static constexpr bool sleeping = true;
};

impulse::world<bad_config> w;
