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
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <span>

#include "impulse/dynamics.hpp"
#include "impulse/io/gltf.hpp"
#include "impulse/shapes.hpp"

namespace {

struct config : impulse::default_config {
  using scalar = double;
  using integrator = impulse::integrators::rk4;
};

/// What gltf_recorder asks of a world, for the one cube of a
/// rigid_body_system (which has no shapes of its own).
struct cube_view {
  using scalar = double;
  const impulse::rigid_body_system<config>& system;
  impulse::body_id cube;
  impulse::box<double> shape{{0.5, 0.5, 0.5}};

  std::span<const impulse::body_id> body_ids() const { return {&cube, 1}; }
  bool contains(impulse::body_id id) const { return id == cube; }
  const impulse::rigid_body<double>& body(impulse::body_id id) const { return system.body(id); }
  impulse::transform<double> shape_pose(impulse::body_id id) const { return system.body(id).pose(); }
  double time() const { return system.time(); }
  template <class F>
  decltype(auto) visit_shape(impulse::body_id, F&& f) const { return f(shape); }
  template <class F>
  void for_each_contact(F&&) const {}
};

}  // namespace

int main() {
  using namespace impulse;
  using T = double;
  rigid_body_system<config> system;
  const vec3<T> corner{0.5, 0.5, 0.5}, anchor{0, 3, 0};
  const body_id cube = system.add_body(
      rigid_body<T>::dynamic(mass_properties_of(box<T>{{0.5, 0.5, 0.5}}, 1.0), {{0.3, 2, 0.1}, quat<T>::identity()}));
  system.add_spring(body_spring<T>::to_anchor(cube, corner, anchor, 100, 2, 0.5));
  const auto air_drag = [](body_id, const body_kinematics<T>& k) {
    return wrench<T>{k.linear_velocity * -1.0, k.angular_velocity * -0.2};
  };

  const cube_view view{system, cube};
  impulse::io::gltf_recorder recording(view);
  std::printf("    t    center (m)                  turned (deg)  |omega| (rad/s)  energy (J)\n");
  const T dt = 1.0 / 120;
  for (int i = 0; i <= 60 * 120; ++i) {
    if (i % 600 == 0 || i == 30 || i == 120) {
      const rigid_body<T>& b = system.body(cube);
      std::printf("%5.2f  (%7.4f, %7.4f, %7.4f)  %12.2f  %15.4f  %10.5f\n", double(system.time()), b.position.x,
                  b.position.y, b.position.z, angle_between(b.orientation, quat<T>::identity()) * 180 / 3.14159265358979,
                  length(b.angular_velocity()), system.kinetic_energy() + system.potential_energy());
    }
    if (i < 60 * 120) system.step(dt, air_drag);
    if (i < 20 * 120 && i % 4 == 3) recording.record(view);  // 30 frames a second
  }
  std::filesystem::create_directories("out");
  const bool saved = recording.save("out/spring_cube.glb");
  std::printf("wrote out/spring_cube.glb (%zu frames)\n", recording.frame_count());

  const rigid_body<T>& b = system.body(cube);
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
