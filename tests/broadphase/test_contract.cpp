// What every broad phase promises (broad_phase.hpp), checked on each of
// them by the same cases: the edges of the contract that the moving-scene
// comparison with brute force does not reach on its own.
#include <doctest/doctest.h>

#include <cstdint>
#include <limits>
#include <vector>

#include "impulse/broadphase.hpp"

#include "../error_code_of.hpp"
#include "cube.hpp"

namespace broadphase_contract_tests {

namespace {

using namespace impulse;
using namespace impulse::broadphase;
using impulse::test::error_code_of;

using test::cube;

template <class BroadPhase>
using scalar_of = std::remove_cvref_t<decltype(std::declval<BroadPhase>().box(proxy_id{}).lower.x)>;

}  // namespace

#define IMPULSE_ALL_BROAD_PHASES                                                                             \
  basic_brute_force<float>, basic_brute_force<double>, basic_sweep_and_prune<float>, basic_sweep_and_prune<double>, \
      basic_dynamic_bvh<float>, basic_dynamic_bvh<double>, basic_octree<float>, basic_octree<double>, \
      basic_spatial_hash<float>, basic_spatial_hash<double>

// Every policy declares its kind, and its type<T> is a broad phase for
// both scalars: what a world's config check asks (world_traits.hpp).
template <class P>
constexpr bool whole_policy = broadphase_policy<P> && broad_phase<typename P::template type<float>, float> &&
                              broad_phase<typename P::template type<double>, double>;
static_assert(whole_policy<brute_force>);
static_assert(whole_policy<sweep_and_prune>);
static_assert(whole_policy<dynamic_bvh>);
static_assert(whole_policy<octree>);
static_assert(whole_policy<spatial_hash>);

TEST_CASE_TEMPLATE("a destroyed proxy is never reported even before the next update", BP, IMPULSE_ALL_BROAD_PHASES) {
  using T = scalar_of<BP>;
  BP bp;
  const proxy_id a = bp.create(cube<T>(0, 0, 0, 1), 1);
  const proxy_id b = bp.create(cube<T>(1, 0, 0, 1), 2);
  bp.update();
  bp.destroy(b);
  std::vector<proxy_id> seen;
  bp.query(cube<T>(0, 0, 0, 5), [&](proxy_id id) { seen.push_back(id); });
  bp.ray_cast(ray<T>{{-5, 0, 0}, {10, 0, 0}}, T(1), [&](proxy_id id, T) { return seen.push_back(id), T(1); });
  CHECK(seen == std::vector<proxy_id>{a, a});
  bp.update();
  CHECK(bp.pairs().empty());
  REQUIRE(bp.ended().size() == 1);
  CHECK(bp.ended()[0] == proxy_pair{a, b});
}

TEST_CASE_TEMPLATE("a slot reused between updates ends the old pairs and begins new ones", BP,
                   IMPULSE_ALL_BROAD_PHASES) {
  using T = scalar_of<BP>;
  BP bp;
  const proxy_id a = bp.create(cube<T>(0, 0, 0, 1), 1);
  const proxy_id b = bp.create(cube<T>(1, 0, 0, 1), 2);
  bp.update();
  bp.destroy(b);
  const proxy_id c = bp.create(cube<T>(-1, 0, 0, 1), 3);  // b's slot, new generation
  REQUIRE(c.index == b.index);
  bp.update();
  REQUIRE(bp.pairs().size() == 1);
  CHECK(bp.pairs()[0] == proxy_pair{a, c});
  REQUIRE(bp.begun().size() == 1);
  CHECK(bp.begun()[0] == proxy_pair{a, c});
  REQUIRE(bp.ended().size() == 1);
  CHECK(bp.ended()[0] == proxy_pair{a, b});
  CHECK(bp.user_data(c) == 3);
}

TEST_CASE_TEMPLATE("an empty broad phase updates queries and casts rays", BP, IMPULSE_ALL_BROAD_PHASES) {
  using T = scalar_of<BP>;
  BP bp;
  bp.update();
  int calls = 0;
  bp.query(cube<T>(0, 0, 0, 1), [&](proxy_id) { ++calls; });
  bp.ray_cast(ray<T>{{0, 0, 0}, {1, 1, 1}}, T(1), [&](proxy_id, T f) { return ++calls, f; });
  CHECK(calls == 0);
  // Filled and emptied again.
  std::vector<proxy_id> ids;
  for (int i = 0; i < 50; ++i) ids.push_back(bp.create(cube<T>(T(i) * T(0.5), 0, 0, T(0.5)), 0));
  bp.update();
  CHECK(bp.pairs().size() == 49 + 48);  // each cube touches two neighbours each side (faces at 0.5 apart)
  for (const proxy_id id : ids) bp.destroy(id);
  bp.update();
  CHECK(bp.pairs().empty());
  CHECK(bp.ended().size() == 49 + 48);
  CHECK(bp.size() == 0);
}

TEST_CASE_TEMPLATE("only the last of several moves between updates counts", BP, IMPULSE_ALL_BROAD_PHASES) {
  using T = scalar_of<BP>;
  BP bp;
  const proxy_id a = bp.create(cube<T>(0, 0, 0, 1), 0);
  const proxy_id b = bp.create(cube<T>(10, 0, 0, 1), 0);
  bp.update();
  bp.move(b, cube<T>(1, 0, 0, 1));    // would overlap a
  bp.move(b, cube<T>(100, 0, 0, 1));  // far away
  bp.move(b, cube<T>(2, 0, 0, 1));    // touches a at x = 1
  bp.update();
  REQUIRE(bp.pairs().size() == 1);
  CHECK(bp.pairs()[0] == proxy_pair{a, b});
  bp.move(b, cube<T>(-50, 0, 0, 1));
  bp.move(b, cube<T>(10, 0, 0, 1));  // back where it started: the pair ends
  bp.update();
  CHECK(bp.pairs().empty());
}

TEST_CASE_TEMPLATE("bad boxes rays and ids are refused and change nothing", BP, IMPULSE_ALL_BROAD_PHASES) {
  using T = scalar_of<BP>;
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const T inf = std::numeric_limits<T>::infinity();
  BP bp;
  const proxy_id a = bp.create(cube<T>(0, 0, 0, 1), 7);
  const proxy_id b = bp.create(cube<T>(1, 0, 0, 1), 8);
  const proxy_id gone = bp.create(cube<T>(9, 0, 0, 1), 9);
  bp.destroy(gone);
  bp.update();
  REQUIRE(bp.pairs().size() == 1);
  CHECK(error_code_of([&] { bp.create(cube<T>(nan, 0, 0, 1), 0); }) == error_code::non_finite);
  CHECK(error_code_of([&] { bp.create(aabb<T>{{0, 0, 0}, {inf, 1, 1}}, 0); }) == error_code::non_finite);
  CHECK(error_code_of([&] { bp.create(aabb<T>{{1, 0, 0}, {0, 1, 1}}, 0); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { bp.move(a, cube<T>(0, nan, 0, 1)); }) == error_code::non_finite);
  CHECK(error_code_of([&] { bp.move(a, aabb<T>{{0, 2, 0}, {1, 1, 1}}); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { bp.move(gone, cube<T>(0, 0, 0, 1)); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { bp.destroy(gone); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { (void)bp.user_data(gone); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { bp.query(aabb<T>{{0, 0, 0}, {nan, 1, 1}}, [](proxy_id) {}); }) == error_code::non_finite);
  CHECK(error_code_of([&] { bp.ray_cast(ray<T>{{0, 0, 0}, {inf, 0, 0}}, T(1), [](proxy_id, T f) { return f; }); }) ==
        error_code::non_finite);
  CHECK(error_code_of([&] { bp.ray_cast(ray<T>{{0, 0, 0}, {1, 0, 0}}, T(-1), [](proxy_id, T f) { return f; }); }) ==
        error_code::invalid_parameter);
  bp.update();
  CHECK(bp.size() == 2);
  REQUIRE(bp.pairs().size() == 1);
  CHECK(bp.pairs()[0] == proxy_pair{a, b});
  CHECK(bp.begun().empty());
  CHECK(bp.ended().empty());
  CHECK(bp.box(a) == cube<T>(0, 0, 0, 1));
  CHECK(bp.user_data(b) == 8);
}

TEST_CASE_TEMPLATE("an update after nothing came, moved or went keeps the pairs and begins and ends none", BP,
                   IMPULSE_ALL_BROAD_PHASES) {
  using T = scalar_of<BP>;
  BP bp;
  const proxy_id a = bp.create(cube<T>(0, 0, 0, 1), 1);
  const proxy_id b = bp.create(cube<T>(1, 0, 0, 1), 2);
  const proxy_id c = bp.create(cube<T>(5, 0, 0, 1), 3);
  bp.update();
  REQUIRE(bp.begun().size() == 1);
  bp.update();  // the world's step with every body asleep
  REQUIRE(bp.pairs().size() == 1);
  CHECK(bp.pairs()[0] == proxy_pair{a, b});
  CHECK(bp.begun().empty());
  CHECK(bp.ended().empty());
  bp.move(c, cube<T>(1.5, 0, 0, 1));  // then one moves: its pairs begin
  bp.update();
  CHECK(bp.pairs().size() == 3);
  CHECK(bp.begun().size() == 2);
  CHECK(bp.ended().empty());
}

}  // namespace broadphase_contract_tests
