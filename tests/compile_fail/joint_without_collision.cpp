// expect: constraints not satisfied
// A world without collision has no solver, so no joints: create_joint is
// not there to call.
#include "impulse/world.hpp"

struct motion : impulse::default_config {
  static constexpr bool collision = false;
};

int main() {
  impulse::world<motion> w;
  impulse::body_def<float> d;
  const impulse::body_id a = w.create_body(d, impulse::sphere<float>{0.5f});
  const impulse::body_id b = w.create_body(d, impulse::sphere<float>{0.5f});
  w.create_joint(impulse::joint_def<float>::ball(a, b, {}));
}
