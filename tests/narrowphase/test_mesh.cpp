// Triangle meshes: the tree's box query and ray cast equal brute force over
// every triangle; spheres, capsules, boxes and hulls resting on a flat grid
// of 200 triangles get the normal and depth they get on a plane wherever
// they stand, over internal edges and corners too (no snagging while a box
// slides across it); a real convex edge keeps its own normal; a concave
// corner gives two manifolds; far from the origin; non-finite poses.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "impulse/core/random.hpp"
#include "impulse/narrowphase/analytic.hpp"
#include "impulse/narrowphase/hull.hpp"
#include "impulse/narrowphase/mesh.hpp"
#include "impulse/shapes/convex_hull.hpp"
#include "impulse/shapes/plane.hpp"
#include "impulse/shapes/triangle_mesh.hpp"

#include "poses.hpp"

namespace narrowphase_mesh_tests {

namespace {

using namespace impulse;
using narrowphase::collide;
using test::at;

template <class T>
constexpr T tolerance = test::contact_tolerance<T>;

/// The bound on a normal's tilt: 1e-5 rad (|n − n'| ≈ the angle).
template <class T>
constexpr T normal_tolerance = T(1e-5);

using manifolds = std::vector<contact_manifold<double>>;

/// An n × n grid of unit quads (two triangles each) in y = 0, x and z in
/// [−n/2, n/2] shifted by `offset`, facing +y.
template <class T>
triangle_mesh<T> grid(int n, const vec3<T>& offset = {}) {
  std::vector<vec3<T>> v;
  std::vector<std::uint32_t> idx;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) v.push_back(offset + vec3<T>{T(i) - T(n) / 2, 0, T(j) - T(n) / 2});
  const auto id = [&](int i, int j) { return std::uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      // Counter-clockwise seen from +y: (x0, z0), (x0, z1), (x1, z0), …
      idx.insert(idx.end(), {id(i, j), id(i, j + 1), id(i + 1, j)});
      idx.insert(idx.end(), {id(i + 1, j), id(i, j + 1), id(i + 1, j + 1)});
    }
  return triangle_mesh<T>::make(v, idx);
}

/// The surface of the cube [−1, 1]³ as 12 triangles facing out.
template <class T>
triangle_mesh<T> cube_mesh() {
  const std::vector<vec3<T>> v = test::box_corners<T>({1, 1, 1});  // bit 0 +x, bit 1 +y, bit 2 +z
  const std::uint32_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  std::vector<std::uint32_t> idx;
  for (const auto& f : faces) idx.insert(idx.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
  return triangle_mesh<T>::make(v, idx);
}

/// Calls collide with room for 8 manifolds and returns those written.
template <class T, class S>
std::vector<contact_manifold<T>> touch(const triangle_mesh<T>& mesh, const transform<T>& pose_mesh, const S& shape,
                                       const transform<T>& pose, T margin = T(0)) {
  std::vector<contact_manifold<T>> out(8);
  out.resize(collide(mesh, pose_mesh, shape, pose, margin, std::span<contact_manifold<T>>(out)));
  return out;
}

int popcount3(std::uint8_t b) { return (b & 1) + ((b >> 1) & 1) + ((b >> 2) & 1); }

/// The random triangles of the tree tests: 400 in a 10 m cube, sides up to 2 m.
template <class T>
triangle_mesh<T> random_mesh(lcg32& g) {
  std::vector<vec3<T>> v;
  std::vector<std::uint32_t> idx;
  for (std::uint32_t t = 0; t < 400; ++t) {
    const vec3<T> c{g.uniform<T>(-5, 5), g.uniform<T>(-5, 5), g.uniform<T>(T(-5), T(5))};
    for (int k = 0; k < 3; ++k) {
      v.push_back(c + vec3<T>{g.uniform<T>(-1, 1), g.uniform<T>(-1, 1), g.uniform<T>(T(-1), T(1))});
      idx.push_back(std::uint32_t(v.size() - 1));
    }
  }
  return triangle_mesh<T>::make(v, idx);
}

}  // namespace

// ---- the tree ------------------------------------------------------------------

TEST_CASE_TEMPLATE("the tree's box query returns exactly the triangles whose boxes overlap", T, float, double) {
  lcg32 g{7};
  for (int round = 0; round < 5; ++round) {
    const triangle_mesh<T> mesh = random_mesh<T>(g);
    // Depth bound of the median split: ⌈log2(400 / 4)⌉ + 1 = 8 levels.
    CHECK(mesh.tree().nodes().size() < 2 * mesh.triangle_count());
    for (int q = 0; q < 400; ++q) {
      const vec3<T> c{g.uniform<T>(-6, 6), g.uniform<T>(-6, 6), g.uniform<T>(T(-6), T(6))};
      const vec3<T> h{g.uniform<T>(0, 2), g.uniform<T>(0, 2), g.uniform<T>(T(0), T(2))};
      const aabb<T> box = aabb<T>::from_center_half_extents(c, h);
      std::vector<std::size_t> found, expected;
      mesh.for_each_overlapping(box, [&](std::size_t t) { found.push_back(t); });
      for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
        if (overlaps(mesh.triangle_aabb(t), box)) expected.push_back(t);
      std::sort(found.begin(), found.end());
      REQUIRE(found == expected);  // exact: each triangle once, none missed
    }
  }
}

TEST_CASE_TEMPLATE("a ray cast through the tree equals brute force over every triangle", T, float, double) {
  lcg32 g{11};
  const auto brute = [](const ray<T>& r, const triangle_mesh<T>& mesh, const transform<T>& pose, T max_fraction) {
    narrowphase::ray_hit<T> best;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      vec3<T> a, b, c;
      mesh.triangle(t, a, b, c);
      const ray<T> local{inverse_apply(pose, r.origin), inverse_apply_direction(pose, r.translation)};
      const auto h = narrowphase::ray_cast_triangle(local, a, b, c, max_fraction);
      if (h && h.feature == 0 && (!best || h.fraction < best.fraction)) best = h, best.feature = std::uint32_t(t);
    }
    return best;
  };
  // The tree's walk runs the same triangle test as brute force, but inlined
  // elsewhere: with fused multiply-adds (-ffp-contract=fast, g++'s default
  // in gnu++ mode, at -march=native) the two can round differently by an
  // ulp or two. So: the same fraction to 1e-5 (float) or 1e-12 (double),
  // and the same triangle, or one whose own hit is as near (a tie at a
  // shared edge or vertex).
  const T fraction_tolerance = sizeof(T) == 4 ? T(1e-5) : T(1e-12);
  const auto check_same_hit = [&](const ray<T>& r, const triangle_mesh<T>& mesh, const transform<T>& pose,
                                  T max_fraction, const narrowphase::ray_hit<T>& found,
                                  const narrowphase::ray_hit<T>& expected) {
    CHECK(std::abs(found.fraction - expected.fraction) <= fraction_tolerance);
    if (found.feature == expected.feature) return;
    vec3<T> a, b, c;
    mesh.triangle(found.feature, a, b, c);
    const ray<T> local{inverse_apply(pose, r.origin), inverse_apply_direction(pose, r.translation)};
    const auto own = narrowphase::ray_cast_triangle(local, a, b, c, max_fraction);
    CHECK(own);
    CHECK(std::abs(own.fraction - expected.fraction) <= fraction_tolerance);
  };
  int hits = 0, total = 0;
  // Random triangles, random rays through the middle of the mesh.
  for (int round = 0; round < 2; ++round) {
    const triangle_mesh<T> mesh = random_mesh<T>(g);
    const transform<T> pose = at<T>({T(1), T(-2), T(3)}, test::random_rotation<T>(g));
    for (int q = 0; q < 2500; ++q) {
      const vec3<T> from = apply(pose, vec3<T>{g.uniform<T>(-8, 8), g.uniform<T>(-8, 8), g.uniform<T>(T(-8), T(8))});
      const vec3<T> to = apply(pose, vec3<T>{g.uniform<T>(-4, 4), g.uniform<T>(-4, 4), g.uniform<T>(T(-4), T(4))});
      const ray<T> r{from, (to - from) * T(2)};
      const T max_fraction = q % 3 == 0 ? T(0.5) : T(1);
      const auto expected = brute(r, mesh, pose, max_fraction);
      const auto found = narrowphase::ray_cast(r, mesh, pose, max_fraction);
      ++total;
      REQUIRE(bool(found) == bool(expected));
      if (!expected) continue;
      ++hits;
      check_same_hit(r, mesh, pose, max_fraction, found, expected);
      CHECK(length(found.point - (r.origin + r.translation * found.fraction)) <= T(100) * tolerance<T>);
      CHECK(dot(found.normal, r.translation) < T(0));  // the front faces the ray
    }
  }
  CHECK(hits > total / 4);  // the rays do find triangles
  // A flat grid (boxes of zero thickness), rays straight down through its
  // vertices and edges: the lower triangle index wins each tie, as in
  // brute force.
  const triangle_mesh<T> flat = grid<T>(10);
  for (int q = 0; q < 2000; ++q) {
    const T x = q % 4 == 0 ? T(int(g.uniform<T>(-5, 5))) : g.uniform<T>(-5, 5);
    const T z = q % 3 == 0 ? T(int(g.uniform<T>(-5, 5))) : g.uniform<T>(-5, 5);
    const ray<T> r{{x, T(3), z}, {g.uniform<T>(T(-0.1), T(0.1)) * T(q % 2), T(-6), 0}};
    const auto expected = brute(r, flat, transform<T>::identity(), T(1));
    const auto found = narrowphase::ray_cast(r, flat, transform<T>::identity());
    REQUIRE(bool(found) == bool(expected));
    if (!expected) continue;
    check_same_hit(r, flat, transform<T>::identity(), T(1), found, expected);
    CHECK(length(found.normal - vec3<T>::unit_y()) <= normal_tolerance<T>);
  }
  // From below, the grid's back: no hit (one-sided).
  CHECK_FALSE(narrowphase::ray_cast(ray<T>{{T(0.3), T(-1), T(0.2)}, {0, T(2), 0}}, flat, transform<T>::identity()));
  // Non-finite input: a miss.
  const T nan = std::numeric_limits<T>::quiet_NaN();
  CHECK_FALSE(narrowphase::ray_cast(ray<T>{{nan, T(1), 0}, {0, T(-2), 0}}, flat, transform<T>::identity()));
  CHECK_FALSE(narrowphase::ray_cast(ray<T>{{0, T(1), 0}, {0, T(-2), 0}}, flat, at<T>({nan, 0, 0})));
}

// ---- active edges -------------------------------------------------------------

TEST_CASE_TEMPLATE("a flat grid's inner edges are internal and its rim and a cube's edges are active", T, float, double) {
  const triangle_mesh<T> flat = grid<T>(10);
  int active = 0;
  for (std::size_t t = 0; t < flat.triangle_count(); ++t) active += popcount3(flat.active_edges(t));
  CHECK(active == 40);  // the rim: 4 sides of 10 edges, each in one triangle
  const triangle_mesh<T> cube = cube_mesh<T>();
  active = 0;
  for (std::size_t t = 0; t < cube.triangle_count(); ++t) active += popcount3(cube.active_edges(t));
  CHECK(active == 24);  // 12 edges at 90°, each in two triangles; the 6 diagonals are flat
  // The same cube unwelded (every triangle with its own corners): the same answer.
  std::vector<vec3<T>> v;
  std::vector<std::uint32_t> idx;
  for (std::size_t t = 0; t < cube.triangle_count(); ++t) {
    vec3<T> a, b, c;
    cube.triangle(t, a, b, c);
    v.insert(v.end(), {a, b, c});
    idx.insert(idx.end(), {std::uint32_t(3 * t), std::uint32_t(3 * t + 1), std::uint32_t(3 * t + 2)});
  }
  const triangle_mesh<T> soup = triangle_mesh<T>::make(v, idx);
  for (std::size_t t = 0; t < cube.triangle_count(); ++t) CHECK(soup.active_edges(t) == cube.active_edges(t));
}

// ---- resting on a flat grid ---------------------------------------------------

TEST_CASE_TEMPLATE("a sphere on a flat grid gets the plane's contact wherever it stands", T, float, double) {
  const triangle_mesh<T> mesh = grid<T>(10);
  const plane<T> ground{};
  const sphere<T> ball{T(0.5)};
  lcg32 g{3};
  for (int q = 0; q < 500; ++q) {
    // Every fourth exactly over a grid line or vertex, or a diagonal.
    T x = g.uniform<T>(-4, 4), z = g.uniform<T>(-4, 4);
    if (q % 4 == 1) x = std::round(x);
    if (q % 4 == 2) x = std::round(x), z = std::round(z);
    if (q % 4 == 3) z = std::round(z) - (x - std::floor(x));  // on a diagonal: x + z whole
    const transform<T> pose = at<T>({x, T(0.49) - T(0.02) * g.uniform<T>(), z}, test::random_rotation<T>(g));
    const auto found = touch(mesh, transform<T>::identity(), ball, pose);
    const contact_manifold<T> expected = collide(ground, transform<T>::identity(), ball, pose);
    REQUIRE(found.size() == 1);
    CHECK(length(found[0].normal - vec3<T>::unit_y()) <= normal_tolerance<T>);
    REQUIRE(found[0].count == 1);  // the copies from the triangles around a vertex welded
    CHECK(std::abs(found[0].points[0].depth - expected.points[0].depth) <= tolerance<T>);
    CHECK(length(found[0].points[0].position - expected.points[0].position) <= tolerance<T>);
  }
  // Swapped: the same contact, the normal reversed.
  std::vector<contact_manifold<T>> out(2);
  REQUIRE(collide(ball, at<T>({T(0.3), T(0.45), T(0.3)}), mesh, transform<T>::identity(), T(0), std::span(out)) == 1);
  CHECK(length(out[0].normal + vec3<T>::unit_y()) <= normal_tolerance<T>);
  CHECK(out[0].points[0].depth == doctest::Approx(0.05).epsilon(tolerance<T> * 100));
}

TEST_CASE_TEMPLATE("a capsule lying or standing on a flat grid gets the plane's contact", T, float, double) {
  const triangle_mesh<T> mesh = grid<T>(10);
  const plane<T> ground{};
  const capsule<T> rod{T(0.25), T(0.6)};
  lcg32 g{5};
  for (int q = 0; q < 400; ++q) {
    const T yaw = g.uniform<T>(-3, 3);
    // Lying (axis turned onto the xz-plane), slightly tilted, or standing.
    const T tilt = q % 3 == 0 ? T(1.5707963267948966) : q % 3 == 1 ? T(1.5) : T(0);
    const quat<T> turn = quat<T>::from_axis_angle(vec3<T>::unit_y(), yaw) * quat<T>::from_axis_angle(vec3<T>::unit_z(), tilt);
    T x = g.uniform<T>(-3, 3), z = g.uniform<T>(-3, 3);
    if (q % 5 == 0) x = std::round(x), z = std::round(z);
    const vec3<T> axis = rotate(turn, vec3<T>{0, rod.half_height, 0});
    const T lowest_core = std::abs(axis.y);  // the lower cap center's drop below the middle
    const transform<T> pose = at<T>({x, lowest_core + rod.radius - T(0.01), z}, turn);
    const auto found = touch(mesh, transform<T>::identity(), rod, pose);
    const contact_manifold<T> expected = collide(ground, transform<T>::identity(), rod, pose);
    REQUIRE(found.size() == 1);
    CHECK(length(found[0].normal - vec3<T>::unit_y()) <= normal_tolerance<T>);
    CHECK(std::abs(test::deepest(found[0]) - test::deepest(expected)) <= tolerance<T> * 10);
    // Every point lies midway between the capsule and the plane, no deeper
    // than the plane's deepest, and the plane's points (the cap centers
    // within reach) are among the mesh's.
    for (const auto& p : found[0].contacts()) {
      CHECK(std::abs(p.position.y + p.depth * T(0.5)) <= tolerance<T> * 10);  // midway: the plane is y = 0
      CHECK(p.depth <= test::deepest(expected) + tolerance<T> * 10);
    }
    if (q % 3 == 0) CHECK(found[0].count == 2);  // lying across several triangles: the two ends, as on a plane
    for (const auto& e : expected.contacts()) {
      bool matched = false;
      for (const auto& p : found[0].contacts())
        matched |= length(p.position - e.position) <= tolerance<T> * 10 && std::abs(p.depth - e.depth) <= tolerance<T> * 10;
      CHECK(matched);
    }
  }
}

TEST_CASE_TEMPLATE("a box on a flat grid gets the plane's normal and depth wherever it stands", T, float, double) {
  const triangle_mesh<T> mesh = grid<T>(10);
  const plane<T> ground{};
  const box<T> crate{{T(0.5), T(0.3), T(0.7)}};
  lcg32 g{9};
  for (int q = 0; q < 400; ++q) {
    const quat<T> yaw = quat<T>::from_axis_angle(vec3<T>::unit_y(), q % 4 == 0 ? T(0) : g.uniform<T>(-3, 3));
    // Flat, or tipped by 1° so that one edge is lower (where a seam snags).
    const quat<T> turn = q % 2 == 0 ? yaw : yaw * quat<T>::from_axis_angle(vec3<T>::unit_x(), T(0.0174533));
    T x = g.uniform<T>(-3, 3), z = g.uniform<T>(-3, 3);
    if (q % 4 == 0) x = std::round(x) + T(0.5), z = std::round(z) + T(0.3);  // corners on grid lines
    const vec3<T> reach = abs(rotate(turn, vec3<T>{0, 1, 0})) * crate.half_extents.y +
                          abs(rotate(turn, vec3<T>{0, 0, 1})) * crate.half_extents.z;
    const transform<T> pose = at<T>({x, reach.y - T(0.01), z}, turn);
    const auto found = touch(mesh, transform<T>::identity(), crate, pose);
    const contact_manifold<T> expected = collide(crate, pose, ground, transform<T>::identity()).flipped();
    REQUIRE(found.size() == 1);
    CHECK(length(found[0].normal - vec3<T>::unit_y()) <= normal_tolerance<T>);
    CHECK(std::abs(test::deepest(found[0]) - test::deepest(expected)) <= tolerance<T> * 10);
    // Flat: at least three of the patch's corners; tipped: the line of the lower edge.
    CHECK(found[0].count >= std::min(expected.count, 3));
    // Each point's depth is the box's depth below the plane there.
    for (const auto& p : found[0].contacts()) {
      const vec3<T> on_box = p.position - vec3<T>::unit_y() * (p.depth * T(0.5));  // the box's surface point
      CHECK(std::abs(on_box.y + p.depth) <= tolerance<T> * 10);
    }
  }
}

TEST_CASE_TEMPLATE("a hull on a flat grid gets the plane's normal and depth", T, float, double) {
  const triangle_mesh<T> mesh = grid<T>(10);
  const plane<T> ground{};
  // A hexagonal prism, radius 0.6, half height 0.3.
  std::vector<vec3<T>> points;
  for (int k = 0; k < 6; ++k)
    for (const T y : {T(-0.3), T(0.3)})
      points.push_back({T(0.6) * std::cos(T(k) * T(1.0471975511965976)), y, T(0.6) * std::sin(T(k) * T(1.0471975511965976))});
  const convex_hull<T> prism = convex_hull<T>::from_points(points);
  lcg32 g{13};
  for (int q = 0; q < 300; ++q) {
    const quat<T> turn = quat<T>::from_axis_angle(vec3<T>::unit_y(), g.uniform<T>(-3, 3));
    T x = g.uniform<T>(-3, 3), z = g.uniform<T>(-3, 3);
    if (q % 3 == 0) x = std::round(x), z = std::round(z);  // the center over a vertex
    const transform<T> pose = at<T>({x, T(0.3) - T(0.02), z}, turn);
    const auto found = touch(mesh, transform<T>::identity(), prism, pose);
    const contact_manifold<T> expected = collide(prism, pose, ground, transform<T>::identity()).flipped();
    REQUIRE(found.size() == 1);
    CHECK(length(found[0].normal - vec3<T>::unit_y()) <= normal_tolerance<T>);
    CHECK(std::abs(test::deepest(found[0]) - test::deepest(expected)) <= tolerance<T> * 10);
    for (const auto& p : found[0].contacts()) CHECK(std::abs(p.depth - T(0.02)) <= tolerance<T> * 10);
    CHECK(found[0].count >= 3);
  }
}

TEST_CASE_TEMPLATE("a box sliding across a grid in small steps never catches on an internal edge", T, float, double) {
  const triangle_mesh<T> mesh = grid<T>(10);
  const box<T> crate{{T(0.5), T(0.5), T(0.5)}};
  // Flat, turned 30° about y, and tipped 2° forward (its leading bottom
  // edge lowest: the edge that drops onto each seam first).
  const quat<T> turns[3] = {quat<T>::identity(), quat<T>::from_axis_angle(vec3<T>::unit_y(), T(0.5235988)),
                            quat<T>::from_axis_angle(vec3<T>::unit_z(), T(0.0349066))};
  for (const quat<T>& turn : turns) {
    // The box's reach below its center: the y extent of the rotated box.
    const T reach = transform_aabb(crate.local_aabb(), at<T>({}, turn)).upper.y;
    int steps = 0;
    for (int i = 0; i <= 700; ++i) {
      const T x = T(-3.5) + T(0.01) * T(i);
      for (const T z : {T(0), T(0.25)}) {  // on a grid line, and between
        const transform<T> pose = at<T>({x, reach - T(0.01), z}, turn);
        const auto found = touch(mesh, transform<T>::identity(), crate, pose);
        REQUIRE(found.size() == 1);
        CHECK(length(found[0].normal - vec3<T>::unit_y()) <= normal_tolerance<T>);
        CHECK(std::abs(test::deepest(found[0]) - T(0.01)) <= tolerance<T> * 100);
        ++steps;
      }
    }
    CHECK(steps == 1402);
  }
}

// ---- real edges and corners -----------------------------------------------------

TEST_CASE_TEMPLATE("a box and a sphere against a mesh cube's edge get the edge's normal", T, float, double) {
  const triangle_mesh<T> cube = cube_mesh<T>();
  const vec3<T> bisector = normalize(vec3<T>{1, 1, 0});
  // A sphere beyond the edge (x = y = 1), 1 cm into it.
  const sphere<T> ball{T(0.5)};
  auto found = touch(cube, transform<T>::identity(), ball, at<T>(vec3<T>{1, 1, 0} + bisector * T(0.49)));
  REQUIRE(found.size() == 1);
  CHECK(length(found[0].normal - bisector) <= tolerance<T> * 10);
  CHECK(test::deepest(found[0]) == doctest::Approx(0.01).epsilon(tolerance<T> * 1000));
  // A box turned 45° about z, its face against the edge, 1 cm into it.
  const box<T> crate{{T(0.5), T(0.5), T(0.5)}};
  const transform<T> pose =
      at<T>(vec3<T>{1, 1, 0} + bisector * T(0.49), quat<T>::from_axis_angle(vec3<T>::unit_z(), T(0.7853981633974483)));
  found = touch(cube, transform<T>::identity(), crate, pose);
  REQUIRE(found.size() == 1);
  CHECK(length(found[0].normal - bisector) <= tolerance<T> * 10);
  REQUIRE(found[0].count == 2);  // the edge clipped by the box's face, z = ±0.5
  for (const auto& p : found[0].contacts()) {
    CHECK(p.depth == doctest::Approx(0.01).epsilon(tolerance<T> * 1000));
    CHECK(std::abs(std::abs(p.position.z) - T(0.5)) <= tolerance<T> * 10);
  }
  // A ridge of 20° slopes: a flat box on it touches the ridge with its face.
  const T drop = std::tan(T(0.3490658504));
  const std::vector<vec3<T>> v = {{-2, -2 * drop, -2}, {-2, -2 * drop, 2}, {0, 0, -2}, {0, 0, 2}, {2, -2 * drop, -2}, {2, -2 * drop, 2}};
  const std::vector<std::uint32_t> idx = {0, 1, 2, 2, 1, 3, 2, 3, 4, 4, 3, 5};
  const triangle_mesh<T> ridge = triangle_mesh<T>::make(v, idx);
  found = touch(ridge, transform<T>::identity(), crate, at<T>({T(0.1), T(0.49), 0}));
  REQUIRE(found.size() == 1);
  CHECK(length(found[0].normal - vec3<T>::unit_y()) <= normal_tolerance<T>);
  CHECK(test::deepest(found[0]) == doctest::Approx(0.01).epsilon(tolerance<T> * 1000));
  // A sphere over the ridge, within its edge's Voronoi region (12.5° off
  // vertical, less than the slopes' 20°): the normal through the center.
  const vec3<T> c{T(0.1), T(0.45), 0};
  found = touch(ridge, transform<T>::identity(), ball, at<T>(c));
  REQUIRE(found.size() == 1);
  CHECK(length(found[0].normal - normalize(c)) <= tolerance<T> * 10);
  CHECK(test::deepest(found[0]) == doctest::Approx(double(T(0.5) - length(c))).epsilon(tolerance<T> * 1000));
}

TEST_CASE_TEMPLATE("a sphere or a box in a concave corner of floor and wall gets two manifolds", T, float, double) {
  // Floor y = 0 for x in [−3, 0]; wall x = 0 for y in [0, 3], facing −x.
  const std::vector<vec3<T>> v = {{-3, 0, -2}, {-3, 0, 2}, {0, 0, -2}, {0, 0, 2}, {0, 3, -2}, {0, 3, 2}};
  const std::vector<std::uint32_t> idx = {0, 1, 2, 2, 1, 3, 2, 3, 4, 4, 3, 5};
  const triangle_mesh<T> corner = triangle_mesh<T>::make(v, idx);
  int active = 0;
  for (std::size_t t = 0; t < corner.triangle_count(); ++t) active += popcount3(corner.active_edges(t));
  CHECK(active == 6);  // the rim; the diagonals are flat, the fold concave
  // The floor's manifold 1 cm deep, the wall's `wall_depth`.
  const auto check_two = [](const std::vector<contact_manifold<T>>& found, T wall_depth, int points) {
    REQUIRE(found.size() == 2);
    bool floor = false, wall = false;
    for (const auto& m : found) {
      const bool is_floor = length(m.normal - vec3<T>::unit_y()) <= normal_tolerance<T>;
      floor |= is_floor;
      wall |= length(m.normal + vec3<T>::unit_x()) <= normal_tolerance<T>;
      CHECK(m.count == points);
      const T depth = is_floor ? T(0.01) : wall_depth;
      for (const auto& p : m.contacts()) CHECK(p.depth == doctest::Approx(double(depth)).epsilon(tolerance<T> * 1000));
    }
    CHECK(floor);
    CHECK(wall);
  };
  check_two(touch(corner, transform<T>::identity(), sphere<T>{T(0.5)}, at<T>({T(-0.49), T(0.49), T(0.3)})), T(0.01), 1);
  check_two(touch(corner, transform<T>::identity(), box<T>{{T(0.5), T(0.5), T(0.5)}}, at<T>({T(-0.48), T(0.49), T(0.3)})),
            T(0.02), 4);
  // Room for one: the deepest (the box 2 cm into the wall, 1 cm into the floor).
  std::vector<contact_manifold<T>> one(1);
  REQUIRE(collide(corner, transform<T>::identity(), box<T>{{T(0.5), T(0.5), T(0.5)}}, at<T>({T(-0.48), T(0.49), T(0.3)}),
                  T(0), std::span(one)) == 1);
  CHECK(length(one[0].normal + vec3<T>::unit_x()) <= normal_tolerance<T>);
}

// ---- far from the origin and bad input -----------------------------------------

TEST_CASE_TEMPLATE("a mesh far from the origin gives the same contacts as at the origin", T, float, double) {
  const vec3<T> far{T(1e4), T(1e4), T(-1e4)};
  const triangle_mesh<T> near_mesh = grid<T>(10), far_vertices = grid<T>(10, far);
  const box<T> crate{{T(0.5), T(0.5), T(0.5)}};
  const sphere<T> ball{T(0.5)};
  lcg32 g{17};
  for (int q = 0; q < 100; ++q) {
    const vec3<T> local{g.uniform<T>(-3, 3), T(0.49), g.uniform<T>(-3, 3)};
    const quat<T> yaw = quat<T>::from_axis_angle(vec3<T>::unit_y(), g.uniform<T>(-3, 3));
    // The far positions as T rounds them; their height above the mesh is
    // exact (Sterbenz), so the depth is known exactly.
    const vec3<T> world = far + local;
    const T height = world.y - far.y;
    for (const bool posed : {false, true}) {
      // The far mesh: either its vertices are far, or its pose is.
      const triangle_mesh<T>& mesh = posed ? near_mesh : far_vertices;
      const transform<T> pose_mesh = posed ? at<T>(far) : transform<T>::identity();
      auto found = touch(mesh, pose_mesh, ball, at<T>(world));
      REQUIRE(found.size() == 1);
      CHECK(length(found[0].normal - vec3<T>::unit_y()) <= normal_tolerance<T>);
      CHECK(std::abs(test::deepest(found[0]) - (ball.radius - height)) <= tolerance<T>);
      found = touch(mesh, pose_mesh, crate, at<T>(world, yaw));
      REQUIRE(found.size() == 1);
      CHECK(length(found[0].normal - vec3<T>::unit_y()) <= normal_tolerance<T>);
      CHECK(std::abs(test::deepest(found[0]) - (crate.half_extents.y - height)) <= tolerance<T>);
      // Positions are as good as T is at 1e4: a few ulps of it.
      for (const auto& p : found[0].contacts())
        CHECK(std::abs(p.position.y - (far.y - (crate.half_extents.y - height) * T(0.5))) <=
              T(4) * std::numeric_limits<T>::epsilon() * T(1e4));
    }
  }
}

TEST_CASE_TEMPLATE("a shape with a non-finite pose touches nothing and writes no NaN", T, float, double) {
  const triangle_mesh<T> mesh = grid<T>(4);
  const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
  const convex_hull<T> hull = convex_hull<T>::from_points(test::box_corners<T>({T(0.5), T(0.5), T(0.5)}));
  for (const transform<T>& pose :
       {at<T>({nan, T(0.4), 0}), at<T>({0, inf, 0}), at<T>({0, T(0.4), 0}, quat<T>{nan, 0, 0, 1})}) {
    CHECK(touch(mesh, transform<T>::identity(), capsule<T>{}, pose).empty());
    CHECK(touch(mesh, transform<T>::identity(), box<T>{}, pose).empty());
    CHECK(touch(mesh, transform<T>::identity(), hull, pose).empty());
    // A sphere has no orientation to spoil: only its center matters.
    for (const auto& m : touch(mesh, transform<T>::identity(), sphere<T>{}, pose)) {
      CHECK(is_finite(m.normal));
      for (const auto& p : m.contacts()) CHECK(std::isfinite(p.depth));
    }
  }
  // A non-finite mesh pose: nothing either.
  CHECK(touch(mesh, at<T>({nan, 0, 0}), box<T>{}, at<T>({0, T(0.4), 0})).empty());
  // Far apart and behind: nothing.
  CHECK(touch(mesh, transform<T>::identity(), box<T>{}, at<T>({0, T(0.6), 0})).empty());
  CHECK(touch(mesh, transform<T>::identity(), box<T>{}, at<T>({0, T(-0.1), 0})).empty());  // center behind: let through
  // Within the margin: a contact of negative depth.
  const auto near = touch(mesh, transform<T>::identity(), box<T>{}, at<T>({0, T(0.55), 0}), T(0.1));
  REQUIRE(near.size() == 1);
  CHECK(test::deepest(near[0]) == doctest::Approx(-0.05).epsilon(tolerance<T> * 1000));
}

TEST_CASE("a hull whose origin lies outside it is met by the mesh it rests on") {
  // The one-sided test asks whether the shape is in front of a triangle;
  // asked of the hull's origin (here 2 m below it, under the floor) it
  // would let the hull fall through.
  const std::vector<vec3<double>> corners = {{-20, 0, -20}, {20, 0, -20}, {20, 0, 20}, {-20, 0, 20}};
  const std::vector<std::uint32_t> triangles = {0, 2, 1, 0, 3, 2};
  const triangle_mesh<double> floor = triangle_mesh<double>::make(corners, triangles);
  std::vector<vec3<double>> points;
  for (int i = 0; i < 8; ++i) points.push_back({1.5 + (i & 1), 1.5 + ((i >> 1) & 1), 1.5 + (i >> 2)});
  const convex_hull<double> hull = convex_hull<double>::from_points(points);
  // Its points span y = −0.01 .. 0.99: sunk 1 cm into the floor.
  std::vector<contact_manifold<double>> out(4);
  const std::size_t n = collide(floor, at<double>({0, 0, 0}), hull, at<double>({-2, -1.51, -2}), 0.0, std::span(out));
  REQUIRE(n == 1);
  CHECK(out[0].normal.y == doctest::Approx(1.0));
  CHECK(out[0].count == 4);
  for (const auto& p : out[0].contacts()) CHECK(p.depth == doctest::Approx(0.01));
}

}  // namespace narrowphase_mesh_tests
