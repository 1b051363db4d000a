// Convex hulls against hulls and boxes by separating axes and clipping:
// hulls made from boxes give box_box's contacts, random hulls agree with
// EPA's depth, a resting hull keeps its ids, edge contacts, many-sided
// faces, size ratios and far from the origin.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "impulse/core/random.hpp"
#include "impulse/narrowphase.hpp"
#include "impulse/shapes/convex_hull.hpp"

#include "poses.hpp"

namespace narrowphase_hull_hull_tests {

namespace {

using namespace impulse;
using narrowphase::collide;
using test::at;
using test::deepest;
using test::ids_of;
using test::random_rotation;

template <class T>
constexpr T tolerance = test::contact_tolerance<T>;

template <class T>
convex_hull<T> box_hull(const vec3<T>& h) {
  return convex_hull<T>::from_points(test::box_corners(h));
}

/// A prism over a regular n-gon of radius r in the x-z plane, height 2·h.
template <class T>
convex_hull<T> prism(int n, T r, T h) {
  std::vector<vec3<T>> points;
  for (int k = 0; k < n; ++k) {
    const T angle = T(2 * 3.14159265358979323846 * k / n);
    points.push_back({r * std::cos(angle), -h, r * std::sin(angle)});
    points.push_back({r * std::cos(angle), h, r * std::sin(angle)});
  }
  return convex_hull<T>::from_points(points);
}

/// The largest signed distance of x (world) from the hull's face planes:
/// ≤ 0 inside.
template <class T>
T outside(const convex_hull<T>& hull, const transform<T>& pose, const vec3<T>& x) {
  const vec3<T> local = inverse_apply(pose, x);
  T worst = -std::numeric_limits<T>::infinity();
  for (const auto& p : hull.planes()) worst = std::max(worst, p.distance(local));
  return worst;
}

}  // namespace

TEST_CASE_TEMPLATE("hulls made from boxes give box_box's contacts on random pairs", T, float, double) {
  // 10 000 random box pairs (sizes 0.05 to 2) as hull–hull, box–hull and
  // hull–box: the same answer as box_box, which is tested against corner
  // containment: touching or not, the normal and the deepest point's
  // depth, to rounding. (The other points, and how many, may differ on
  // deep overlaps, whose patches have more than four: a hull splits its
  // patch into quarters along its face's first edge, which may be a box
  // axis reversed, and points within the 1 % dead band then fall in
  // another quarter. The ids differ too: quickhull numbers the hull's
  // vertices and faces in its own order.)
  lcg32 random{7};
  int touching = 0, differ = 0;
  const T slack = sizeof(T) == 4 ? T(2e-4) : T(1e-9);
  for (int k = 0; k < 10000; ++k) {
    const vec3<T> ha{random.uniform<T>(T(0.05), T(2)), random.uniform<T>(T(0.05), T(2)), random.uniform<T>(T(0.05), T(2))};
    const vec3<T> hb{random.uniform<T>(T(0.05), T(2)), random.uniform<T>(T(0.05), T(2)), random.uniform<T>(T(0.05), T(2))};
    const transform<T> pa = at<T>({random.uniform<T>(-1, 1), random.uniform<T>(-1, 1), random.uniform<T>(T(-1), T(1))},
                                  random_rotation<T>(random));
    const transform<T> pb = at<T>({random.uniform<T>(-2, 2), random.uniform<T>(-2, 2), random.uniform<T>(T(-2), T(2))},
                                  random_rotation<T>(random));
    const box<T> a{ha}, b{hb};
    const convex_hull<T> hull_a = box_hull(ha), hull_b = box_hull(hb);
    const contact_manifold<T> expected = collide(a, pa, b, pb);
    const contact_manifold<T> got[3] = {collide(hull_a, pa, hull_b, pb), collide(a, pa, hull_b, pb),
                                        collide(hull_a, pa, b, pb)};
    if (!expected.empty()) ++touching;
    for (const contact_manifold<T>& m : got) {
      bool same = m.empty() == expected.empty();
      if (same && !m.empty())
        same = length(m.normal - expected.normal) <= slack && std::abs(deepest(m) - deepest(expected)) <= slack;
      if (!same) ++differ;
    }
  }
  MESSAGE("touching pairs: " << touching);
  CHECK(touching > 3000);
  CHECK(differ == 0);
}

TEST_CASE_TEMPLATE("random hull pairs: touching when EPA says so, depth within the face bias, points on both", T, float,
                   double) {
  // 5 000 pairs of hulls of 6 to 40 random points (sizes 0.1 to 2). The
  // separating axis test must find a contact whenever EPA finds them
  // overlapping, none when GJK finds them apart, a deepest point no deeper
  // than the face bias allows over EPA's least penetration, and every point with A's
  // surface point (position + n·depth/2) in A and B's in B.
  lcg32 random{2027};
  const auto cloud = [&] {
    const int n = 6 + int(random.next() % 35);
    const vec3<T> size{random.uniform<T>(T(0.1), T(2)), random.uniform<T>(T(0.1), T(2)), random.uniform<T>(T(0.1), T(2))};
    std::vector<vec3<T>> points;
    for (int k = 0; k < n; ++k)
      points.push_back(mul(size, vec3<T>{random.uniform<T>(-1, 1), random.uniform<T>(-1, 1), random.uniform<T>(T(-1), T(1))}));
    return convex_hull<T>::from_points(points);
  };
  const T slack = sizeof(T) == 4 ? T(3e-4) : T(1e-9);
  int touching = 0, missed = 0, phantom = 0, too_deep = 0, off_surface = 0;
  for (int k = 0; k < 5000; ++k) {
    const convex_hull<T> a = cloud(), b = cloud();
    const transform<T> pa = at<T>({random.uniform<T>(-1, 1), random.uniform<T>(-1, 1), random.uniform<T>(T(-1), T(1))},
                                  random_rotation<T>(random));
    const transform<T> pb = at<T>({random.uniform<T>(-1, 1), random.uniform<T>(-1, 1), random.uniform<T>(T(-1), T(1))},
                                  random_rotation<T>(random));
    const contact_manifold<T> m = collide(a, pa, b, pb);
    const auto g = narrowphase::gjk_distance(a, pa, b, pb);
    if (!m.empty()) ++touching;
    if (!g.overlapping && g.distance > slack && !m.empty()) ++phantom;
    if (g.overlapping) {
      const auto e = narrowphase::epa_penetration(a, pa, b, pb);
      if (e.penetrating && e.depth > slack && m.empty()) ++missed;
      const auto least = [](const convex_hull<T>& h) {
        return min_component(h.local_aabb().upper - h.local_aabb().lower) * T(0.5);
      };
      // A face is kept over an axis up to 5 % plus 1 % of the least half
      // extent less deep than it: d_face ≤ (d_least + 1 %)/0.95.
      const T allowed = (e.depth + T(0.01) * std::min(least(a), least(b))) / T(0.95);
      if (!m.empty() && deepest(m) > allowed + slack) ++too_deep;
    }
    for (const auto& p : m.contacts()) {
      if (outside(a, pa, p.position + m.normal * (p.depth / 2)) > slack) ++off_surface;
      if (outside(b, pb, p.position - m.normal * (p.depth / 2)) > slack) ++off_surface;
    }
  }
  MESSAGE("touching pairs: " << touching);
  CHECK(touching > 1500);
  CHECK(missed == 0);
  CHECK(phantom == 0);
  CHECK(too_deep == 0);
  CHECK(off_surface == 0);
}

TEST_CASE_TEMPLATE("a hull resting on a hull keeps the same four ids step after step", T, float, double) {
  // Jitter of the kind a solver leaves: 0.1 mm and 1 mrad, 1000 steps, for
  // a cube hull on a cube hull and an octagonal prism on a box.
  const convex_hull<T> cube = box_hull(vec3<T>::splat(T(0.5)));
  const convex_hull<T> octagon = prism<T>(8, T(0.5), T(0.5));
  const box<T> ground{{T(2), T(0.5), T(2)}};
  lcg32 random{2026};
  std::set<std::uint32_t> first_cube, first_octagon;
  for (int step = 0; step < 1000; ++step) {
    const vec3<T> shift{random.uniform<T>(T(-1e-4), T(1e-4)), random.uniform<T>(T(-1e-4), T(1e-4)),
                        random.uniform<T>(T(-1e-4), T(1e-4))};
    const quat<T> tilt = random_rotation<T>(random);
    const quat<T> jitter = quat<T>::from_axis_angle(rotate(tilt, vec3<T>::unit_x()), random.uniform<T>(T(-1e-3), T(1e-3)));
    auto m = collide(cube, at<T>({}), cube, at<T>(vec3<T>{0, T(0.995), 0} + shift, jitter));
    REQUIRE(m.count == 4);
    if (step == 0) first_cube = ids_of(m);
    CHECK(ids_of(m) == first_cube);
    m = collide(ground, at<T>({}), octagon, at<T>(vec3<T>{T(0.2), T(0.995), 0} + shift, jitter));
    REQUIRE(m.count == 4);
    CHECK(length(m.normal - vec3<T>::unit_y()) <= T(2e-3));
    if (step == 0) first_octagon = ids_of(m);
    CHECK(ids_of(m) == first_octagon);
  }
  CHECK(first_cube.size() == 4);
  CHECK(first_octagon.size() == 4);
}

TEST_CASE_TEMPLATE("two cube hulls crossing edge to edge touch at one point", T, float, double) {
  const convex_hull<T> cube = box_hull(vec3<T>::splat(T(0.5)));
  const test::crossing_edges<T> pair;
  pair.check(collide(cube, pair.a, cube, pair.b), 1u << 31);
}

TEST_CASE_TEMPLATE("faces of 64 sides, the margin, swapped pairs", T, float, double) {
  // Two 64-sided prisms cap to cap (each clip holds up to 129 points: the
  // scratch space leaves the stack), 1 cm into each other: four points,
  // each 1 cm deep, spanning the cap.
  const convex_hull<T> disc = prism<T>(64, T(1), T(0.25));
  auto m = collide(disc, at<T>({}), disc, at<T>({T(0.1), T(0.49), 0}));
  REQUIRE(m.count == 4);
  CHECK(length(m.normal - vec3<T>::unit_y()) <= tolerance<T> * 10);
  for (const auto& p : m.contacts()) {
    CHECK(p.depth == doctest::Approx(0.01).epsilon(tolerance<T> * 1000));
    CHECK(length(p.position - vec3<T>{T(0.05), T(0.245), 0}) > T(0.7));  // near the rim of the overlap
  }
  // 1 cm apart: nothing without a margin, four points 1 cm short with one.
  m = collide(disc, at<T>({}), disc, at<T>({0, T(0.51), 0}));
  CHECK(m.empty());
  m = collide(disc, at<T>({}), disc, at<T>({0, T(0.51), 0}), T(0.02));
  REQUIRE(m.count == 4);
  for (const auto& p : m.contacts()) CHECK(p.depth == doctest::Approx(-0.01).epsilon(tolerance<T> * 1000));
  // A box against a hull, and the same pair swapped: the normal reversed,
  // the points the same.
  const box<T> slab{{T(0.3), T(0.1), T(0.3)}};
  const transform<T> pb = at<T>({T(0.2), T(0.33), T(-0.1)}, quat<T>::from_axis_angle(vec3<T>::unit_y(), T(0.3)));
  const auto ab = collide(disc, at<T>({}), slab, pb);
  const auto ba = collide(slab, pb, disc, at<T>({}));
  REQUIRE(ab.count == 4);
  REQUIRE(ba.count == 4);
  CHECK(length(ab.normal + ba.normal) <= tolerance<T>);
  for (const auto& p : ab.contacts()) CHECK(p.depth == doctest::Approx(0.02).epsilon(tolerance<T> * 1000));
}

TEST_CASE_TEMPLATE("size ratio 1000:1 and far from the origin", T, float, double) {
  // A 2 cm cube hull on a 20 m one, both ways round.
  const convex_hull<T> big = box_hull(vec3<T>::splat(T(10))), pebble = box_hull(vec3<T>::splat(T(0.01)));
  auto m = collide(big, at<T>({}), pebble, at<T>({T(3), T(10.009), T(-4)}));
  REQUIRE(m.count == 4);
  for (const auto& p : m.contacts()) CHECK(p.depth == doctest::Approx(0.001).epsilon(sizeof(T) == 4 ? 2e-3 : 1e-9));
  m = collide(pebble, at<T>({}), big, at<T>({T(3), T(10.009), T(-4)}));
  REQUIRE(m.count == 4);
  for (const auto& p : m.contacts()) CHECK(p.depth == doctest::Approx(0.001).epsilon(sizeof(T) == 4 ? 2e-3 : 1e-9));
  // An octagonal prism on a cube hull 10 km out: the depth within two
  // float spacings at 1e4 (1 mm each), since the test works in A's frame.
  const convex_hull<T> cube = box_hull(vec3<T>::splat(T(0.5)));
  const convex_hull<T> octagon = prism<T>(8, T(0.5), T(0.5));
  const vec3<T> far{T(1e4), T(-2e3), T(1e4)};
  m = collide(cube, at<T>(far), octagon, at<T>(far + vec3<T>{0, T(0.99), 0}));
  REQUIRE(m.count == 4);
  const T allowed = sizeof(T) == 4 ? T(2e-3) : T(1e-9);
  for (const auto& p : m.contacts()) CHECK(std::abs(p.depth - T(0.01)) <= allowed);
}

TEST_CASE_TEMPLATE("a hull with nearly coplanar points on its faces collides as the clean one", T, float, double) {
  // Points sprinkled on a cube's faces, each lifted or sunk by a hundredth
  // of the hull's tolerance: quickhull merges them into the six faces, and
  // the contact is the clean cube's.
  std::vector<vec3<T>> points = test::box_corners(vec3<T>::splat(T(0.5)));
  lcg32 random{5};
  const T wobble = T(0.01) * convex_hull<T>::from_points(points).tolerance();
  for (int k = 0; k < 200; ++k) {
    vec3<T> p{random.uniform<T>(T(-0.5), T(0.5)), random.uniform<T>(T(-0.5), T(0.5)), random.uniform<T>(T(-0.5), T(0.5))};
    const int axis = int(random.next() % 3);
    p[axis] = (random.next() % 2 ? T(0.5) : T(-0.5)) + random.uniform<T>(-wobble, wobble);
    points.push_back(p);
  }
  const convex_hull<T> noisy = convex_hull<T>::from_points(points);
  CHECK(noisy.face_count() == 6);
  const convex_hull<T> clean = box_hull(vec3<T>::splat(T(0.5)));
  const transform<T> pb = at<T>({T(0.1), T(0.98), T(0.05)}, quat<T>::from_axis_angle(vec3<T>::unit_y(), T(0.2)));
  const auto m = collide(noisy, at<T>({}), noisy, pb);
  const auto expected = collide(clean, at<T>({}), clean, pb);
  REQUIRE(m.count == 4);
  REQUIRE(expected.count == 4);
  CHECK(length(m.normal - expected.normal) <= tolerance<T> * 10);
  for (const auto& p : m.contacts()) CHECK(p.depth == doctest::Approx(0.02).epsilon(tolerance<T> * 1000));
}

}  // namespace narrowphase_hull_hull_tests
