// tests/broadphase/against_brute_force.hpp — the property test every broad
// phase runs: a seeded scene of moving boxes, stepped in the broad phase
// under test and in brute_force side by side, compared after every update.
//
// Both broad phases see the same creates and destroys in the same order, so
// they hand out the same ids (every broad phase keeps its proxies in a
// detail::proxy_store) and their pairs can be compared directly: the whole
// set, the begun and the ended pairs, each sorted. Queries and ray casts are
// compared too, a few random ones per step, with the entry fractions exactly
// (every broad phase must report ray_enters on the proxy's own box, not on a
// fattened one).
//
// The scenes are the hard cases: uniform, clustered, mixed
// huge and tiny boxes (1000:1), everything in one spot, zero-size boxes on a
// lattice (coincident points and exactly touching faces), far from the
// origin (1e5), and heavy adding and removing mid-run. In every scene a
// quarter of the boxes stand still, most move coherently (a small velocity,
// bouncing off the scene's bounds), and a few jump somewhere else each step;
// in one more (mostly resting) only 3 % move, as in a scene that has
// settled, which takes structures down their paths for a few moved boxes.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "impulse/broadphase.hpp"
#include "impulse/core/random.hpp"

namespace impulse::test {

enum class scene_kind { uniform, clustered, mixed_sizes, one_spot, points, far_away, churn, mostly_resting };

inline std::string name_of(scene_kind kind) {
  switch (kind) {
    case scene_kind::uniform: return "uniform";
    case scene_kind::clustered: return "clustered";
    case scene_kind::mixed_sizes: return "mixed sizes 1000:1";
    case scene_kind::one_spot: return "all in one spot";
    case scene_kind::points: return "zero-size boxes on a lattice";
    case scene_kind::far_away: return "far from the origin";
    case scene_kind::churn: return "added and removed mid-run";
    case scene_kind::mostly_resting: return "mostly resting";
  }
  return "?";
}

inline constexpr scene_kind all_scene_kinds[] = {scene_kind::uniform,  scene_kind::clustered, scene_kind::mixed_sizes,
                                                 scene_kind::one_spot, scene_kind::points,    scene_kind::far_away,
                                                 scene_kind::churn,    scene_kind::mostly_resting};

/// A seeded scene of boxes that move, jump, appear and disappear.
template <scalar_type T>
class moving_boxes {
 public:
  struct body {
    vec3<T> center;
    vec3<T> half;
    vec3<T> velocity;  ///< per step; zero for a body that stands still
  };

  moving_boxes(scene_kind kind, int count, std::uint32_t seed) : kind_(kind), random_{seed} {
    // World size for about one overlap per box among boxes of mean size 0.7.
    extent_ = T(1.5) * std::cbrt(T(count));
    if (kind == scene_kind::far_away) origin_ = vec3<T>{T(1e5), T(-1e5), T(1e5)};
    if (kind == scene_kind::clustered)
      for (auto& c : clusters_) c = origin_ + random_vec(T(0), T(3) * extent_);
  }

  body make_body() {
    body b{};
    const T u = random_.template uniform<T>();
    switch (kind_) {
      case scene_kind::uniform:
      case scene_kind::far_away:
      case scene_kind::churn:
      case scene_kind::mostly_resting:
        b.center = origin_ + random_vec(T(0), extent_);
        b.half = random_vec(T(0.1), T(0.6));
        break;
      case scene_kind::clustered: {
        // Sum of three uniforms: a rounded bump of about one cube-root of
        // the count around one of eight centers.
        const vec3<T> spread = random_vec(T(-1), T(1)) + random_vec(T(-1), T(1)) + random_vec(T(-1), T(1));
        b.center = clusters_[random_.next() % 8] + spread * (T(0.1) * extent_);
        b.half = random_vec(T(0.1), T(0.6));
        break;
      }
      case scene_kind::mixed_sizes:
        // Tiny (0.005 to 0.01), ordinary, and 2 % huge (5 to 10): 1000:1.
        b.center = origin_ + random_vec(T(0), extent_);
        b.half = u < T(0.02) ? random_vec(T(5), T(10)) : u < T(0.5) ? random_vec(T(0.005), T(0.01)) : random_vec(T(0.1), T(0.6));
        break;
      case scene_kind::one_spot:
        // One center; half the boxes the same size, the rest from points up.
        b.center = vec3<T>{T(1), T(2), T(3)};
        b.half = u < T(0.5) ? vec3<T>::splat(T(0.5)) : random_vec(T(0), T(0.5));
        break;
      case scene_kind::points:
        // Integer lattice points in a 5³ block: coincident points meet, and
        // the unit cubes among them touch exactly at their faces.
        b.center = lattice_point();
        b.half = u < T(0.5) ? vec3<T>{} : vec3<T>::splat(T(0.5));
        break;
    }
    const T resting = kind_ == scene_kind::mostly_resting ? T(0.97) : T(0.25);
    if (random_.template uniform<T>() >= resting) b.velocity = random_vec(T(-0.05), T(0.05)) * std::max(T(1), extent_ / T(20));
    if (kind_ == scene_kind::one_spot || kind_ == scene_kind::points) b.velocity = vec3<T>{};
    return b;
  }

  /// Moves one body by a step: coherent drift bouncing off the bounds, or,
  /// for one body in fifty, a jump to a fresh place. Returns false when the
  /// body stays where it was.
  bool advance(body& b) {
    if (random_.next() % 50 == 0) {
      const vec3<T> half = b.half;
      b = make_body();
      b.half = half;
      return true;
    }
    if (kind_ == scene_kind::points) {
      // Lattice hops, so that exact coincidences keep happening.
      if (random_.next() % 4 != 0) return false;
      b.center = lattice_point();
      return true;
    }
    if (b.velocity == vec3<T>{}) return false;
    b.center += b.velocity;
    for (int axis = 0; axis < 3; ++axis) {
      const T lo = origin_[axis] - T(2), hi = origin_[axis] + extent_ * (kind_ == scene_kind::clustered ? T(3) : T(1)) + T(2);
      if ((b.center[axis] < lo && b.velocity[axis] < T(0)) || (b.center[axis] > hi && b.velocity[axis] > T(0)))
        b.velocity[axis] = -b.velocity[axis];
    }
    return true;
  }

  aabb<T> random_region(T half_size) {
    if (kind_ == scene_kind::clustered)  // where the boxes are
      return aabb<T>::from_center_half_extents(clusters_[random_.next() % 8] + random_vec(-extent_, extent_) * T(0.2),
                                               vec3<T>::splat(half_size));
    const vec3<T> lo = origin_ - vec3<T>::splat(T(2));
    const T span = extent_ * (kind_ == scene_kind::clustered ? T(3) : T(1)) + T(4);
    return aabb<T>::from_center_half_extents(lo + random_vec(T(0), span), vec3<T>::splat(half_size));
  }

  /// A segment across the scene, from one side of its bounds to the other.
  ray<T> random_ray() {
    const aabb<T> start = random_region(T(0)), end = random_region(T(0));
    return {start.lower, end.lower - start.lower};
  }

  std::uint32_t next() { return random_.next(); }

 private:
  vec3<T> random_vec(T lo, T hi) {
    const T x = random_.uniform(lo, hi), y = random_.uniform(lo, hi), z = random_.uniform(lo, hi);
    return {x, y, z};
  }
  vec3<T> lattice_point() {
    const T x = T(random_.next() % 5), y = T(random_.next() % 5), z = T(random_.next() % 5);
    return origin_ + vec3<T>{x, y, z};
  }

  scene_kind kind_;
  lcg32 random_;
  T extent_;
  vec3<T> origin_{};
  vec3<T> clusters_[8]{};
};

// Messages are built with += only: g++ 12 at -O3 warns falsely
// (-Wrestrict, its bug 105329) on std::string's operator+ chains.
inline std::string describe(const proxy_pair& p) {
  std::string s = "(";
  s += std::to_string(p.a.index);
  s += ".";
  s += std::to_string(p.a.generation);
  s += ", ";
  s += std::to_string(p.b.index);
  s += ".";
  s += std::to_string(p.b.generation);
  s += ")";
  return s;
}

/// Reports the first difference between two sorted pair lists; true when equal.
inline bool same_pairs(std::span<const proxy_pair> got, std::span<const proxy_pair> expected, const char* what,
                       int step) {
  if (std::equal(got.begin(), got.end(), expected.begin(), expected.end())) return true;
  std::vector<proxy_pair> missing, extra;
  std::set_difference(expected.begin(), expected.end(), got.begin(), got.end(), std::back_inserter(missing));
  std::set_difference(got.begin(), got.end(), expected.begin(), expected.end(), std::back_inserter(extra));
  std::string message = what;
  message += " differ at step ";
  message += std::to_string(step);
  message += ": ";
  message += std::to_string(got.size());
  message += " reported, ";
  message += std::to_string(expected.size());
  message += " expected";
  if (!missing.empty()) message += "; missing ", message += describe(missing.front());
  if (!extra.empty()) message += "; extra ", message += describe(extra.front());
  if (missing.empty() && extra.empty()) message += "; same set, different order or duplicates";
  FAIL_CHECK(message);
  return false;
}

struct comparison_counts {
  std::size_t pairs = 0, queries = 0, ray_hits = 0;  ///< totals compared, to show the test saw something
};

/// Steps `tested` and a brute_force through the same scene and compares
/// them after every update. Returns the totals compared; stops at the first
/// step that differs (after reporting it).
template <class BroadPhase, scalar_type T>
comparison_counts run_against_brute_force(BroadPhase& tested, scene_kind kind, int count, int steps,
                                          std::uint32_t seed) {
  static_assert(broadphase::broad_phase<BroadPhase, T>);
  broadphase::basic_brute_force<T> reference;
  moving_boxes<T> scene{kind, count, seed};
  std::vector<typename moving_boxes<T>::body> bodies;
  std::vector<proxy_id> ids;
  comparison_counts counts;

  const auto add = [&] {
    const auto b = scene.make_body();
    const aabb<T> box = aabb<T>::from_center_half_extents(b.center, b.half);
    const proxy_id id = tested.create(box, std::uint64_t(ids.size()) * 7 + 1);
    const proxy_id expected = reference.create(box, std::uint64_t(ids.size()) * 7 + 1);
    REQUIRE(id == expected);
    bodies.push_back(b);
    ids.push_back(id);
  };
  const auto remove = [&](std::size_t i) {
    tested.destroy(ids[i]);
    reference.destroy(ids[i]);
    bodies[i] = bodies.back();
    ids[i] = ids.back();
    bodies.pop_back();
    ids.pop_back();
  };

  for (int i = 0; i < count; ++i) add();
  for (int step = 0; step < steps; ++step) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (!scene.advance(bodies[i])) continue;
      const aabb<T> box = aabb<T>::from_center_half_extents(bodies[i].center, bodies[i].half);
      tested.move(ids[i], box);
      reference.move(ids[i], box);
    }
    // Adding and removing between updates: a little in every scene, a lot
    // in the churn scene, which also empties and refills itself once.
    const int turnover = kind == scene_kind::churn ? count / 10 : step % 7 == 3 ? 2 : 0;
    for (int k = 0; k < turnover && !bodies.empty(); ++k) remove(scene.next() % bodies.size());
    if (kind == scene_kind::churn && step == steps / 2)
      while (!bodies.empty()) remove(scene.next() % bodies.size());
    while (int(bodies.size()) < count) add();
    if (kind == scene_kind::churn && step % 5 == 1)  // a box created and destroyed between two updates
      tested.destroy(tested.create(scene.random_region(T(1)), 0)), reference.destroy(reference.create(scene.random_region(T(1)), 0));

    tested.update();
    reference.update();
    CHECK(tested.size() == reference.size());
    if (!same_pairs(tested.pairs(), reference.pairs(), "pairs", step) ||
        !same_pairs(tested.begun(), reference.begun(), "begun pairs", step) ||
        !same_pairs(tested.ended(), reference.ended(), "ended pairs", step))
      return counts;
    counts.pairs += reference.pairs().size();

    for (int q = 0; q < 3; ++q) {
      const aabb<T> region = scene.random_region(T(q + 1));
      std::vector<std::uint64_t> got, expected;
      const auto key = [](proxy_id id) { return (std::uint64_t(id.index) << 32) | id.generation; };
      tested.query(region, [&](proxy_id id) { got.push_back(key(id)); });
      reference.query(region, [&](proxy_id id) { expected.push_back(key(id)); });
      std::sort(got.begin(), got.end());
      std::sort(expected.begin(), expected.end());
      if (got != expected) {
        FAIL_CHECK("query differs at step " << step << ": " << got.size() << " reported, " << expected.size()
                                             << " expected");
        return counts;
      }
      counts.queries += expected.size();

      // Every box the unclipped segment enters, with its entry fraction,
      // then the nearest hit through a clipping callback.
      const ray<T> r = scene.random_ray();
      struct hit {
        std::uint64_t key;
        T fraction;
        bool operator<(const hit& o) const { return key < o.key; }
        bool operator==(const hit& o) const = default;
      };
      std::vector<hit> hits, expected_hits;
      tested.ray_cast(r, T(1), [&](proxy_id id, T t) { return hits.push_back({key(id), t}), T(1); });
      reference.ray_cast(r, T(1), [&](proxy_id id, T t) { return expected_hits.push_back({key(id), t}), T(1); });
      std::sort(hits.begin(), hits.end());
      std::sort(expected_hits.begin(), expected_hits.end());
      if (hits != expected_hits) {
        FAIL_CHECK("ray hits differ at step " << step << ": " << hits.size() << " reported, " << expected_hits.size()
                                               << " expected");
        return counts;
      }
      counts.ray_hits += expected_hits.size();
      T nearest = T(1), expected_nearest = T(1);
      tested.ray_cast(r, T(1), [&](proxy_id, T t) { return nearest = std::min(nearest, t); });
      reference.ray_cast(r, T(1), [&](proxy_id, T t) { return expected_nearest = std::min(expected_nearest, t); });
      CHECK(nearest == expected_nearest);
    }
  }
  return counts;
}

}  // namespace impulse::test
