// particles_attractors — 4000 particles under gravity and drag, pulled and pushed by
// three softened inverse-square points, inside a floor and two tilted walls.
//
// While it runs, point A circles the middle of the box, point B turns from an
// attractor into a repeller halfway through, and point C is off from t = 3 s
// to t = 6 s. Every simulated second it prints how many particles are near
// each point, their mean height and speed, how many lie on the floor, and the
// deepest any particle is behind any plane. The two walls meet at 53°, an
// acute crease where projecting a particle out of one wall pushes it behind
// the other; the planes still promise no particle behind any of them beyond
// float rounding, and the run fails if one is.
//
//   cmake --build build/debug --target particles_attractors && build/debug/examples/particles_attractors
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "impulse/io/particle_recording.hpp"
#include "impulse/particles.hpp"

using namespace impulse::particles;
using impulse::vec3;

// Nothing ages here, so the system stores no age or lifetime columns.
struct lab_config : impulse::default_config {
  static constexpr bool particle_lifetime = false;
};

int main() {
  using T = float;
  const T dt = T(1) / 120, near = T(1.5), seconds = 10;

  point_forces<T> points;
  points.softening = T(0.25);  // caps the pull at 0.385·s/ε, so one step near a point stays small
  points.add({4, 5, 0}, 300);   // A: moves in a circle
  points.add({-3, 8, 2}, 200);  // B: re-signed at t = 5 s
  points.add({3, 3, -3}, 150);  // C: off from t = 3 s to 6 s
  impulse::particle_system<lab_config, gravity, drag, point_forces> lab{
      4000, gravity<T>{}, drag<T>{.coefficient = T(0.1)}, points};

  // n·x + d ≥ 0 is inside; restitution 0.5, friction 0.2. The walls lean out.
  const plane_collider<T> planes[] = {
      plane_collider<T>::half_space({0, 1, 0}, 0, T(0.5), T(0.2)),  // floor
      plane_collider<T>::half_space(impulse::normalize(vec3<T>{1, T(0.3), 0}), 9, T(0.5), T(0.2)),
      plane_collider<T>::half_space(impulse::normalize(vec3<T>{-1, T(0.3), -1}), 9, T(0.5), T(0.2))};
  for (const auto& p : planes) lab.add_plane(p);

  // Start uniform in a box, velocities uniform in [-5, 5]³: one emitter burst.
  emitter<T> start{.position = {0, T(7.75), 0}, .half_extents = {6, T(7.25), 6}, .velocity_spread = {5, 5, 5}};
  lab.emit(start, lab.capacity());

  std::printf("attractors: %zu particles, dt = 1/120 s, 3 planes; A circles, B re-signs at 5 s, "
              "C is off for 3-6 s\n", lab.size());
  std::printf("   t   near A  near B  near C   mean y  mean |v|  on floor  deepest behind (m)\n");
  // The planes promise no particle behind one by more than the rounding a
  // projection leaves, plane_collider::rounding_at(x); `worst` ≤ 1 is that promise.
  T worst = 0, deepest = 0;  // over the run, in budgets; this second, in m
  const int steps_per_second = int(std::lround(1 / dt));
  impulse::io::particle_recorder recording(impulse::io::color_by::speed, 8);
  for (int step = 1; step <= int(seconds) * steps_per_second; ++step) {
    const T t = T(lab.time());
    auto& f = lab.force<point_forces>();
    f.points[0].position = {4 * std::cos(t), 5, 4 * std::sin(t)};  // one turn in 2π s
    f.points[1].strength = t < 5 ? T(200) : T(-200);
    f.points[2].enabled = t < 3 || t >= 6;
    lab.step(dt);
    if (step % 4 == 0) recording.record(lab);  // 30 frames a second

    const auto x = lab.positions();
    for (std::size_t i = 0; i < lab.size(); ++i)
      for (const auto& p : planes) {
        deepest = std::max(deepest, -p.distance(x[i]));
        worst = std::max(worst, -p.distance(x[i]) / p.rounding_at(x[i]));
      }
    if (step % steps_per_second != 0) continue;

    const auto v = lab.velocities();
    int close[3] = {}, on_floor = 0;
    double height = 0, speed = 0;
    for (std::size_t i = 0; i < lab.size(); ++i) {
      for (int k = 0; k < 3; ++k) close[k] += impulse::distance(x[i], f.points[k].position) < near;
      on_floor += x.y[i] < T(0.01);
      height += x.y[i];
      speed += impulse::length(v[i]);
    }
    const auto tag = [&](int k) { return !f.points[k].enabled ? "off" : f.points[k].strength > 0 ? "+" : "-"; };
    std::printf("%4.0f  %5d%-2s %5d%-2s %5d%-3s %6.2f  %7.2f  %8d  %15.2e\n", lab.time(), close[0], tag(0),
                close[1], tag(1), close[2], tag(2), height / double(lab.size()), speed / double(lab.size()),
                on_floor, double(deepest));
    deepest = 0;
  }
  std::printf("(+ attracts, - repels; near = within %.1f m)\n", double(near));
  std::printf("deepest behind a plane over all %d steps: %.2f of the rounding allowance: %s\n",
              int(seconds) * steps_per_second, double(worst), worst <= 1 ? "ok" : "FAILED");
  std::filesystem::create_directories("out");
  const bool recorded = recording.save("out/particles_attractors.ipr");
  std::printf("wrote out/particles_attractors.ipr (%zu frames)\n", recording.frame_count());
  return worst <= 1 && recorded ? 0 : 1;
}
