// scene_fuzz — libFuzzer target for the scene loader (io/scene.hpp).
//
// Any input must either load or be refused with an io::scene_error; a
// refused scene must leave the world as it was (checked here, aborting if
// not); a scene that loads must step. Sanitizers (address, undefined) catch
// what the loader does wrong on the way. Build with -DIMPULSE_BUILD_FUZZERS=ON
// and clang; seed it with examples/scenes:
//
//   build/fuzz/tests/impulse_scene_fuzz -max_total_time=600 -max_len=8192 corpus examples/scenes
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "impulse/io/scene.hpp"

namespace {

struct fuzz_config : impulse::default_config {};
using world_type = impulse::world<fuzz_config>;
using particles_type = impulse::particles::particle_system<fuzz_config, impulse::particles::gravity,
                                                           impulse::particles::drag, impulse::particles::wind,
                                                           impulse::particles::point_forces>;

void check(bool promise) {
  if (!promise) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  impulse::io::scene<float> scene;
  try {
    scene = impulse::io::parse_scene<float>(text, "fuzz.json");
  } catch (const impulse::io::scene_error&) {
    return 0;
  }
  // Loaded into a world that holds a body already: all of the scene or none.
  world_type world;
  const impulse::body_id resident = world.create_body({}, impulse::sphere<float>{0.5f});
  try {
    const impulse::io::scene_ids ids = impulse::io::add_scene(world, scene);
    check(world.body_count() == 1 + scene.bodies.size() && ids.joints.size() == scene.joints.size());
  } catch (const impulse::io::scene_error&) {
    check(world.body_count() == 1 && world.joint_count() == 0 && world.contains(resident));
    return 0;
  }
  // A few steps: what loads must run (a state that turns non-finite is reported, not crashed on).
  if (scene.bodies.size() <= 64) {
    try {
      for (int i = 0; i < 4; ++i) world.step(1.0f / 60);
    } catch (const impulse::invalid_argument&) {
    }
  }
  for (const auto& p : scene.particle_systems) {
    if (p.capacity > 4096) continue;
    try {
      particles_type system(p.capacity);
      impulse::io::add_particles(system, p, "fuzz.json");
      for (int i = 0; i < 4; ++i) system.step(1.0f / 60);
    } catch (const impulse::invalid_argument&) {
    }
  }
  return 0;
}
