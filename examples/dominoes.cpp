// dominoes — 100 dominoes stood along a 270° arc (examples/scenes/dominoes.json),
// set off by a ball. Prints when each tenth domino topples, checks that each
// one topples after the one before it and that the last one falls, and
// writes the run to out/dominoes.glb (open it in viewer/ or any glTF viewer).
//
//   build/native/examples/dominoes [scene.json] [out.glb]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "impulse/io/gltf.hpp"
#include "impulse/io/scene.hpp"

using T = float;
struct config : impulse::default_config {};

int main(int argc, char** argv) {
  const std::string scene_file = argc > 1 ? argv[1] : IMPULSE_SCENES_DIR "/dominoes.json";
  const std::string out_file = argc > 2 ? argv[2] : "out/dominoes.glb";
  const impulse::io::scene<T> scene = impulse::io::read_scene<T>(scene_file);
  impulse::world<config> world;
  const impulse::io::scene_ids ids = impulse::io::add_scene(world, scene);
  std::vector<impulse::body_id> dominoes;
  for (int k = 0; ids.body_names.contains("domino[" + std::to_string(k) + "]"); ++k)
    dominoes.push_back(ids.body("domino[" + std::to_string(k) + "]"));

  // A domino has toppled when its long axis leans 45° from the vertical.
  std::vector<double> toppled(dominoes.size(), -1);
  impulse::io::gltf_recorder recording(world, {.contacts = true});
  const T dt = scene.settings.fixed_dt;
  const int steps = int(std::lround(scene.duration / dt));
  const auto start = std::chrono::steady_clock::now();
  for (int i = 1; i <= steps; ++i) {
    world.step(dt);
    if (i % 2 == 0) recording.record(world);
    for (std::size_t k = 0; k < dominoes.size(); ++k) {
      const impulse::vec3<T> up = impulse::rotate(world.body(dominoes[k]).orientation, impulse::vec3<T>{0, 1, 0});
      if (toppled[k] < 0 && up.y < std::cos(T(0.25) * T(3.14159265))) toppled[k] = double(world.time());
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::printf("dominoes: %zu dominoes, %d steps of %.2f ms in %.2f s (%.3f ms per step)\n", dominoes.size(), steps,
              1e3 * double(dt), seconds, 1e3 * seconds / steps);
  bool in_order = true;
  for (std::size_t k = 0; k < dominoes.size(); ++k) {
    if (k % 10 == 9 || k == 0) std::printf("  domino %3zu toppled at %6.3f s\n", k, toppled[k]);
    if (toppled[k] < 0 || (k > 0 && !(toppled[k] > toppled[k - 1]))) in_order = false;
  }
  const bool reached_end = toppled.back() >= 0;
  std::printf("  each toppled after the one before: %s; the last fell: %s\n", in_order ? "yes" : "NO",
              reached_end ? "yes" : "NO");
  const std::filesystem::path out(out_file);
  if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
  const bool saved = recording.save(out_file.c_str());
  std::printf("  wrote %s (%zu frames, %.1f MB)\n", out_file.c_str(), recording.frame_count(),
              double(recording.glb().size()) / 1e6);
  return in_order && reached_end && saved ? 0 : 1;
}
