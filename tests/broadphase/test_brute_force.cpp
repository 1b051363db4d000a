// The brute-force broad phase, the reference every other broad phase is
// tested against: its pairs, their begin and end, queries and ray casts,
// each checked against a direct computation (bad input and the other edges
// of the contract: test_contract.cpp).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include "impulse/broadphase.hpp"
#include "impulse/core/random.hpp"
#include "cube.hpp"

namespace broadphase_brute_force_tests {

namespace {

using namespace impulse;
using impulse::broadphase::basic_brute_force;

static_assert(broadphase::broad_phase<basic_brute_force<float>, float>);
static_assert(broadphase::broad_phase<basic_brute_force<double>, double>);
static_assert(broadphase::broad_phase<broadphase::brute_force::type<float>, float>);

using test::cube;

}  // namespace

TEST_CASE_TEMPLATE("touching boxes overlap and each pair is reported once in slot order", T, float, double) {
  basic_brute_force<T> bp;
  const proxy_id a = bp.create(cube<T>(0, 0, 0, 1), 10);
  const proxy_id b = bp.create(cube<T>(2, 0, 0, 1), 11);  // touches a at x = 1
  const proxy_id c = bp.create(cube<T>(5, 0, 0, 1), 12);  // alone
  bp.update();
  REQUIRE(bp.pairs().size() == 1);
  CHECK(bp.pairs()[0] == proxy_pair{a, b});
  CHECK(bp.begun().size() == 1);
  CHECK(bp.ended().empty());
  CHECK(bp.user_data(c) == 12);

  bp.move(c, cube<T>(3, 0, 0, 1));  // now touches b
  bp.move(a, cube<T>(-5, 0, 0, 1));  // leaves b
  bp.update();
  REQUIRE(bp.pairs().size() == 1);
  CHECK(bp.pairs()[0] == proxy_pair{b, c});
  REQUIRE(bp.begun().size() == 1);
  CHECK(bp.begun()[0] == proxy_pair{b, c});
  REQUIRE(bp.ended().size() == 1);
  CHECK(bp.ended()[0] == proxy_pair{a, b});
}

TEST_CASE_TEMPLATE("pairs begins ends queries and rays match a direct computation over a moving scene", T, float,
                   double) {
  // 200 boxes of sizes from 0 (points) to 2 m, moving at random for 50
  // steps, some destroyed and created on the way.
  basic_brute_force<T> bp;
  impulse::lcg32 random{12345};
  const auto draw_box = [&] {
    const T size = random.template uniform<T>() < T(0.1) ? T(0) : T(2) * random.template uniform<T>();
    return cube<T>(T(20) * random.template uniform<T>(), T(20) * random.template uniform<T>(),
                   T(20) * random.template uniform<T>(), size);
  };
  std::vector<proxy_id> live;
  for (int i = 0; i < 200; ++i) live.push_back(bp.create(draw_box(), std::uint64_t(i)));
  std::set<std::pair<std::uint64_t, std::uint64_t>> previous;
  const auto key = [](proxy_id id) { return (std::uint64_t(id.index) << 32) | id.generation; };
  for (int step = 0; step < 50; ++step) {
    for (proxy_id id : live) bp.move(id, draw_box());
    if (step % 10 == 5) {
      bp.destroy(live[step]);
      live[step] = bp.create(draw_box(), 999);
    }
    bp.update();
    std::set<std::pair<std::uint64_t, std::uint64_t>> expected;
    for (std::size_t i = 0; i < live.size(); ++i)
      for (std::size_t j = 0; j < live.size(); ++j)
        if (live[i].index < live[j].index && overlaps(bp.box(live[i]), bp.box(live[j])))
          expected.insert({key(live[i]), key(live[j])});
    std::set<std::pair<std::uint64_t, std::uint64_t>> got, begun, ended;
    for (const proxy_pair& p : bp.pairs()) got.insert({key(p.a), key(p.b)});
    for (const proxy_pair& p : bp.begun()) begun.insert({key(p.a), key(p.b)});
    for (const proxy_pair& p : bp.ended()) ended.insert({key(p.a), key(p.b)});
    CHECK(got == expected);
    CHECK(got.size() == bp.pairs().size());  // each once
    CHECK(std::is_sorted(bp.pairs().begin(), bp.pairs().end()));
    std::set<std::pair<std::uint64_t, std::uint64_t>> should_begin, should_end;
    std::set_difference(expected.begin(), expected.end(), previous.begin(), previous.end(),
                        std::inserter(should_begin, should_begin.end()));
    std::set_difference(previous.begin(), previous.end(), expected.begin(), expected.end(),
                        std::inserter(should_end, should_end.end()));
    CHECK(begun == should_begin);
    CHECK(ended == should_end);
    previous = expected;

    const aabb<T> region = cube<T>(10, 10, 10, 3);
    std::set<std::uint64_t> queried, inside;
    bp.query(region, [&](proxy_id id) { queried.insert(key(id)); });
    for (proxy_id id : live)
      if (overlaps(bp.box(id), region)) inside.insert(key(id));
    CHECK(queried == inside);

    // A ray through the middle of the scene, unclipped: every box the
    // segment touches, with the entry fraction of the slab test.
    const ray<T> r{{-1, 9, 11}, {22, 2, -2}};
    std::set<std::uint64_t> hit, crossed;
    bp.ray_cast(r, T(1), [&](proxy_id id, T) {
      hit.insert(key(id));
      return T(1);
    });
    for (proxy_id id : live)
      if (ray_enters(r, T(1), bp.box(id))) crossed.insert(key(id));
    CHECK(hit == crossed);
  }
}

TEST_CASE_TEMPLATE("a ray enters a box at the slab-test fraction and a clipping callback stops at the nearest hit",
                   T, float, double) {
  basic_brute_force<T> bp;
  bp.create(cube<T>(5, 0, 0, 1), 0);  // entered at x = 4: fraction 0.4
  const proxy_id near = bp.create(cube<T>(2, 0, 0, T(0.5)), 1);  // entered at x = 1.5: 0.15
  bp.create(cube<T>(5, 5, 0, 1), 2);  // missed
  const ray<T> r{{0, 0, 0}, {10, 0, 0}};
  T nearest = T(1);
  proxy_id nearest_id{};
  bp.ray_cast(r, T(1), [&](proxy_id id, T fraction) {
    if (fraction < nearest) nearest = fraction, nearest_id = id;
    return nearest;  // clip: farther boxes need not be reported
  });
  CHECK(nearest_id == near);
  CHECK(nearest == doctest::Approx(0.15));
  // Along an axis the ray does not move, it must start inside the slab.
  CHECK_FALSE(ray_enters(ray<T>{{0, 2, 0}, {10, 0, 0}}, T(1), cube<T>(5, 0, 0, 1)));
  CHECK(ray_enters(ray<T>{{5, 0, 0}, {0, 0, 0}}, T(1), cube<T>(5, 0, 0, 1)) == T(0));
}

}  // namespace broadphase_brute_force_tests
