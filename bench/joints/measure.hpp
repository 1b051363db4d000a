// bench/joints/measure.hpp — what the joint benchmarks share: an awake
// world configuration, the joint grid's numbers, and one run of a built
// scene, timed and measured the same way on impulse and on Bullet
// (peers.cpp).
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

#include "impulse/world.hpp"

namespace joints_bench {

struct result {
  double ms_per_step = 0;  ///< median of the last half of the steps
  double worst_gap = 0;    ///< m, the largest gap between a joint's anchors at the end
  double lowest = 0;       ///< m, the lowest body's center at the end
  int moving = 0;          ///< bodies faster than 0.1 m/s at the end
};

/// The joint grid (main.cpp describes it).
struct grid_spec {
  int n = 100;
  int steps = 300;
  static constexpr double radius = 0.4, dt = 1.0 / 60;
  [[nodiscard]] bool is_static(int row, int column) const noexcept {
    return row == 0 && column >= n / 2 - 3 && column <= n / 2 + 3;
  }
};

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

/// Runs `steps` steps; the median time of the last half, ms.
template <class Step>
double median_step_ms(int steps, Step&& step) {
  std::vector<double> ms;
  for (int i = 0; i < steps; ++i) {
    const auto start = std::chrono::steady_clock::now();
    step();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  return median(std::vector<double>(ms.begin() + steps / 2, ms.end()));
}

template <class Solver>
struct awake_config : impulse::default_config {
  using solver = Solver;
  static constexpr bool sleeping = false;
};

/// Steps an impulse world and measures it.
template <class World>
result run_impulse_world(World& w, const std::vector<impulse::body_id>& bodies,
                         const std::vector<impulse::joint_id>& joints, int steps, double dt) {
  using T = typename World::scalar;
  result out;
  out.ms_per_step = median_step_ms(steps, [&] { w.step(T(dt)); });
  for (const impulse::joint_id j : joints) out.worst_gap = std::max(out.worst_gap, double(w.joint_separation(j)));
  out.lowest = 1e9;
  for (const impulse::body_id b : bodies) {
    out.lowest = std::min(out.lowest, double(w.body(b).position.y));
    out.moving += impulse::length(w.body(b).linear_velocity()) > T(0.1) ? 1 : 0;
  }
  return out;
}


}  // namespace joints_bench
