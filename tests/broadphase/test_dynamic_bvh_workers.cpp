// The dynamic BVH's update across the workers of a task hook
// (broadphase/dynamic_bvh.hpp, keep_candidates): the same pairs, begun and
// ended, in the same order, as on one thread, step after step.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <vector>

#include "impulse/broadphase/dynamic_bvh.hpp"
#include "impulse/core/random.hpp"
#include "impulse/thread_pool.hpp"

#include "../core/schedulers.hpp"
#include "cube.hpp"

namespace broadphase_dynamic_bvh_workers_tests {

using namespace impulse;
using impulse::broadphase::basic_dynamic_bvh;
using impulse::test::cube;

TEST_CASE("dynamic_bvh gives the same pairs, begun and ended, in the same order, with a task hook of any width") {
  // 4000 boxes of 1 m in a 16 m cube, most drifting, some jumping: tens of
  // thousands of carried candidates, in many chunks shared across workers.
  using T = float;
  constexpr int n = 4000;
  impulse::thread_pool pool2{2}, pool3{3};
  const task_system hooks[] = {pool2.tasks(), pool3.tasks(), test::backwards_scheduler::tasks()};
  basic_dynamic_bvh<T> alone;
  std::vector<basic_dynamic_bvh<T>> hooked(std::size(hooks));
  std::vector<vec3<T>> at(n), drift(n);
  lcg32 random{11};
  std::vector<std::vector<proxy_id>> ids(1 + std::size(hooks));
  for (int i = 0; i < n; ++i) {
    at[std::size_t(i)] = {random.uniform(T(0), T(16)), random.uniform(T(0), T(16)), random.uniform(T(0), T(16))};
    drift[std::size_t(i)] = {random.uniform(T(-0.05), T(0.05)), random.uniform(T(-0.05), T(0.05)), T(0)};
    const aabb<T> box = cube<T>(at[std::size_t(i)].x, at[std::size_t(i)].y, at[std::size_t(i)].z, T(0.5));
    ids[0].push_back(alone.create(box, std::uint64_t(i)));
    for (std::size_t h = 0; h < std::size(hooks); ++h) ids[h + 1].push_back(hooked[h].create(box, std::uint64_t(i)));
  }
  std::size_t candidates_seen = 0;
  for (int step = 0; step < 30; ++step) {
    for (int i = 0; i < n; ++i) {
      vec3<T>& p = at[std::size_t(i)];
      p += drift[std::size_t(i)];
      if (i % 97 == step % 97) p = {random.uniform(T(0), T(16)), random.uniform(T(0), T(16)), random.uniform(T(0), T(16))};
      const aabb<T> box = cube<T>(p.x, p.y, p.z, T(0.5));
      alone.move(ids[0][std::size_t(i)], box);
      for (std::size_t h = 0; h < std::size(hooks); ++h) hooked[h].move(ids[h + 1][std::size_t(i)], box);
    }
    alone.update();
    candidates_seen = std::max(candidates_seen, alone.pairs().size());
    for (std::size_t h = 0; h < std::size(hooks); ++h) {
      CAPTURE(h);
      CAPTURE(step);
      hooked[h].update(hooks[h]);
      CHECK(std::equal(alone.pairs().begin(), alone.pairs().end(), hooked[h].pairs().begin(), hooked[h].pairs().end()));
      CHECK(std::equal(alone.begun().begin(), alone.begun().end(), hooked[h].begun().begin(), hooked[h].begun().end()));
      CHECK(std::equal(alone.ended().begin(), alone.ended().end(), hooked[h].ended().begin(), hooked[h].ended().end()));
    }
  }
  CHECK(candidates_seen > 8192);  // the pairs alone fill eight chunks
}

}  // namespace broadphase_dynamic_bvh_workers_tests
