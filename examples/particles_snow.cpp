// particles_snow — a minute of snowfall from a 30 m × 30 m cloud, blown by a
// gusty wind
// onto a floor that neither bounces nor lets it slide back (restitution 0,
// friction 1). Flakes age and die; the emitter reuses their slots.
//
// Every five simulated seconds it prints the live count, the emitter's
// dropped count, the flakes in the air and on the ground, the mean and spread
// of the airborne flakes' drift speed (the wind gives each flake its own
// steady gust, w·(1 + σ·r), r uniform in [-1, 1): spread w·σ/√3), and how far
// the flakes on the ground have drifted. The count settles at rate × mean
// lifetime inside the capacity fixed at creation: memory stays constant.
//
//   cmake --build build/debug --target particles_snow && build/debug/examples/particles_snow
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "impulse/io/particle_recording.hpp"
#include "impulse/particles.hpp"

using namespace impulse::particles;

int main() {
  using T = float;
  const T dt = T(1) / 60;

  // k/m = 5 /s: a flake takes up its gust in 0.2 s and falls at g·m/k ≈ 2 m/s.
  const wind<T> breeze{.velocity = {2, 0, 0}, .coefficient = 5, .variation = T(0.5)};
  impulse::particle_system<impulse::default_config, gravity, wind> snow{5000, gravity<T>{}, breeze};
  snow.add_plane(plane_collider<T>::half_space({0, 1, 0}, 0, 0, 1));
  const emitter<T> cloud{.position = {0, 20, 0}, .half_extents = {15, 0, 15},
                         .velocity_spread = {T(0.3), T(0.3), T(0.3)}, .rate = 300,
                         .lifetime = 15, .lifetime_spread = 3};
  snow.add_emitter(cloud);
  const T expected = cloud.rate * cloud.lifetime;

  std::printf("snow: capacity %zu, emitter %.0f flakes/s living %.0f ± %.0f s: steady state %.0f\n",
              snow.capacity(), double(cloud.rate), double(cloud.lifetime), double(cloud.lifetime_spread),
              double(expected));
  std::printf("   t   live  dropped  in air  on ground  drift speed (m/s)  spread (expect %.2f)  "
              "ground drift (m)\n", double(breeze.velocity.x * breeze.variation / std::sqrt(T(3))));
  impulse::io::particle_recorder recording(impulse::io::color_by::age);
  while (snow.time() < 60 - dt / 2) {
    snow.step(dt);
    if (std::lround(snow.time() / dt) % 12 == 0) recording.record(snow);  // 5 frames a second
    const long step = std::lround(snow.time() / dt);
    if (step % 300 != 0) continue;

    // Drift of the flakes in the air (speed) and on the ground (distance:
    // the cloud is centered on x = 0, so their mean x is how far they went,
    // about w·20 m / 1.96 m/s ≈ 20.4 m, plus a creep along the floor: the
    // wind's push in one step, dt·k·w/m, is undone at contact only as speed).
    const auto x = snow.positions();
    const auto v = snow.velocities();
    double n_air = 0, sum_v = 0, sum_v2 = 0, n_ground = 0, sum_x = 0;
    for (std::size_t i = 0; i < snow.size(); ++i) {
      if (x.y[i] > 0) {
        n_air += 1, sum_v += v.x[i], sum_v2 += double(v.x[i]) * v.x[i];
      } else {
        n_ground += 1, sum_x += x.x[i];
      }
    }
    const double mean_v = n_air > 0 ? sum_v / n_air : 0;
    const double spread_v = n_air > 0 ? std::sqrt(std::max(0.0, sum_v2 / n_air - mean_v * mean_v)) : 0;
    std::printf("%4.0f  %5zu  %7llu  %6.0f  %9.0f  %17.2f  %19.2f  %16.1f\n", snow.time(), snow.size(),
                static_cast<unsigned long long>(snow.emitters()[0].dropped), n_air, n_ground, mean_v, spread_v,
                n_ground > 0 ? sum_x / n_ground : 0.0);
  }

  const double off = std::abs(double(snow.size()) - double(expected)) / double(expected);
  const bool steady = off < 0.03 && snow.emitters()[0].dropped == 0;
  std::printf("after %.0f s: %zu flakes (%.1f%% from rate × lifetime) in %zu slots, none dropped: %s\n",
              snow.time(), snow.size(), 100 * off, snow.capacity(), steady ? "ok" : "FAILED");
  std::filesystem::create_directories("out");
  const bool recorded = recording.save("out/particles_snow.ipr");
  std::printf("wrote out/particles_snow.ipr (%zu frames)\n", recording.frame_count());
  return steady && recorded ? 0 : 1;
}
