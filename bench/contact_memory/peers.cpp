// bench/contact_memory/peers.cpp — the run on Bullet 3 (peers.hpp),
// compiled in when the build found it (IMPULSE_BENCH_HAVE_BULLET), with
// Bullet's allocations sent through the same counters as ours.
#include "peers.hpp"

#ifdef IMPULSE_BENCH_HAVE_BULLET

#include <vector>

#include <btBulletDynamicsCommon.h>

namespace contact_memory {

namespace {

void* bullet_alloc(std::size_t size, int align) { return counted_alloc(size, std::size_t(align)); }
void* bullet_alloc_plain(std::size_t size) { return counted_alloc(size); }

}  // namespace

std::optional<figures> bullet_heap(int n) {
  btAlignedAllocSetCustomAligned(bullet_alloc, counted_free);
  btAlignedAllocSetCustom(bullet_alloc_plain, counted_free);
  held = peak = 0;
  figures f{};
  {
    btDefaultCollisionConfiguration configuration;
    btCollisionDispatcher dispatcher(&configuration);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
    world.setGravity({0, -9.81f, 0});
    btBoxShape shape({0.5f, 0.5f, 0.5f});
    btVector3 inertia;
    shape.calculateLocalInertia(1, inertia);
    std::vector<btDefaultMotionState*> states;
    std::vector<btRigidBody*> bodies;
    for (int i = 0; i < n; ++i) {
      btTransform pose;
      pose.setIdentity();
      pose.setOrigin({0.001f * float(i), 5, 0});
      states.push_back(new btDefaultMotionState(pose));
      bodies.push_back(new btRigidBody(1, states.back(), &shape, inertia));
      world.addRigidBody(bodies.back());
    }
    f.before = held;
    peak = held;
    world.stepSimulation(1.0f / 60, 0);
    f.peak = peak;
    f.after = held;
    for (int m = 0; m < dispatcher.getNumManifolds(); ++m)
      f.touching += dispatcher.getManifoldByIndexInternal(m)->getNumContacts() > 0;
    for (btRigidBody* b : bodies) {
      world.removeRigidBody(b);
      delete b;
    }
    for (btDefaultMotionState* s : states) delete s;
  }
  return f;
}

}  // namespace contact_memory

#else

std::optional<contact_memory::figures> contact_memory::bullet_heap(int) { return std::nullopt; }

#endif
