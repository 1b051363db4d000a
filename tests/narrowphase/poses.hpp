// Poses and shapes for the narrow-phase tests: a pose from a position (and
// a rotation), a random rotation, a box's corners, two cubes crossing edge
// to edge; and the contact tolerance and a manifold's ids.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <vector>

#include "impulse/core/random.hpp"
#include "impulse/math/transform.hpp"
#include "impulse/narrowphase/manifold.hpp"

namespace impulse::test {

/// Rounding allowed in a contact's normal, depth and position for 1 m
/// shapes: a few float spacings, or a few thousand double ones.
template <class T>
constexpr T contact_tolerance = sizeof(T) == 4 ? T(2e-5) : T(1e-12);

/// Whether a manifold is free of NaN and infinity, with a unit normal.
template <class T>
bool finite(const impulse::contact_manifold<T>& m) {
  bool ok = is_finite(m.normal) && std::abs(length(m.normal) - T(1)) <= T(10) * contact_tolerance<T>;
  for (const auto& p : m.contacts()) ok = ok && is_finite(p.position) && std::isfinite(p.depth);
  return ok;
}

/// The depth of a manifold's deepest point.
template <class T>
T deepest(const impulse::contact_manifold<T>& m) {
  T d = -std::numeric_limits<T>::infinity();
  for (const auto& p : m.contacts()) d = std::max(d, p.depth);
  return d;
}

/// The feature ids of a manifold's points.
template <class T>
std::set<std::uint32_t> ids_of(const impulse::contact_manifold<T>& m) {
  std::set<std::uint32_t> ids;
  for (const auto& p : m.contacts()) ids.insert(p.feature);
  return ids;
}

template <class T>
impulse::transform<T> at(const impulse::vec3<T>& p, const impulse::quat<T>& q = impulse::quat<T>::identity()) {
  return {p, q};
}

/// A rotation about a random axis by a random angle in (−3.14, 3.14).
template <class T>
impulse::quat<T> random_rotation(impulse::lcg32& random) {
  const impulse::vec3<T> axis = normalize(
      impulse::vec3<T>{random.uniform<T>(-1, 1), random.uniform<T>(-1, 1), random.uniform<T>(T(-1), T(1))} +
      impulse::vec3<T>{T(1e-3), 0, 0});
  return impulse::quat<T>::from_axis_angle(axis, random.uniform<T>(T(-3.14), T(3.14)));
}

/// The eight corners of a box of half extents h.
template <class T>
std::vector<impulse::vec3<T>> box_corners(const impulse::vec3<T>& h) {
  std::vector<impulse::vec3<T>> corners;
  for (int k = 0; k < 8; ++k) corners.push_back({(k & 1) ? h.x : -h.x, (k & 2) ? h.y : -h.y, (k & 4) ? h.z : -h.z});
  return corners;
}

/// Two unit cubes crossing edge to edge, 1 cm into each other: A turned 45°
/// about z (its top is an edge along z), B turned 45° about x (its bottom
/// is an edge along x), B above. The edges cross at x = z = 0; the contact
/// point, midway between them, is `point`, and the normal is +y.
template <class T>
struct crossing_edges {
  T reach = T(0.5) * std::sqrt(T(2));
  impulse::transform<T> a{{}, impulse::quat<T>::from_axis_angle(impulse::vec3<T>::unit_z(), T(0.785398163397448))};
  impulse::transform<T> b{{0, 2 * reach - T(0.01), 0},
                          impulse::quat<T>::from_axis_angle(impulse::vec3<T>::unit_x(), T(0.785398163397448))};
  impulse::vec3<T> point{0, reach - T(0.005), 0};

  /// Checks a pair test's answer: one point, 1 cm deep, at `point`, the
  /// normal +y, and the id flagged as an edge pair by `edge_bit`.
  void check(const impulse::contact_manifold<T>& m, std::uint32_t edge_bit) const {
    REQUIRE(m.count == 1);
    CHECK(length(m.normal - impulse::vec3<T>::unit_y()) <= contact_tolerance<T> * 10);
    CHECK(m.points[0].depth == doctest::Approx(0.01).epsilon(contact_tolerance<T> * 1000));
    CHECK(length(m.points[0].position - point) <= contact_tolerance<T> * 10);
    CHECK((m.points[0].feature & edge_bit) != 0);
  }
};

}  // namespace impulse::test
