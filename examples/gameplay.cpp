// gameplay — what a game asks of a physics engine beyond stacking, in one
// scene: a ball thrown up through a one-way platform lands on top of it (a
// pre-solve hook), a conveyor belt carries three crates into a sensor gate
// that counts them (a hook's surface velocity, sensor events), a ghost
// ball whose filter leaves the crates out falls through a crate onto the
// belt, a shape cast finds the platform under a probe, and a chair made of
// a seat, four legs and a back (a compound) is dropped and stands on its
// legs. Prints each as it happens, checks them, and writes
// out/gameplay.glb and out/gameplay.png.
//
//   build/native/examples/gameplay [out.glb]
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "impulse/io/gltf.hpp"
#include "impulse/io/picture.hpp"
#include "impulse/world.hpp"

using T = float;
struct config : impulse::default_config {};
using world_type = impulse::world<config>;
using impulse::body_id;
using impulse::vec3;

namespace {

constexpr T dt = T(1) / T(60);
constexpr std::uint32_t crate_category = 2;

/// The hooks' view of the scene: the platform lets through whatever is
/// below its top, and the belt drives what lies on it along +x at 1.5 m/s.
struct rules {
  const world_type* world = nullptr;
  body_id platform, belt;
  static void pre_solve(body_id a, body_id b, const impulse::contact_manifold<T>&,
                        impulse::contact_settings<T>& s, void* context) {
    const auto& self = *static_cast<const rules*>(context);
    if (a == self.platform || b == self.platform) {
      const body_id other = a == self.platform ? b : a;
      s.enabled = self.world->body(other).position.y > T(2.1) + T(0.2);  // its center above the top, less 5 cm
    }
    if (a == self.belt) s.surface_velocity = {T(1.5), 0, 0};
    if (b == self.belt) s.surface_velocity = {T(-1.5), 0, 0};
  }
};

body_id add_box(world_type& w, vec3<T> at, vec3<T> half, impulse::body_type type, bool sensor = false,
                impulse::collision_filter filter = {}) {
  impulse::body_def<T> d;
  d.type = type;
  d.pose.position = at;
  d.sensor = sensor;
  d.filter = filter;
  return w.create_body(d, impulse::box<T>::make(half));
}

/// A chair 0.5 m wide as one body: a seat 3 cm thick whose top is 0.48 m
/// above the legs' feet, four legs 5 cm square, and a back; its origin at
/// the feet.
impulse::compound<T> chair() {
  using impulse::box;
  using impulse::transform;
  const auto at = [](T x, T y, T z) { return transform<T>{{x, y, z}, impulse::quat<T>::identity()}; };
  impulse::compound<T>::builder b;
  b.add(box<T>{{T(0.25), T(0.015), T(0.25)}}, at(0, T(0.465), 0));
  for (const T x : {T(-0.22), T(0.22)})
    for (const T z : {T(-0.22), T(0.22)}) b.add(box<T>{{T(0.025), T(0.225), T(0.025)}}, at(x, T(0.225), z));
  b.add(box<T>{{T(0.25), T(0.3), T(0.02)}}, at(0, T(0.78), T(-0.23)));
  return b.build();
}

}  // namespace

int main(int argc, char** argv) {
  const std::string out_file = argc > 1 ? argv[1] : "out/gameplay.glb";
  world_type world;
  add_box(world, {0, -1, 0}, {30, 1, 30}, impulse::body_type::static_body);
  rules scene;
  scene.world = &world;
  // A one-way platform 4 m square, its top at y = 2.1.
  scene.platform = add_box(world, {-6, 2, 0}, {2, T(0.1), 2}, impulse::body_type::static_body);
  // A belt 10 m long from x = −1, its top at y = 0.3, and a gate at its far end.
  scene.belt = add_box(world, {4, T(0.15), 0}, {5, T(0.15), 1}, impulse::body_type::static_body);
  // The gate sees crates only: its mask holds their category alone.
  const body_id gate = add_box(world, {8, 1, 0}, {T(0.5), 1, T(1.2)}, impulse::body_type::static_body, true,
                               {4, crate_category, 0});
  world.set_pre_solve({&rules::pre_solve, &scene});
  std::vector<body_id> crates;
  for (int k = 0; k < 3; ++k)
    crates.push_back(add_box(world, {T(0.5) + T(1.5) * T(k), T(0.7), 0}, {T(0.4), T(0.4), T(0.4)},
                             impulse::body_type::dynamic, false, {crate_category, impulse::all_categories, 0}));
  // A ball thrown up from under the platform at 8 m/s.
  impulse::body_def<T> throw_def;
  throw_def.pose.position = {-6, T(0.25), 0};
  throw_def.linear_velocity = {0, 8, 0};
  const body_id ball = world.create_body(throw_def, impulse::sphere<T>::make(T(0.25)));
  // A ghost ball over the last crate that collides with everything but
  // crates: it falls through the crate onto the belt.
  impulse::body_def<T> ghost_def;
  ghost_def.pose.position = {T(3.5), 3, 0};
  ghost_def.filter = {1, impulse::all_categories & ~crate_category, 0};
  const body_id ghost = world.create_body(ghost_def, impulse::sphere<T>::make(T(0.2)));
  // A chair dropped from 0.5 m, turned a little: it lands on its legs.
  impulse::body_def<T> chair_def;
  chair_def.pose = {{-2, T(0.5), 4}, impulse::quat<T>::from_axis_angle({0, 1, 0}, T(0.6))};
  chair_def.material.density = 600;  // wood
  const body_id seat = world.create_body(chair_def, chair());

  impulse::io::gltf_recorder recording(world, {.contacts = true});
  int counted = 0;
  bool ghost_in_crate = false;
  T ball_peak = 0;
  std::printf("gameplay: a one-way platform, a conveyor belt, a sensor gate and a ghost\n");
  for (int i = 1; i <= 360; ++i) {
    world.step(dt);
    if (i % 2 == 0) recording.record(world);
    ball_peak = std::max(ball_peak, world.body(ball).position.y);
    for (const impulse::sensor_event& e : world.sensor_begin_events())
      if (e.sensor == gate) std::printf("  t = %.2f s: crate %d enters the gate\n", double(world.time()), ++counted);
    for (const body_id c : crates)
      ghost_in_crate = ghost_in_crate || impulse::length(world.body(c).position - world.body(ghost).position) < T(0.4);
  }
  const T ball_y = world.body(ball).position.y, ghost_y = world.body(ghost).position.y;
  std::printf("  the ball rose to %.2f m through the platform and rests on it at %.3f m (its top 2.1 m + 0.25)\n",
              double(ball_peak), double(ball_y));
  std::printf("  the ghost passed through a crate: %s; it lies on the belt at %.3f m (its top 0.3 m + 0.2)\n",
              ghost_in_crate ? "yes" : "no", double(ghost_y));
  const impulse::transform<T> chair_pose = world.shape_pose(seat);
  const T chair_up = impulse::rotate(chair_pose.rotation, vec3<T>{0, 1, 0}).y;
  std::printf("  the chair stands on its legs, its feet at %.3f m, leaning %.2f degrees\n",
              double(chair_pose.position.y), double(std::acos(std::min(T(1), chair_up)) * T(180) / T(3.14159265)));
  // A probe dropped from above the platform: where does it land?
  const auto probe = world.shape_cast(impulse::sphere<T>::make(T(0.3)), {{-5, 6, 0}, impulse::quat<T>::identity()},
                                      {0, -10, 0});
  const bool probe_hits_platform = probe && probe->body == scene.platform;
  std::printf("  a ball of 0.3 m cast down from 6 m meets the platform at y = %.3f\n",
              probe ? double(6 - 10 * probe->fraction) : -1.0);
  // The throw peaks at 0.25 + 8²/(2g) = 3.51 m, less the steps' rounding.
  const bool ok = ball_peak > T(3.4) && std::abs(ball_y - T(2.35)) < T(0.01) && counted == 3 && ghost_in_crate &&
                  std::abs(ghost_y - T(0.5)) < T(0.01) && probe_hits_platform &&
                  std::abs(probe->fraction * 10 - T(3.6)) < T(0.001) && std::abs(chair_pose.position.y) < T(0.01) &&
                  chair_up > std::cos(T(0.01));

  const std::filesystem::path out(out_file);
  if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
  const bool saved = recording.save(out_file.c_str());
  const std::string picture = out_file.substr(0, out_file.rfind('.')) + ".png";
  const impulse::io::camera<T> eye{.position = {-2, 7, 14}, .target = {1, 1, 0}};
  const bool drawn = impulse::io::save_png(impulse::io::render(world, eye), picture);
  std::printf("  wrote %s and %s\n", out_file.c_str(), picture.c_str());
  return ok && saved && drawn ? 0 : 1;
}
