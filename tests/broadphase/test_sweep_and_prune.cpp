// Sweep and prune: exactly brute force's pairs, queries and rays on every
// hard scene, and the incremental sort doing little work under coherent
// motion and a lot under its documented worst case.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "impulse/broadphase.hpp"
#include "impulse/core/random.hpp"

#include "against_brute_force.hpp"
#include "../error_code_of.hpp"
#include "cube.hpp"

namespace broadphase_sweep_and_prune_tests {

namespace {

using namespace impulse;
using impulse::broadphase::basic_sweep_and_prune;

static_assert(broadphase::broad_phase<basic_sweep_and_prune<float>, float>);
static_assert(broadphase::broad_phase<basic_sweep_and_prune<double>, double>);
static_assert(broadphase::broad_phase<broadphase::sweep_and_prune::type<float>, float>);
static_assert(broadphase::check_broad_phase<basic_sweep_and_prune<float>, float>());

using test::cube;
using impulse::test::error_code_of;

}  // namespace

TEST_CASE_TEMPLATE("sweep and prune reports exactly the brute-force pairs on every hard scene", T, float, double) {
  for (const test::scene_kind kind : test::all_scene_kinds) {
    INFO(test::name_of(kind));
    basic_sweep_and_prune<T> bp;
    const int count = kind == test::scene_kind::one_spot ? 120 : 300;
    const auto seen = test::run_against_brute_force<basic_sweep_and_prune<T>, T>(bp, kind, count, 40, 2024);
    CHECK(seen.pairs > 0);
    CHECK(seen.queries > 0);
    CHECK(seen.ray_hits > 0);
  }
}

TEST_CASE_TEMPLATE("regions of a few boxes each report exactly the brute-force pairs on every hard scene", T, float,
                   double) {
  // Eight boxes a region: dozens of regions, most boxes over two or more
  // cells, boxes crossing between regions every step, and the huge boxes of
  // the mixed scene kept out of the regions.
  for (const test::scene_kind kind : test::all_scene_kinds) {
    CAPTURE(test::name_of(kind));
    basic_sweep_and_prune<T> bp{8};
    const int count = kind == test::scene_kind::one_spot ? 120 : 300;
    const auto seen = test::run_against_brute_force<basic_sweep_and_prune<T>, T>(bp, kind, count, 40, 2025);
    CHECK(seen.pairs > 0);
    CHECK(seen.queries > 0);
    CHECK(seen.ray_hits > 0);
    // All in one spot leaves nothing to cut; everything else is cut up.
    if (kind == test::scene_kind::one_spot)
      CHECK(bp.region_count() == 1);
    else
      CHECK(bp.region_count() >= 8);
  }
}

TEST_CASE_TEMPLATE("regions divide the swaps of a shaken scene", T, float, double) {
  // 2000 boxes in a 19 m cube, each moving up to 0.1 m a step at random:
  // in one set of lists an end overtakes every end between its old and new
  // place; in regions of about 64 boxes only those of its own region.
  // Swap counts are exact (no timing here), and the pairs are the same.
  basic_sweep_and_prune<T> one{1'000'000}, many{64};
  lcg32 random{7};
  const T side = T(19);
  std::vector<aabb<T>> boxes;
  std::vector<proxy_id> in_one, in_many;
  for (int i = 0; i < 2000; ++i) {
    const T half = random.uniform<T>(T(0.1), T(0.6));
    boxes.push_back(cube<T>(random.uniform<T>(0, side), random.uniform<T>(0, side), random.uniform<T>(0, side), half));
    in_one.push_back(one.create(boxes.back(), 0));
    in_many.push_back(many.create(boxes.back(), 0));
  }
  one.update();
  many.update();
  REQUIRE(one.region_count() == 1);
  REQUIRE(many.region_count() >= 16);
  std::size_t swaps_one = 0, swaps_many = 0;
  for (int step = 0; step < 10; ++step) {
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      const vec3<T> d{random.uniform<T>(T(-0.1), T(0.1)), random.uniform<T>(T(-0.1), T(0.1)),
                      random.uniform<T>(T(-0.1), T(0.1))};
      boxes[i] = {boxes[i].lower + d, boxes[i].upper + d};
      one.move(in_one[i], boxes[i]);
      many.move(in_many[i], boxes[i]);
    }
    one.update();
    many.update();
    swaps_one += one.swaps();
    swaps_many += many.swaps();
    REQUIRE(std::equal(one.pairs().begin(), one.pairs().end(), many.pairs().begin(), many.pairs().end()));
  }
  CHECK(one.pairs().size() > 500);
  MESSAGE("swaps in one region: " << swaps_one << ", in " << many.region_count() << " regions: " << swaps_many);
  CHECK(4 * swaps_many < swaps_one);
}

TEST_CASE_TEMPLATE("a world grown one box an update regrids as it doubles and a ground stays out of the regions", T,
                   float, double) {
  basic_sweep_and_prune<T> bp{16};
  broadphase::basic_brute_force<T> reference;
  // The ground first: a 40 m slab under everything, over every cell.
  const aabb<T> ground{{T(-20), T(-1), T(-20)}, {T(20), T(0), T(20)}};
  bp.create(ground, 0);
  reference.create(ground, 0);
  lcg32 random{11};
  std::size_t regions_seen = 0;
  for (int i = 0; i < 600; ++i) {
    const aabb<T> box = cube<T>(random.uniform<T>(-19, 19), random.uniform<T>(T(0.3), T(3)), random.uniform<T>(-19, 19),
                                T(0.5));
    bp.create(box, 0);
    reference.create(box, 0);
    bp.update();
    reference.update();
    REQUIRE(std::equal(bp.pairs().begin(), bp.pairs().end(), reference.pairs().begin(), reference.pairs().end()));
    regions_seen = std::max(regions_seen, bp.region_count());
  }
  // The grid is chosen afresh each time the count passes twice that of the
  // last choice (2, 5, 11, …, 383 boxes): at last for about 383 / 16 = 23
  // regions.
  CHECK(regions_seen >= 16);
  CHECK(bp.big_count() == 1);
  CHECK(reference.pairs().size() > 300);
}

TEST_CASE_TEMPLATE("coherent motion costs no swaps and reversing a row costs one per crossing of ends", T, float,
                   double) {
  // n unit cubes in a row along x, 2 m apart: 1 m gaps.
  constexpr int n = 64;
  basic_sweep_and_prune<T> bp;
  std::vector<proxy_id> row;
  for (int i = 0; i < n; ++i) row.push_back(bp.create(cube<T>(T(2 * i), 0, 0, T(0.5)), std::uint64_t(i)));
  bp.update();
  CHECK(bp.pairs().empty());

  // The whole row slides 0.4 m: no end overtakes another (the gaps are 1 m).
  for (int i = 0; i < n; ++i) bp.move(row[std::size_t(i)], cube<T>(T(2 * i) + T(0.4), 0, 0, T(0.5)));
  bp.update();
  CHECK(bp.swaps() == 0);
  CHECK(bp.pairs().empty());

  // The worst case: the row mirrored about x = 0. Every box overtakes every
  // other, and each box pair's four ends all cross: insertion sort performs
  // exactly 4·n(n−1)/2 swaps, all on the x axis.
  for (int i = 0; i < n; ++i) bp.move(row[std::size_t(i)], cube<T>(-T(2 * i), 0, 0, T(0.5)));
  bp.update();
  CHECK(bp.swaps() == std::size_t(2 * n * (n - 1)));
  CHECK(bp.pairs().empty());  // passing through each other, they end apart

  // Half a metre closer together: neighbours touch at their faces.
  for (int i = 0; i < n; ++i) bp.move(row[std::size_t(i)], cube<T>(-T(i), 0, 0, T(0.5)));
  bp.update();
  CHECK(bp.pairs().size() == std::size_t(n - 1));
}

TEST_CASE_TEMPLATE("a box landing level with resting boxes walks past none of their ends", T, float, double) {
  // A 10 × 10 floor of unit cubes, bottoms at y = 0 and tops at y = 1, and
  // one more cube 20 m away along x, 0.5 m up. It drops to y = 0: level with
  // all the others. Ends of one kind at equal values stay where they are,
  // so its lower end stops above the hundred lower ends at 0 and its upper
  // end above the hundred upper ends at 1: no swap at all (and no pair).
  // Walking past equal ends would cost 200 swaps here, and a crowd resting
  // on one floor makes that every landing.
  basic_sweep_and_prune<T> bp;
  for (int i = 0; i < 10; ++i)
    for (int k = 0; k < 10; ++k) bp.create(cube<T>(T(2 * i), T(0.5), T(2 * k), T(0.5)), 0);
  const proxy_id falling = bp.create(cube<T>(T(40), T(1), T(0), T(0.5)), 0);
  bp.update();
  bp.move(falling, cube<T>(T(40), T(0.5), T(0), T(0.5)));
  bp.update();
  CHECK(bp.swaps() == 0);
  CHECK(bp.pairs().empty());
  // Moved onto the first cube's top face, it touches that cube alone.
  bp.move(falling, cube<T>(T(0), T(1.5), T(0), T(0.5)));
  bp.update();
  CHECK(bp.pairs().size() == 1);
}

TEST_CASE_TEMPLATE("boxes added one at a time and many at once give the same pairs", T, float, double) {
  // Two ways in: a few new boxes are sifted in from the top of each axis, a
  // crowd of them triggers a fresh sort and one sweep.
  basic_sweep_and_prune<T> one_by_one, crowd;
  broadphase::basic_brute_force<T> reference;
  lcg32 random{99};
  for (int round = 0; round < 20; ++round) {
    for (int k = 0; k < 3; ++k) {  // 3 < log2(size): sifted in
      const aabb<T> box = cube<T>(random.uniform<T>(0, 8), random.uniform<T>(0, 8), random.uniform<T>(0, 8), T(0.7));
      one_by_one.create(box, 0);
      crowd.create(box, 0);
      reference.create(box, 0);
    }
    one_by_one.update();
    if (round % 5 == 4) crowd.update();  // 15 at a time: sorted afresh
    reference.update();
    if (round % 5 == 4) CHECK(std::equal(crowd.pairs().begin(), crowd.pairs().end(), reference.pairs().begin(),
                                         reference.pairs().end()));
    CHECK(std::equal(one_by_one.pairs().begin(), one_by_one.pairs().end(), reference.pairs().begin(),
                     reference.pairs().end()));
  }
  CHECK(reference.pairs().size() > 50);
}

TEST_CASE_TEMPLATE("regions of no boxes are refused", T, float, double) {
  CHECK(error_code_of([] { basic_sweep_and_prune<T>{0}; }) == error_code::invalid_parameter);
  // One box a region is allowed: every box its own region, as far as the
  // grid can cut (no cell thinner than twice the mean box).
  basic_sweep_and_prune<T> bp{1};
  for (int i = 0; i < 50; ++i) bp.create(cube<T>(T(3 * i), 0, 0, T(0.5)), 0);
  bp.update();
  CHECK(bp.region_count() >= 25);
  CHECK(bp.pairs().empty());
}

}  // namespace broadphase_sweep_and_prune_tests
