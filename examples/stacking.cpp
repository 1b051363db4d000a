// stacking — a tower of 12 boxes and a pyramid of 36 on the ground
// (examples/scenes/stacking.json). Stacks must stand still: prints how far
// any box moved from where it was placed, when the last one fell asleep,
// what a step cost and the first step's profile (world::profile), and
// writes out/stacking.glb and out/stacking.png.
//
//   build/native/examples/stacking [scene.json] [out.glb]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "impulse/io/gltf.hpp"
#include "impulse/io/scene.hpp"
#include "impulse/io/picture.hpp"

struct config : impulse::default_config {};
using T = float;

int main(int argc, char** argv) {
  const std::string scene_file = argc > 1 ? argv[1] : IMPULSE_SCENES_DIR "/stacking.json";
  const std::string out_file = argc > 2 ? argv[2] : "out/stacking.glb";
  const impulse::io::scene<T> scene = impulse::io::read_scene<T>(scene_file);
  impulse::world<config> world;
  const impulse::io::scene_ids ids = impulse::io::add_scene(world, scene);
  std::vector<std::pair<impulse::body_id, impulse::vec3<T>>> boxes;
  for (const impulse::body_id id : ids.bodies)
    if (world.body(id).type == impulse::body_type::dynamic) boxes.emplace_back(id, world.body(id).position);

  impulse::io::gltf_recorder recording(world, {.contacts = true});
  const T dt = scene.settings.fixed_dt;
  const int steps = int(std::lround(scene.duration / dt));
  double asleep_at = -1, seconds = 0;
  T drift = 0;
  impulse::world_profile first;
  for (int i = 1; i <= steps; ++i) {
    const auto start = std::chrono::steady_clock::now();
    world.step(dt);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (i == 1) first = world.profile();
    if (i % 2 == 0) recording.record(world);
    for (const auto& [id, placed] : boxes) drift = std::max(drift, impulse::length(world.body(id).position - placed));
    if (asleep_at < 0 && world.awake_body_count() == 0) asleep_at = double(world.time());
  }
  std::printf("stacking: a tower of 12 and a pyramid of 36 boxes, %d steps of %.1f ms\n", steps, 1e3 * double(dt));
  std::printf("  the farthest any box moved from where it was placed: %.2f mm\n", 1e3 * double(drift));
  std::printf("  every box asleep from %.2f s; %.3f ms a step on average\n", asleep_at, 1e3 * seconds / steps);
  // The busiest step's profile: the first, before anything slept.
  std::printf("  the first step: %.3f ms (broad %.3f, narrow %.3f, prepare %.3f, solve %.3f, integrate %.3f); "
              "%zu pairs, %zu touching, %zu manifolds in %zu colors, %zu islands\n",
              first.times.total, first.times.broad, first.times.narrow, first.times.prepare, first.times.solve,
              first.times.integrate, first.pairs, first.touching, first.counts.solved_manifolds, first.counts.colors,
              first.counts.islands);
  const std::filesystem::path out(out_file);
  if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
  const bool saved = recording.save(out_file.c_str());
  const std::string picture = out_file.substr(0, out_file.rfind('.')) + ".png";
  const impulse::io::camera<T> eye{.position = {4, 9, 22}, .target = {1.5, 4, 0}};
  const bool drawn = impulse::io::save_png(impulse::io::render(world, eye), picture);
  std::printf("  wrote %s and %s\n", out_file.c_str(), picture.c_str());
  // A stack that stands still: no box moves a centimetre, and all sleep.
  return drift < T(0.01) && asleep_at > 0 && saved && drawn ? 0 : 1;
}
