// rube_goldberg — the README's demo (examples/scenes/rube_goldberg.json):
// a ball rolls down a ramp and strikes a lever on a hinge; the lever tips
// eight dominoes; the last falls on a shelf held to the table by a weld that
// breaks past 1 200 N·m and drops a 96 kg block on a seesaw, whose far end
// throws a ball into a cup. Prints each stage as it happens, with the time
// the steps took, and writes the run to out/rube_goldberg.glb (open it in
// any glTF viewer) and a picture of the ball at the top of its flight to
// out/rube_goldberg.png.
//
//   build/native/examples/rube_goldberg [scene.json] [out.glb]
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

using T = float;
struct config : impulse::default_config {
  static constexpr bool ccd = true;
};
using world_type = impulse::world<config>;

namespace {

/// The cup's inside: between the inner faces of its walls, below their top.
struct cup_inside {
  impulse::aabb<T> box;
  bool holds(const impulse::vec3<T>& p) const {
    return p.x > box.lower.x && p.x < box.upper.x && p.z > box.lower.z && p.z < box.upper.z && p.y < box.upper.y;
  }
};

cup_inside find_cup(const impulse::io::scene<T>& scene) {
  const auto wall = [&](const char* name) {
    const impulse::io::scene_body<T>& b = scene.bodies[*scene.find_body(name)];
    return std::pair{b.def.pose.position, std::get<impulse::box<T>>(*b.shape).half_extents};
  };
  const auto [x0, hx0] = wall("cup_wall[0]");
  const auto [x1, hx1] = wall("cup_wall[1]");
  const auto [z0, hz0] = wall("cup_side[0]");
  const auto [z1, hz1] = wall("cup_side[1]");
  return {{{x0.x + hx0.x, 0, z0.z + hz0.z}, {x1.x - hx1.x, x0.y + hx0.y, z1.z - hz1.z}}};
}

}  // namespace

int main(int argc, char** argv) {
  const std::string scene_file = argc > 1 ? argv[1] : IMPULSE_SCENES_DIR "/rube_goldberg.json";
  const std::string out_file = argc > 2 ? argv[2] : "out/rube_goldberg.glb";
  const impulse::io::scene<T> scene = impulse::io::read_scene<T>(scene_file);
  world_type world;
  const impulse::io::scene_ids ids = impulse::io::add_scene(world, scene);
  const cup_inside cup = find_cup(scene);
  const impulse::body_id projectile = ids.body("projectile");
  std::vector<impulse::body_id> dominoes;
  for (int k = 0; ids.body_names.contains("domino[" + std::to_string(k) + "]"); ++k)
    dominoes.push_back(ids.body("domino[" + std::to_string(k) + "]"));

  std::printf("rube_goldberg: %zu bodies, %zu joints, %.0f Hz for %.1f s\n", world.body_count(),
              world.joint_count(), double(1 / scene.settings.fixed_dt), double(scene.duration));
  impulse::io::gltf_recorder recording(world, {.contacts = true});
  const auto report = [&](const char* what) { std::printf("  %6.3f s  %s\n", double(world.time()), what); };
  bool lever_hit = false, seesaw_hit = false, in_cup = false, pictured = false;
  // Side on to the chain, the cup in front.
  const impulse::io::camera<T> eye{.position = {1.5, 5.5, 11}, .target = {-0.2, 1.8, 0}, .vertical_fov_degrees = 50};
  const std::string picture_file = out_file.substr(0, out_file.rfind('.')) + ".png";
  impulse::io::image picture;
  std::size_t toppled = 0;
  std::vector<double> step_ms;
  const T dt = scene.settings.fixed_dt;
  const int steps = int(std::lround(scene.duration / dt));
  for (int i = 1; i <= steps; ++i) {
    const auto start = std::chrono::steady_clock::now();
    world.step(dt);
    step_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    if (i % 4 == 0) recording.record(world);  // 60 frames a second

    if (!lever_hit && std::abs(world.joint_position(ids.joint("lever_hinge"))) > T(0.1)) {
      lever_hit = true;
      report("the ball strikes the lever");
    }
    while (toppled < dominoes.size() &&
           impulse::rotate(world.body(dominoes[toppled]).orientation, impulse::vec3<T>{0, 1, 0}).y < T(0.7071)) {
      if (++toppled == 1 || toppled == dominoes.size())
        report(toppled == 1 ? "the first domino topples" : "the last domino topples");
    }
    for (const auto& broken : world.joint_broken_events()) {
      char line[96];
      std::snprintf(line, sizeof line, "the shelf's weld breaks at %.0f N·m", double(broken.torque));
      report(line);
    }
    if (!seesaw_hit && world.joint_position(ids.joint("seesaw_hinge")) > T(0.1)) {
      seesaw_hit = true;
      report("the block lands on the seesaw");
    }
    if (seesaw_hit && !pictured && world.body(projectile).linear_velocity().y < 0) {
      pictured = true;
      picture = impulse::io::render(world, eye);
      report("the ball is at the top of its flight (the picture)");
    }
    if (!in_cup && cup.holds(world.body(projectile).position)) {
      in_cup = true;
      report("the ball drops into the cup");
    }
  }
  const bool stays = cup.holds(world.body(projectile).position);
  std::sort(step_ms.begin(), step_ms.end());
  std::printf("  the ball %s in the cup at the end\n", stays ? "is" : "is NOT");
  std::printf("  %d steps: median %.3f ms, slowest %.3f ms (%.1fx real time)\n", steps, step_ms[step_ms.size() / 2],
              step_ms.back(), double(dt) * 1e3 / step_ms[step_ms.size() / 2]);

  const std::filesystem::path out(out_file);
  if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
  const bool saved = recording.save(out_file.c_str());
  std::printf("  wrote %s (%zu frames, %.1f MB)\n", out_file.c_str(), recording.frame_count(),
              double(recording.glb().size()) / 1e6);
  if (!pictured) picture = impulse::io::render(world, eye);
  const bool drawn = impulse::io::save_png(picture, picture_file);
  std::printf("  wrote %s (%d x %d)\n", picture_file.c_str(), picture.width, picture.height);
  return stays && lever_hit && seesaw_hit && saved && drawn ? 0 : 1;
}
