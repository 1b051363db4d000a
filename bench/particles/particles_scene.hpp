// The `particles` scene of docs/standard_scenes.md, built
// exactly: gravity (0, −9.81, 0), drag k = 0.1, three softened (ε = 0.05)
// inverse-square attractors, three planes with restitution 0.5 and friction
// 0.2, unit masses; start positions uniform in x, z ∈ [−8, 8], y ∈ [0.5, 15]
// and velocities uniform in [−5, 5]³, drawn from lcg32 (seed 12345) in the
// order x, y, z, vx, vy, vz for each particle in turn.
#pragma once

#include <cmath>
#include <cstddef>

#include "impulse/particles.hpp"

namespace particles_scene {

using namespace impulse::particles;

inline constexpr double dt = 1.0 / 120;

template <class T>
gravity<T> scene_gravity() {
  return {{T(0), T(-9.81), T(0)}};
}
template <class T>
drag<T> scene_drag() {
  return {T(0.1)};
}
template <class T>
point_forces<T> scene_attractors() {
  point_forces<T> p;
  p.softening = T(0.05);
  p.add({T(0), T(5), T(0)}, T(20));
  p.add({T(-5), T(8), T(3)}, T(10));
  p.add({T(5), T(3), T(-4)}, T(15));
  return p;
}

template <class T>
struct plane_spec {
  impulse::vec3<T> normal;
  T offset;
};
template <class T>
std::array<plane_spec<T>, 3> scene_planes() {
  const T s = T(std::sqrt(0.5));
  return {{{{T(0), T(1), T(0)}, T(0)}, {{T(1), T(0), T(0)}, T(10)}, {{-s, T(0), -s}, T(10)}}};
}
inline constexpr double restitution = 0.5, friction = 0.2;

/// Start state of particle i, in draw order.
template <class T>
struct start_state {
  impulse::vec3<T> position, velocity;
};
template <class T>
start_state<T> draw(impulse::lcg32& random) {
  start_state<T> s;
  s.position.x = random.uniform<T>(T(-8), T(8));
  s.position.y = random.uniform<T>(T(0.5), T(15));
  s.position.z = random.uniform<T>(T(-8), T(8));
  s.velocity.x = random.uniform<T>(T(-5), T(5));
  s.velocity.y = random.uniform<T>(T(-5), T(5));
  s.velocity.z = random.uniform<T>(T(-5), T(5));
  return s;
}

/// Fills a particle system created with (gravity, drag, point_forces) in that order.
template <class System>
void build(System& system, std::size_t n) {
  using T = typename System::scalar;
  for (const auto& p : scene_planes<T>())
    system.add_plane(plane_collider<T>::half_space(p.normal, p.offset, T(restitution), T(friction)));
  impulse::lcg32 random{12345};
  for (std::size_t i = 0; i < n; ++i) {
    const start_state<T> s = draw<T>(random);
    system.add(s.position, s.velocity, T(1));
  }
}

template <class Config>
using system = particle_system<Config, gravity, drag, point_forces>;

template <class Config>
system<Config> make(std::size_t n) {
  using T = typename Config::scalar;
  system<Config> s{n, scene_gravity<T>(), scene_drag<T>(), scene_attractors<T>()};
  build(s, n);
  return s;
}

}  // namespace particles_scene
