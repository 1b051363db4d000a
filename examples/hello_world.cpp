// hello_world: a world, a ground and a box dropped from 4 m; prints the box's
// height every third of a second and checks that it comes to rest on the
// ground (its center half a metre up, within 1 cm). The README's first program.
#include <cmath>
#include <cstdio>

#include "impulse/world.hpp"

int main() {
  impulse::world<impulse::default_config> world;  // gravity (0, -9.81, 0) m/s²
  impulse::body_def<float> ground;
  ground.type = impulse::body_type::static_body;
  ground.pose.position = {0, -1, 0};
  world.create_body(ground, impulse::box<float>::make({100, 1, 100}));  // its top face is y = 0

  impulse::body_def<float> crate;
  crate.pose.position = {0, 4, 0};
  const impulse::body_id box = world.create_body(crate, impulse::box<float>::make({0.5f, 0.5f, 0.5f}));
  for (int step = 1; step <= 120; ++step) {
    world.step(1.0f / 60);
    const float y = world.shape_pose(box).position.y;
    if (step % 20 == 0) std::printf("t = %.2f s  box center at y = %.3f m\n", step / 60.0, y);
  }
  return std::abs(world.shape_pose(box).position.y - 0.5f) < 0.01f ? 0 : 1;
}
