// bench/scenes/run.hpp — one engine's run of one scene (run_scene), and the
// entries of main.cpp's engine list. Shared by main.cpp (impulse's entries)
// and peers.cpp (the peers'), which is compiled in a target of its own: the
// peers' flags and headers stay out of main.cpp, whose objects are then the
// same with and without the peers installed.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine.hpp"
#include "metrics.hpp"
#include "scene_spec.hpp"

namespace bench::scenes {

struct scene_result {
  std::string config;
  double ms_per_step_median = 0;
  std::vector<metric_value> metrics;
  std::uint64_t final_bits = 0;  ///< FNV-1a over every body's final position and orientation
  bool profiled = false;         ///< whether stage_ms holds the engine's stages
  double stage_ms[stage_count] = {};  ///< each stage's mean over the timed window
};

inline std::uint64_t bits_of(std::span<const body_state> states) {
  std::uint64_t h = 1469598103934665603ull;
  for (const body_state& b : states)
    for (const double x : {b.position.x, b.position.y, b.position.z, b.orientation.w, b.orientation.x,
                           b.orientation.y, b.orientation.z}) {
      unsigned char bytes[sizeof x];
      std::memcpy(bytes, &x, sizeof x);
      for (const unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
    }
  return h;
}

template <scene_engine E>
scene_result run_scene(const scene_spec& spec) {
  E engine;
  engine.build(spec);
  // An _asleep scene settles first, untimed (scene_spec::settle_limit).
  int settled = 0;
  const auto all_asleep = [&] {
    for (const body_state& b : engine.states())
      if (b.awake) return false;
    return true;
  };
  if (spec.settle_limit > 0)
    while (settled < spec.settle_limit && !all_asleep()) engine.step(), ++settled;
  metric_recorder recorder{spec};
  std::vector<double> step_ms;
  step_ms.reserve(static_cast<std::size_t>(spec.steps));
  std::vector<stage_times> stages;
  for (int step = 1; step <= spec.steps; ++step) {
    const auto start = std::chrono::steady_clock::now();
    engine.step();
    const auto stop = std::chrono::steady_clock::now();
    step_ms.push_back(std::chrono::duration<double, std::milli>(stop - start).count());
    if constexpr (profiled_engine<E>) stages.push_back(engine.profile());
    if (recorder.wants(step)) recorder.observe(step, engine.states());
  }
  const std::size_t window = timing_window(spec.steps);
  scene_result result{engine.config(), median_of_last(step_ms, window), recorder.results(), bits_of(engine.states())};
  // Means, not medians, over the same window: they add up to the step.
  if constexpr (profiled_engine<E>) {
    result.profiled = true;
    for (std::size_t s = stages.size() - window; s < stages.size(); ++s)
      for (int k = 0; k < stage_count; ++k) result.stage_ms[k] += stages[s].ms[k] / double(window);
  }
  if (spec.settle_limit > 0) result.metrics.push_back({"steps_to_sleep", double(settled)});
  return result;
}

struct engine_entry {
  std::string_view name;
  scene_result (*run)(const scene_spec&);
  std::string (*config)();  ///< a fresh engine's config column
};

template <scene_engine E>
engine_entry entry() {
  return {E::name, &run_scene<E>, [] { return E{}.config(); }};
}

/// The peers compiled in (peers.cpp): Bullet's and ODE's entries, when the
/// build found them.
std::vector<engine_entry> peer_engines();

}  // namespace bench::scenes
