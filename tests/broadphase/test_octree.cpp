// The loose octree: against brute force over every standard scene, and the
// properties of the structure itself: the depth a box is filed at follows
// from its size alone, coherent motion leaves the tree alone, the root grows
// to take in a box far away, and an emptied tree gives back its nodes.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "impulse/broadphase/octree.hpp"

#include "../error_code_of.hpp"
#include "against_brute_force.hpp"
#include "cube.hpp"

namespace broadphase_octree_tests {

namespace {

using namespace impulse;
using impulse::broadphase::basic_brute_force;
using impulse::broadphase::basic_octree;
using impulse::test::error_code_of;

static_assert(broadphase::broad_phase<basic_octree<float>, float>);
static_assert(broadphase::broad_phase<basic_octree<double>, double>);
static_assert(broadphase_policy<broadphase::octree>);

using test::cube;

template <class T>
T edge_of(const aabb<T>& b) {
  return b.upper.x - b.lower.x;
}

/// Updates both and compares the pairs, begun and ended of `tested` with
/// those of a brute force fed the same boxes.
template <class T>
void check_exact(basic_octree<T>& tested, basic_brute_force<T>& reference) {
  tested.update();
  reference.update();
  CHECK(std::equal(tested.pairs().begin(), tested.pairs().end(), reference.pairs().begin(), reference.pairs().end()));
  CHECK(std::equal(tested.begun().begin(), tested.begun().end(), reference.begun().begin(), reference.begun().end()));
  CHECK(std::equal(tested.ended().begin(), tested.ended().end(), reference.ended().begin(), reference.ended().end()));
}

}  // namespace

TEST_CASE_TEMPLATE("the octree finds the same pairs as brute force in every scene", T, float, double) {
  for (const auto kind : impulse::test::all_scene_kinds) {
    INFO(impulse::test::name_of(kind));
    basic_octree<T> bp;
    const int count = kind == impulse::test::scene_kind::one_spot ? 120 : 300;
    const auto counts = impulse::test::run_against_brute_force<basic_octree<T>, T>(bp, kind, count, 40, 2024);
    CHECK(counts.pairs > 0);
    CHECK(counts.queries > 0);
    CHECK(counts.ray_hits > 0);
  }
}

TEST_CASE_TEMPLATE("the octree stays exact at its extreme depth caps", T, float, double) {
  // max_depth 0 files everything at the root (a brute force with extra
  // steps); 16 lets zero-size boxes sink as far as the keys allow.
  for (const int depth : {0, 1, 16}) {
    INFO("max_depth " << depth);
    for (const auto kind : {impulse::test::scene_kind::mixed_sizes, impulse::test::scene_kind::points,
                            impulse::test::scene_kind::far_away}) {
      INFO(impulse::test::name_of(kind));
      basic_octree<T> bp{depth};
      const auto counts = impulse::test::run_against_brute_force<basic_octree<T>, T>(bp, kind, 150, 12, 77);
      CHECK(counts.pairs > 0);
    }
  }
}

TEST_CASE_TEMPLATE("a box is filed at the depth its size implies", T, float, double) {
  // A root-sized box fixes the root; then boxes of edge e0 / 2^k, centered
  // on the root's center, are filed at depth k (every size here is a power
  // of two times e0, so there is no rounding to allow for), down to
  // max_depth and no further; a box a quarter larger than e0 / 2^k goes
  // one level up.
  basic_octree<T> bp;
  bp.create(cube<T>(0, 0, 0, 40), 0);
  const aabb<T> root = bp.root_box();
  const T e0 = edge_of(root);
  CHECK(e0 >= T(80));  // encloses the first box
  const vec3<T> mid = center(root);
  for (int k = 0; k <= bp.max_depth() + 3; ++k) {
    INFO("k = " << k);
    const T half = std::ldexp(e0, -k) / T(2);
    const proxy_id exact = bp.create(aabb<T>::from_center_half_extents(mid, vec3<T>::splat(half)), 1);
    CHECK(bp.depth_of(exact) == std::min(k, bp.max_depth()));
    if (k >= 1) {
      const proxy_id larger = bp.create(aabb<T>::from_center_half_extents(mid, vec3<T>::splat(half * T(1.25))), 2);
      CHECK(bp.depth_of(larger) == std::min(k, bp.max_depth() + 1) - 1);
    }
  }
  // Thin boxes go by their largest extent, and a point sinks to the bottom.
  const proxy_id plank = bp.create(aabb<T>{mid, mid + vec3<T>{e0 / T(8), 0, 0}}, 3);
  CHECK(bp.depth_of(plank) == 3);
  const proxy_id point = bp.create(aabb<T>{mid, mid}, 4);
  CHECK(bp.depth_of(point) == bp.max_depth());
  // A box wider than half the root (the root's children's cells) sits at
  // the root itself.
  const proxy_id wide = bp.create(aabb<T>{root.lower, root.lower + vec3<T>{e0 * T(0.75), T(1), T(1)}}, 5);
  CHECK(bp.depth_of(wide) == 0);
  CHECK(bp.root_box() == root);  // nothing above grew the root

  // A box larger than the whole root cell grows the root around it (to a
  // power of two 1.5 to 3 times the data: 4·e0 for an edge of 2.4·e0) and
  // then, wider than half the new root, sits at its top.
  const proxy_id huge = bp.create(aabb<T>::from_center_half_extents(mid, vec3<T>::splat(T(1.2) * e0)), 6);
  CHECK(edge_of(bp.root_box()) == 4 * e0);
  CHECK(bp.depth_of(huge) == 0);
  CHECK(bp.depth_of(wide) == 2);  // the others follow the rule under the new root
  CHECK(bp.depth_of(plank) == 5);

  basic_octree<T> shallow{3};
  shallow.create(cube<T>(0, 0, 0, 40), 0);
  CHECK(shallow.depth_of(shallow.create(cube<T>(1, 1, 1, T(0.01)), 1)) == 3);
}

TEST_CASE_TEMPLATE("random boxes are filed at the deepest depth whose cell edge covers their largest extent", T,
                   float, double) {
  // The rule d = min(max_depth, floor(log2(e0 / extent))), checked with
  // exact powers of two. A box may go one level up only where rounding its
  // center puts it a hair outside the loose box, which takes a center
  // within rounding of a cell face and an extent within rounding of the
  // cell edge: the random boxes here never do, so no tolerance is allowed.
  basic_octree<T> bp;
  lcg32 random{21};
  bp.create(cube<T>(50, 50, 50, 50), 0);  // fixes the root
  const aabb<T> root = bp.root_box();
  const T e0 = edge_of(root);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const T largest = T(60) * std::pow(T(2), -T(12) * random.template uniform<T>());  // 60 m down to 1.5 cm
    const vec3<T> half{largest / 2, largest / 2 * random.template uniform<T>(), largest / 2 * random.template uniform<T>()};
    const vec3<T> c{T(20) + T(60) * random.template uniform<T>(), T(20) + T(60) * random.template uniform<T>(),
                    T(20) + T(60) * random.template uniform<T>()};
    const aabb<T> b = aabb<T>::from_center_half_extents(c, half);
    if (!contains(bp.root_box(), b)) continue;
    const T size = b.upper.x - b.lower.x;
    int expected = 0;
    while (expected < bp.max_depth() && std::ldexp(e0, -(expected + 1)) >= size) ++expected;
    const proxy_id id = bp.create(b, 0);
    CHECK(bp.depth_of(id) == expected);
    ++checked;
  }
  CHECK(checked > 1000);
  CHECK(bp.root_box() == root);  // nothing grew the root on the way
}

TEST_CASE_TEMPLATE("queries and rays see creates moves and destroys before the next update", T, float, double) {
  // Pairs wait for update(), but a query or a ray cast answers for the
  // boxes as they are now, as brute force does.
  basic_octree<T> bp;
  basic_brute_force<T> reference;
  lcg32 random{8};
  std::vector<proxy_id> ids;
  const auto draw = [&] {
    return cube<T>(T(15) * random.template uniform<T>(), T(15) * random.template uniform<T>(),
                   T(15) * random.template uniform<T>(), T(0.05) + T(0.8) * random.template uniform<T>());
  };
  const auto key = [](proxy_id id) { return (std::uint64_t(id.index) << 32) | id.generation; };
  const auto compare = [&](int round) {
    INFO("round " << round);
    for (int q = 0; q < 5; ++q) {
      const aabb<T> region = cube<T>(T(15) * random.template uniform<T>(), T(15) * random.template uniform<T>(),
                                     T(15) * random.template uniform<T>(), T(1) + T(3) * random.template uniform<T>());
      std::vector<std::uint64_t> got, expected;
      bp.query(region, [&](proxy_id id) { got.push_back(key(id)); });
      reference.query(region, [&](proxy_id id) { expected.push_back(key(id)); });
      std::sort(got.begin(), got.end());
      std::sort(expected.begin(), expected.end());
      CHECK(got == expected);
      const ray<T> r{region.lower, region.upper - region.lower + vec3<T>{T(4), T(-2), T(3)}};
      std::vector<std::pair<std::uint64_t, T>> hits, expected_hits;
      bp.ray_cast(r, T(1), [&](proxy_id id, T t) { return hits.push_back({key(id), t}), T(1); });
      reference.ray_cast(r, T(1), [&](proxy_id id, T t) { return expected_hits.push_back({key(id), t}), T(1); });
      std::sort(hits.begin(), hits.end());
      std::sort(expected_hits.begin(), expected_hits.end());
      CHECK(hits == expected_hits);
    }
  };
  for (int i = 0; i < 200; ++i) {
    const aabb<T> b = draw();
    ids.push_back(bp.create(b, 0));
    reference.create(b, 0);
  }
  compare(0);  // before any update at all
  bp.update();
  reference.update();
  for (int round = 1; round <= 6; ++round) {
    for (std::size_t i = 0; i < ids.size(); i += 3) {
      const aabb<T> b = draw();
      bp.move(ids[i], b);
      reference.move(ids[i], b);
    }
    for (int k = 0; k < 10; ++k) {
      const std::size_t i = random.next() % ids.size();
      bp.destroy(ids[i]);
      reference.destroy(ids[i]);
      const aabb<T> b = draw();
      ids[i] = bp.create(b, 0);
      CHECK(reference.create(b, 0) == ids[i]);
    }
    if (round == 4) {  // and after a box far away has grown the root
      ids.push_back(bp.create(cube<T>(T(-3000), 0, 0, 1), 0));
      reference.create(cube<T>(T(-3000), 0, 0, 1), 0);
    }
    compare(round);
    if (round % 2 == 0) {
      bp.update();
      reference.update();
      CHECK(std::equal(bp.pairs().begin(), bp.pairs().end(), reference.pairs().begin(), reference.pairs().end()));
    }
  }
}

TEST_CASE_TEMPLATE("moving within its node changes nothing and moving across the world stays exact", T, float,
                   double) {
  basic_octree<T> bp;
  basic_brute_force<T> reference;
  std::vector<proxy_id> ids;
  lcg32 random{99};
  const auto add = [&](const aabb<T>& b) {
    ids.push_back(bp.create(b, ids.size()));
    reference.create(b, ids.size());
  };
  // A lattice of unit cubes a little apart, inside a root of edge 64.
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k) add(cube<T>(T(4 * i), T(4 * j), T(4 * k), T(0.5)));
  add(cube<T>(T(10), T(10), T(10), T(20)));  // a big one over most of them
  check_exact(bp, reference);
  const std::size_t nodes = bp.node_count();
  const aabb<T> root = bp.root_box();

  // The root's edge is a power of two and its corner a multiple of a
  // sixteenth of it, so these lattice centers (multiples of 4) sit on the
  // lower corners of cells of edge 1 and 2: drifting by up to 0.1 m in +x
  // keeps the center in its cell and the size in its depth.
  const proxy_id mover = ids[43];  // at (4, 4, 4)
  const int depth = bp.depth_of(mover);
  const aabb<T> start = bp.box(mover);
  for (int step = 1; step <= 10; ++step) {
    const aabb<T> moved = cube<T>(T(4) + T(0.01) * T(step), T(4), T(4), T(0.5));
    bp.move(mover, moved);
    reference.move(mover, moved);
    CHECK(bp.depth_of(mover) == depth);
    CHECK(bp.node_count() == nodes);
    check_exact(bp, reference);
  }
  CHECK(bp.box(mover) != start);

  // Across the world, through the others: pairs begin and end exactly, and
  // the query finds it where it is now.
  for (int step = 0; step < 20; ++step) {
    const T u = T(20) * random.template uniform<T>(), v = T(20) * random.template uniform<T>();
    // (Half 0.45, not 0.5: an edge of exactly 1 m computed from a rounded
    // center can come out a hair over 1 and go up a level, rightly.)
    const aabb<T> moved = cube<T>(u, v, T(20) - u, T(0.45));
    bp.move(mover, moved);
    reference.move(mover, moved);
    CHECK(bp.depth_of(mover) == depth);
    check_exact(bp, reference);
    std::vector<proxy_id> found;
    bp.query(moved, [&](proxy_id id) { found.push_back(id); });
    CHECK(std::find(found.begin(), found.end(), mover) != found.end());
  }
  CHECK(bp.root_box() == root);
  // Back home, the nodes made on the way have all been freed again.
  bp.move(mover, start);
  reference.move(mover, start);
  check_exact(bp, reference);
  CHECK(bp.node_count() == nodes);
}

TEST_CASE_TEMPLATE("a box created 1e5 m away grows the root and everything stays exact", T, float, double) {
  basic_octree<T> bp;
  basic_brute_force<T> reference;
  std::vector<proxy_id> ids;
  lcg32 random{7};
  const auto add = [&](const aabb<T>& b) {
    ids.push_back(bp.create(b, 0));
    CHECK(reference.create(b, 0) == ids.back());
  };
  for (int i = 0; i < 200; ++i) {
    const T x = T(10) * random.template uniform<T>(), y = T(10) * random.template uniform<T>(),
            z = T(10) * random.template uniform<T>();
    add(cube<T>(x, y, z, T(0.3) + T(0.5) * random.template uniform<T>()));
  }
  check_exact(bp, reference);
  const aabb<T> before = bp.root_box();
  CHECK(edge_of(before) <= T(64));

  // A box at 1e5, and a few around it overlapping each other.
  add(cube<T>(T(1e5), T(-1e5), T(1e5), T(1)));
  const aabb<T> after = bp.root_box();
  CHECK(edge_of(after) > T(1e5));
  CHECK(contains(after, before));
  CHECK(contains(after, bp.box(ids.back())));
  for (int i = 0; i < 20; ++i)
    add(cube<T>(T(1e5) + T(i) * T(0.5), T(-1e5), T(1e5), T(0.5)));
  check_exact(bp, reference);
  CHECK(bp.pairs().size() > 20);

  // Every proxy moves a little; the far ones still meet exactly.
  for (int step = 0; step < 5; ++step) {
    for (const proxy_id id : ids) {
      const aabb<T> b = bp.box(id);
      const vec3<T> shift = vec3<T>{T(0.1), T(-0.05), T(0.02)} * T(step % 2 == 0 ? 1 : -1);
      bp.move(id, {b.lower + shift, b.upper + shift});
      reference.move(id, {b.lower + shift, b.upper + shift});
    }
    check_exact(bp, reference);
  }
  // The far boxes leave again: the root shrinks back at the next update.
  for (std::size_t i = 200; i < ids.size(); ++i) {
    bp.destroy(ids[i]);
    reference.destroy(ids[i]);
  }
  check_exact(bp, reference);
  CHECK(edge_of(bp.root_box()) <= T(64));
}

TEST_CASE_TEMPLATE("destroying every proxy leaves no pairs and no nodes", T, float, double) {
  basic_octree<T> bp;
  std::vector<proxy_id> ids;
  lcg32 random{3};
  for (int i = 0; i < 300; ++i)
    ids.push_back(bp.create(cube<T>(T(12) * random.template uniform<T>(), T(12) * random.template uniform<T>(),
                                    T(12) * random.template uniform<T>(), T(0.1) + random.template uniform<T>()),
                            0));
  bp.update();
  const std::size_t had = bp.pairs().size();
  CHECK(had > 0);
  CHECK(bp.node_count() > 1);
  for (const proxy_id id : ids) bp.destroy(id);
  CHECK(bp.root_box() == aabb<T>::empty());  // the next box chooses a root of its own
  bp.update();
  CHECK(bp.node_count() == 0);
  CHECK(bp.pairs().empty());
  CHECK(bp.ended().size() == had);
  CHECK(bp.size() == 0);
  int visited = 0;
  bp.query(cube<T>(6, 6, 6, 100), [&](proxy_id) { ++visited; });
  bp.ray_cast(ray<T>{{0, 0, 0}, {12, 12, 12}}, T(1), [&](proxy_id, T f) { return ++visited, f; });
  CHECK(visited == 0);

  // And it works again from scratch, somewhere else.
  const proxy_id a = bp.create(cube<T>(-500, 0, 0, 1), 0);
  const proxy_id b = bp.create(cube<T>(-499, 0, 0, 1), 0);
  bp.update();
  REQUIRE(bp.pairs().size() == 1);
  CHECK(bp.pairs()[0] == pair_of(a, b));
  CHECK(edge_of(bp.root_box()) <= T(16));
}

TEST_CASE_TEMPLATE("a ray cast visits the nearest boxes first and stops when clipped", T, float, double) {
  // A row of 64 unit cubes along x; a clipping callback should see only a
  // few of them before the nearest hit clips the rest away (a tree that
  // visited in arbitrary order would report about half).
  basic_octree<T> bp;
  for (int i = 0; i < 64; ++i) bp.create(cube<T>(T(3 * i), 0, 0, T(0.5)), std::uint64_t(i));
  int calls = 0;
  T nearest = T(1);
  bp.ray_cast(ray<T>{{T(-10), 0, 0}, {T(300), 0, 0}}, T(1), [&](proxy_id, T f) {
    ++calls;
    return nearest = std::min(nearest, f);
  });
  CHECK(nearest == T(9.5) / T(300));
  CHECK(calls <= 8);
  // Starting clipped at 0 reports nothing, as brute force.
  calls = 0;
  bp.ray_cast(ray<T>{{T(0), 0, 0}, {T(1), 0, 0}}, T(0), [&](proxy_id, T f) { return ++calls, f; });
  CHECK(calls == 0);
}

TEST_CASE_TEMPLATE("bad boxes rays ids and depths are refused and change nothing", T, float, double) {
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const T inf = std::numeric_limits<T>::infinity();
  basic_octree<T> bp;
  const proxy_id a = bp.create(cube<T>(0, 0, 0, 1), 7);
  const proxy_id b = bp.create(cube<T>(1, 0, 0, 1), 8);
  const proxy_id gone = bp.create(cube<T>(9, 0, 0, 1), 9);
  bp.destroy(gone);
  bp.update();
  const std::vector<proxy_pair> before(bp.pairs().begin(), bp.pairs().end());
  const std::size_t nodes = bp.node_count();
  const aabb<T> root = bp.root_box();

  CHECK(error_code_of([&] { bp.create(cube<T>(nan, 0, 0, 1), 0); }) == error_code::non_finite);
  CHECK(error_code_of([&] { bp.create(cube<T>(inf, 0, 0, 1), 0); }) == error_code::non_finite);
  CHECK(error_code_of([&] { bp.create(aabb<T>{{1, 0, 0}, {0, 1, 1}}, 0); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { bp.move(a, cube<T>(0, nan, 0, 1)); }) == error_code::non_finite);
  CHECK(error_code_of([&] { bp.move(a, aabb<T>{{1e6, 0, 0}, {-1e6, 1, 1}}); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { bp.move(gone, cube<T>(0, 0, 0, 1)); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { bp.destroy(gone); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { (void)bp.depth_of(gone); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { bp.query(cube<T>(0, 0, nan, 1), [](proxy_id) {}); }) == error_code::non_finite);
  CHECK(error_code_of([&] { bp.ray_cast(ray<T>{{nan, 0, 0}, {1, 0, 0}}, T(1), [](proxy_id, T f) { return f; }); }) ==
        error_code::non_finite);
  CHECK(error_code_of([&] { bp.ray_cast(ray<T>{{0, 0, 0}, {1, 0, 0}}, T(-1), [](proxy_id, T f) { return f; }); }) ==
        error_code::invalid_parameter);
  // Finite but so far out that a root around it would overflow.
  const T too_far = std::numeric_limits<T>::max() / T(16);
  CHECK(error_code_of([&] { bp.create(cube<T>(too_far, 0, 0, 1), 0); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { bp.move(a, cube<T>(0, -too_far, 0, 1)); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { bp.move(gone, cube<T>(0, -too_far, 0, 1)); }) == error_code::out_of_range);
  CHECK(error_code_of([] { basic_octree<T> bad{-1}; }) == error_code::invalid_parameter);
  CHECK(error_code_of([] { basic_octree<T> bad{17}; }) == error_code::invalid_parameter);

  CHECK(bp.size() == 2);
  CHECK(bp.node_count() == nodes);
  CHECK(bp.root_box() == root);
  CHECK(bp.box(a) == cube<T>(0, 0, 0, 1));
  CHECK(bp.user_data(b) == 8);
  bp.update();
  CHECK(std::equal(bp.pairs().begin(), bp.pairs().end(), before.begin(), before.end()));
  CHECK(bp.begun().empty());
  CHECK(bp.ended().empty());
}

}  // namespace broadphase_octree_tests
