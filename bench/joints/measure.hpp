// bench/joints/measure.hpp — what the joint benchmarks share: an awake
// world configuration, and one run of a built scene, timed and measured the
// same way on impulse and on Bullet.
#pragma once

#include <algorithm>
#include <chrono>
#include <memory>
#include <vector>

#include "impulse/world.hpp"

#ifdef IMPULSE_BENCH_HAVE_BULLET
#include <btBulletDynamicsCommon.h>
#endif

namespace joints_bench {

struct result {
  double ms_per_step = 0;  ///< median of the last half of the steps
  double worst_gap = 0;    ///< m, the largest gap between a joint's anchors at the end
  double lowest = 0;       ///< m, the lowest body's center at the end
  int moving = 0;          ///< bodies faster than 0.1 m/s at the end
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

#ifdef IMPULSE_BENCH_HAVE_BULLET
/// btDiscreteDynamicsWorld out of the box (bench/scenes/bullet_engine.hpp
/// says what that is), owning the bodies and joints a scene adds.
struct bullet_world {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broad_phase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broad_phase, &solver, &configuration};
  std::vector<std::unique_ptr<btRigidBody>> bodies, statics;  ///< measured, and not
  std::vector<std::unique_ptr<btTypedConstraint>> joints;

  bullet_world() { world.setGravity(btVector3(0, btScalar(-9.81), 0)); }
  bullet_world(const bullet_world&) = delete;
  bullet_world& operator=(const bullet_world&) = delete;
  ~bullet_world() {
    for (const auto& j : joints) world.removeConstraint(j.get());
    for (const auto& b : bodies) world.removeRigidBody(b.get());
    for (const auto& b : statics) world.removeRigidBody(b.get());
  }

  /// A static body that takes no part in the measures (the ground).
  void add_static(const btRigidBody::btRigidBodyConstructionInfo& info) {
    statics.push_back(std::make_unique<btRigidBody>(info));
    world.addRigidBody(statics.back().get());
  }

  btRigidBody& add_body(const btRigidBody::btRigidBodyConstructionInfo& info) {
    bodies.push_back(std::make_unique<btRigidBody>(info));
    bodies.back()->setActivationState(DISABLE_DEACTIVATION);
    world.addRigidBody(bodies.back().get());
    return *bodies.back();
  }
  /// Adds a joint; the bodies it joins do not collide.
  void add_joint(std::unique_ptr<btTypedConstraint> joint) {
    joints.push_back(std::move(joint));
    world.addConstraint(joints.back().get(), true);
  }

  /// Steps it (one internal step of dt each) and measures the bodies added.
  result run(int steps, double dt) {
    result out;
    out.ms_per_step = median_step_ms(steps, [&] { world.stepSimulation(btScalar(dt), 0); });
    for (const auto& c : joints) {
      btVector3 a, b;
      if (c->getConstraintType() == HINGE_CONSTRAINT_TYPE) {
        const auto* hinge = static_cast<const btHingeConstraint*>(c.get());
        a = c->getRigidBodyA().getWorldTransform() * hinge->getAFrame().getOrigin();
        b = c->getRigidBodyB().getWorldTransform() * hinge->getBFrame().getOrigin();
      } else {
        const auto* ball = static_cast<const btPoint2PointConstraint*>(c.get());
        a = c->getRigidBodyA().getWorldTransform() * ball->getPivotInA();
        b = c->getRigidBodyB().getWorldTransform() * ball->getPivotInB();
      }
      out.worst_gap = std::max(out.worst_gap, double((a - b).length()));
    }
    out.lowest = 1e9;
    for (const auto& b : bodies) {
      out.lowest = std::min(out.lowest, double(b->getWorldTransform().getOrigin().y()));
      out.moving += b->getLinearVelocity().length() > btScalar(0.1) ? 1 : 0;
    }
    return out;
  }
};
#endif

}  // namespace joints_bench
