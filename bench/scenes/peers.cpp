// bench/scenes/peers.cpp — the peer engines' entries (run.hpp): Bullet's
// and ODE's adapters, each compiled in when the build found it
// (IMPULSE_BENCH_HAVE_BULLET, IMPULSE_BENCH_HAVE_ODE). Its own target in
// CMakeLists.txt, so that only this file sees the peers' headers and flags.
#include <vector>

#include "run.hpp"

#ifdef IMPULSE_BENCH_HAVE_BULLET
#include "bullet_engine.hpp"
#endif
#ifdef IMPULSE_BENCH_HAVE_ODE
#include "ode_engine.hpp"
#endif

std::vector<bench::scenes::engine_entry> bench::scenes::peer_engines() {
  std::vector<engine_entry> list;
#ifdef IMPULSE_BENCH_HAVE_BULLET
  list.push_back(entry<bullet_engine>());
#endif
#ifdef IMPULSE_BENCH_HAVE_ODE
  list.push_back(entry<ode_engine>());
#endif
  return list;
}
