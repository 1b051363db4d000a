// Box against box: face contacts clipped to the overlap, edge contacts, the
// bias towards faces, ids that hold while a box rests on a box, size ratios,
// far from the origin, and no missing contact over random pairs.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "impulse/core/random.hpp"
#include "impulse/narrowphase.hpp"

#include "poses.hpp"

namespace narrowphase_box_box_tests {

namespace {

using namespace impulse;
using narrowphase::collide;
using test::at;
using test::finite;
using test::ids_of;

template <class T>
constexpr T tolerance = test::contact_tolerance<T>;

/// Whether x lies inside the box at pose, shrunk by `inset` (grown if negative).
template <class T>
bool inside(const box<T>& b, const transform<T>& pose, const vec3<T>& x, T inset) {
  const vec3<T> local = inverse_apply(pose, x);
  for (int k = 0; k < 3; ++k)
    if (std::abs(local[k]) > b.half_extents[k] - inset) return false;
  return true;
}

}  // namespace

TEST_CASE_TEMPLATE("a box resting on a wider box: four corners, one normal, the depth everywhere", T, float, double) {
  const box<T> ground{{T(2), T(0.5), T(2)}}, cube{vec3<T>::splat(T(0.5))};
  const auto m = collide(ground, at<T>({}), cube, at<T>({T(0.3), T(0.99), T(-0.2)}));
  REQUIRE(m.count == 4);
  CHECK(length(m.normal - vec3<T>::unit_y()) <= tolerance<T>);
  for (const auto& p : m.contacts()) {
    CHECK(p.depth == doctest::Approx(0.01).epsilon(tolerance<T> * 1000));
    CHECK(p.position.y == doctest::Approx(0.495).epsilon(tolerance<T> * 100));
    CHECK(std::abs(std::abs(p.position.x - T(0.3)) - T(0.5)) <= tolerance<T> * 10);
    CHECK(std::abs(std::abs(p.position.z + T(0.2)) - T(0.5)) <= tolerance<T> * 10);
  }
  // Apart by 0.2: nothing, or, within a margin of 0.3, the same four at
  // depth -0.2.
  CHECK(collide(ground, at<T>({}), cube, at<T>({0, T(1.2), 0})).empty());
  const auto near_miss = collide(ground, at<T>({}), cube, at<T>({0, T(1.2), 0}), T(0.3));
  REQUIRE(near_miss.count == 4);
  for (const auto& p : near_miss.contacts()) CHECK(p.depth == doctest::Approx(-0.2).epsilon(tolerance<T> * 100));
  // Exactly touching: four points at depth 0.
  const auto touching = collide(ground, at<T>({}), cube, at<T>({0, T(1), 0}));
  REQUIRE(touching.count == 4);
  for (const auto& p : touching.contacts()) CHECK(std::abs(p.depth) <= tolerance<T> * 10);
  // The swapped pair: the same contact, the normal reversed.
  const auto swapped = collide(cube, at<T>({T(0.3), T(0.99), T(-0.2)}), ground, at<T>({}));
  REQUIRE(swapped.count == 4);
  CHECK(length(swapped.normal + vec3<T>::unit_y()) <= tolerance<T>);
}

TEST_CASE_TEMPLATE("a wide box on a small one is clipped to the small one's face", T, float, double) {
  // The reference face is the small box's top; the wide box's bottom is
  // clipped to it: the four contacts are the small face's corners.
  const box<T> small{vec3<T>::splat(T(0.5))}, wide{{T(2), T(0.5), T(2)}};
  const auto m = collide(small, at<T>({}), wide, at<T>({T(0.1), T(0.99), 0}));
  REQUIRE(m.count == 4);
  for (const auto& p : m.contacts()) {
    CHECK(p.depth == doctest::Approx(0.01).epsilon(tolerance<T> * 1000));
    CHECK(std::abs(std::abs(p.position.x) - T(0.5)) <= tolerance<T> * 10);
    CHECK(std::abs(std::abs(p.position.z) - T(0.5)) <= tolerance<T> * 10);
  }
  // A box turned 45° about y on the small one: each clips the other, eight
  // candidate points (an octagon), four kept.
  const auto turned = collide(small, at<T>({}), small,
                              at<T>({0, T(0.99), 0}, quat<T>::from_axis_angle(vec3<T>::unit_y(), T(0.785398163397448))));
  REQUIRE(turned.count == 4);
  for (const auto& p : turned.contacts()) CHECK(p.depth == doctest::Approx(0.01).epsilon(tolerance<T> * 1000));
}

TEST_CASE_TEMPLATE("two boxes crossing edge to edge touch at one point", T, float, double) {
  const box<T> cube{vec3<T>::splat(T(0.5))};
  const test::crossing_edges<T> pair;
  pair.check(collide(cube, pair.a, cube, pair.b), 1u << 15);
}

TEST_CASE_TEMPLATE("a box resting on a box keeps the same four ids step after step", T, float, double) {
  // Jitter of the kind a solver leaves: 0.1 mm and 1 mrad, 1000 steps.
  const box<T> cube{vec3<T>::splat(T(0.5))};
  lcg32 random{2026};
  std::set<std::uint32_t> first;
  for (int step = 0; step < 1000; ++step) {
    const vec3<T> shift{random.uniform<T>(T(-1e-4), T(1e-4)), random.uniform<T>(T(-1e-4), T(1e-4)),
                        random.uniform<T>(T(-1e-4), T(1e-4))};
    const vec3<T> axis = normalize(vec3<T>{random.uniform<T>(-1, 1), random.uniform<T>(-1, 1), random.uniform<T>(T(-1), T(1))} +
                                   vec3<T>{0, 0, T(1e-3)});
    const auto m = collide(cube, at<T>({}), cube,
                           at<T>(vec3<T>{0, T(0.995), 0} + shift, quat<T>::from_axis_angle(axis, random.uniform<T>(T(-1e-3), T(1e-3)))));
    REQUIRE(m.count == 4);
    if (step == 0) first = ids_of(m);
    CHECK(ids_of(m) == first);
  }
  CHECK(first.size() == 4);
}

TEST_CASE_TEMPLATE("size ratio 1000:1 and far from the origin", T, float, double) {
  // A 2 cm cube on a 20 m one.
  const box<T> big{vec3<T>::splat(T(10))}, pebble{vec3<T>::splat(T(0.01))};
  auto m = collide(big, at<T>({}), pebble, at<T>({T(3), T(10.009), T(-4)}));
  REQUIRE(m.count == 4);
  for (const auto& p : m.contacts()) CHECK(p.depth == doctest::Approx(0.001).epsilon(sizeof(T) == 4 ? 2e-3 : 1e-9));
  // And the other way round: the big one on the pebble.
  m = collide(pebble, at<T>({}), big, at<T>({T(3), T(10.009), T(-4)}));
  REQUIRE(m.count == 4);
  for (const auto& p : m.contacts()) CHECK(p.depth == doctest::Approx(0.001).epsilon(sizeof(T) == 4 ? 2e-3 : 1e-9));

  // The resting pair 10 km out: the depth within two float spacings at
  // 1e4 (1 mm each): the test works in A's frame, so it loses only what
  // forming B's offset from A costs.
  const box<T> cube{vec3<T>::splat(T(0.5))};
  const vec3<T> far{T(1e4), T(-2e3), T(1e4)};
  m = collide(cube, at<T>(far), cube, at<T>(far + vec3<T>{0, T(0.99), 0}));
  REQUIRE(m.count == 4);
  const T allowed = sizeof(T) == 4 ? T(2e-3) : T(1e-9);
  for (const auto& p : m.contacts()) CHECK(std::abs(p.depth - T(0.01)) <= allowed);
}

TEST_CASE_TEMPLATE("random box pairs: no missing contact, no NaN, points on both boxes", T, float, double) {
  // 10 000 pairs of random boxes, sizes 0.05 to 2, at random poses close
  // enough to overlap about half the time. Whenever a corner or the center
  // of one lies inside the other, there must be a contact; every contact
  // must have A's surface point (position + n·depth/2) in A and B's
  // (position − n·depth/2) in B, to rounding.
  lcg32 random{99};
  const auto random_quat = [&] { return test::random_rotation<T>(random); };
  int touching = 0, missed = 0, off_surface = 0;
  for (int k = 0; k < 10000; ++k) {
    const box<T> a{{random.uniform<T>(T(0.05), T(2)), random.uniform<T>(T(0.05), T(2)), random.uniform<T>(T(0.05), T(2))}};
    const box<T> b{{random.uniform<T>(T(0.05), T(2)), random.uniform<T>(T(0.05), T(2)), random.uniform<T>(T(0.05), T(2))}};
    const transform<T> pa = at<T>({random.uniform<T>(-1, 1), random.uniform<T>(-1, 1), random.uniform<T>(T(-1), T(1))}, random_quat());
    const transform<T> pb = at<T>({random.uniform<T>(-2, 2), random.uniform<T>(-2, 2), random.uniform<T>(T(-2), T(2))}, random_quat());
    const auto m = collide(a, pa, b, pb);
    REQUIRE(finite(m));
    bool must_touch = inside(a, pa, pb.position, T(0)) || inside(b, pb, pa.position, T(0));
    for (std::uint32_t c = 0; c < 8; ++c) {
      const auto corner = [&](const box<T>& x) {
        return vec3<T>{(c & 1u) ? x.half_extents.x : -x.half_extents.x, (c & 2u) ? x.half_extents.y : -x.half_extents.y,
                       (c & 4u) ? x.half_extents.z : -x.half_extents.z};
      };
      must_touch = must_touch || inside(b, pb, apply(pa, corner(a)), T(0)) || inside(a, pa, apply(pb, corner(b)), T(0));
    }
    if (must_touch && m.empty()) ++missed;
    if (!m.empty()) ++touching;
    const T slack = T(100) * tolerance<T> * T(4);
    for (const auto& p : m.contacts()) {
      if (!inside(a, pa, p.position + m.normal * (p.depth / 2), -slack)) ++off_surface;
      if (!inside(b, pb, p.position - m.normal * (p.depth / 2), -slack)) ++off_surface;
      CHECK(p.depth >= -slack);
    }
  }
  MESSAGE("touching pairs: " << touching);
  CHECK(touching > 3000);
  CHECK(missed == 0);
  CHECK(off_surface == 0);
}

}  // namespace narrowphase_box_box_tests
