// bench/broadphase: microseconds per step of every broad phase, ours and
// Bullet's, on the same moving boxes (moving_boxes.hpp), N = 100 to 100 000.
//
// A run creates the N proxies and updates once (not timed), then times
// `steps` steps of: move every box that moved, update. us_per_step is that
// time over the steps; each figure is the median of `repeats` runs, each
// from a fresh broad phase. `pairs` is the pair count after the last step
// (Bullet's counts fat pairs; ours are exact and equal across ours, which
// the program checks, failing if they differ).
//
//   broadphase [--quick]     CSV on stdout: algorithm,distribution,n,us_per_step,pairs
//
// --quick stops at N = 10 000 and runs one repeat (a smoke test). Brute
// force runs once up to N = 10 000 and not at 100 000, where one update
// would take seconds; Bullet's axis sweep not at 100 000 either (peers.cpp).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "impulse/broadphase.hpp"
#include "moving_boxes.hpp"
#include "peers.hpp"

namespace {

using bench::distribution;

/// Ours, behind the calls the driver makes.
template <class BroadPhase>
class ours {
 public:
  void create(const bench::box& b) { ids_.push_back(bp_.create(b, ids_.size())); }
  void move(std::uint32_t i, const bench::box& b) { bp_.move(ids_[i], b); }
  void update() { bp_.update(); }
  [[nodiscard]] std::size_t pair_count() const { return bp_.pairs().size(); }

 private:
  BroadPhase bp_;
  std::vector<impulse::proxy_id> ids_;
};

struct result {
  double us_per_step;
  std::size_t pairs;
};

template <class Make>
result run_once(distribution d, int n, int steps, Make&& make) {
  bench::moving_boxes scene{d, n};
  auto bp = make(scene);
  for (const bench::box& b : scene.boxes()) bp->create(b);
  bp->update();
  double seconds = 0;
  for (int s = 0; s < steps; ++s) {
    scene.step();
    const auto start = std::chrono::steady_clock::now();
    for (const std::uint32_t i : scene.moved()) bp->move(i, scene.boxes()[i]);
    bp->update();
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return {1e6 * seconds / steps, bp->pair_count()};
}

template <class Make>
result median_run(distribution d, int n, int steps, int repeats, Make&& make) {
  std::vector<result> runs;
  for (int r = 0; r < repeats; ++r) runs.push_back(run_once(d, n, steps, make));
  std::sort(runs.begin(), runs.end(), [](const result& a, const result& b) { return a.us_per_step < b.us_per_step; });
  return runs[runs.size() / 2];
}

template <class BroadPhase>
auto make_ours() {
  return [](const bench::moving_boxes&) { return std::make_unique<ours<BroadPhase>>(); };
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const int repeats = quick ? 1 : 3;
  std::vector<int> sizes{100, 1000, 10000};
  if (!quick) sizes.push_back(100000);

  std::printf("algorithm,distribution,n,us_per_step,pairs\n");
  bool agree = true;
  for (const distribution d : {distribution::uniform, distribution::clustered, distribution::falling_pile}) {
    const int steps = d == distribution::falling_pile ? 90 : 60;
    for (const int n : sizes) {
      const auto report = [&](const char* name, const result& r) {
        std::printf("%s,%s,%d,%.2f,%zu\n", name, std::string(bench::name_of(d)).c_str(), n, r.us_per_step, r.pairs);
        std::fflush(stdout);
      };
      std::size_t exact_pairs = 0;
      const auto ours_report = [&](const char* name, const result& r) {
        report(name, r);
        if (exact_pairs == 0) exact_pairs = r.pairs;
        if (r.pairs != exact_pairs) {
          std::fprintf(stderr, "%s: %zu pairs where the others found %zu\n", name, r.pairs, exact_pairs);
          agree = false;
        }
      };
      using namespace impulse::broadphase;
      if (n <= 10000)  // one run: at N = 10 000 each update tests 5·10⁷ pairs
        ours_report("brute_force", median_run(d, n, steps, 1, make_ours<basic_brute_force<float>>()));
      ours_report("sweep_and_prune", median_run(d, n, steps, repeats, make_ours<basic_sweep_and_prune<float>>()));
      ours_report("spatial_hash", median_run(d, n, steps, repeats, make_ours<basic_spatial_hash<float>>()));
      ours_report("dynamic_bvh", median_run(d, n, steps, repeats, make_ours<basic_dynamic_bvh<float>>()));
      ours_report("octree", median_run(d, n, steps, repeats, make_ours<basic_octree<float>>()));
      for (const bench::peer_broad_phase& peer : bench::peer_broad_phases())
        if (n <= peer.max_n)
          report(peer.name, median_run(d, n, steps, repeats, [&](const bench::moving_boxes& scene) {
                   return peer.make(scene.bounds(), std::size_t(n));
                 }));
    }
  }
  if (!agree) return 1;
}
