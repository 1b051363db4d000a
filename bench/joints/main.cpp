// bench/joints — the joint grid, Box2D's joint_grid benchmark in 3D, on
// impulse's sequential_impulse and soft_step solvers and on Bullet, timed in
// the same run, each with how well it holds its joints.
//
// The scene, exactly (so that another engine can be run on it):
// - N × N spheres (N = 100: 10 000 bodies), radius 0.4, mass 1, at
//   (c, −r, 0) m for column c and row r in 0..N−1; in row 0 the seven
//   columns N/2 − 3 … N/2 + 3 are static, the rest dynamic.
// - A ball joint from each body to the one above it (row r − 1) and to the
//   one on its left (column c − 1), anchored midway between their centers:
//   2·N·(N − 1) joints (19 800). Joined bodies do not collide; the others
//   do (friction 0.6, restitution 0).
// - Gravity (0, −9.81, 0), dt = 1/60, no sleeping, no damping; 300 steps.
// Measured: ms/step (median of the last 150 steps), the largest gap between
// a joint's two anchors at the end, the lowest body at the end, and the
// bodies still moving faster than 0.1 m/s.
//
// The ragdoll pile: ragdoll_pile.hpp.
//
// Bullet: btDiscreteDynamicsWorld out of the box (10 iterations, split
// impulse, ERP 0.2; bench/scenes/bullet_engine.hpp says more), each joint a
// btPoint2PointConstraint added with collisions between its bodies
// disabled. impulse: its defaults (4 parts of 8 iterations; soft_step 4 substeps).
//
// Usage: joints [--scene grid|ragdolls]... [--n N] [--steps S] [--runs R]
//               [--engine impulse|soft_step|impulse_gs|soft_step_gs|bullet]...
// The _gs engines solve the ragdolls' joint trees joint by joint
// (solver_settings::exact_joint_trees false).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "impulse/world.hpp"
#include "measure.hpp"
#include "peers.hpp"
#include "ragdoll_pile.hpp"

namespace {

using joints_bench::awake_config;
using joints_bench::grid_spec;
using joints_bench::result;


template <class Solver>
result run_impulse(const grid_spec& spec) {
  using config = awake_config<Solver>;
  using T = float;
  impulse::world<config> w;
  std::vector<impulse::body_id> bodies;
  std::vector<impulse::joint_id> joints;
  for (int row = 0; row < spec.n; ++row)
    for (int column = 0; column < spec.n; ++column) {
      impulse::body_def<T> d;
      d.type = spec.is_static(row, column) ? impulse::body_type::static_body : impulse::body_type::dynamic;
      d.pose.position = {T(column), T(-row), 0};
      d.mass = 1;
      d.material.friction = T(0.6);
      bodies.push_back(w.create_body(d, impulse::sphere<T>::make(T(grid_spec::radius))));
      const impulse::body_id self = bodies.back();
      // A joint needs a dynamic end: two of the static anchors side by side
      // are not joined.
      if (row > 0)
        joints.push_back(w.create_joint(impulse::joint_def<T>::ball(
            bodies[std::size_t((row - 1) * spec.n + column)], self, {T(column), T(-row) + T(0.5), 0})));
      if (column > 0 && !(spec.is_static(row, column) && spec.is_static(row, column - 1)))
        joints.push_back(w.create_joint(impulse::joint_def<T>::ball(bodies[bodies.size() - 2], self,
                                                                   {T(column) - T(0.5), T(-row), 0})));
    }
  return joints_bench::run_impulse_world(w, bodies, joints, spec.steps, grid_spec::dt);
}


}  // namespace

int main(int argc, char** argv) {
  grid_spec grid;
  joints_bench::ragdoll_pile_spec pile;
  int runs = 1;
  std::vector<std::string> engines, scenes;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--n" && has_value) {
      grid.n = std::atoi(argv[++i]);
    } else if (arg == "--steps" && has_value) {
      grid.steps = pile.steps = std::atoi(argv[++i]);
    } else if (arg == "--runs" && has_value) {
      runs = std::atoi(argv[++i]);
    } else if (arg == "--engine" && has_value) {
      engines.push_back(argv[++i]);
    } else if (arg == "--scene" && has_value) {
      scenes.push_back(argv[++i]);
    } else {
      std::fprintf(stderr,
                   "usage: joints [--scene grid|ragdolls]... [--n N] [--steps S] [--runs R] "
                   "[--engine impulse|soft_step|impulse_gs|soft_step_gs|bullet]...\n");
      return 2;
    }
  }
  if (grid.n < 8 || grid.steps < 2 || runs < 1) {
    std::fprintf(stderr, "joints: --n must be >= 8, --steps >= 2, --runs >= 1\n");
    return 2;
  }
  if (engines.empty()) {
    engines = {"impulse", "soft_step", "impulse_gs", "soft_step_gs"};
    if (joints_bench::have_bullet()) engines.push_back("bullet");
  }
  if (scenes.empty()) scenes = {"grid", "ragdolls"};
  for (const std::string& scene : scenes) {
    const bool is_grid = scene == "grid";
    if (!is_grid && scene != "ragdolls") {
      std::fprintf(stderr, "joints: no scene %s (grid, ragdolls)\n", scene.c_str());
      return 2;
    }
    const int steps = is_grid ? grid.steps : pile.steps;
    if (is_grid)
      std::printf("joint_grid %dx%d", grid.n, grid.n);
    else
      std::printf("ragdoll_pile %d ragdolls", pile.columns * pile.columns * pile.layers);
    std::printf(", %d steps, %d run(s); ms/step is the median of the last %d steps\n", steps, runs, steps - steps / 2);
    std::printf("%-12s %4s %10s %14s %10s %7s\n", "engine", "run", "ms/step", "worst gap (m)", "lowest y", "moving");
    for (int run = 1; run <= runs; ++run)
      for (const std::string& engine : engines) {
        result r;
        const bool by_joint = engine.ends_with("_gs");
        // The grid's joints form loops, which are always solved joint by
        // joint: its _gs rows would repeat the others.
        if (by_joint && is_grid) continue;
        if (engine == "impulse_gs") {
          r = joints_bench::run_ragdolls_impulse<impulse::solver::sequential_impulse>(pile, false);
        } else if (engine == "soft_step_gs") {
          r = joints_bench::run_ragdolls_impulse<impulse::solver::soft_step>(pile, false);
        } else if (engine == "impulse") {
          r = is_grid ? run_impulse<impulse::solver::sequential_impulse>(grid)
                      : joints_bench::run_ragdolls_impulse<impulse::solver::sequential_impulse>(pile);
        } else if (engine == "soft_step") {
          r = is_grid ? run_impulse<impulse::solver::soft_step>(grid)
                      : joints_bench::run_ragdolls_impulse<impulse::solver::soft_step>(pile);
        } else if (engine == "bullet" && joints_bench::have_bullet()) {
          r = *(is_grid ? joints_bench::run_bullet(grid) : joints_bench::run_bullet(pile));
        } else {
          std::fprintf(stderr, "joints: no engine %s in this build\n", engine.c_str());
          return 2;
        }
        std::printf("%-12s %4d %10.3f %14.5f %10.3f %7d\n", engine.c_str(), run, r.ms_per_step, r.worst_gap, r.lowest,
                    r.moving);
        std::fflush(stdout);
      }
  }
}
