// bench/joints — the joint grid, Box2D's joint_grid benchmark in 3D, on
// impulse's sequential_impulse and soft_step solvers and on Bullet, timed in
// the same run, each with how well it holds its joints.
//
// The scene, exactly (so that another engine can be run on it):
// - N × N spheres (N = 100: 10 000 bodies), radius 0.4, mass 1, at
//   (c, −r, 0) m for column c and row r in 0..N−1; in row 0 the seven
//   columns N/2 − 3 … N/2 + 3 are static, the rest dynamic.
// - A ball joint from each body to the one above it (row r − 1) and to the
//   one on its left (column c − 1), anchored midway between their centres:
//   2·N·(N − 1) joints (19 800). Joined bodies do not collide; the others
//   do (friction 0.6, restitution 0).
// - Gravity (0, −9.81, 0), dt = 1/60, no sleeping, no damping; 300 steps.
// Measured: ms/step (median of the last 150 steps), the largest gap between
// a joint's two anchors at the end, and the lowest body at the end.
//
// Bullet: btDiscreteDynamicsWorld out of the box (10 iterations, split
// impulse, ERP 0.2; bench/scenes/bullet_engine.hpp says more), each joint a
// btPoint2PointConstraint added with collisions between its bodies
// disabled. impulse: its defaults (20 iterations; soft_step 4 substeps).
//
// Usage: joints [--n N] [--steps S] [--runs R] [--engine impulse|soft_step|bullet]...
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "impulse/world.hpp"

#ifdef IMPULSE_BENCH_HAVE_BULLET
#include <btBulletDynamicsCommon.h>
#endif

namespace {

struct grid_spec {
  int n = 100;
  int steps = 300;
  static constexpr double radius = 0.4, dt = 1.0 / 60;
  [[nodiscard]] bool is_static(int row, int column) const noexcept {
    return row == 0 && column >= n / 2 - 3 && column <= n / 2 + 3;
  }
};

struct result {
  double ms_per_step = 0;  ///< median of the last half of the steps
  double worst_gap = 0;    ///< m, at the end
  double lowest = 0;       ///< m, the lowest body's centre at the end
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

template <class Step>
std::vector<double> time_steps(int steps, Step&& step) {
  std::vector<double> ms;
  for (int i = 0; i < steps; ++i) {
    const auto start = std::chrono::steady_clock::now();
    step();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  return std::vector<double>(ms.begin() + steps / 2, ms.end());
}

template <class Solver>
struct awake_config : impulse::default_config {
  using solver = Solver;
  static constexpr bool sleeping = false;
};

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
  result out;
  out.ms_per_step = median(time_steps(spec.steps, [&] { w.step(T(grid_spec::dt)); }));
  for (const impulse::joint_id j : joints) out.worst_gap = std::max(out.worst_gap, double(w.joint_separation(j)));
  out.lowest = 1e9;
  for (const impulse::body_id b : bodies) out.lowest = std::min(out.lowest, double(w.body(b).position.y));
  return out;
}

#ifdef IMPULSE_BENCH_HAVE_BULLET
result run_bullet(const grid_spec& spec) {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  btDbvtBroadphase broad_phase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world(&dispatcher, &broad_phase, &solver, &configuration);
  world.setGravity(btVector3(0, btScalar(-9.81), 0));
  btSphereShape shape{btScalar(grid_spec::radius)};
  btVector3 inertia(0, 0, 0);
  shape.calculateLocalInertia(1, inertia);
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<std::unique_ptr<btPoint2PointConstraint>> joints;
  const auto join = [&](btRigidBody& a, btRigidBody& b, const btVector3& anchor) {
    joints.push_back(std::make_unique<btPoint2PointConstraint>(
        a, b, a.getWorldTransform().inverse() * anchor, b.getWorldTransform().inverse() * anchor));
    world.addConstraint(joints.back().get(), true);
  };
  for (int row = 0; row < spec.n; ++row)
    for (int column = 0; column < spec.n; ++column) {
      const bool fixed = spec.is_static(row, column);
      btRigidBody::btRigidBodyConstructionInfo info(fixed ? 0 : 1, nullptr, &shape,
                                                   fixed ? btVector3(0, 0, 0) : inertia);
      info.m_startWorldTransform.setIdentity();
      info.m_startWorldTransform.setOrigin(btVector3(btScalar(column), btScalar(-row), 0));
      // sqrt(0.6): Bullet multiplies the pair's values (bench/scenes/bullet_engine.hpp).
      info.m_friction = btScalar(std::sqrt(0.6));
      bodies.push_back(std::make_unique<btRigidBody>(info));
      bodies.back()->setActivationState(DISABLE_DEACTIVATION);
      world.addRigidBody(bodies.back().get());
      btRigidBody& self = *bodies.back();
      if (row > 0)
        join(*bodies[std::size_t((row - 1) * spec.n + column)], self,
             btVector3(btScalar(column), btScalar(-row + 0.5), 0));
      if (column > 0 && !(fixed && spec.is_static(row, column - 1)))
        join(*bodies[bodies.size() - 2], self, btVector3(btScalar(column - 0.5), btScalar(-row), 0));
    }
  result out;
  out.ms_per_step = median(time_steps(spec.steps, [&] { world.stepSimulation(btScalar(grid_spec::dt), 0); }));
  for (const auto& j : joints) {
    const btVector3 a = j->getRigidBodyA().getWorldTransform() * j->getPivotInA();
    const btVector3 b = j->getRigidBodyB().getWorldTransform() * j->getPivotInB();
    out.worst_gap = std::max(out.worst_gap, double((a - b).length()));
  }
  out.lowest = 1e9;
  for (const auto& b : bodies) out.lowest = std::min(out.lowest, double(b->getWorldTransform().getOrigin().y()));
  for (const auto& j : joints) world.removeConstraint(j.get());
  for (const auto& b : bodies) world.removeRigidBody(b.get());
  return out;
}
#endif

}  // namespace

int main(int argc, char** argv) {
  grid_spec spec;
  int runs = 1;
  std::vector<std::string> engines;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--n" && has_value) {
      spec.n = std::atoi(argv[++i]);
    } else if (arg == "--steps" && has_value) {
      spec.steps = std::atoi(argv[++i]);
    } else if (arg == "--runs" && has_value) {
      runs = std::atoi(argv[++i]);
    } else if (arg == "--engine" && has_value) {
      engines.push_back(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: joints [--n N] [--steps S] [--runs R] [--engine impulse|soft_step|bullet]...\n");
      return 2;
    }
  }
  if (spec.n < 8 || spec.steps < 2 || runs < 1) {
    std::fprintf(stderr, "joints: --n must be >= 8, --steps >= 2, --runs >= 1\n");
    return 2;
  }
  if (engines.empty()) {
    engines = {"impulse", "soft_step"};
#ifdef IMPULSE_BENCH_HAVE_BULLET
    engines.push_back("bullet");
#endif
  }
  std::printf("joint_grid %dx%d, %d steps, %d run(s); ms/step is the median of the last %d steps\n", spec.n, spec.n,
              spec.steps, runs, spec.steps - spec.steps / 2);
  std::printf("%-10s %4s %10s %14s %10s\n", "engine", "run", "ms/step", "worst gap (m)", "lowest y");
  for (int run = 1; run <= runs; ++run)
    for (const std::string& engine : engines) {
      result r;
      if (engine == "impulse") {
        r = run_impulse<impulse::solver::sequential_impulse>(spec);
      } else if (engine == "soft_step") {
        r = run_impulse<impulse::solver::soft_step>(spec);
#ifdef IMPULSE_BENCH_HAVE_BULLET
      } else if (engine == "bullet") {
        r = run_bullet(spec);
#endif
      } else {
        std::fprintf(stderr, "joints: no engine %s in this build\n", engine.c_str());
        return 2;
      }
      std::printf("%-10s %4d %10.3f %14.5f %10.3f\n", engine.c_str(), run, r.ms_per_step, r.worst_gap, r.lowest);
      std::fflush(stdout);
    }
}
