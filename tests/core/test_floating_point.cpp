// What cross_platform_determinism asks of the build (core/floating_point.hpp):
// a world or particle system with the switch refuses to be made exactly when
// this build's code fuses multiplies and adds, and says how to build it. The
// bits themselves are checked across builds by tests/lockstep/lockstep.cpp.
#include <doctest/doctest.h>

#include <cstring>

#include "impulse/particles.hpp"
#include "impulse/world.hpp"

namespace core_floating_point_tests {

namespace {

// No collision: the world's constructor and its check without the broad
// phase, narrow phase and solver, which lockstep/lockstep.cpp compiles.
struct lockstep_forces_only : impulse::default_config {
  static constexpr bool collision = false;
  static constexpr bool cross_platform_determinism = true;
};
struct lockstep_particles : impulse::default_config {
  static constexpr bool cross_platform_determinism = true;
};

bool fused() { return impulse::detail::contraction_in_effect() || impulse::detail::quat_product_fused(); }

template <class Make>
void check_refused_exactly_when_fused(Make&& make) {
  bool refused = false;
  try {
    make();
  } catch (const impulse::invalid_argument& e) {
    refused = true;
    CHECK(e.code() == impulse::error_code::invalid_parameter);
    CHECK(std::strstr(e.what(), "-ffp-contract=off") != nullptr);
  }
  CHECK(refused == fused());
}

}  // namespace

TEST_CASE("a world with cross_platform_determinism is refused exactly when this build fuses multiplies and adds") {
  MESSAGE("this build fuses multiplies and adds: ", fused());
  check_refused_exactly_when_fused([] { impulse::world<lockstep_forces_only> w; (void)w; });
  static_assert(impulse::world<lockstep_forces_only>::cross_platform_determinism);
  static_assert(!impulse::world<impulse::default_config>::cross_platform_determinism);
}

TEST_CASE("a particle system with cross_platform_determinism is refused exactly when this build fuses") {
  // The particle system checks the scalar sum only: it has no quaternions.
  bool refused = false;
  try {
    impulse::particles::particle_system<lockstep_particles, impulse::particles::gravity> s{8};
  } catch (const impulse::invalid_argument& e) {
    refused = true;
    CHECK(std::strstr(e.what(), "-ffp-contract=off") != nullptr);
  }
  CHECK(refused == impulse::detail::contraction_in_effect());
}

}  // namespace core_floating_point_tests
