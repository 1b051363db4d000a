// newtons_cradle — five steel balls on hinged 1 m rods, 1 mm apart
// (examples/scenes/newtons_cradle.json); the first is let go from 40°.
// Momentum and energy pass down the row: the last ball swings up to nearly
// the height the first fell from, and the first stops. Prints each ball's
// highest rise over every swing, and writes out/newtons_cradle.glb.
//
//   build/native/examples/newtons_cradle [scene.json] [out.glb]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "impulse/io/gltf.hpp"
#include "impulse/io/scene.hpp"

struct config : impulse::default_config {
  using scalar = double;
  static constexpr bool sleeping = false;
};
using T = double;

int main(int argc, char** argv) {
  const std::string scene_file = argc > 1 ? argv[1] : IMPULSE_SCENES_DIR "/newtons_cradle.json";
  const std::string out_file = argc > 2 ? argv[2] : "out/newtons_cradle.glb";
  const impulse::io::scene<T> scene = impulse::io::read_scene<T>(scene_file);
  impulse::world<config> world;
  const impulse::io::scene_ids ids = impulse::io::add_scene(world, scene);
  const std::vector<impulse::body_id> balls{ids.body("striker"), ids.body("ball[0]"), ids.body("ball[1]"),
                                            ids.body("ball[2]"), ids.body("ball[3]")};
  const T rest = world.body(balls[1]).position.y;
  const T drop = world.body(balls[0]).position.y - rest;  // 1 - cos 40° = 0.234 m

  impulse::io::gltf_recorder recording(world, {.contacts = true});
  const T dt = scene.settings.fixed_dt;
  const int steps = int(std::lround(scene.duration / dt));
  // Each swing: the first ball falls, the last rises and returns, about 1 s.
  std::vector<std::vector<T>> rise(4, std::vector<T>(balls.size(), 0));
  for (int i = 1; i <= steps; ++i) {
    world.step(dt);
    if (i % 8 == 0) recording.record(world);
    const std::size_t swing = std::min<std::size_t>(3, std::size_t(world.time()));
    for (std::size_t k = 0; k < balls.size(); ++k)
      rise[swing][k] = std::max(rise[swing][k], world.body(balls[k]).position.y - rest);
  }
  std::printf("newtons_cradle: 5 balls, the first dropped %.1f mm; highest rise of each, in mm:\n", 1e3 * drop);
  std::printf("  second      1      2      3      4      5\n");
  for (std::size_t s = 0; s < rise.size(); ++s) {
    std::printf("  %zu-%zu   ", s, s + 1);
    for (const T r : rise[s]) std::printf(" %6.1f", 1e3 * r);
    std::printf("\n");
  }
  // In the first second the last ball takes the first one's energy: it rises
  // as high, give or take what the contacts lose, and the middle three stay.
  const T kept = rise[1][4] / drop;
  const T middle = std::max({rise[1][1], rise[1][2], rise[1][3]});
  std::printf("  the last ball rose to %.1f %% of the drop; the middle balls moved up %.2f mm at most\n", 100 * kept,
              1e3 * middle);
  const std::filesystem::path out(out_file);
  if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
  const bool saved = recording.save(out_file.c_str());
  std::printf("  wrote %s (%zu frames)\n", out_file.c_str(), recording.frame_count());
  return kept > 0.95 && middle < 0.001 && saved ? 0 : 1;
}
