// spring_cube — a cube hanging from a spring at one corner: it swings,
// turns as the corner drags it round, and settles with its center straight
// below the corner.
//
// The spring (k = 100 N/m, c = 2 N·s/m along the spring, rest length
// 0.5 m) holds the corner (½, ½, ½) of a 1 kg unit cube from the anchor
// (0, 3, 0); the cube starts at rest, unturned, off to one side. Air drag
// (a force field evaluated at every RK4 stage) lets it settle. At rest the
// spring is vertical and stretched by m·g/k, and the center hangs √¾ below
// the corner: the program checks both and exits non-zero if either is off by
// more than 1e-4. The first 20 s are written to out/spring_cube.glb.
//
// The world is one without collision (config `collision = false`): no
// broad phase, contacts, joints or solver, and the spring is a force
// evaluated at every stage of the integrator, as the drag is.
// hanging_cube.cpp hangs a cube on springs in a colliding world, where
// they are solved with the contacts.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "impulse/dynamics.hpp"
#include "impulse/io/gltf.hpp"
#include "impulse/shapes.hpp"
#include "impulse/world.hpp"

namespace {

struct config : impulse::default_config {
  using scalar = double;
  using integrator = impulse::integrators::rk4;
  static constexpr bool collision = false;  // bodies moved by forces alone
};

}  // namespace

int main() {
  using namespace impulse;
  using T = double;
  world<config> w;  // gravity (0, -9.81, 0)
  const vec3<T> corner{0.5, 0.5, 0.5}, anchor{0, 3, 0};
  body_def<T> def;  // density 1: the unit cube weighs 1 kg
  def.pose = {{0.3, 2, 0.1}, quat<T>::identity()};
  const body_id cube = w.create_body(def, box<T>{{0.5, 0.5, 0.5}});
  w.create_spring(body_spring<T>::to_anchor(cube, corner, anchor, 100, 2, 0.5));
  const auto air_drag = [](body_id, const body_kinematics<T>& k) {
    return wrench<T>{k.linear_velocity * -1.0, k.angular_velocity * -0.2};
  };

  impulse::io::gltf_recorder recording(w);
  std::printf("    t    center (m)                  turned (deg)  |omega| (rad/s)  energy (J)\n");
  const T dt = 1.0 / 120;
  for (int i = 0; i <= 60 * 120; ++i) {
    if (i % 600 == 0 || i == 30 || i == 120) {
      const rigid_body<T>& b = w.body(cube);
      std::printf("%5.2f  (%7.4f, %7.4f, %7.4f)  %12.2f  %15.4f  %10.5f\n", double(w.time()), b.position.x,
                  b.position.y, b.position.z, angle_between(b.orientation, quat<T>::identity()) * 180 / 3.14159265358979,
                  length(b.angular_velocity()), w.kinetic_energy() + w.potential_energy());
    }
    if (i < 60 * 120) w.step(dt, air_drag);
    if (i < 20 * 120 && i % 4 == 3) recording.record(w);  // 30 frames a second
  }
  std::filesystem::create_directories("out");
  const bool saved = recording.save("out/spring_cube.glb");
  std::printf("wrote out/spring_cube.glb (%zu frames)\n", recording.frame_count());

  const rigid_body<T>& b = w.body(cube);
  const T stretch = 9.81 / 100;
  const vec3<T> expected{0, anchor.y - 0.5 - stretch - std::sqrt(0.75), 0};
  const vec3<T> up = normalize(rotate(b.orientation, corner));
  const T position_error = length(b.position - expected);
  const T tilt = std::atan2(length(cross(up, vec3<T>{0, 1, 0})), up.y);
  std::printf("equilibrium: center off by %.2e m, corner-to-center axis off vertical by %.2e rad\n", position_error,
              tilt);
  const bool ok = position_error < 1e-4 && tilt < 1e-4 && saved;
  std::printf("%s\n", ok ? "ok" : "FAILED: the cube did not settle where statics says");
  return ok ? 0 : 1;
}
