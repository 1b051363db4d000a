// contact_memory — bytes per overlapping pair, counted at the allocator.
//
// n unit boxes (half-extent 0.5, 1 kg) are created 1 mm apart along x, so
// every one of the n(n−1)/2 pairs overlaps and touches; then one step of
// 1/60 s. Printed per engine and n: the bytes the world held before the
// step, the peak during it and what it held after, and the peak's growth
// over the pairs. The counts are exact (every operator new and every
// Bullet allocation goes through the counters below), so the figures are
// the same on any run of the same build.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string_view>
#include <vector>

#include "impulse/world.hpp"

#ifdef IMPULSE_BENCH_HAVE_BULLET
#include <btBulletDynamicsCommon.h>
#endif

namespace {

// ---- counting every allocation ----

std::size_t held = 0, peak = 0;

/// Each block carries its size in front of it, so that free can count it.
constexpr std::size_t header = 64;  // keeps any alignment up to 64 bytes

void* counted_alloc(std::size_t size, std::size_t align = alignof(std::max_align_t)) {
  if (align > header) std::abort();
  auto* base = static_cast<unsigned char*>(std::aligned_alloc(header, (size + 2 * header - 1) / header * header));
  if (base == nullptr) throw std::bad_alloc();
  *reinterpret_cast<std::size_t*>(base) = size;
  held += size;
  if (held > peak) peak = held;
  return base + header;
}
void counted_free(void* p) noexcept {
  if (p == nullptr) return;
  unsigned char* base = static_cast<unsigned char*>(p) - header;
  held -= *reinterpret_cast<std::size_t*>(base);
  std::free(base);
}

}  // namespace

void* operator new(std::size_t size) { return counted_alloc(size); }
void* operator new[](std::size_t size) { return counted_alloc(size); }
void* operator new(std::size_t size, std::align_val_t align) { return counted_alloc(size, std::size_t(align)); }
void* operator new[](std::size_t size, std::align_val_t align) { return counted_alloc(size, std::size_t(align)); }
void operator delete(void* p) noexcept { counted_free(p); }
void operator delete[](void* p) noexcept { counted_free(p); }
void operator delete(void* p, std::size_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::size_t) noexcept { counted_free(p); }
void operator delete(void* p, std::align_val_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { counted_free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { counted_free(p); }

namespace {

struct figures {
  std::size_t before, peak, after, touching;
};

void print(const char* engine, int n, const figures& f) {
  const double pairs = double(n) * double(n - 1) / 2;
  std::printf("| %s | %d | %.0f | %zu | %.0f | %.0f | %.0f |\n", engine, n, pairs, f.touching,
              double(f.before) / 1024, double(f.peak) / 1024, double(f.peak - f.before) / pairs);
}

template <class Config>
figures impulse_heap(int n) {
  using T = typename Config::scalar;
  held = peak = 0;
  figures f{};
  {
    impulse::world<Config> world;
    for (int i = 0; i < n; ++i) {
      impulse::body_def<T> d;
      d.pose.position = {T(0.001) * T(i), T(5), T(0)};
      d.mass = 1;
      world.create_body(d, impulse::box<T>::make({T(0.5), T(0.5), T(0.5)}));
    }
    f.before = held;
    peak = held;
    world.step(T(1) / T(60));
    f.peak = peak;
    f.after = held;
    f.touching = world.touching_pair_count();
  }
  return f;
}

#ifdef IMPULSE_BENCH_HAVE_BULLET
void* bullet_alloc(std::size_t size, int align) { return counted_alloc(size, std::size_t(align)); }
void* bullet_alloc_plain(std::size_t size) { return counted_alloc(size); }

figures bullet_heap(int n) {
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
#endif

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::string_view(argv[1]) == "--quick";
  std::printf("| engine | boxes | pairs | touching | before, KiB | peak in the step, KiB | bytes per pair |\n");
  std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  const std::vector<int> sizes = quick ? std::vector<int>{100, 300} : std::vector<int>{100, 300, 1000};
  for (const int n : sizes) {
    print("impulse, float", n, impulse_heap<impulse::default_config>(n));
    print("impulse, double", n, impulse_heap<impulse::default_double_config>(n));
#ifdef IMPULSE_BENCH_HAVE_BULLET
    print("Bullet 3 (float)", n, bullet_heap(n));
#endif
  }
}
