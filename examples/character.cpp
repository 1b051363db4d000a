// character — a character controller (impulse/character.hpp) walks a
// course: over rolling ground (a heightfield), up a flight of stairs and
// down the far side, onto a turning platform that carries it half round,
// and into a row of crates it pushes aside. Prints each leg as it is done
// and checks where the character is; writes out/character.glb (the
// character drawn as a capsule that nothing collides with) and
// out/character.png.
//
//   build/native/examples/character [out.glb]
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "impulse/character.hpp"
#include "impulse/io/gltf.hpp"
#include "impulse/io/picture.hpp"

using T = float;
struct config : impulse::default_config {};
using world_type = impulse::world<config>;
using impulse::vec3;

namespace {

constexpr T dt = T(1) / T(60);

/// The ground's height under (x, z).
T ground_height(T x, T z) { return T(0.25) * std::sin(x / 2) * std::sin(z / 2); }

/// Rolling ground: y = 0.25·sin(x/2)·sin(z/2) over x, z in [−20, 40]
/// (at most 0.125 of slope, 7°), as a heightfield of 0.5 m cells.
impulse::body_id add_rolling_ground(world_type& w) {
  const std::size_t n = 121;
  std::vector<T> heights(n * n);
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t i = 0; i < n; ++i)
      heights[k * n + i] = ground_height(T(-20) + T(0.5) * T(i), T(-20) + T(0.5) * T(k));
  impulse::body_def<T> d;
  d.type = impulse::body_type::static_body;
  d.pose.position = {-20, 0, -20};
  return w.create_body(d, impulse::heightfield<T>::make(n, n, T(0.5), T(0.5), heights));
}

impulse::body_id add_box(world_type& w, vec3<T> at, vec3<T> half, impulse::body_type type, T mass = 0) {
  impulse::body_def<T> d;
  d.type = type;
  d.pose.position = at;
  d.mass = mass;
  return w.create_body(d, impulse::box<T>::make(half));
}


}  // namespace

int main(int argc, char** argv) {
  const std::string out_file = argc > 1 ? argv[1] : "out/character.glb";
  world_type world;
  add_rolling_ground(world);
  // Stairs along x from x = 8: five steps of 0.2 m, 0.5 m deep, 3 m wide,
  // the top step 1.5 m long; then down five again.
  for (int k = 0; k < 5; ++k) {
    const T rise = T(0.2) * T(k + 1);
    add_box(world, {T(8.25) + T(0.5) * T(k), rise / 2 - T(0.5), 0}, {T(0.25), rise / 2 + T(0.5), T(1.5)},
            impulse::body_type::static_body);
    add_box(world, {T(13.25) - T(0.5) * T(k), rise / 2 - T(0.5), 0}, {T(0.25), rise / 2 + T(0.5), T(1.5)},
            impulse::body_type::static_body);
  }
  add_box(world, {T(11), T(0.5) - T(0.5) / 2, 0}, {T(0.75), T(0.75), T(1.5)}, impulse::body_type::static_body);
  // A platform 4 m square at x = 20, its top at y = 0.25 (a step up),
  // turning at 0.8 rad/s.
  const impulse::body_id platform = add_box(world, {20, 0, 0}, {2, T(0.25), 2}, impulse::body_type::kinematic);
  world.set_velocity(platform, {}, {0, T(0.8), 0});
  // Three 10 kg crates in a row along z at x = 20, z = 8 to 12.
  std::vector<impulse::body_id> crates;
  for (int k = 0; k < 3; ++k) crates.push_back(add_box(world, {20, T(0.6), T(8 + 2 * k)}, {T(0.4), T(0.4), T(0.4)},
                                                       impulse::body_type::dynamic, 10));
  // The character's picture: a kinematic capsule that nothing collides
  // with (no category) and no query sees, moved to the character each step.
  impulse::body_def<T> look;
  look.type = impulse::body_type::kinematic;
  look.filter = {0, 0, 0};
  const impulse::character_def<T> def{};
  const impulse::body_id avatar = world.create_body(look, impulse::capsule<T>::make(def.radius, def.height / 2 - def.radius));

  impulse::character<config> hero(world, def, {0, ground_height(0, 0) + T(0.05), 0});
  impulse::io::gltf_recorder recording(world);
  bool ok = true;
  int frame = 0;
  const auto tick = [&](vec3<T> velocity) {
    world.step(dt);
    hero.move(velocity, dt);
    const impulse::transform<T> pose = hero.pose();
    world.set_pose(avatar, {pose.position, impulse::quat<T>::identity()});
    if (++frame % 2 == 0) recording.record(world);
  };
  // Walks toward `target` (x, z) at `speed`; returns the seconds it took.
  const auto walk_to = [&](T x, T z, T speed, T limit) {
    const double start = double(world.time());
    for (int i = 0; i < int(limit / dt); ++i) {
      vec3<T> to{x - hero.feet().x, 0, z - hero.feet().z};
      const T distance = impulse::length(to);
      if (distance < T(0.05)) break;
      tick(to * (std::min(speed, distance / dt) / distance));
    }
    return double(world.time()) - start;
  };
  const auto leg = [&](const char* what, bool held) {
    std::printf("  %-52s %s (%.2f, %.2f, %.2f)\n", what, held ? "ok  " : "FAIL", double(hero.feet().x),
                double(hero.feet().y), double(hero.feet().z));
    ok = ok && held;
  };

  std::printf("character: a capsule of radius %.2f m and height %.1f m walks the course\n", double(def.radius),
              double(def.height));
  walk_to(6, 0, 3, 5);
  leg("over the rolling ground to the stairs", hero.on_ground() &&
      std::abs(hero.feet().y - (ground_height(hero.feet().x, hero.feet().z) + def.skin)) < T(0.02));
  walk_to(11, 0, 2, 6);
  leg("up five steps of 0.2 m to the landing at 1 m", hero.on_ground() && std::abs(hero.feet().y - (1 + def.skin)) < T(0.002));
  walk_to(17, 0, 2, 6);
  leg("down the far side", hero.on_ground() && hero.feet().x > T(16.9));
  walk_to(19, 0, 2, 4);
  const vec3<T> on = hero.feet();
  for (int i = 0; i < int(std::numbers::pi_v<T> / T(0.8) / dt); ++i) tick({});
  // Carried half round the platform's axis: from 1 m west of it to 1 m east.
  const T radius_now = std::hypot(hero.feet().x - 20, hero.feet().z);
  leg("onto the turning platform, carried half round", hero.on_ground() && std::abs(radius_now - (20 - on.x)) < T(0.01) &&
      hero.feet().x > T(20.9));
  world.set_velocity(platform, {}, {});
  walk_to(22.5, 0, 2, 3);
  walk_to(22.5, 6, 2, 4);
  walk_to(20, 6.5, 2, 4);
  T before = 0;
  for (const impulse::body_id c : crates) before += world.body(c).position.z;
  walk_to(20, 14, T(1.5), 8);
  T after = 0;
  for (const impulse::body_id c : crates) after += world.body(c).position.z;
  leg("into the crates, pushing them along", (after - before) / 3 > T(0.5) && hero.feet().z > T(9));
  for (int i = 0; i < 60; ++i) tick({});

  const std::filesystem::path out(out_file);
  if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
  const bool saved = recording.save(out_file.c_str());
  const std::string picture = out_file.substr(0, out_file.rfind('.')) + ".png";
  const impulse::io::camera<T> eye{.position = {2, 8, 24}, .target = {16, 0, 6}};
  const bool drawn = impulse::io::save_png(impulse::io::render(world, eye), picture);
  std::printf("  wrote %s and %s\n", out_file.c_str(), picture.c_str());
  return ok && saved && drawn ? 0 : 1;
}
