// bench/towers — how tall a tower of boxes each solver configuration holds,
// and what its sway looks like: the measurements behind docs/stacks.md.
//
// A tower is the standard scene's (docs/standard_scenes.md, `tower20`): n
// unit boxes (half-extent 0.5, density 1000, friction 0.6) stacked exactly
// at y = 0.5 + k on the standard ground, sleeping off, stepped 60 s at
// 60 Hz. A run stops when the top box has lost 0.5 m of height (fallen).
//
//   towers            CSV: configuration, boxes, stood, fell_at_s,
//                     top_drift_m (horizontal), height_lost_m, ms_per_frame
//   towers --shape    the 20-box tower in one part of 20 sweeps after 15 s:
//                     each box's offset, tilt and vertical speed
//   towers --sway     the same tower's top drift every 2.5 s until it falls
//
// Configurations: sequential_impulse in one part of 10 to 80 velocity
// iterations; the same 20 iterations a frame spread over 2 to 20 world
// steps a frame (each a whole step of 1/(60·n) s: collision, solve,
// integration); the step in 2, 4 or 8 parts (sequential_impulse_settings::
// substeps: collision and preparation once), 4 parts of 8 being the
// default; soft_step at its default 4 substeps and at 16.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "impulse/world.hpp"

namespace {

using namespace impulse;

struct awake_config : default_config {
  static constexpr bool sleeping = false;
};
struct soft_config : awake_config {
  using solver = impulse::solver::soft_step;
};

/// sequential_impulse's settings for `parts` parts of `sweeps` sweeps.
world_settings<float> in_parts(int parts, int sweeps) {
  world_settings<float> s;
  s.solver.substeps = parts;
  s.solver.velocity_iterations = sweeps;
  return s;
}

struct outcome {
  bool stood = true;
  double fell_at = 0;      // s
  double drift = 0;        // m, horizontal, at the end or the fall
  double height_lost = 0;  // m
  double ms_per_frame = 0; // median
};

template <class World>
std::vector<body_id> build(World& w, int boxes) {
  body_def<float> ground;
  ground.type = body_type::static_body;
  ground.pose.position = {0, -1, 0};
  ground.material.friction = 0.6f;
  w.create_body(ground, box<float>::make({100, 1, 100}));
  std::vector<body_id> ids;
  for (int k = 0; k < boxes; ++k) {
    body_def<float> d;
    d.pose.position = {0, 0.5f + float(k), 0};
    d.material.friction = 0.6f;
    ids.push_back(w.create_body(d, box<float>::make({0.5f, 0.5f, 0.5f})));
  }
  return ids;
}

template <class World>
outcome run(World& w, int boxes, int steps_per_frame) {
  const std::vector<body_id> ids = build(w, boxes);
  const vec3<float> start = w.body(ids.back()).position;
  const float h = 1.0f / (60.0f * float(steps_per_frame));
  outcome o;
  std::vector<double> times;
  for (int frame = 1; frame <= 3600; ++frame) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int j = 0; j < steps_per_frame; ++j) w.step(h);
    times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    const vec3<float> p = w.body(ids.back()).position;
    o.drift = std::hypot(double(p.x - start.x), double(p.z - start.z));
    o.height_lost = double(start.y - p.y);
    if (o.height_lost > 0.5) {
      o.stood = false;
      o.fell_at = frame / 60.0;
      break;
    }
  }
  std::nth_element(times.begin(), times.begin() + std::ptrdiff_t(times.size() / 2), times.end());
  o.ms_per_frame = times[times.size() / 2];
  return o;
}

void print(const std::string& name, int boxes, const outcome& o) {
  std::printf("%s,%d,%d,%.2f,%.3e,%.3e,%.4f\n", name.c_str(), boxes, o.stood ? 1 : 0, o.fell_at, o.drift,
              o.height_lost, o.ms_per_frame);
  std::fflush(stdout);
}

void shape() {
  world<awake_config> w(in_parts(1, 20));
  const std::vector<body_id> ids = build(w, 20);
  for (int i = 0; i < 900; ++i) w.step(1.0f / 60);
  std::printf("box,x_m,z_m,tilt_x,tilt_z,vy_m_per_s\n");
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const rigid_body<float>& b = w.body(ids[k]);
    const vec3<float> up = rotate(b.orientation, vec3<float>{0, 1, 0});
    std::printf("%zu,%.3e,%.3e,%.3e,%.3e,%.3e\n", k, b.position.x, b.position.z, up.x, up.z, b.linear_velocity().y);
  }
}

void sway() {
  world<awake_config> w(in_parts(1, 20));
  const std::vector<body_id> ids = build(w, 20);
  const vec3<float> start = w.body(ids.back()).position;
  std::printf("t_s,top_drift_m,height_lost_m\n");
  for (int i = 1; i <= 3600; ++i) {
    w.step(1.0f / 60);
    const vec3<float> p = w.body(ids.back()).position;
    const double lost = double(start.y - p.y);
    if (i % 150 == 0 || lost > 0.5)
      std::printf("%.1f,%.3e,%.3e\n", i / 60.0, std::hypot(double(p.x - start.x), double(p.z - start.z)), lost);
    if (lost > 0.5) break;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "--shape") == 0) {
    shape();
    return 0;
  }
  if (argc > 1 && std::strcmp(argv[1], "--sway") == 0) {
    sway();
    return 0;
  }
  if (argc > 1) {
    std::fprintf(stderr, "usage: %s [--shape | --sway] > towers.csv\n", argv[0]);
    return 2;
  }
  const int heights[] = {10, 12, 14, 16, 18, 20, 25, 30, 40};
  std::printf("configuration,boxes,stood,fell_at_s,top_drift_m,height_lost_m,ms_per_frame\n");
  for (const int iterations : {10, 20, 40, 80})
    for (const int n : heights) {
      world<awake_config> w(in_parts(1, iterations));
      print("sequential_impulse 1x" + std::to_string(iterations), n, run(w, n, 1));
    }
  for (const int steps : {2, 4, 10, 20})
    for (const int n : heights) {
      world<awake_config> w(in_parts(1, 20 / steps));
      print("sequential_impulse " + std::to_string(steps) + "x" + std::to_string(20 / steps) + " world steps", n,
            run(w, n, steps));
    }
  for (const auto& [parts, sweeps] : {std::pair{2, 10}, std::pair{4, 5}, std::pair{4, 8}, std::pair{8, 4}})
    for (const int n : heights) {
      world<awake_config> w(in_parts(parts, sweeps));
      print("sequential_impulse " + std::to_string(parts) + " parts x" + std::to_string(sweeps), n, run(w, n, 1));
    }
  for (const int substeps : {4, 16})
    for (const int n : heights) {
      world<soft_config>::settings_type s;
      s.solver.substeps = substeps;
      world<soft_config> w(s);
      print("soft_step substeps=" + std::to_string(substeps), n, run(w, n, 1));
    }
  return 0;
}
