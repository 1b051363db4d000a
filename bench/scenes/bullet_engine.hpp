// bench/scenes/bullet_engine.hpp — Bullet 3 (btDiscreteDynamicsWorld) behind
// the scenes benchmark's engine interface (engine.hpp), set up as a user
// gets it out of the box:
//
// - btDefaultCollisionConfiguration, btCollisionDispatcher,
//   btDbvtBroadphase, btSequentialImpulseConstraintSolver with its default
//   btContactSolverInfo: 10 iterations, warm starting 0.85, split impulse
//   on, ERP 0.2, restitution ignored below 0.2 m/s of approach speed.
// - boxes as btBoxShape (default 0.04 m collision margin, taken from inside
//   the box, so the box keeps its size), spheres as btSphereShape (the
//   radius is the margin); bodies of the same shape and size share one
//   shape. Inertia from the shape (calculateLocalInertia), no motion
//   state: the benchmark reads getWorldTransform() directly.
// - no damping (btRigidBodyConstructionInfo's defaults: 0 linear, 0
//   angular, no "additional damping").
// - sleeping: Bullet's default deactivation (2 s below 0.8 m/s and
//   1 rad/s) when the scene has it, DISABLE_DEACTIVATION on every body
//   when it does not.
// - one step is stepSimulation(dt, 0): maxSubSteps 0 makes Bullet take
//   exactly one internal step of dt, with no accumulator or interpolation.
//
// Materials. Bullet 3.24 combines a pair's values by multiplying them
// (btManifoldResult::calculateCombinedFriction: f0·f1, clamped to ±10;
// calculateCombinedRestitution: e0·e1), where the standard scenes
// (docs/standard_scenes.md) combine friction as sqrt(f0·f1) and restitution
// as max(e0, e1). With every body of a scene
// holding the scene's value v, the spec's pair value is v, and Bullet's
// would be v² (0.36 for friction 0.6, 0.64 for restitution 0.8). So each
// body gets sqrt(v): Bullet's product is then v, the spec's effective
// value. build() checks this through Bullet's own combine callbacks.
#pragma once

#include <cmath>
#include <map>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include <btBulletDynamicsCommon.h>

#include "engine.hpp"
#include "scene_spec.hpp"

namespace bench::scenes {

class bullet_engine {
 public:
  static constexpr std::string_view name = "bullet";

  bullet_engine()
      : dispatcher_(std::make_unique<btCollisionDispatcher>(configuration_.get())),
        world_(std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broad_phase_.get(), solver_.get(),
                                                         configuration_.get())) {}
  bullet_engine(const bullet_engine&) = delete;
  bullet_engine& operator=(const bullet_engine&) = delete;

  [[nodiscard]] std::string config() const {
    return "iterations=" + std::to_string(world_->getSolverInfo().m_numIterations) +
           (sizeof(btScalar) == sizeof(double) ? " double" : " float");
  }

  void build(const scene_spec& spec) {
    dt_ = static_cast<btScalar>(spec.dt);
    world_->setGravity(to_bullet(spec.gravity));  // before adding: addRigidBody hands it to each body
    bodies_.reserve(spec.bodies.size());
    for (const body_spec& b : spec.bodies) {
      btCollisionShape* shape = shape_for(b);
      const auto mass = static_cast<btScalar>(b.is_static ? 0 : b.mass);
      btVector3 inertia(0, 0, 0);
      if (!b.is_static) shape->calculateLocalInertia(mass, inertia);
      btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
      info.m_startWorldTransform.setOrigin(to_bullet(b.position));
      info.m_startWorldTransform.setRotation(btQuaternion(static_cast<btScalar>(b.orientation.x),
                                                          static_cast<btScalar>(b.orientation.y),
                                                          static_cast<btScalar>(b.orientation.z),
                                                          static_cast<btScalar>(b.orientation.w)));
      // sqrt: Bullet multiplies the two bodies' values (see the file comment).
      info.m_friction = static_cast<btScalar>(std::sqrt(b.surface.friction));
      info.m_restitution = static_cast<btScalar>(std::sqrt(b.surface.restitution));
      auto body = std::make_unique<btRigidBody>(info);
      if (!b.is_static) {
        body->setLinearVelocity(to_bullet(b.linear_velocity));
        if (!spec.sleeping) body->setActivationState(DISABLE_DEACTIVATION);
      }
      world_->addRigidBody(body.get());
      bodies_.push_back(std::move(body));
    }
    check_material_combine(spec);
    states_.resize(spec.bodies.size());
  }

  void step() { world_->stepSimulation(dt_, 0); }

  std::span<const body_state> states() {
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const btRigidBody& b = *bodies_[i];
      const btTransform& t = b.getWorldTransform();
      const btQuaternion q = t.getRotation();
      states_[i] = {from_bullet(t.getOrigin()),
                    {q.w(), q.x(), q.y(), q.z()},
                    from_bullet(b.getLinearVelocity()),
                    from_bullet(b.getAngularVelocity()),
                    !b.isStaticObject() && b.isActive()};
    }
    return states_;
  }

 private:
  static btVector3 to_bullet(const vec3& v) {
    return {static_cast<btScalar>(v.x), static_cast<btScalar>(v.y), static_cast<btScalar>(v.z)};
  }
  static vec3 from_bullet(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

  btCollisionShape* shape_for(const body_spec& b) {
    const auto key = b.shape == shape_kind::box
                         ? std::make_tuple(0, b.half_extents.x, b.half_extents.y, b.half_extents.z)
                         : std::make_tuple(1, b.radius, 0.0, 0.0);
    auto [it, added] = shapes_.try_emplace(key);
    if (added) {
      if (b.shape == shape_kind::box)
        it->second = std::make_unique<btBoxShape>(to_bullet(b.half_extents));
      else
        it->second = std::make_unique<btSphereShape>(static_cast<btScalar>(b.radius));
    }
    return it->second.get();
  }

  // The effective pair values Bullet will use must be the spec's: checked on
  // every pair of the first body with another, through the combine
  // callbacks Bullet itself calls (a program may have replaced them).
  void check_material_combine(const scene_spec& spec) const {
    for (std::size_t i = 1; i < bodies_.size(); ++i) {
      const double f = gCalculateCombinedFrictionCallback(bodies_[0].get(), bodies_[i].get());
      const double e = gCalculateCombinedRestitutionCallback(bodies_[0].get(), bodies_[i].get());
      const material& a = spec.bodies[0].surface;
      const material& b = spec.bodies[i].surface;
      const double want_f = std::sqrt(a.friction * b.friction), want_e = std::max(a.restitution, b.restitution);
      if (std::abs(f - want_f) > 1e-5 || std::abs(e - want_e) > 1e-5)
        throw std::runtime_error("bullet: combined friction " + std::to_string(f) + " restitution " +
                                 std::to_string(e) + " differ from the spec's " + std::to_string(want_f) + " " +
                                 std::to_string(want_e) + " (bodies of one scene must share one material)");
    }
  }

  // Declaration order is destruction order reversed: the world goes first,
  // while the bodies, broad phase and dispatcher it cleans up after still
  // exist; then the bodies, then the shapes they point to.
  std::unique_ptr<btDefaultCollisionConfiguration> configuration_ = std::make_unique<btDefaultCollisionConfiguration>();
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broad_phase_ = std::make_unique<btDbvtBroadphase>();
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
  std::map<std::tuple<int, double, double, double>, std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::vector<body_state> states_;
  btScalar dt_ = btScalar(1) / 60;
};

static_assert(scene_engine<bullet_engine>);

}  // namespace bench::scenes
