// bench/joints/peers.cpp — the joint grid and the ragdoll pile on Bullet
// (peers.hpp), compiled in when the build found it
// (IMPULSE_BENCH_HAVE_BULLET).
#include "peers.hpp"

#ifdef IMPULSE_BENCH_HAVE_BULLET

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <btBulletDynamicsCommon.h>

namespace joints_bench {

namespace {

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

}  // namespace

bool have_bullet() noexcept { return true; }

std::optional<result> run_bullet(const grid_spec& spec) {
  btSphereShape shape{btScalar(grid_spec::radius)};
  bullet_world w;
  btVector3 inertia(0, 0, 0);
  shape.calculateLocalInertia(1, inertia);
  const auto join = [&](btRigidBody& a, btRigidBody& b, const btVector3& anchor) {
    w.add_joint(std::make_unique<btPoint2PointConstraint>(a, b, a.getWorldTransform().inverse() * anchor,
                                                          b.getWorldTransform().inverse() * anchor));
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
      btRigidBody& self = w.add_body(info);
      if (row > 0)
        join(*w.bodies[std::size_t((row - 1) * spec.n + column)], self,
             btVector3(btScalar(column), btScalar(-row + 0.5), 0));
      if (column > 0 && !(fixed && spec.is_static(row, column - 1)))
        join(*w.bodies[w.bodies.size() - 2], self, btVector3(btScalar(column - 0.5), btScalar(-row), 0));
    }
  return w.run(spec.steps, grid_spec::dt);
}

std::optional<result> run_bullet(const ragdoll_pile_spec& spec) {
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  btBoxShape ground_shape{btVector3(20, btScalar(0.5), 20)};
  bullet_world w;
  // sqrt(friction): Bullet multiplies the pair's values (bench/scenes/bullet_engine.hpp).
  const btScalar friction = btScalar(std::sqrt(ragdoll_pile_spec::friction));
  btRigidBody::btRigidBodyConstructionInfo ground(0, nullptr, &ground_shape);
  ground.m_startWorldTransform.setIdentity();
  ground.m_startWorldTransform.setOrigin(btVector3(0, btScalar(-0.5), 0));
  ground.m_friction = friction;
  w.add_static(ground);
  for (const ragdoll_part& part : ragdoll_pile_spec::parts) {
    const btScalar a = btScalar(part.size[0]), b = btScalar(part.size[1]), c = btScalar(part.size[2]);
    switch (part.shape) {
      case ragdoll_part::shape_kind::box:
        shapes.push_back(std::make_unique<btBoxShape>(btVector3(a, b, c)));
        break;
      case ragdoll_part::shape_kind::sphere:
        shapes.push_back(std::make_unique<btSphereShape>(a));
        break;
      case ragdoll_part::shape_kind::capsule:
        shapes.push_back(std::make_unique<btCapsuleShape>(a, 2 * b));
        break;
    }
  }
  const auto v = [](const double (&a)[3]) { return btVector3(btScalar(a[0]), btScalar(a[1]), btScalar(a[2])); };
  for (int i = 0; i < spec.columns; ++i)
    for (int k = 0; k < spec.columns; ++k)
      for (int l = 0; l < spec.layers; ++l) {
        const ragdoll_pile_spec::placement p = spec.place(i, k, l);
        const btQuaternion turn =
            btQuaternion(btVector3(0, 1, 0), btScalar(p.yaw)) * btQuaternion(btVector3(1, 0, 0), btScalar(p.pitch));
        const btTransform frame(turn, v(p.origin));
        const std::size_t first = w.bodies.size();
        for (std::size_t n = 0; n < ragdoll_pile_spec::parts.size(); ++n) {
          const ragdoll_part& part = ragdoll_pile_spec::parts[n];
          btVector3 inertia(0, 0, 0);
          shapes[n]->calculateLocalInertia(btScalar(part.mass), inertia);
          btRigidBody::btRigidBodyConstructionInfo info(btScalar(part.mass), nullptr, shapes[n].get(), inertia);
          info.m_startWorldTransform = btTransform(turn, frame * v(part.center));
          info.m_friction = friction;
          w.add_body(info);
        }
        for (const ragdoll_joint& j : ragdoll_pile_spec::joints) {
          btRigidBody& parent = *w.bodies[first + std::size_t(j.parent)];
          btRigidBody& child = *w.bodies[first + std::size_t(j.child)];
          const btVector3 anchor = frame * v(j.anchor);
          const btVector3 in_parent = parent.getWorldTransform().inverse() * anchor;
          const btVector3 in_child = child.getWorldTransform().inverse() * anchor;
          if (j.hinge) {
            // Every body of a ragdoll shares its frame's turn: the axis is
            // x in each body's frame.
            auto hinge = std::make_unique<btHingeConstraint>(parent, child, in_parent, in_child, btVector3(1, 0, 0),
                                                             btVector3(1, 0, 0));
            hinge->setLimit(btScalar(-j.upper), btScalar(-j.lower));
            w.add_joint(std::move(hinge));
          } else {
            w.add_joint(std::make_unique<btPoint2PointConstraint>(parent, child, in_parent, in_child));
          }
        }
      }
  return w.run(spec.steps, ragdoll_pile_spec::dt);
}

}  // namespace joints_bench

#else

namespace joints_bench {

bool have_bullet() noexcept { return false; }
std::optional<result> run_bullet(const grid_spec&) { return std::nullopt; }
std::optional<result> run_bullet(const ragdoll_pile_spec&) { return std::nullopt; }

}  // namespace joints_bench

#endif
