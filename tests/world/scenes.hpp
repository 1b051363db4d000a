// The standard scenes and the hard cases of the world tests, built as
// docs/standard_scenes.md specifies them, with what the tests measure of them.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "impulse/world.hpp"

namespace impulse::test {

/// The default policies with sleeping off: the hard cases are measured on
/// the solver alone.
struct awake_config : impulse::default_config {
  static constexpr bool sleeping = false;
};
struct awake_double_config : awake_config {
  using scalar = double;
};
struct sleeping_config : impulse::default_config {
  static constexpr bool sleeping = true;
};
/// The soft-step solver in place of sequential impulses, sleeping off.
struct soft_config : awake_config {
  using solver = impulse::solver::soft_step;
};
struct soft_double_config : awake_double_config {
  using solver = impulse::solver::soft_step;
};
/// Sleeping off, continuous collision on: the fast bodies' and bullets' tests.
struct ccd_config : awake_config {
  static constexpr bool ccd = true;
};

template <class T>
inline constexpr T step_dt = T(1) / T(60);

/// check(world) in a world with sleeping off, then in one with it on:
/// sleep can hide drift, and a case must hold either way.
template <class Check>
void with_sleeping_off_and_on(Check&& check) {
  {
    impulse::world<awake_config> w;
    check(w);
  }
  {
    impulse::world<sleeping_config> w;
    check(w);
  }
}

/// The standard ground: a static box of half-extents (100, 1, 100) whose
/// top face is y = 0 (or, shifted, the plane through `origin`).
template <class World>
impulse::body_id add_ground(World& w, typename World::scalar friction = 0.6,
                            impulse::vec3<typename World::scalar> origin = {}, typename World::scalar half = 100) {
  using T = typename World::scalar;
  impulse::body_def<T> d;
  d.type = impulse::body_type::static_body;
  d.pose.position = origin + impulse::vec3<T>{0, -1, 0};
  d.material.friction = friction;
  return w.create_body(d, impulse::box<T>::make({half, 1, half}));
}

/// A dynamic cube of half-extent 0.5 and the given mass.
template <class World>
impulse::body_id add_cube(World& w, impulse::vec3<typename World::scalar> at, typename World::scalar mass = 1,
                          typename World::scalar friction = 0.6,
                          impulse::quat<typename World::scalar> turn = impulse::quat<typename World::scalar>::identity()) {
  using T = typename World::scalar;
  impulse::body_def<T> d;
  d.pose = {at, turn};
  d.mass = mass;
  d.material.friction = friction;
  return w.create_body(d, impulse::box<T>::make({0.5, 0.5, 0.5}));
}

/// `pyramid`: rows k = 0..n−1 of n − k cubes at x = i − (n − k − 1)/2,
/// y = 0.5 + k, z = 0, friction 0.6, bottom row first.
template <class World>
std::vector<impulse::body_id> add_pyramid(World& w, int base, impulse::vec3<typename World::scalar> origin = {}) {
  using T = typename World::scalar;
  std::vector<impulse::body_id> ids;
  for (int k = 0; k < base; ++k) {
    const int n = base - k;
    for (int i = 0; i < n; ++i)
      ids.push_back(add_cube(w, origin + impulse::vec3<T>{T(i) - T(n - 1) / T(2), T(0.5) + T(k), 0}));
  }
  return ids;
}

/// `pile`: 1000 cubes on the grid ((i − 4.5)·1.2, 1 + 1.2·j, (k − 4.5)·1.2).
template <class World>
std::vector<impulse::body_id> add_pile(World& w) {
  using T = typename World::scalar;
  std::vector<impulse::body_id> ids;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      for (int k = 0; k < 10; ++k)
        ids.push_back(add_cube(w, {(T(i) - T(4.5)) * T(1.2), T(1) + T(1.2) * T(j), (T(k) - T(4.5)) * T(1.2)}));
  return ids;
}

/// Steps of a scene that must hold for a long time: all of them in
/// optimised builds (NDEBUG), a quarter in debug and sanitizer builds, which
/// check the same assertions over the shorter run. Those builds are there
/// for what assertions and sanitizers catch, and the first seconds of a
/// scene reach the same code as the last; its stability over the whole run
/// is the optimised builds' to show, which run it about 18 times faster
/// (the 20 s soft_step pyramid: 31 s at -O0, 1.7 s at -O3). Test names give
/// the full length.
constexpr int long_run(int steps) {
#ifdef NDEBUG
  return steps;
#else
  return steps / 4;
#endif
}

template <class World>
void run(World& w, int steps) {
  for (int i = 0; i < steps; ++i) w.step(step_dt<typename World::scalar>);
}

/// The largest displacement of any of `ids` from `start`, per axis.
template <class World>
impulse::vec3<typename World::scalar> largest_displacement(const World& w, const std::vector<impulse::body_id>& ids,
                                                           const std::vector<impulse::vec3<typename World::scalar>>& start) {
  impulse::vec3<typename World::scalar> worst{};
  for (std::size_t i = 0; i < ids.size(); ++i) worst = max(worst, abs(w.body(ids[i]).position - start[i]));
  return worst;
}

template <class World>
std::vector<impulse::vec3<typename World::scalar>> positions(const World& w, const std::vector<impulse::body_id>& ids) {
  std::vector<impulse::vec3<typename World::scalar>> p;
  for (const impulse::body_id id : ids) p.push_back(w.body(id).position);
  return p;
}

/// Whether every body's position, orientation and momenta are finite.
template <class World>
bool all_finite(const World& w) {
  for (const impulse::body_id id : w.body_ids()) {
    const auto& b = w.body(id);
    if (!impulse::is_finite(b.position) || !impulse::is_finite(b.orientation) ||
        !impulse::is_finite(b.linear_momentum) || !impulse::is_finite(b.angular_momentum))
      return false;
  }
  return true;
}

/// FNV-1a over the bits of every body's position and orientation, in id
/// order: equal hashes mean bit-identical transforms.
template <class World>
std::uint64_t transform_hash(const World& w) {
  std::uint64_t h = 1469598103934665603ull;
  const auto mix = [&](const void* data, std::size_t n) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ bytes[i]) * 1099511628211ull;
  };
  for (const impulse::body_id id : w.body_ids()) {
    const auto& b = w.body(id);
    // The slot and generation, not the world's number (world_state.hpp,
    // next_world_owner), which counts the worlds made before this one.
    mix(&id.index, sizeof id.index);
    mix(&id.generation, sizeof id.generation);
    mix(&b.position, sizeof b.position);
    mix(&b.orientation, sizeof b.orientation);
  }
  return h;
}

}  // namespace impulse::test

// The unit-test executable compiles these worlds once, in
// tests/instantiate/*.cpp, instead of in every translation unit that steps
// one (a world's pipeline is the bulk of a test file's compile time).
#if IMPULSE_TEST_WORLDS_EXTERN
IMPULSE_DECLARE_WORLD(impulse::test::awake_config);
IMPULSE_DECLARE_WORLD(impulse::test::awake_double_config);
IMPULSE_DECLARE_WORLD(impulse::test::sleeping_config);
IMPULSE_DECLARE_WORLD(impulse::test::soft_config);
IMPULSE_DECLARE_WORLD(impulse::test::soft_double_config);
IMPULSE_DECLARE_WORLD(impulse::test::ccd_config);
#endif
