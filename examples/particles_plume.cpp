// particles_plume — particles resting on a rough floor (friction 0.95, no bounce) under
// an attractor 2 m above them whose strength ramps up from zero; the plume
// lifts off once the pull at the floor beats gravity.
//
// A softened point force s·d / (|d|² + ε)^1.5 pulls a unit mass at the floor,
// a horizontal distance r from below the point, upward with s·h / (r² + h² + ε)^1.5.
// Lift-off at r needs s > g·(r² + h² + ε)^1.5 / h: first directly below
// (r = 0), then in a widening disc. Every simulated second it prints the
// strength, the fraction of particles off the floor, and the fraction the
// formula predicts if none had slid; at the end, the strength at which the
// first particle lifted against the analytic threshold.
//
//   cmake --build build/debug --target particles_plume && build/debug/examples/particles_plume
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "impulse/io/particle_recording.hpp"
#include "impulse/particles.hpp"

using namespace impulse::particles;

// Nothing ages here, so the system stores no age or lifetime columns. The
// default symplectic Euler evaluates the forces at the start of each step,
// where a resting particle lies exactly on the floor: lift-off is decided by
// the pull at the floor itself, the quantity the threshold is about.
struct plume_config : impulse::default_config {
  static constexpr bool particle_lifetime = false;
};

int main() {
  using T = float;
  const T dt = T(1) / 120, h = 2, ramp = 20, g = T(9.81), radius = 3, spacing = T(0.1);

  point_forces<T> pull;
  pull.add({0, h, 0}, 0);
  // Drag settles the lifted particles around the point instead of letting
  // them swing through it and back down to the floor.
  impulse::particle_system<plume_config, gravity, drag, point_forces> plume{
      3000, gravity<T>{.acceleration = {0, -g, 0}}, drag<T>{.coefficient = 1}, pull};
  plume.add_plane(plane_collider<T>::half_space({0, 1, 0}, 0, 0, T(0.95)));
  // A disc of particles on a grid, one of them directly below the point. No
  // particle dies, so index i keeps naming the same one: r0[i] is its start.
  const int n = int(radius / spacing);
  std::vector<T> r0;
  for (int i = -n; i <= n; ++i)
    for (int k = -n; k <= n; ++k)
      if (i * i + k * k <= n * n) {
        plume.add({T(i) * spacing, 0, T(k) * spacing});
        r0.push_back(spacing * std::sqrt(T(i * i + k * k)));
      }

  // The strength that lifts a particle at distance r from below the point.
  auto threshold = [&](T r) { return g * std::pow(r * r + h * h + pull.softening, T(1.5)) / h; };
  std::printf("plume: %zu particles on the floor in a disc of radius %.0f m, attractor %.0f m above, "
              "strength %.0f·t N·m²\n", plume.size(), double(radius), double(h), double(ramp));
  std::printf("   t   strength  pull below / g  lifted  predicted  slid in, m (mean)\n");
  double first_lift = -1;
  impulse::io::particle_recorder recording(impulse::io::color_by::speed, 8);
  for (int step = 0; step < 12 * 120; ++step) {
    const T strength = ramp * T(plume.time());
    plume.force<point_forces>().points[0].strength = strength;
    plume.step(dt);
    if (step % 4 == 3) recording.record(plume);  // 30 frames a second

    const auto x = plume.positions();
    std::size_t lifted = 0;
    for (std::size_t i = 0; i < plume.size(); ++i) lifted += x.y[i] > 0;
    if (lifted > 0 && first_lift < 0) first_lift = strength;
    if ((step + 1) % 120 != 0) continue;

    // The prediction counts the start positions that the pull can lift; the
    // particles still down have meanwhile slid in toward the point by `slid`.
    std::size_t predicted = 0, down = 0;
    double slid = 0;
    for (std::size_t i = 0; i < plume.size(); ++i) {
      predicted += threshold(r0[i]) < strength;
      if (x.y[i] > 0) continue;
      down += 1;
      slid += r0[i] - std::hypot(x.x[i], x.z[i]);
    }
    const auto percent = [&](std::size_t k) { return 100.0 * double(k) / double(plume.size()); };
    char slid_in[16] = "-";
    if (down > 0) std::snprintf(slid_in, sizeof slid_in, "%.2f", slid / double(down));
    std::printf("%4.0f  %9.1f  %14.2f  %5.1f%%  %8.1f%%  %15s\n", plume.time(), double(strength),
                double(strength / threshold(0)), percent(lifted), percent(predicted), slid_in);
  }

  // The ramp moves in steps of ramp·dt, so the threshold must lie between the
  // last strength that held every particle down and the first that lifted one
  // (to the float rounding of the force, a few parts in 10⁷: 10⁻⁵ is ample).
  const double s_star = double(threshold(0)), held = first_lift - double(ramp * dt);
  const bool agrees = held < s_star * (1 + 1e-5) && s_star < first_lift * (1 + 1e-5);
  std::printf("analytic threshold below the point, g·(h² + ε)^1.5 / h = %.3f\n", s_star);
  std::printf("last strength that held: %.3f, first that lifted a particle: %.3f (%+.2f%%): %s\n", held, first_lift,
              100 * (first_lift - s_star) / s_star, agrees ? "ok, the threshold lies between" : "FAILED");
  std::filesystem::create_directories("out");
  const bool recorded = recording.save("out/particles_plume.ipr");
  std::printf("wrote out/particles_plume.ipr (%zu frames)\n", recording.frame_count());
  return agrees && recorded ? 0 : 1;
}
