// tests/peers/ccd_agreement.cpp — our GJK distances and EPA depths against
// libccd's (Debian's libccd-dev 2.1, double) and against the exact answer
// of a brute force (convex_pairs.hpp) on 11 000 seeded random convex pairs:
// ten pairings of sphere, box, capsule and hull, 1 100 each, half
// overlapping and half apart, sizes 0.1 m to 2 m, random rotations.
//
// Built as its own executable, impulse_peer_tests, only when libccd is
// found (tests/CMakeLists.txt); it is not part of test_sources.txt.
//
// Errors are relative with a floor of 1 cm: |x − ref| / max(|ref|, 0.01 m),
// so that 1e-9 m on a 1e-6 m distance does not count as 1e-3 "relative"
// (and no pair is closer to touching than 1e-6 m: convex_pairs.hpp draws
// those again).
//
// libccd 2.1 is not always right, and the test says so rather than widen
// its tolerance. Its EPA expands only the polytope's nearest face (or the
// two faces at its nearest edge) towards each new support point, instead
// of every face the point can see: the polytope folds inwards, and its
// nearest face can lie well inside A − B, so the depth comes out short
// (FCL's copy of libccd was fixed for this in 2018; Debian ships the
// original). A sphere 0.5 m inside a unit sphere along x (exact depth 0.8)
// gets 0.725 from ccdGJKPenetration; its MPR gets 0.8 there, but MPR's
// depth is along the line between the centers, not the least. libccd 2.1
// also has no distance query: ccd_shapes.hpp gets one from its EPA on B
// grown by a ball, which inherits the fold on a curved surface.
//
// So, for every pair: ours must match the exact answer to 1e-8; wherever
// libccd is within 1e-4 of the exact answer, ours must be within 1e-4 of
// libccd; wherever libccd is not, its depth must be short of the exact one
// (the fold, and not a broken adapter, which would err either way). Measured
// (g++ 12 and clang 14, -O3 -march=native, seeds 2024 to 2033; the counts
// move by a few pairs between compilers, libccd's rounding differing):
//   depth:    libccd right on 5159 of 5500 pairs, short on the other 341;
//             ours vs exact worst 6e-14 (box–box)
//   distance: libccd right on 3880 of 5500, short on the other 1620 (the
//             grown shape is curved, where the fold is most frequent);
//             ours vs exact worst 7.2e-14 (hull–hull)
//   ours vs libccd where libccd is right: worst 9.9e-05 (box–box), which
//   is libccd's own error, not ours: its EPA stops up to 1e-6 m short
//   (epa_tolerance below), and that is within 1e-4 of the exact answer.
//   ours vs libccd over every pair: up to 1.7 m (relative 170) on a
//   sphere–sphere pair, where libccd's depth is nearly 0.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "ccd_shapes.hpp"
#include "convex_pairs.hpp"
#include "impulse/narrowphase/epa.hpp"
#include "impulse/narrowphase/gjk.hpp"

namespace {

using namespace peers;

/// The agreement required, relative with a 1 cm floor (above).
constexpr double agreement = 1e-4;
/// Ours against the brute-force exact answer: our GJK and EPA end within
/// 1e-12 and 1e-10 relative in double (gjk.hpp, epa.hpp); 1e-8 leaves
/// room for the rounding of poses and hull planes.
constexpr double exact_agreement = 1e-8;
constexpr double floor_m = 0.01;

double relative_error(double value, double reference) {
  return std::abs(value - reference) / std::max(std::abs(reference), floor_m);
}

struct our_answer {
  bool overlapping;
  double value;  ///< distance when apart, depth when overlapping
};

template <class A, class B>
our_answer ours(const pair_spec& p) {
  const A a = make<A>(p.a);
  const B b = make<B>(p.b);
  const auto pa = pose_of<double>(p.a), pb = pose_of<double>(p.b);
  const auto g = impulse::narrowphase::gjk_distance(a, pa, b, pb);
  if (!g.overlapping) return {false, g.distance};
  const auto e = impulse::narrowphase::epa_penetration(a, pa, b, pb);
  return {true, e.depth};
}

struct worst {
  double error = 0;
  std::string where;
  void update(double e, const std::string& name, std::size_t i) {
    if (e > error) error = e, where = name + " #" + std::to_string(i);
  }
};

/// One quantity (depth or distance) over all pairs.
struct tally {
  int pairs = 0;
  int ccd_right = 0;        ///< libccd within `agreement` of the exact answer
  int ccd_short = 0;        ///< libccd wrong, with a depth less than the exact one
  worst ours_vs_ccd;        ///< over the pairs where libccd is right
  worst ours_vs_ccd_all;    ///< over every pair
  worst ours_vs_exact;
};

template <class A, class B>
void compare(shape_kind ka, shape_kind kb, std::uint32_t seed, tally& depth, tally& gap) {
  const std::string name = std::string(name_of(ka)) + "-" + name_of(kb);
  constexpr int pairs = 1100;
  const generated_pairs g = random_pairs(ka, kb, pairs, seed);
  // libccd's EPA stops when either of two tests passes: the support point
  // less than epa_tolerance beyond the nearest face, measured as |w|·(gap)
  // with |w| the face's distance, or its *squared* distance from the face
  // below epa_tolerance. The default 1e-4 thus stops 1 cm short; 1e-12
  // stops 1e-6 m short. Much tighter (1e-18) never ends on a curved shape.
  const ccd_t ccd = ccd_setup(1e-12);
  for (std::size_t i = 0; i < g.pairs.size(); ++i) {
    const pair_spec& p = g.pairs[i];
    const exact_answer& e = g.answers[i];
    const our_answer o = ours<A, B>(p);
    const ccd_shape ca(p.a), cb(p.b);
    const double exact = e.overlapping ? e.depth : e.distance;
    CAPTURE(name);
    CAPTURE(i);
    CAPTURE(exact);
    REQUIRE(o.overlapping == e.overlapping);
    CHECK(relative_error(o.value, exact) <= exact_agreement);
    tally& t = e.overlapping ? depth : gap;
    // For a separated pair, B grown by more than the distance between the
    // centers (which bounds the distance between the shapes: each holds
    // its center) overlaps A.
    const double peer = e.overlapping ? ccd_depth(ccd, ca, cb)
                                      : ccd_distance(ccd, ca, cb, distance(p.a.pose.position, p.b.pose.position) + 0.01);
    CAPTURE(peer);
    ++t.pairs;
    t.ours_vs_exact.update(relative_error(o.value, exact), name, i);
    t.ours_vs_ccd_all.update(relative_error(o.value, peer), name, i);
    if (relative_error(peer, exact) <= agreement) {
      ++t.ccd_right;
      t.ours_vs_ccd.update(relative_error(o.value, peer), name, i);
      CHECK(relative_error(o.value, peer) <= agreement);
    } else if ((e.overlapping && peer < exact) || (!e.overlapping && peer > exact)) {
      ++t.ccd_short;
    }
  }
}

std::string sci(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2g", x);
  return buffer;
}

}  // namespace

TEST_CASE("GJK distances and EPA depths agree with libccd where libccd is right and are exact where it is not") {
  using impulse::box;
  using impulse::capsule;
  using impulse::convex_hull;
  using impulse::sphere;
  using D = double;
  tally depth, gap;
  compare<box<D>, box<D>>(shape_kind::box, shape_kind::box, 2024, depth, gap);
  compare<box<D>, convex_hull<D>>(shape_kind::box, shape_kind::hull, 2025, depth, gap);
  compare<convex_hull<D>, convex_hull<D>>(shape_kind::hull, shape_kind::hull, 2026, depth, gap);
  compare<sphere<D>, convex_hull<D>>(shape_kind::sphere, shape_kind::hull, 2027, depth, gap);
  compare<capsule<D>, box<D>>(shape_kind::capsule, shape_kind::box, 2028, depth, gap);
  compare<capsule<D>, convex_hull<D>>(shape_kind::capsule, shape_kind::hull, 2029, depth, gap);
  compare<sphere<D>, box<D>>(shape_kind::sphere, shape_kind::box, 2030, depth, gap);
  compare<capsule<D>, capsule<D>>(shape_kind::capsule, shape_kind::capsule, 2031, depth, gap);
  compare<sphere<D>, sphere<D>>(shape_kind::sphere, shape_kind::sphere, 2032, depth, gap);
  compare<sphere<D>, capsule<D>>(shape_kind::sphere, shape_kind::capsule, 2033, depth, gap);
  const auto report = [](const char* what, const tally& t) {
    return std::string(what) + ": libccd right on " + std::to_string(t.ccd_right) + " of " + std::to_string(t.pairs) +
           " (short of the exact depth on " + std::to_string(t.ccd_short) + " of the rest)\n" +
           "    ours vs libccd where it is right: " + sci(t.ours_vs_ccd.error) + " (" + t.ours_vs_ccd.where + ")\n" +
           "    ours vs libccd, every pair:       " + sci(t.ours_vs_ccd_all.error) + " (" + t.ours_vs_ccd_all.where + ")\n" +
           "    ours vs exact, every pair:        " + sci(t.ours_vs_exact.error) + " (" + t.ours_vs_exact.where + ")\n";
  };
  MESSAGE("relative errors (1 cm floor)\n" << report("depth", depth) << report("distance", gap));
  // Where libccd is wrong, its EPA has stopped short (a folded polytope,
  // see above): a broken adapter here would instead make it wrong at
  // random, and rarely right. Measured: right on 94 % of depths and 70 %
  // of distances, short on every pair where it is wrong.
  CHECK(depth.ccd_right >= depth.pairs * 9 / 10);
  CHECK(gap.ccd_right >= gap.pairs * 6 / 10);
  CHECK(depth.ccd_short == depth.pairs - depth.ccd_right);
  CHECK(gap.ccd_short == gap.pairs - gap.ccd_right);
}
