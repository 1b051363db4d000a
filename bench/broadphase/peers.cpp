// bench/broadphase/peers.cpp — Bullet's btDbvtBroadphase and btAxisSweep3
// (bullet_broad_phases.hpp) as the benchmark's peers (peers.hpp), when the
// build found Bullet (IMPULSE_BENCH_HAVE_BULLET).
#include <climits>
#include <memory>
#include <vector>

#include "peers.hpp"

#ifdef IMPULSE_BENCH_HAVE_BULLET
#include "bullet_broad_phases.hpp"
#endif

std::vector<bench::peer_broad_phase> bench::peer_broad_phases() {
  std::vector<peer_broad_phase> list;
#ifdef IMPULSE_BENCH_HAVE_BULLET
  const auto make = [](bullet_broad_phase::kind k) {
    return [k](const box& bounds, std::size_t capacity) -> std::unique_ptr<broad_phase_driver> {
      return std::make_unique<bullet_broad_phase>(k, bounds, capacity);
    };
  };
  list.push_back({"bullet_dbvt", INT_MAX, make(bullet_broad_phase::kind::dbvt)});
  // At 100 000, bt32BitAxisSweep3 takes minutes just to create the proxies
  // (each sifts in from the top of all three axes, O(n²)): it is left out
  // there.
  list.push_back({"bullet_axis_sweep", 10000, make(bullet_broad_phase::kind::axis_sweep)});
#endif
  return list;
}
