// compare_broadphases — the same scene (examples/scenes/dominoes.json, 100
// dominoes on an arc) run once with each broad phase, chosen at compile time
// by one type in the config. Prints the median step time of each beside what
// it computed: the time the last domino toppled and the step's contact
// pairs, which must agree, since a broad phase only decides which pairs the
// narrow phase tests. The dynamic BVH's run is written to
// out/compare_broadphases.glb.
//
//   build/native/examples/compare_broadphases [scene.json]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "impulse/broadphase.hpp"
#include "impulse/io/gltf.hpp"
#include "impulse/io/scene.hpp"

namespace {

template <class BroadPhase>
struct config : impulse::default_config {
  using broadphase = BroadPhase;
};

struct outcome {
  double median_ms = 0, last_topple = -1;
  std::size_t most_pairs = 0;
  bool saved = true;
};

template <class BroadPhase>
outcome run(const impulse::io::scene<float>& scene, const char* recording_file = nullptr) {
  impulse::world<config<BroadPhase>> world;
  const impulse::io::scene_ids ids = impulse::io::add_scene(world, scene);
  impulse::io::gltf_recorder recording(world);
  const impulse::body_id last = ids.body("domino[99]");
  outcome o;
  std::vector<double> ms;
  const float dt = scene.settings.fixed_dt;
  for (int i = 0; i < int(std::lround(scene.duration / dt)); ++i) {
    const auto start = std::chrono::steady_clock::now();
    world.step(dt);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    if (recording_file && i % 4 == 3) recording.record(world);
    o.most_pairs = std::max(o.most_pairs, world.touching_pair_count());
    if (o.last_topple < 0 && impulse::rotate(world.body(last).orientation, impulse::vec3<float>{0, 1, 0}).y < 0.7071f)
      o.last_topple = double(world.time());
  }
  std::sort(ms.begin(), ms.end());
  o.median_ms = ms[ms.size() / 2];
  if (recording_file) {
    std::filesystem::create_directories("out");
    o.saved = recording.save(recording_file);
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  namespace bp = impulse::broadphase;
  const auto scene = impulse::io::read_scene<float>(argc > 1 ? argv[1] : IMPULSE_SCENES_DIR "/dominoes.json");
  const struct {
    const char* name;
    outcome result;
  } runs[] = {{"dynamic_bvh", run<bp::dynamic_bvh>(scene, "out/compare_broadphases.glb")},        {"sweep_and_prune", run<bp::sweep_and_prune>(scene)},
              {"spatial_hash", run<bp::spatial_hash>(scene)},      {"octree", run<bp::octree>(scene)},
              {"brute_force", run<bp::brute_force>(scene)}};
  std::printf("compare_broadphases: %zu bodies of %s, the same scene with each broad phase\n", scene.bodies.size(),
              scene.file.c_str());
  std::printf("  %-16s %12s %14s %18s\n", "broad phase", "median ms", "÷ dynamic_bvh", "last topples at s");
  bool agree = true;
  for (const auto& r : runs) {
    std::printf("  %-16s %12.3f %14.2f %18.3f   (at most %zu touching pairs)\n", r.name, r.result.median_ms,
                r.result.median_ms / runs[0].result.median_ms, r.result.last_topple, r.result.most_pairs);
    agree = agree && r.result.last_topple > 0 && std::abs(r.result.last_topple - runs[0].result.last_topple) < 0.05;
  }
  std::printf("  every broad phase topples the chain to the end within 0.05 s of the others: %s\n",
              agree ? "yes" : "NO");
  std::printf("  wrote out/compare_broadphases.glb (the dynamic_bvh run)\n");
  return agree && runs[0].result.saved ? 0 : 1;
}
