// A downstream program that loads a scene (io/scene.hpp, which needs
// nlohmann-json): built by tests/consumer/run.sh through
// find_package(impulse COMPONENTS scene) and the impulse::scene target, and
// against the scene single header (single_include/impulse/impulse_scene.hpp)
// when compiled with -DIMPULSE_CONSUMER_SINGLE_HEADER.
//
// The scene: a ground box and a ball dropped on it. Exits 0 only if the
// scene loads, the world steps it for 2 s and the ball rests on the ground.
#include <cmath>
#include <cstdio>
#include <exception>

#ifdef IMPULSE_CONSUMER_SINGLE_HEADER
#include "impulse/impulse_scene.hpp"
#else
#include "impulse/impulse.hpp"
#include "impulse/io/scene.hpp"
#endif

namespace {

constexpr const char* scene_text = R"({
  "impulse_scene": 1,
  "description": "a ball of radius 0.25 m dropped from 2 m onto the ground",
  "settings": { "gravity": [0, -9.81, 0], "time_step": 0.016666666666666666 },
  "bodies": [
    { "name": "ground", "type": "static", "shape": { "type": "box", "half_extents": [100, 1, 100] },
      "position": [0, -1, 0] },
    { "name": "ball", "shape": { "type": "sphere", "radius": 0.25 }, "position": [0, 2, 0] }
  ]
})";

}  // namespace

int main() {
  using config = impulse::default_config;
  using T = config::scalar;
  try {
    const impulse::io::scene<T> scene = impulse::io::parse_scene<T>(scene_text, "consumer.json");
    impulse::world<config> world;
    const impulse::io::scene_ids ids = impulse::io::add_scene(world, scene);
    const impulse::body_id ball = ids.body("ball");
    for (int i = 0; i < 120; ++i) world.step(scene.settings.fixed_dt);
    const T y = world.shape_pose(ball).position.y;
    std::printf("impulse %s: %zu bodies from a scene; the ball rests at y = %.4f m after 2 s\n",
                IMPULSE_VERSION_STRING, scene.bodies.size(), double(y));
    if (!(std::fabs(y - T(0.25)) <= T(0.01))) {
      std::fprintf(stderr, "scene consumer: the ball is not resting on the ground (y should be 0.25)\n");
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "scene consumer: %s\n", e.what());
    return 1;
  }
}
