// bench/scenes: the standard rigid-body scenes (docs/standard_scenes.md,
// scene_spec.hpp) on every engine compiled in, judged by the same metrics (metrics.hpp).
//
//   scenes [--scene NAME]... [--engine NAME]... [--config TEXT]... [--threads N,M,...] [--csv FILE]
//
// prints CSV on stdout, one row per metric:
//
//   engine,config,scene,ms_per_step_median,metric,value
//
// ms_per_step_median is the median time of the engine's step call
// (steady_clock around step() alone: collision detection, solving and
// integration, not the reading of states) over the last 300 steps, or the
// last half of a shorter run, repeated on each of the scene's rows. Every
// scene is built fresh for each engine. --csv FILE writes the same CSV to
// FILE too; progress goes to stderr.
//
// --threads runs impulse's entries once per worker count listed, on an
// impulse::thread_pool of that many workers (1: the calling thread alone),
// the peers once. Each of those runs adds two rows: speedup, the first
// count's median step time over this one's (in the same run, so the
// machine's drift cancels), and same_bits, 1 when every body's final
// position and orientation equal the first count's to the bit. impulse's
// runs add, per stage of its step (world::last_step_profile: broad,
// narrow, prepare, solve, integrate, continuous, sleep), ms_STAGE, the
// stage's mean time over the same window, and speedup_STAGE. A run on W > 1
// workers adds independent_speedup: W one-worker runs of the scene at once,
// each on a thread of its own, W × the first count's step time over
// theirs; the speed-up the machine gives work that shares nothing, which
// is the ceiling to read `speedup` against (on a shared virtual machine,
// seldom W). It also adds core_round_trip_ns and core_round_trip_ns_after:
// the time a cache line takes to go from the calling thread to another
// and back, measured just before and just after the W-worker run. Every
// loop spread across workers pays it, many times over, and a host that
// moves a guest's cores between last-level caches changes it by several
// times from one minute to the next.
//
// An engine is a type modelling scene_engine (engine.hpp): to add one,
// include its header and add it to engines() below (a peer: to peers.cpp). impulse is always
// compiled in, once per set of policies compared (its rows tell them apart
// by the config column); Bullet and ODE when the build found them.
// --engine NAME selects every entry of that name: `--engine impulse` runs
// all of impulse's. --config TEXT keeps the entries whose config (as a
// fresh engine reports it) contains TEXT: `--config sweep_and_prune`.
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "engine.hpp"
#include "impulse/thread_pool.hpp"
#include "impulse_engine.hpp"
#include "metrics.hpp"
#include "run.hpp"
#include "scene_spec.hpp"

namespace {

using namespace bench::scenes;

// impulse's policy sets, in float like the peers: the default (dynamic
// BVH, sequential impulses), every other broad phase with the default
// solver, and the other solver with the default broad phase. Sleeping is
// left out: the adapter sets it per scene.
template <class BroadPhase, class Solver = impulse::solver::sequential_impulse>
struct impulse_set : impulse::default_config {
  using broadphase = BroadPhase;
  using solver = Solver;
  using scalar = float;
};
using impulse_dynamic_bvh = impulse_set<impulse::broadphase::dynamic_bvh>;
using impulse_sweep_and_prune = impulse_set<impulse::broadphase::sweep_and_prune>;
using impulse_spatial_hash = impulse_set<impulse::broadphase::spatial_hash>;
using impulse_octree = impulse_set<impulse::broadphase::octree>;
using impulse_brute_force = impulse_set<impulse::broadphase::brute_force>;
using impulse_soft_step = impulse_set<impulse::broadphase::dynamic_bvh, impulse::solver::soft_step>;
#if defined(IMPULSE_BENCH_LOCKSTEP)
/// The default policies with cross_platform_determinism: only in
/// scenes_lockstep, built with impulse::deterministic's flags (no fused
/// multiply-adds), where it is the one engine; its cost is read beside
/// `scenes --config dynamic_bvh` (docs/world.md, "Lockstep determinism").
struct impulse_lockstep : impulse_dynamic_bvh {
  static constexpr bool cross_platform_determinism = true;
};
#endif

std::vector<engine_entry> engines() {
  std::vector<engine_entry> list;
#if defined(IMPULSE_BENCH_LOCKSTEP)
  list.push_back(entry<impulse_engine<impulse_lockstep>>());
#else
  list.push_back(entry<impulse_engine<impulse_dynamic_bvh>>());
  list.push_back(entry<impulse_engine<impulse_sweep_and_prune>>());
  list.push_back(entry<impulse_engine<impulse_spatial_hash>>());
  list.push_back(entry<impulse_engine<impulse_octree>>());
  list.push_back(entry<impulse_engine<impulse_brute_force>>());
  list.push_back(entry<impulse_engine<impulse_soft_step>>());
  for (const engine_entry& peer : peer_engines()) list.push_back(peer);
#endif
  return list;
}

/// The machine's own ceiling for `copies` workers on a scene: that many
/// one-worker runs of it at once, each on a thread of its own, sharing
/// nothing. Returns their mean median step time (ms), or 0 if a run
/// failed. `copies` × one run alone ÷ this is the speed-up `copies` cores
/// give work that shares nothing: on a shared virtual machine, seldom
/// `copies`.
double ms_per_step_side_by_side(const engine_entry& e, const scene_spec& spec, std::uint32_t copies) {
  std::fprintf(stderr, "%.*s %s: %u one-worker runs side by side ... ", int(e.name.size()), e.name.data(),
               spec.name.c_str(), copies);
  std::vector<double> ms(copies, 0.0);
  std::vector<std::thread> runs;
  for (std::uint32_t c = 0; c < copies; ++c)
    runs.emplace_back([&, c] {
      try {
        ms[c] = e.run(spec).ms_per_step_median;
      } catch (const std::exception&) {
        ms[c] = 0;
      }
    });
  double sum = 0;
  bool failed = false;
  for (std::uint32_t c = 0; c < copies; ++c) {
    runs[c].join();
    sum += ms[c];
    failed = failed || ms[c] <= 0;
  }
  std::fprintf(stderr, failed ? "failed\n" : "%.4f ms/step\n", sum / copies);
  return failed ? 0.0 : sum / copies;
}

/// The round trip of a cache line between the calling thread and a thread
/// of its own (ns): up to 100 000 hand-offs of a counter, each side waiting
/// for the other's write, or as many as fit in 50 ms (on a loaded machine
/// a hand-off can wait out a time slice). Run only with at least two
/// hardware threads.
double core_round_trip_ns() {
  constexpr long most = 100000, stop = -1;
  alignas(64) std::atomic<long> turn{0};
  std::thread other([&turn] {
    for (long next = 1;; next += 2) {
      long seen = turn.load(std::memory_order_acquire);
      while (seen != next && seen != stop) seen = turn.load(std::memory_order_acquire);
      if (seen == stop) return;
      turn.store(next + 1, std::memory_order_release);
    }
  });
  const auto start = std::chrono::steady_clock::now();
  const auto deadline = start + std::chrono::milliseconds(50);
  long done = 0;
  while (done < most) {
    turn.store(2 * done + 1, std::memory_order_release);
    while (turn.load(std::memory_order_acquire) != 2 * done + 2) {
    }
    ++done;
    if (done % 64 == 0 && std::chrono::steady_clock::now() > deadline) break;
  }
  const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
  turn.store(stop, std::memory_order_release);
  other.join();
  return ns / double(done);
}

/// Six significant digits: more than any of these figures can be trusted to.
std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

bool contains(const std::vector<std::string_view>& list, std::string_view s) {
  for (std::string_view x : list)
    if (x == s) return true;
  return false;
}

/// "1,2,4" as {1, 2, 4}; empty if any count is not between 1 and 256.
std::vector<std::uint32_t> counts_of(std::string_view list) {
  std::vector<std::uint32_t> counts;
  while (!list.empty()) {
    const std::size_t comma = list.find(',');
    const std::string item(list.substr(0, comma));
    char* end = nullptr;
    const unsigned long n = std::strtoul(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || n < 1 || n > impulse::thread_pool::max_workers) return {};
    counts.push_back(std::uint32_t(n));
    list = comma == std::string_view::npos ? std::string_view() : list.substr(comma + 1);
  }
  return counts;
}

int usage(const char* program) {
  std::fprintf(stderr,
               "usage: %s [--scene NAME]... [--engine NAME]... [--config TEXT]... [--threads N,M,...] [--csv FILE]\n"
               "scenes:",
               program);
  for (std::string_view s : scene_names()) std::fprintf(stderr, " %.*s", int(s.size()), s.data());
  std::fprintf(stderr, "\nengines:");
  std::string_view last;  // impulse's entries share a name: list it once
  for (const engine_entry& e : engines()) {
    if (e.name != last) std::fprintf(stderr, " %.*s", int(e.name.size()), e.name.data());
    last = e.name;
  }
  std::fprintf(stderr, "\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string_view> scenes, engine_names, config_texts;
  const char* csv_path = nullptr;
  std::vector<std::uint32_t> worker_counts;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if ((arg == "--scene" || arg == "--engine" || arg == "--config" || arg == "--csv" || arg == "--threads") &&
        i + 1 < argc) {
      const char* value = argv[++i];
      if (arg == "--scene") scenes.emplace_back(value);
      else if (arg == "--engine") engine_names.emplace_back(value);
      else if (arg == "--config") config_texts.emplace_back(value);
      else if (arg == "--threads") worker_counts = counts_of(value);
      else csv_path = value;
      if (arg == "--threads" && worker_counts.empty()) return usage(argv[0]);
    } else {
      return usage(argv[0]);
    }
  }
  if (worker_counts.empty()) worker_counts.push_back(1);
  for (std::string_view s : scenes)
    if (!contains(scene_names(), s)) {
      std::fprintf(stderr, "unknown scene: %.*s\n", int(s.size()), s.data());
      return usage(argv[0]);
    }
  std::vector<engine_entry> selected;
  std::vector<std::string_view> known;
  for (const engine_entry& e : engines()) {
    known.push_back(e.name);
    if (!engine_names.empty() && !contains(engine_names, e.name)) continue;
    const std::string config = e.config();
    bool wanted = config_texts.empty();
    for (std::string_view text : config_texts) wanted = wanted || config.find(text) != std::string::npos;
    if (wanted) selected.push_back(e);
  }
  for (std::string_view n : engine_names)
    if (!contains(known, n)) {
      std::fprintf(stderr, "no such engine compiled in: %.*s\n", int(n.size()), n.data());
      return usage(argv[0]);
    }
  if (selected.empty()) {
    std::fprintf(stderr, "no engine entry matches the --engine and --config given\n");
    return usage(argv[0]);
  }
  if (scenes.empty()) scenes = scene_names();

  std::FILE* csv = nullptr;
  if (csv_path != nullptr && (csv = std::fopen(csv_path, "w")) == nullptr) {
    std::fprintf(stderr, "cannot write %s: %s\n", csv_path, std::strerror(errno));
    return 1;
  }
  auto emit = [csv](const std::string& line) {
    std::fputs(line.c_str(), stdout);
    if (csv != nullptr) std::fputs(line.c_str(), csv);
  };
  emit("engine,config,scene,ms_per_step_median,metric,value\n");
  std::fflush(stdout);

  int status = 0;
  for (std::string_view scene_name : scenes) {
    const scene_spec spec = make_scene(scene_name);
    for (const engine_entry& e : selected) {
      const bool threaded = e.name == impulse_engine<impulse_dynamic_bvh>::name && worker_counts.size() > 1;
      scene_result first;
      const bool probe_cores = threaded && std::thread::hardware_concurrency() >= 2;
      for (std::size_t k = 0; k < (threaded ? worker_counts.size() : 1); ++k) {
        const double trip_before = probe_cores && worker_counts[k] > 1 ? core_round_trip_ns() : 0.0;
        std::unique_ptr<impulse::thread_pool> pool;
        impulse::task_system tasks;
        if (worker_counts[k] > 1) {
          pool = std::make_unique<impulse::thread_pool>(worker_counts[k]);
          tasks = pool->tasks();
        }
        impulse_workers = &tasks;
        std::fprintf(stderr, "%.*s %s: %zu bodies, %d steps ... ", int(e.name.size()), e.name.data(),
                     spec.name.c_str(), spec.bodies.size(), spec.steps);
        const auto start = std::chrono::steady_clock::now();
        try {
          scene_result r = e.run(spec);
          const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          // The config too: impulse's entries share a name.
          std::fprintf(stderr, "%.4f ms/step (%.1f s) [%s]\n", r.ms_per_step_median, seconds, r.config.c_str());
          if (threaded) {
            if (k == 0) first = r;
            r.metrics.push_back({"speedup", first.ms_per_step_median / r.ms_per_step_median});
            r.metrics.push_back({"same_bits", r.final_bits == first.final_bits ? 1.0 : 0.0});
            for (int s = 0; r.profiled && s < stage_count; ++s) {
              const std::string stage = stage_names[s];
              r.metrics.push_back({"ms_" + stage, r.stage_ms[s]});
              if (r.stage_ms[s] > 0) r.metrics.push_back({"speedup_" + stage, first.stage_ms[s] / r.stage_ms[s]});
            }
            if (trip_before > 0) {
              impulse_workers = nullptr;
              pool.reset();  // its threads out of the probe's way
              r.metrics.push_back({"core_round_trip_ns", trip_before});
              r.metrics.push_back({"core_round_trip_ns_after", core_round_trip_ns()});
            }
            if (worker_counts[k] > 1) {
              impulse_workers = nullptr;
              const double together = ms_per_step_side_by_side(e, spec, worker_counts[k]);
              if (together > 0)
                r.metrics.push_back(
                    {"independent_speedup", double(worker_counts[k]) * first.ms_per_step_median / together});
            }
          }
          for (const metric_value& m : r.metrics)
            emit(std::string(e.name) + ',' + r.config + ',' + spec.name + ',' + number(r.ms_per_step_median) + ',' +
                 m.name + ',' + number(m.value) + '\n');
          std::fflush(stdout);
        } catch (const std::exception& error) {
          std::fprintf(stderr, "failed: %s\n", error.what());
          status = 1;
        }
        impulse_workers = nullptr;
      }
    }
  }
  if (csv != nullptr) std::fclose(csv);
  return status;
}
