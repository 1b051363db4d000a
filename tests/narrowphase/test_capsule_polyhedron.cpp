// A capsule against a box and a hull: lying on a face it stands on two
// points (clipped where it overhangs), upright on one; its core sunk into
// the box, the least penetrating axis; random pairs agree with GJK/EPA and
// every point lies on both surfaces; ids hold while it rests.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "impulse/core/random.hpp"
#include "impulse/narrowphase.hpp"
#include "impulse/shapes/convex_hull.hpp"

#include "poses.hpp"

namespace narrowphase_capsule_polyhedron_tests {

namespace {

using namespace impulse;
using narrowphase::collide;
using test::at;
using test::deepest;
using test::ids_of;
using test::random_rotation;

template <class T>
constexpr T tolerance = test::contact_tolerance<T>;

/// A capsule lying along x: its axis (local y) turned onto x.
template <class T>
quat<T> lying() {
  return quat<T>::from_axis_angle(vec3<T>::unit_z(), T(1.5707963267948966));
}

/// How far x lies outside the capsule at pose (≤ 0 inside).
template <class T>
T outside(const capsule<T>& c, const transform<T>& pose, const vec3<T>& x) {
  const vec3<T> local = inverse_apply(pose, x);
  const T y = std::clamp(local.y, -c.half_height, c.half_height);
  return length(local - vec3<T>{0, y, 0}) - c.radius;
}
template <class T>
T outside(const box<T>& b, const transform<T>& pose, const vec3<T>& x) {
  const vec3<T> local = inverse_apply(pose, x);
  return max_component(abs(local) - b.half_extents);
}

}  // namespace

TEST_CASE_TEMPLATE("a capsule lying on a box stands on two points, clipped where it overhangs", T, float, double) {
  // Radius 0.25, core 1 m long, lying along x 1 cm into the top of a box
  // whose top face is y = 0.5.
  const box<T> slab{{T(2), T(0.5), T(2)}};
  const capsule<T> rod{T(0.25), T(0.5)};
  auto m = collide(rod, at<T>({T(0.3), T(0.74), T(-0.2)}, lying<T>()), slab, at<T>({}));
  REQUIRE(m.count == 2);
  CHECK(length(m.normal + vec3<T>::unit_y()) <= tolerance<T>);  // from the capsule down into the box
  std::vector<T> xs;
  for (const auto& p : m.contacts()) {
    CHECK(p.depth == doctest::Approx(0.01).epsilon(tolerance<T> * 1000));
    CHECK(p.position.y == doctest::Approx(0.495).epsilon(tolerance<T> * 100));
    xs.push_back(p.position.x);
  }
  std::sort(xs.begin(), xs.end());
  CHECK(xs[0] == doctest::Approx(-0.2).epsilon(tolerance<T> * 10));
  CHECK(xs[1] == doctest::Approx(0.8).epsilon(tolerance<T> * 10));
  // Overhanging the edge at x = 2 by 0.3: the outer point at the edge.
  m = collide(rod, at<T>({T(1.8), T(0.74), 0}, lying<T>()), slab, at<T>({}));
  REQUIRE(m.count == 2);
  xs.clear();
  for (const auto& p : m.contacts()) xs.push_back(p.position.x);
  std::sort(xs.begin(), xs.end());
  CHECK(xs[0] == doctest::Approx(1.3).epsilon(tolerance<T> * 10));
  CHECK(xs[1] == doctest::Approx(2.0).epsilon(tolerance<T> * 10));
  // Swapped: the normal reversed.
  const auto swapped = collide(slab, at<T>({}), rod, at<T>({T(0.3), T(0.74), T(-0.2)}, lying<T>()));
  REQUIRE(swapped.count == 2);
  CHECK(length(swapped.normal - vec3<T>::unit_y()) <= tolerance<T>);
}

TEST_CASE_TEMPLATE("a capsule upright on a box, apart within the margin, and on a hull", T, float, double) {
  const box<T> slab{{T(2), T(0.5), T(2)}};
  const capsule<T> rod{T(0.25), T(0.5)};
  // Upright, its lower cap 2 cm into the top: one point under the cap.
  auto m = collide(rod, at<T>({T(0.1), T(1.23), 0}), slab, at<T>({}));
  REQUIRE(m.count == 1);
  CHECK(m.points[0].depth == doctest::Approx(0.02).epsilon(tolerance<T> * 1000));
  CHECK(length(m.points[0].position - vec3<T>{T(0.1), T(0.49), 0}) <= tolerance<T> * 10);
  // Lying 1 cm above the top: nothing, or two points 1 cm apart with a margin.
  m = collide(rod, at<T>({0, T(0.76), 0}, lying<T>()), slab, at<T>({}));
  CHECK(m.empty());
  m = collide(rod, at<T>({0, T(0.76), 0}, lying<T>()), slab, at<T>({}), T(0.02));
  REQUIRE(m.count == 2);
  for (const auto& p : m.contacts()) CHECK(p.depth == doctest::Approx(-0.01).epsilon(tolerance<T> * 1000));
  // The same on a hull made of the box's corners.
  const convex_hull<T> hull = convex_hull<T>::from_points(test::box_corners(slab.half_extents));
  m = collide(rod, at<T>({T(0.3), T(0.74), T(-0.2)}, lying<T>()), hull, at<T>({}));
  REQUIRE(m.count == 2);
  for (const auto& p : m.contacts()) CHECK(p.depth == doctest::Approx(0.01).epsilon(tolerance<T> * 1000));
}

TEST_CASE_TEMPLATE("a capsule's core sunk into a box leaves by the least penetrating face", T, float, double) {
  // Upright, centered 0.4 from the box's +x face (half extent 1), the core
  // 0.6 long, entirely inside: the way out is +x, 0.4 + 0.25 deep.
  const box<T> cube{vec3<T>::splat(T(1))};
  const capsule<T> rod{T(0.25), T(0.3)};
  const auto m = collide(rod, at<T>({T(0.6), 0, 0}), cube, at<T>({}));
  REQUIRE(m.count == 2);
  CHECK(length(m.normal + vec3<T>::unit_x()) <= tolerance<T>);
  for (const auto& p : m.contacts()) CHECK(p.depth == doctest::Approx(0.65).epsilon(tolerance<T> * 100));
}

TEST_CASE_TEMPLATE("random capsule–box and capsule–hull pairs: agree with GJK/EPA, points on both", T, float, double) {
  // 10 000 random capsules (radius 0.05 to 0.5, half height 0 to 1)
  // against random boxes (half extents 0.05 to 1), and the same boxes as
  // hulls: a contact whenever GJK finds them overlapping by more than
  // rounding, none when apart, the deepest point no deeper than the face
  // bias allows over EPA's least penetration, and every point's capsule
  // surface point in the capsule and box point in the box. The hull's
  // answer equals the box's (normal and deepest depth).
  lcg32 random{31};
  const T slack = sizeof(T) == 4 ? T(3e-4) : T(1e-9);
  int touching = 0, missed = 0, phantom = 0, too_deep = 0, off_surface = 0, differ = 0;
  for (int k = 0; k < 10000; ++k) {
    const capsule<T> c{random.uniform<T>(T(0.05), T(0.5)), random.uniform<T>(T(0), T(1))};
    const box<T> b{{random.uniform<T>(T(0.05), T(1)), random.uniform<T>(T(0.05), T(1)), random.uniform<T>(T(0.05), T(1))}};
    const transform<T> pc = at<T>({random.uniform<T>(-1, 1), random.uniform<T>(-1, 1), random.uniform<T>(T(-1), T(1))},
                                  random_rotation<T>(random));
    const transform<T> pb = at<T>({random.uniform<T>(T(-0.5), T(0.5)), random.uniform<T>(T(-0.5), T(0.5)),
                                   random.uniform<T>(T(-0.5), T(0.5))},
                                  random_rotation<T>(random));
    const contact_manifold<T> m = collide(c, pc, b, pb);
    const auto g = narrowphase::gjk_distance(c, pc, b, pb);
    if (!m.empty()) ++touching;
    if (!g.overlapping && g.distance > slack && !m.empty()) ++phantom;
    if (g.overlapping) {
      const auto e = narrowphase::epa_penetration(c, pc, b, pb);
      if (e.penetrating && e.depth > slack && m.empty()) ++missed;
      const T allowed = (e.depth + T(0.01) * std::min(c.radius, min_component(b.half_extents))) / T(0.95);
      if (!m.empty() && deepest(m) > allowed + slack) ++too_deep;
    }
    for (const auto& p : m.contacts()) {
      if (outside(c, pc, p.position + m.normal * (p.depth / 2)) > slack) ++off_surface;
      if (outside(b, pb, p.position - m.normal * (p.depth / 2)) > slack) ++off_surface;
    }
    const convex_hull<T> hull = convex_hull<T>::from_points(test::box_corners(b.half_extents));
    const contact_manifold<T> h = collide(c, pc, hull, pb);
    if (h.empty() != m.empty() ||
        (!m.empty() && (length(h.normal - m.normal) > slack || std::abs(deepest(h) - deepest(m)) > slack)))
      ++differ;
  }
  MESSAGE("touching pairs: " << touching);
  CHECK(touching > 3000);
  CHECK(missed == 0);
  CHECK(phantom == 0);
  CHECK(too_deep == 0);
  CHECK(off_surface == 0);
  CHECK(differ == 0);
}

TEST_CASE_TEMPLATE("a capsule resting on a box keeps its two ids step after step", T, float, double) {
  // Jitter of the kind a solver leaves: 0.1 mm and 1 mrad, 1000 steps.
  const box<T> slab{{T(2), T(0.5), T(2)}};
  const capsule<T> rod{T(0.25), T(0.5)};
  lcg32 random{8};
  std::set<std::uint32_t> first;
  for (int step = 0; step < 1000; ++step) {
    const vec3<T> shift{random.uniform<T>(T(-1e-4), T(1e-4)), random.uniform<T>(T(-1e-4), T(1e-4)),
                        random.uniform<T>(T(-1e-4), T(1e-4))};
    const quat<T> jitter = quat<T>::from_axis_angle(rotate(random_rotation<T>(random), vec3<T>::unit_x()),
                                                    random.uniform<T>(T(-1e-3), T(1e-3)));
    const auto m = collide(rod, at<T>(vec3<T>{0, T(0.745), 0} + shift, jitter * lying<T>()), slab, at<T>({}));
    REQUIRE(m.count == 2);
    if (step == 0) first = ids_of(m);
    CHECK(ids_of(m) == first);
  }
  CHECK(first.size() == 2);
}

}  // namespace narrowphase_capsule_polyhedron_tests
