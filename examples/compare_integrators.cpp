// compare_integrators — the same particle system stepped by each integrator,
// chosen at compile time by one type in the config: 100 000 particles
// thrown with scattered velocities under gravity and viscous drag, for 2 s.
// Drag makes the motion exact in closed form (k/m = c, v∞ = g/c):
//
//   x(t) = x0 + v∞·t + (v0 − v∞)(1 − e^(−c·t))/c
//
// so the error of every particle is known. Prints, side by side, the median
// time of a step and the largest error at 1/30 s and 1/60 s steps, and the
// order their ratio shows (1 for Euler and symplectic Euler, 2 for the
// midpoint rule, 4 for RK4), in double so that RK4's error is not lost
// under rounding. The RK4 run at 1/60 s is written, every half second and
// colored by speed, to out/compare_integrators.ipr.
//
//   build/native/examples/compare_integrators
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "impulse/io/particle_recording.hpp"
#include "impulse/particles.hpp"

namespace {

using T = double;
constexpr std::size_t count = 100'000;
constexpr T drag_rate = 0.8, g = 9.81, duration = 2;  // c = k/m in 1/s, m/s², s

template <class Integrator>
struct config : impulse::default_config {
  using scalar = T;
  using integrator = Integrator;
  static constexpr bool particle_lifetime = false;
};

impulse::vec3<T> start_velocity(std::size_t i) {
  impulse::lcg32 r{std::uint32_t(i) * 2654435761u + 1};
  return {r.uniform(-5.0, 5.0), r.uniform(0.0, 15.0), r.uniform(-5.0, 5.0)};
}

struct outcome {
  double median_ms = 0, error = 0;
};

template <class Integrator>
outcome run(T dt, impulse::io::particle_recorder* recording = nullptr) {
  using namespace impulse::particles;
  impulse::particle_system<config<Integrator>, gravity, drag> system(count, gravity<T>{{0, -g, 0}},
                                                                      drag<T>{drag_rate});
  for (std::size_t i = 0; i < count; ++i) system.add({0, 0, 0}, start_velocity(i), 1);
  std::vector<double> ms;
  const int steps = int(std::lround(duration / dt));
  for (int s = 0; s < steps; ++s) {
    const auto start = std::chrono::steady_clock::now();
    system.step(dt);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    if (recording && (s + 1) % int(std::lround(0.5 / dt)) == 0) recording->record(system);
  }
  std::sort(ms.begin(), ms.end());
  outcome o{ms[ms.size() / 2], 0};
  const impulse::vec3<T> terminal{0, -g / drag_rate, 0};
  const T decay = (1 - std::exp(-drag_rate * duration)) / drag_rate;
  for (std::size_t i = 0; i < count; ++i) {
    const impulse::vec3<T> exact = terminal * duration + (start_velocity(i) - terminal) * decay;
    o.error = std::max(o.error, double(impulse::length(system.position(std::uint32_t(i)) - exact)));
  }
  return o;
}

template <class Integrator>
bool report(const char* name, int order, impulse::io::particle_recorder* recording = nullptr) {
  const outcome coarse = run<Integrator>(1.0 / 30), fine = run<Integrator>(1.0 / 60, recording);
  const double seen = std::log2(coarse.error / fine.error);
  std::printf("  %-17s %9.3f %9.3f %12.3e %12.3e %8.2f (%d)\n", name, coarse.median_ms, fine.median_ms, coarse.error,
              fine.error, seen, order);
  return std::abs(seen - order) < 0.3;
}

}  // namespace

int main() {
  namespace in = impulse::integrators;
  std::printf("compare_integrators: %zu particles, gravity and drag (c = %.1f /s), %.0f s, double\n", count,
              drag_rate, duration);
  std::printf("  %-17s %9s %9s %12s %12s %8s\n", "integrator", "ms 1/30", "ms 1/60", "error 1/30", "error 1/60",
              "order");
  impulse::io::particle_recorder recording(impulse::io::color_by::speed, 15);
  const bool ok = report<in::euler>("euler", 1) && report<in::symplectic_euler>("symplectic_euler", 1) &&
                  report<in::midpoint>("midpoint", 2) && report<in::rk4>("rk4", 4, &recording);
  std::printf("  each observed order within 0.3 of its theory: %s\n", ok ? "yes" : "NO");
  std::filesystem::create_directories("out");
  const bool saved = recording.save("out/compare_integrators.ipr");
  std::printf("  wrote out/compare_integrators.ipr (the rk4 run, %zu frames)\n", recording.frame_count());
  return ok && saved ? 0 : 1;
}
