// Lockstep determinism: the same scenes, stepped with cross_platform_determinism
// on, hash to the same bits in every build: g++ or clang, -O2 or -O3, SSE2,
// AVX2 or AVX-512 (docs/world.md, "Lockstep determinism").
//
//   lockstep --full    runs the scenes for 600 steps each, prints each hash,
//                      and exits 1 if one differs from the recorded hash
//   lockstep --quick   60 steps of each but large_pyramid
//   lockstep           --full in an optimised build (NDEBUG), else --quick:
//                      debug and sanitizer builds run the short form
//
// tools/lockstep_check.sh builds this file under several compilers and flags
// and runs each build; CI runs it, and so can anyone on their own machines
// (ARM included) to see whether their builds agree with these.
//
// The scenes (docs/standard_scenes.md):
//   - pile: 1000 cubes landing as 100 columns, sleeping off; the same scene
//     stepped again on two workers of a thread pool must hash alike;
//   - large_pyramid: 5050 cubes of 100 kg, ground half-extents 400;
//   - joints: a chain of twelve links on hinges whose limits stop it, hung
//     from a ball joint; a wheel driven by a motor; a slider against its
//     limit; a box on a spring; a fixed pair falling together;
//   - particles: the `particles` scene at N = 10 000, dt = 1/120, stepped
//     at the machine's width and at 1, 4 and 16 lanes, all alike.
// The hash is FNV-1a over the bits of every body's id, position and
// orientation in id order (as tests/world/scenes.hpp's transform_hash), or
// of every particle's position and velocity. The program builds from
// include/ or, with IMPULSE_LOCKSTEP_SINGLE_HEADER, from single_include/.
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <vector>

// Built from the single header (single_include/) or from include/; the
// program needs nothing else, so that it builds anywhere impulse does.
#if defined(IMPULSE_LOCKSTEP_SINGLE_HEADER)
#include <impulse/impulse.hpp>
#include <impulse/impulse_thread_pool.hpp>
#else
#include <impulse/impulse.hpp>
#include <impulse/thread_pool.hpp>
#endif

namespace {

using namespace impulse;

struct lockstep_config : default_config {
  static constexpr bool sleeping = false;
  static constexpr bool cross_platform_determinism = true;
};
/// Particles W lanes at a time: every width steps to the same bits.
template <int W>
struct lockstep_particles : default_config {
  static constexpr bool cross_platform_determinism = true;
  static constexpr int particle_width = W;
};
using T = float;
using lockstep_world = world<lockstep_config>;

/// FNV-1a over bytes, continued from h.
std::uint64_t mix(std::uint64_t h, const void* data, std::size_t n) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) h = (h ^ bytes[i]) * 1099511628211ull;
  return h;
}
constexpr std::uint64_t fnv_basis = 1469598103934665603ull;

/// Every body's id, position and orientation, in id order.
std::uint64_t transform_hash(const lockstep_world& w) {
  std::uint64_t h = fnv_basis;
  for (const body_id id : w.body_ids()) {
    const auto& b = w.body(id);
    h = mix(h, &id.index, sizeof id.index);
    h = mix(h, &id.generation, sizeof id.generation);
    h = mix(h, &b.position, sizeof b.position);
    h = mix(h, &b.orientation, sizeof b.orientation);
  }
  return h;
}

void run(lockstep_world& w, int steps) {
  for (int i = 0; i < steps; ++i) w.step(T(1) / T(60));
}

/// The standard ground: a static box of half-extents (half, 1, half), top face at y = 0.
body_id add_ground(lockstep_world& w, T half = 100) {
  body_def<T> d;
  d.type = body_type::static_body;
  d.pose.position = {0, -1, 0};
  d.material.friction = T(0.6);
  return w.create_body(d, box<T>::make({half, 1, half}));
}

body_id add_box(lockstep_world& w, vec3<T> at, vec3<T> half, T mass, quat<T> turn = quat<T>::identity()) {
  body_def<T> d;
  d.pose = {at, turn};
  d.mass = mass;
  d.material.friction = T(0.6);
  return w.create_body(d, box<T>::make(half));
}

std::uint64_t pile(int steps, int workers) {
  lockstep_world w;
  thread_pool pool{std::uint32_t(workers)};
  if (workers > 1) w.set_task_system(pool.tasks());
  add_ground(w);
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      for (int k = 0; k < 10; ++k)
        add_box(w, {(T(i) - T(4.5)) * T(1.2), T(1) + T(1.2) * T(j), (T(k) - T(4.5)) * T(1.2)}, {T(0.5), T(0.5), T(0.5)},
                1);
  run(w, steps);
  return transform_hash(w);
}

std::uint64_t large_pyramid(int steps) {
  lockstep_world w;
  add_ground(w, T(400));
  for (int k = 0; k < 100; ++k) {
    const int n = 100 - k;
    for (int i = 0; i < n; ++i) add_box(w, {T(i) - T(n - 1) / 2, T(0.5) + T(k), 0}, {T(0.5), T(0.5), T(0.5)}, 100);
  }
  run(w, steps);
  return transform_hash(w);
}

std::uint64_t joints(int steps) {
  lockstep_world w;
  const body_id ground = add_ground(w);
  // The chain: links 0.8 m long, level at first, each on a hinge about z
  // limited to ±0.6 rad, the first hung from the ground by a ball joint.
  body_id above = ground;
  for (int i = 0; i < 12; ++i) {
    const body_id link = add_box(w, {T(0.4) + T(0.8) * T(i), 12, 0}, {T(0.4), T(0.1), T(0.1)}, 1);
    const vec3<T> anchor{T(0.8) * T(i), 12, 0};
    if (i == 0) {
      w.create_joint(joint_def<T>::ball(above, link, anchor));
    } else {
      joint_def<T> hinge = joint_def<T>::hinge(above, link, anchor, {0, 0, 1});
      hinge.enable_limit = true;
      hinge.lower = T(-0.6), hinge.upper = T(0.6);
      w.create_joint(hinge);
    }
    above = link;
  }
  // A wheel on a motor about x, 2 rad/s at most 50 N·m, above the ground.
  const body_id wheel = add_box(w, {-4, 2, 0}, {T(0.1), T(0.8), T(0.8)}, 4);
  joint_def<T> motor = joint_def<T>::hinge(ground, wheel, {-4, 2, 0}, {1, 0, 0});
  motor.enable_motor = true;
  motor.motor_speed = 2, motor.max_motor_force = 50;
  w.create_joint(motor);
  // A slider along a slope that its limit stops after 1 m.
  const body_id sled = add_box(w, {-8, 3, 0}, {T(0.3), T(0.3), T(0.3)}, 2);
  joint_def<T> slider = joint_def<T>::slider(ground, sled, {-8, 3, 0}, {1, -1, 0});
  slider.enable_limit = true;
  slider.lower = -1, slider.upper = 1;
  w.create_joint(slider);
  // A box on a 2 Hz spring, a rod's length below a point of the ground body.
  const body_id bob = add_box(w, {-12, 3, 0}, {T(0.25), T(0.25), T(0.25)}, 1);
  joint_def<T> spring = joint_def<T>::distance(ground, bob, {-12, 6, 0}, {-12, T(3.25), 0});
  spring.spring_hertz = 2, spring.spring_damping_ratio = T(0.1);
  w.create_joint(spring);
  // Two boxes held together, dropped turned onto the ground.
  const quat<T> turn = quat<T>::from_axis_angle({0, 0, 1}, T(0.4));
  const body_id left = add_box(w, {-16, 3, 0}, {T(0.5), T(0.5), T(0.5)}, 1, turn);
  const body_id right = add_box(w, {-15, 3, 0}, {T(0.5), T(0.5), T(0.5)}, 1, turn);
  w.create_joint(joint_def<T>::fixed(left, right, {T(-15.5), 3, 0}));
  run(w, steps);
  return transform_hash(w);
}

/// The `particles` scene: gravity, drag 0.1, three attractors (ε = 0.05),
/// three planes (restitution 0.5, friction 0.2), starts drawn from lcg32
/// (seed 12345) as x, y, z, vx, vy, vz per particle; dt = 1/120; stepped
/// W particles at a time.
template <int W>
std::uint64_t particle_scene(int steps) {
  using namespace impulse::particles;
  point_forces<T> attractors;
  attractors.softening = T(0.05);
  attractors.add({0, 5, 0}, 20);
  attractors.add({-5, 8, 3}, 10);
  attractors.add({5, 3, -4}, 15);
  particle_system<lockstep_particles<W>, gravity, drag, point_forces> s{
      10000, gravity<T>{{0, T(-9.81), 0}}, drag<T>{T(0.1)}, attractors};
  const T r = T(std::sqrt(0.5));  // as docs/standard_scenes.md builds it: √½ in double, rounded
  s.add_plane(plane_collider<T>::half_space({0, 1, 0}, 0, T(0.5), T(0.2)));
  s.add_plane(plane_collider<T>::half_space({1, 0, 0}, 10, T(0.5), T(0.2)));
  s.add_plane(plane_collider<T>::half_space({-r, 0, -r}, 10, T(0.5), T(0.2)));
  lcg32 random{12345};
  for (int i = 0; i < 10000; ++i) {
    const T x = random.uniform<T>(-8, 8), y = random.uniform<T>(T(0.5), 15), z = random.uniform<T>(-8, 8);
    const T vx = random.uniform<T>(-5, 5), vy = random.uniform<T>(-5, 5), vz = random.uniform<T>(-5, 5);
    s.add({x, y, z}, {vx, vy, vz}, 1);
  }
  for (int i = 0; i < steps; ++i) s.step(T(1) / T(120));
  std::uint64_t h = fnv_basis;
  const auto x = s.positions(), v = s.velocities();
  for (std::size_t i = 0; i < s.size(); ++i) {
    const T values[6] = {x.x[i], x.y[i], x.z[i], v.x[i], v.y[i], v.z[i]};
    h = mix(h, values, sizeof values);
  }
  return h;
}

struct recorded {
  const char* scene;
  std::uint64_t full, quick;  ///< after 600 steps; after 60 (large_pyramid is not run by --quick)
};

/// Recorded on 2026-12-07 on x86-64 (AMD EPYC, Debian 12), and equal in
/// every build tools/lockstep_check.sh makes there.
constexpr recorded hashes[] = {
    {"pile", 0xae036fe203d99846ull, 0x016eaef3d20c9f0dull},
    {"pile on 2 workers", 0xae036fe203d99846ull, 0x016eaef3d20c9f0dull},
    {"large_pyramid", 0x965b57ce39d0a348ull, 0},
    {"joints", 0x4f2a53cd90031fffull, 0xa6f9e3da4588a4b4ull},
    {"particles", 0x74fbde5432342c37ull, 0x67e419a6b02b6e5full},
    {"particles, 1 lane", 0x74fbde5432342c37ull, 0x67e419a6b02b6e5full},
    {"particles, 4 lanes", 0x74fbde5432342c37ull, 0x67e419a6b02b6e5full},
    {"particles, 16 lanes", 0x74fbde5432342c37ull, 0x67e419a6b02b6e5full},
};

}  // namespace

int main(int argc, char** argv) try {
#ifdef NDEBUG
  bool quick = false;
#else
  bool quick = true;
#endif
  if (argc > 1) quick = std::strcmp(argv[1], "--full") != 0;
  const int steps = quick ? 60 : 600;
  const std::uint64_t computed[] = {pile(steps, 1),           pile(steps, 2),
                                    quick ? 0 : large_pyramid(steps),
                                    joints(steps),             particle_scene<native_width<T>>(steps),
                                    particle_scene<1>(steps),  particle_scene<4>(steps),
                                    particle_scene<16>(steps)};
  static_assert(std::size(computed) == std::size(hashes));
  int differ = 0;
  for (std::size_t i = 0; i < std::size(hashes); ++i) {
    const std::uint64_t expected = quick ? hashes[i].quick : hashes[i].full;
    if (quick && i == 2) continue;
    const bool same = computed[i] == expected;
    differ += same ? 0 : 1;
    std::printf("%-20s %3d steps  %016" PRIx64 "  %s\n", hashes[i].scene, steps, computed[i],
                same ? "as recorded" : "DIFFERS from the recorded hash");
  }
  if (differ) std::printf("%d of the scenes differ from the hashes recorded in tests/lockstep/lockstep.cpp\n", differ);
  return differ ? 1 : 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "lockstep: %s\n", e.what());
  return 2;
}
