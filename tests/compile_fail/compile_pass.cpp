// expect: success
// The control for the compile-fail harness: a config that overrides the scalar
// and names valid (test-local) policies must be accepted.
#include "impulse/config.hpp"

struct my_integrator {
  static constexpr impulse::policy_kind kind = impulse::policy_kind::integrator;
  static constexpr int order = 1;
  static constexpr int stages = 1;
  template <class S, class H, class A>
  static void step(S&, S&, H, A&&) {}
};

struct my_config : impulse::default_config {
  using scalar = double;
  using integrator = my_integrator;
  static constexpr bool sleeping = false;
};

static_assert(impulse::check_config<my_config>());
static_assert(impulse::world_config<my_config>);
int main() {}
