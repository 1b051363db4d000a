// The cases that break narrow phases, for every polyhedral pair test (box–
// box, hull–hull, box–hull, capsule–box, capsule–hull): edges a hair off
// parallel, faces exactly touching, one shape centered inside the other.
// Each must give a finite contact with the right depth and normal, never
// NaN and never nothing.
#include <doctest/doctest.h>

#include <cmath>

#include "impulse/narrowphase.hpp"
#include "impulse/shapes/convex_hull.hpp"

#include "poses.hpp"

namespace narrowphase_hard_cases_tests {

namespace {

using namespace impulse;
using narrowphase::collide;
using test::at;
using test::finite;
using test::deepest;

template <class T>
constexpr T tolerance = test::contact_tolerance<T>;

/// The same pair test on a box and on the hull of its corners, A then B.
template <class T>
struct polyhedra {
  box<T> box_a, box_b;
  convex_hull<T> hull_a = convex_hull<T>::from_points(test::box_corners(box_a.half_extents));
  convex_hull<T> hull_b = convex_hull<T>::from_points(test::box_corners(box_b.half_extents));

  /// box–box, hull–hull, box–hull and hull–box at the same poses.
  template <class F>
  void each(const transform<T>& pa, const transform<T>& pb, F&& check) const {
    check(collide(box_a, pa, box_b, pb));
    check(collide(hull_a, pa, hull_b, pb));
    check(collide(box_a, pa, hull_b, pb));
    check(collide(hull_a, pa, box_b, pb));
  }
};

}  // namespace

TEST_CASE_TEMPLATE("edges a hair off parallel: a contact, finite, at the right depth", T, float, double) {
  // Two unit cubes each turned 45° about z, B on top of A, so that A's top
  // edge and B's bottom edge both run along z, 1 cm into each other; then
  // B turned a further ε about y, so the edges cross at ε. Their cross
  // product, the edge axis, is ε long: it must neither give NaN nor lose
  // the contact. Parallel edges have no axis of their own: the least
  // penetration is along a face normal at 45°, 1 cm · cos 45° deep, to
  // within the ε·0.5 m the turn moves the edge's ends.
  const polyhedra<T> cubes{{vec3<T>::splat(T(0.5))}, {vec3<T>::splat(T(0.5))}};
  const T reach = T(0.5) * std::sqrt(T(2));
  const quat<T> edge_up = quat<T>::from_axis_angle(vec3<T>::unit_z(), T(0.785398163397448));
  for (const T epsilon : {T(0), T(1e-7), T(1e-5), T(1e-3)}) {
    CAPTURE(epsilon);
    const transform<T> pa = at<T>({}, edge_up);
    const transform<T> pb =
        at<T>({0, 2 * reach - T(0.01), 0}, quat<T>::from_axis_angle(vec3<T>::unit_y(), epsilon) * edge_up);
    cubes.each(pa, pb, [&](const contact_manifold<T>& m) {
      REQUIRE(finite(m));
      REQUIRE(!m.empty());
      CHECK(std::abs(m.normal.y) == doctest::Approx(std::sqrt(T(0.5))).epsilon(T(1e-3)));
      CHECK(std::abs(deepest(m) - T(0.01) * std::sqrt(T(0.5))) <= T(0.5) * epsilon + T(100) * tolerance<T>);
    });
  }
}

TEST_CASE_TEMPLATE("faces exactly touching: points at depth 0", T, float, double) {
  // A unit cube resting with no gap and no overlap on a wider box, turned
  // about y; a capsule lying on it likewise. With no margin the contact
  // must still be reported, at depth 0.
  const polyhedra<T> pair{{{T(2), T(0.5), T(2)}}, {vec3<T>::splat(T(0.5))}};
  const transform<T> pb = at<T>({T(0.3), T(1), T(-0.2)}, quat<T>::from_axis_angle(vec3<T>::unit_y(), T(0.4)));
  pair.each(at<T>({}), pb, [&](const contact_manifold<T>& m) {
    REQUIRE(finite(m));
    REQUIRE(m.count == 4);
    for (const auto& p : m.contacts()) CHECK(std::abs(p.depth) <= T(10) * tolerance<T>);
  });
  const capsule<T> rod{T(0.25), T(0.5)};
  const transform<T> lying =
      at<T>({T(0.1), T(0.75), 0}, quat<T>::from_axis_angle(vec3<T>::unit_z(), T(1.5707963267948966)));
  // The capsule's turn onto x is not exact in T: its ends sit a rounding
  // apart in height, and with no margin at all the higher one may count as
  // apart. The contact is there; a micrometre of margin gives both ends.
  for (const T margin : {T(0), T(1e-6)}) {
    for (const contact_manifold<T>& m :
         {collide(rod, lying, pair.box_a, at<T>({}), margin), collide(rod, lying, pair.hull_a, at<T>({}), margin)}) {
      REQUIRE(finite(m));
      REQUIRE(!m.empty());
      if (margin > T(0)) CHECK(m.count == 2);
      for (const auto& p : m.contacts()) CHECK(std::abs(p.depth) <= T(10) * tolerance<T>);
    }
  }
}

TEST_CASE_TEMPLATE("one shape centered inside the other: out along a face, the full depth", T, float, double) {
  // A box of half extents (0.3, 0.2, 0.4) centered in a unit cube (and
  // turned 0.1 rad about x): the least way out is along y, where the two
  // overlap by 0.5 + 0.2·cos 0.1 + 0.4·sin 0.1 (the turned box's reach);
  // a capsule centered upright inside the cube: out sideways, 0.5 + radius.
  const polyhedra<T> pair{{vec3<T>::splat(T(0.5))}, {{T(0.3), T(0.2), T(0.4)}}};
  const T angle = T(0.1);
  const transform<T> pb = at<T>({}, quat<T>::from_axis_angle(vec3<T>::unit_x(), angle));
  const T reach = T(0.2) * std::cos(angle) + T(0.4) * std::sin(angle);
  pair.each(at<T>({}), pb, [&](const contact_manifold<T>& m) {
    REQUIRE(finite(m));
    REQUIRE(!m.empty());
    CHECK(std::abs(m.normal.y) >= T(1) - T(1e-4));
    CHECK(deepest(m) == doctest::Approx(T(0.5) + reach).epsilon(T(1e-4)));
  });
  const capsule<T> rod{T(0.1), T(0.2)};
  for (const contact_manifold<T>& m : {collide(rod, at<T>({}), pair.box_a, at<T>({})),
                                       collide(rod, at<T>({}), pair.hull_a, at<T>({}))}) {
    REQUIRE(finite(m));
    REQUIRE(!m.empty());
    CHECK(std::abs(m.normal.y) <= T(1e-4));  // sideways: x or z
    CHECK(deepest(m) == doctest::Approx(0.6).epsilon(T(1e-4)));
  }
}

}  // namespace narrowphase_hard_cases_tests
