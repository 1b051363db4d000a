// hanging_cube — a cube hanging from four damped springs at its top
// corners, in a world where it also collides: a box dropped onto it lands
// and rides it, and the cube sags under the extra weight.
//
// The springs (k = 300 N/m, c = 30 N·s/m, rest length 1.5 m) hold the
// corners of a 1 kg cube of side 1 m from anchors 1.5 m above them; a 1 kg
// box of side 0.5 m falls onto the cube's top face from 1.25 m above it.
// The springs are solved with the contacts (world::create_spring): at rest
// the four of them bear both weights, so the cube hangs 2·m·g/(4·k) below
// their rest length and the box sits on its top face (sunk at most the
// contacts' 0.5 mm slop into it). The program checks both within 1 mm and
// exits non-zero if either is off; the first 8 s are written to
// out/hanging_cube.glb.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "impulse/io/gltf.hpp"
#include "impulse/world.hpp"

namespace {
/// Sleeping off: the cube is checked where the springs alone hold it.
struct config : impulse::default_config {
  static constexpr bool sleeping = false;
};
}  // namespace

int main() {
  using T = float;
  impulse::world<config> world;

  const T k = 300, c = 30, rest = 1.5f, g = 9.81f;
  impulse::body_def<T> d;
  d.pose.position = {0, 5, 0};
  d.mass = 1;
  const impulse::body_id cube = world.create_body(d, impulse::box<T>::make({0.5f, 0.5f, 0.5f}));
  for (const T x : {T(-0.5), T(0.5)})
    for (const T z : {T(-0.5), T(0.5)})
      world.create_spring(impulse::body_spring<T>::to_anchor(cube, {x, 0.5f, z}, {x, 5.5f + rest, z}, k, c, rest));
  d.pose.position = {0, 7, 0};
  const impulse::body_id load = world.create_body(d, impulse::box<T>::make({0.25f, 0.25f, 0.25f}));

  impulse::io::gltf_recorder recording(world, {.contacts = true});
  const T dt = T(1) / T(60);
  T landed = -1;
  for (int i = 1; i <= 900; ++i) {
    world.step(dt);
    if (i <= 480 && i % 2 == 0) recording.record(world);
    if (landed < 0 && !world.contact_begin_events().empty()) landed = world.time();
  }

  const T top = 5.5f - 2 * 1 * g / (4 * k);  // the top face, both weights on the springs
  const T cube_off = world.body(cube).position.y - (top - 0.5f);
  const T load_off = world.body(load).position.y - (top + 0.25f);
  std::printf("hanging_cube: a 1 kg cube on four springs of %.0f N/m, a 1 kg box dropped on it\n", double(k));
  std::printf("  the box landed at %.2f s\n", double(landed));
  std::printf("  cube's center %.4f m (expected %.4f), off by %.2f mm\n", double(world.body(cube).position.y),
              double(top - 0.5f), 1e3 * double(cube_off));
  std::printf("  box's center %.4f m (expected %.4f), off by %.2f mm\n", double(world.body(load).position.y),
              double(top + 0.25f), 1e3 * double(load_off));
  std::printf("  spring tension %.3f N each (expected %.3f)\n", double(world.spring_tension(world.spring_ids()[0])),
              double(2 * g / 4));
  std::filesystem::create_directories("out");
  const bool saved = recording.save("out/hanging_cube.glb");
  std::printf("  wrote out/hanging_cube.glb\n");
  return landed > 0 && std::abs(cube_off) < T(1e-3) && std::abs(load_off) < T(1e-3) && saved ? 0 : 1;
}
