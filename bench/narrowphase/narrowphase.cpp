// bench/narrowphase: pair tests per second for each shape pair and each
// algorithm, ours beside libccd's and Bullet's, on the same pairs in the
// same run.
//
// The pairs: 4 096 per shape pairing, seeded (tests/peers/convex_pairs.hpp,
// shared with the libccd agreement test), half overlapping and half apart,
// sizes 0.1 m to 2 m, random rotations, each with its exact distance or
// depth from a brute force over features and axes (the closed form for
// two spheres, exact for every pairing here).
//
// The algorithms, each run over all the pairs of a pairing:
// - collide: our dedicated pair test and its contact manifold (analytic
//   for spheres and capsules, SAT + clipping for boxes and hulls) with
//   margin 0. A row appears for every pairing that has a `collide`
//   overload.
// - gjk_epa: the general query: GJK distance, then EPA if they overlap.
//   libccd: ccdGJKPenetration (GJK, then EPA if they intersect; no
//   distance when apart); mpr: ccdMPRPenetration. Bullet:
//   btGjkPairDetector with btVoronoiSimplexSolver and
//   btGjkEpaPenetrationDepthSolver, which gives the distance or depth.
// - box_box: Bullet's btBoxBoxDetector (ODE's dBoxBox), box–box only.
// - gjk_distance: GJK alone, on the separated pairs of box–box and
//   hull–hull. libccd 2.1 has no distance query: its row is
//   ccdGJKIntersect, a yes/no answer, with no error figure.
//
// Engines: impulse_f32 and impulse_f64 (ours in float and double); libccd
// (double, as a user gets it: CCD_INIT's tolerances, 1e-4, which its EPA
// compares with a squared distance, so it stops up to 1 cm short) and
// libccd_tight (epa/mpr_tolerance 1e-12, as tests/peers uses it); bullet
// (Debian's float build), every shape with collision margin 0 so that it
// answers for the same shapes (a sphere's and a capsule's radius are their
// margin in Bullet, as they are our core radius).
//
// Timing: every case of a pairing runs once per round, interleaved, for
// `rounds` rounds; ns_per_test is the median over the rounds of the time
// of one pass over the pairs divided by their number.
// max_abs_error_vs_reference (m) compares the signed distance (distance
// when apart, minus the depth when overlapping) with the exact one, over
// the pairs where the engine gives a figure: collide only on overlapping
// pairs (the deepest contact point's depth; a missed overlap counts its
// whole depth), libccd only on overlapping pairs.
//
//   narrowphase [--quick]   CSV on stdout, a markdown table on stderr
//
// --quick runs 512 pairs and 3 rounds (a smoke test).
//
// Then each shape on the ground, ours only (libccd has no plane or mesh,
// and Bullet meets them only through its whole collision world, which
// bench/scenes will time): the plane y = 0 (`collide` with a plane) and a
// flat mesh of 100 × 100 one-metre squares (20 000 triangles, `collide`
// with a triangle_mesh through its tree), each shape at a random spot and
// turn, its lowest point up to half its depth below the center into the
// ground or above it (half overlapping). The reference is the exact
// height of its lowest point.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "cases.hpp"
#include "convex_pairs.hpp"
#include "impulse/narrowphase.hpp"

namespace {

using namespace peers;
using namespace narrowphase_bench;

/// Our shapes and poses for a pairing, in scalar T.
template <class A, class B, class T>
struct our_pairs {
  std::vector<A> a;
  std::vector<B> b;
  std::vector<impulse::transform<T>> pose_a, pose_b;

  explicit our_pairs(const generated_pairs& g) {
    for (const pair_spec& p : g.pairs) {
      a.push_back(make<A>(p.a));
      b.push_back(make<B>(p.b));
      pose_a.push_back(pose_of<T>(p.a));
      pose_b.push_back(pose_of<T>(p.b));
    }
  }
};

/// GJK, then EPA if they overlap: the signed distance.
template <class A, class B, class T>
double gjk_epa(const A& a, const impulse::transform<T>& pa, const B& b, const impulse::transform<T>& pb) {
  const auto g = impulse::narrowphase::gjk_distance(a, pa, b, pb);
  if (!g.overlapping) return double(g.distance);
  return -double(impulse::narrowphase::epa_penetration(a, pa, b, pb).depth);
}

/// Ours: collide (where the pairing has one) and gjk_epa, in scalar T.
template <class A, class B, class T>
void add_ours(std::vector<timed_case>& cases, const std::string& pair, const char* engine,
              const generated_pairs& g, const std::vector<std::size_t>& all, const std::vector<double>& reference,
              const std::vector<std::size_t>& separated, bool distance_row) {
  auto shapes = std::make_shared<const our_pairs<A, B, T>>(g);
  if constexpr (requires(const A& a, const B& b, const impulse::transform<T>& p) {
                  impulse::narrowphase::collide(a, p, b, p, T(0));
                }) {
    cases.push_back(make_case(pair, "collide", engine, all, reference, [shapes, &g](std::size_t i) {
      const auto m = impulse::narrowphase::collide(shapes->a[i], shapes->pose_a[i], shapes->b[i], shapes->pose_b[i], T(0));
      double deepest = -std::numeric_limits<double>::infinity();
      for (const auto& c : m.contacts()) deepest = std::max(deepest, double(c.depth));
      if (m.empty()) return g.answers[i].overlapping ? 0.0 : not_given;  // a missed overlap: error = its depth
      return -deepest;
    }));
  }
  cases.push_back(make_case(pair, "gjk_epa", engine, all, reference, [shapes](std::size_t i) {
    return gjk_epa(shapes->a[i], shapes->pose_a[i], shapes->b[i], shapes->pose_b[i]);
  }));
  if (distance_row)
    cases.push_back(make_case(pair, "gjk_distance", engine, separated, reference, [shapes](std::size_t i) {
      return double(impulse::narrowphase::gjk_distance(shapes->a[i], shapes->pose_a[i], shapes->b[i], shapes->pose_b[i])
                        .distance);
    }));
}

/// Every case of one pairing.
template <template <class> class SA, template <class> class SB>
std::vector<timed_case> pairing(shape_kind ka, shape_kind kb, int n, std::uint32_t seed, bool distance_row,
                                std::vector<std::unique_ptr<generated_pairs>>& keep) {
  const std::string pair = std::string(name_of(ka)) + "-" + name_of(kb);
  keep.push_back(std::make_unique<generated_pairs>(random_pairs(ka, kb, n, seed)));
  const generated_pairs& g = *keep.back();
  std::vector<std::size_t> all, separated;
  std::vector<double> reference;
  for (std::size_t i = 0; i < g.pairs.size(); ++i) {
    all.push_back(i);
    if (!g.answers[i].overlapping) separated.push_back(i);
    reference.push_back(g.answers[i].overlapping ? -g.answers[i].depth : g.answers[i].distance);
  }
  std::vector<timed_case> cases;
  add_ours<SA<float>, SB<float>, float>(cases, pair, "impulse_f32", g, all, reference, separated, distance_row);
  add_ours<SA<double>, SB<double>, double>(cases, pair, "impulse_f64", g, all, reference, separated, distance_row);
  add_peers(cases, pair, g, all, reference, separated, distance_row, ka == shape_kind::box && kb == shape_kind::box);
  return cases;
}

/// A shape resting on the ground at a random spot: its spec, posed.
shape_spec on_ground(shape_kind k, impulse::lcg32& random, double& lowest_height) {
  shape_spec s = random_shape(k, random);
  s.pose = {v3{}, random_rotation(random)};
  const world_core core = core_of(s);
  double lowest = core.vertices[0].y;
  for (const v3& v : core.vertices) lowest = std::min(lowest, v.y);
  lowest -= core.radius;  // below the center: < 0
  // The center stays above the ground (a mesh is one-sided): the lowest
  // point from half its depth below the center into the ground to as far
  // above it.
  lowest_height = random.uniform(-0.5, 0.5) * -lowest;
  s.pose.position = {random.uniform(-45.0, 45.0), lowest_height - lowest, random.uniform(-45.0, 45.0)};
  return s;
}

/// The ground as a mesh: n × n one-metre squares centered on the origin.
template <class T>
impulse::triangle_mesh<T> ground_mesh(int n) {
  std::vector<vec3<T>> vertices;
  std::vector<std::uint32_t> indices;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) vertices.push_back({T(i - n / 2), T(0), T(j - n / 2)});
  const auto at = [n](int i, int j) { return std::uint32_t(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      indices.insert(indices.end(), {at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i + 1, j)});
  return impulse::triangle_mesh<T>::make(vertices, indices);
}

/// The deepest point of the manifolds as a signed distance; a missed
/// overlap counts its whole depth (0), a pair found apart gives nothing.
template <class T>
double signed_from(std::span<const impulse::contact_manifold<T>> manifolds, bool overlapping) {
  double deepest = -std::numeric_limits<double>::infinity();
  for (const auto& m : manifolds)
    for (const auto& c : m.contacts()) deepest = std::max(deepest, double(c.depth));
  if (deepest == -std::numeric_limits<double>::infinity()) return overlapping ? 0.0 : not_given;
  return -deepest;
}

/// Shape S on the plane and on the mesh, in scalar T.
template <template <class> class S, class T>
void add_ground(std::vector<timed_case>& cases, shape_kind k, const char* engine, const std::vector<shape_spec>& specs,
                const std::vector<double>& reference, const std::vector<std::size_t>& all) {
  struct shapes {
    std::vector<S<T>> shape;
    std::vector<impulse::transform<T>> pose;
    impulse::plane<T> ground{vec3<T>::unit_y(), T(0)};
    impulse::triangle_mesh<T> mesh = ground_mesh<T>(100);
  };
  auto s = std::make_shared<shapes>();
  for (const shape_spec& spec : specs) {
    s->shape.push_back(make<S<T>>(spec));
    s->pose.push_back(pose_of<T>(spec));
  }
  const std::string name = name_of(k);
  cases.push_back(make_case(name + "-plane", "collide", engine, all, reference, [s, &reference](std::size_t i) {
    const impulse::contact_manifold<T> m[1] = {
        impulse::narrowphase::collide(s->shape[i], s->pose[i], s->ground, impulse::transform<T>::identity(), T(0))};
    return signed_from<T>(m, reference[i] < 0);
  }));
  cases.push_back(make_case(name + "-mesh", "collide", engine, all, reference, [s, &reference](std::size_t i) {
    std::array<impulse::contact_manifold<T>, 4> out;
    const std::size_t n = impulse::narrowphase::collide(s->mesh, impulse::transform<T>::identity(), s->shape[i],
                                                        s->pose[i], T(0), std::span<impulse::contact_manifold<T>>(out));
    return signed_from<T>(std::span<const impulse::contact_manifold<T>>(out.data(), n), reference[i] < 0);
  }));
}

template <template <class> class S>
std::vector<timed_case> ground(shape_kind k, int n, std::uint32_t seed, std::vector<std::vector<double>>& keep) {
  impulse::lcg32 random{seed};
  std::vector<shape_spec> specs;
  std::vector<double> reference;
  std::vector<std::size_t> all;
  for (int i = 0; i < n; ++i) {
    double height = 0;
    specs.push_back(on_ground(k, random, height));
    reference.push_back(height);
    all.push_back(std::size_t(i));
  }
  keep.push_back(reference);  // the cases read it by reference
  std::vector<timed_case> cases;
  add_ground<S, float>(cases, k, "impulse_f32", specs, keep.back(), all);
  add_ground<S, double>(cases, k, "impulse_f64", specs, keep.back(), all);
  return cases;
}

/// Runs every case of a pairing once per round, interleaved.
void time_cases(std::vector<timed_case>& cases, int rounds) {
  volatile double sink = 0;
  for (int r = 0; r < rounds; ++r) {
    for (timed_case& c : cases) {
      const auto start = std::chrono::steady_clock::now();
      sink = sink + c.pass();
      const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
      c.ns_per_test.push_back(ns / double(c.tests));
    }
  }
}

std::string figure(double x, const char* format) {
  if (std::isnan(x)) return "";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, format, x);
  return buffer;
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const int n = quick ? 512 : 4096;
  const int rounds = quick ? 3 : 9;

  using impulse::box;
  using impulse::capsule;
  using impulse::convex_hull;
  using impulse::sphere;
  using K = shape_kind;
  std::vector<std::unique_ptr<generated_pairs>> keep;  // the pairs the cases read
  std::vector<std::vector<timed_case>> pairings;
  pairings.push_back(pairing<sphere, sphere>(K::sphere, K::sphere, n, 101, false, keep));
  pairings.push_back(pairing<sphere, box>(K::sphere, K::box, n, 102, false, keep));
  pairings.push_back(pairing<box, box>(K::box, K::box, n, 103, true, keep));
  pairings.push_back(pairing<capsule, capsule>(K::capsule, K::capsule, n, 104, false, keep));
  pairings.push_back(pairing<capsule, box>(K::capsule, K::box, n, 105, false, keep));
  pairings.push_back(pairing<sphere, convex_hull>(K::sphere, K::hull, n, 106, false, keep));
  pairings.push_back(pairing<convex_hull, convex_hull>(K::hull, K::hull, n, 107, true, keep));
  pairings.push_back(pairing<sphere, capsule>(K::sphere, K::capsule, n, 108, false, keep));
  pairings.push_back(pairing<box, convex_hull>(K::box, K::hull, n, 109, false, keep));
  pairings.push_back(pairing<capsule, convex_hull>(K::capsule, K::hull, n, 110, false, keep));
  std::vector<std::vector<double>> heights;
  heights.reserve(4);  // the cases hold references into it
  pairings.push_back(ground<sphere>(K::sphere, n, 111, heights));
  pairings.push_back(ground<capsule>(K::capsule, n, 112, heights));
  pairings.push_back(ground<box>(K::box, n, 113, heights));
  pairings.push_back(ground<convex_hull>(K::hull, n, 114, heights));

  std::printf("pair,algorithm,engine,ns_per_test_median,tests_per_second,max_abs_error_vs_reference\n");
  std::fprintf(stderr, "| pair | algorithm | engine | ns/test (median of %d) | tests/s | max error (m) |\n", rounds);
  std::fprintf(stderr, "| --- | --- | --- | ---: | ---: | ---: |\n");
  for (auto& cases : pairings) {
    time_cases(cases, rounds);
    for (const timed_case& c : cases) {
      const double ns = c.median();
      std::printf("%s,%s,%s,%.1f,%.0f,%s\n", c.pair.c_str(), c.algorithm.c_str(), c.engine.c_str(), ns, 1e9 / ns,
                  figure(c.max_error, "%.3g").c_str());
      std::fprintf(stderr, "| %s | %s | %s | %.0f | %.3g | %s |\n", c.pair.c_str(), c.algorithm.c_str(),
                   c.engine.c_str(), ns, 1e9 / ns, figure(c.max_error, "%.2g").c_str());
    }
    std::fflush(stdout);
  }
}
