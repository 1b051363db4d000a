// Compound shapes on their own: mass properties against closed forms (two
// boxes are the box they make; a dumbbell by the parallel-axis theorem), the
// children's tree against testing every child, ray casts against the
// nearest child, the pair test against the hull around the children, and
// bad compounds refused.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <set>
#include <vector>

#include "../error_code_of.hpp"
#include "two_cubes.hpp"
#include "impulse/core/random.hpp"
#include "impulse/narrowphase.hpp"
#include "impulse/shapes.hpp"

namespace shapes_compound_tests {

using namespace impulse;
using impulse::test::error_code_of;

namespace {

using tf = transform<double>;
const quat<double> upright = quat<double>::identity();

/// Two unit cubes side by side along x: the 2 × 1 × 1 box centered at 0.
compound<double> two_cubes() { return test::two_cubes<double>(); }

/// Mass properties are sums of values near 1: relative rounding.
constexpr double mass_tolerance = 1e-12;

void check_same(const mat3<double>& a, const mat3<double>& b, double tolerance) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) CHECK(a.col[std::size_t(c)][r] == doctest::Approx(b.col[std::size_t(c)][r]).epsilon(tolerance));
}

}  // namespace

TEST_CASE("two cubes side by side have the mass properties of the box they make") {
  const compound<double> c = two_cubes();
  const mass_properties<double> sum = mass_properties_of(c, 2.5);
  const mass_properties<double> whole = mass_properties_of(box<double>{{1, 0.5, 0.5}}, 2.5);
  CHECK(sum.mass == doctest::Approx(whole.mass).epsilon(mass_tolerance));
  CHECK(length(sum.center - whole.center) < mass_tolerance);
  check_same(sum.inertia, whole.inertia, mass_tolerance);
  // The same box turned a quarter about z, from two cubes stacked along y.
  compound<double>::builder b;
  const quat<double> quarter = quat<double>::from_axis_angle({0, 0, 1}, std::numbers::pi / 2);
  b.add(box<double>{{0.5, 0.5, 0.5}}, tf{{0, -0.5, 0}, quarter});
  b.add(box<double>{{0.5, 0.5, 0.5}}, tf{{0, 0.5, 0}, upright});
  const mass_properties<double> tall = mass_properties_of(b.build(), 2.5);
  check_same(tall.inertia, mass_properties_of(box<double>{{0.5, 1, 0.5}}, 2.5).inertia, mass_tolerance);
}

TEST_CASE("a dumbbell's inertia is its balls' by the parallel-axis theorem plus its bar's") {
  const double r = 0.2, half = 0.6, bar = 0.05, rho = 7800;
  compound<double>::builder b;
  b.add(sphere<double>{r}, tf{{-half, 0, 0}, upright});
  b.add(sphere<double>{r}, tf{{half, 0, 0}, upright});
  // The bar along x: a capsule's axis is y, turned a quarter about z.
  b.add(capsule<double>{bar, half}, tf{{}, quat<double>::from_axis_angle({0, 0, 1}, std::numbers::pi / 2)});
  const mass_properties<double> p = mass_properties_of(b.build(), rho);
  const double ball = rho * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const mass_properties<double> rod = mass_properties_of(capsule<double>{bar, half}, rho);
  CHECK(p.mass == doctest::Approx(2 * ball + rod.mass).epsilon(mass_tolerance));
  CHECK(length(p.center) < mass_tolerance);
  const double ball_own = 0.4 * ball * r * r;
  // About x (the bar's axis): the balls spin on their centers; the rod's
  // moment about its own axis is its Iyy.
  CHECK(p.inertia.col[0].x == doctest::Approx(2 * ball_own + rod.inertia.col[1].y).epsilon(mass_tolerance));
  // About y and z: each ball half away; the rod across its axis.
  const double across = 2 * (ball_own + ball * half * half) + rod.inertia.col[0].x;
  CHECK(p.inertia.col[1].y == doctest::Approx(across).epsilon(mass_tolerance));
  CHECK(p.inertia.col[2].z == doctest::Approx(across).epsilon(mass_tolerance));
}

TEST_CASE("a child's relative density moves the center of mass to the weighted mean") {
  compound<double>::builder b;
  b.add(box<double>{{0.5, 0.5, 0.5}}, tf{{-0.5, 0, 0}, upright});
  b.add(box<double>{{0.5, 0.5, 0.5}}, tf{{0.5, 0, 0}, upright}, 3.0);  // three times as dense
  const mass_properties<double> p = mass_properties_of(b.build(), 1000.0);
  CHECK(p.mass == doctest::Approx(4000.0).epsilon(mass_tolerance));
  // (1000·(−0.5) + 3000·0.5) / 4000 = 0.25.
  CHECK(p.center.x == doctest::Approx(0.25).epsilon(mass_tolerance));
  // About z through the center: each cube's own m/6 plus m·d², d = 0.75 and 0.25.
  CHECK(p.inertia.col[2].z ==
        doctest::Approx(1000.0 / 6 + 1000.0 * 0.75 * 0.75 + 3000.0 / 6 + 3000.0 * 0.25 * 0.25).epsilon(mass_tolerance));
}

TEST_CASE("the children's tree finds the same children as testing every child's box") {
  lcg32 rng{29};
  compound<double>::builder b;
  for (int i = 0; i < 200; ++i) {
    const vec3<double> at{rng.uniform(-10.0, 10.0), rng.uniform(-10.0, 10.0), rng.uniform(-10.0, 10.0)};
    const quat<double> turn = normalize(quat<double>{rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0),
                                                     rng.uniform(-1.0, 1.0), rng.uniform(0.1, 1.0)});
    if (i % 4 == 0) b.add(sphere<double>{rng.uniform(0.1, 1.0)}, tf{at, turn});
    else if (i % 4 == 1) b.add(box<double>{{rng.uniform(0.1, 1.0), 0.2, 0.5}}, tf{at, turn});
    else if (i % 4 == 2) b.add(capsule<double>{0.2, rng.uniform(0.0, 1.0)}, tf{at, turn});
    else b.add(convex_hull<double>::from_points(std::vector<vec3<double>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}), tf{at, turn});
  }
  const compound<double> c = b.build();
  REQUIRE(c.child_count() == 200);
  for (int q = 0; q < 300; ++q) {
    const vec3<double> at{rng.uniform(-12.0, 12.0), rng.uniform(-12.0, 12.0), rng.uniform(-12.0, 12.0)};
    const aabb<double> query = aabb<double>::from_center_half_extents(at, vec3<double>::splat(rng.uniform(0.1, 4.0)));
    std::set<std::size_t> found, expected;
    c.for_each_overlapping(query, [&](std::size_t i) { CHECK(found.insert(i).second); });
    for (std::size_t i = 0; i < c.child_count(); ++i)
      if (overlaps(c.child_at(i).bounds, query)) expected.insert(i);
    CHECK(found == expected);
  }
}

TEST_CASE("a ray meets a compound's nearest child and reports its index") {
  const compound<double> c = two_cubes();
  const tf pose{{10, 2, 0}, quat<double>::from_axis_angle({0, 1, 0}, std::numbers::pi / 2)};
  // Turned a quarter about y, the cubes lie along z: the ray along −z
  // from z = 5 meets the cube at z = +0.5 (child 0, at local x = −0.5,
  // which the turn takes to z = +0.5) on its face z = 1.
  const narrowphase::ray_hit<double> h = narrowphase::ray_cast(ray<double>{{10.2, 2.1, 5}, {0, 0, -10}}, c, pose);
  REQUIRE(h.hit);
  CHECK(h.fraction == doctest::Approx(0.4).epsilon(1e-12));
  CHECK(h.feature == 0);
  CHECK(length(h.normal - vec3<double>{0, 0, 1}) < 1e-12);
  CHECK_FALSE(narrowphase::ray_cast(ray<double>{{10.2, 2.1, 5}, {0, 0, -10}}, c, pose, 0.35).hit);
  CHECK_FALSE(narrowphase::ray_cast(ray<double>{{11.2, 2.1, 5}, {0, 0, -10}}, c, pose).hit);  // beside both
  // Against testing every child, for rays in every direction.
  lcg32 rng{7};
  for (int k = 0; k < 500; ++k) {
    const ray<double> r{{rng.uniform(6.0, 14.0), rng.uniform(-2.0, 6.0), rng.uniform(-4.0, 4.0)},
                        {rng.uniform(-8.0, 8.0), rng.uniform(-8.0, 8.0), rng.uniform(-8.0, 8.0)}};
    const narrowphase::ray_hit<double> got = narrowphase::ray_cast(r, c, pose);
    narrowphase::ray_hit<double> best;
    for (std::size_t i = 0; i < c.child_count(); ++i) {
      const narrowphase::ray_hit<double> h2 = c.visit(
          i, [&](const auto& s, const tf& local) { return narrowphase::ray_cast(r, s, pose * local); });
      if (h2.hit && (!best.hit || h2.fraction < best.fraction)) best = h2;
    }
    REQUIRE(got.hit == best.hit);
    if (got.hit) CHECK(got.fraction == best.fraction);
  }
}

TEST_CASE("two cubes on a floor touch it as the hull around them does: one manifold of four corners") {
  using dispatch = narrowphase::dispatcher<shape_list<sphere, box, capsule, convex_hull, compound>, double>;
  const compound<double> c = two_cubes();
  const std::vector<vec3<double>> corners = {{-1, -0.5, -0.5}, {1, -0.5, -0.5}, {1, 0.5, -0.5}, {-1, 0.5, -0.5},
                                             {-1, -0.5, 0.5},  {1, -0.5, 0.5},  {1, 0.5, 0.5},  {-1, 0.5, 0.5}};
  const convex_hull<double> hull = convex_hull<double>::from_points(corners);
  const box<double> floor{{10, 1, 10}};
  const tf floor_pose{{0.3, -1, -0.2}, upright};
  // Slightly tilted about x and sunk 1 cm: four corners at two depths.
  const tf pose{{0.1, 0.49, 0}, quat<double>::from_axis_angle({1, 0, 0}, 0.002)};
  std::array<contact_manifold<double>, 4> from_compound, from_hull;
  const std::size_t n = dispatch::collide(dispatch::ref(c), pose, dispatch::ref(floor), floor_pose, 0.0, from_compound);
  const std::size_t m = dispatch::collide(dispatch::ref(hull), pose, dispatch::ref(floor), floor_pose, 0.0, from_hull);
  REQUIRE(n == 1);
  REQUIRE(m == 1);
  REQUIRE(from_compound[0].count == 4);
  REQUIRE(from_hull[0].count == 4);
  CHECK(length(from_compound[0].normal - from_hull[0].normal) < 1e-12);
  for (const contact_point<double>& p : from_compound[0].contacts()) {
    const auto same = [&](const contact_point<double>& q) {
      return length(q.position - p.position) < 1e-9 && std::abs(q.depth - p.depth) < 1e-9;
    };
    CHECK(std::any_of(from_hull[0].points.begin(), from_hull[0].points.end(), same));
  }
  // The ids are four different ones, and the same after a 0.1 mm slide.
  std::set<std::uint32_t> ids;
  for (const contact_point<double>& p : from_compound[0].contacts()) ids.insert(p.feature);
  CHECK(ids.size() == 4);
  std::array<contact_manifold<double>, 4> moved;
  const tf slid{pose.position + vec3<double>{1e-4, 0, 0}, pose.rotation};
  REQUIRE(dispatch::collide(dispatch::ref(c), slid, dispatch::ref(floor), floor_pose, 0.0, moved) == 1);
  std::set<std::uint32_t> moved_ids;
  for (const contact_point<double>& p : moved[0].contacts()) moved_ids.insert(p.feature);
  CHECK(moved_ids == ids);
  // The floor as A: the same points, the normal reversed.
  std::array<contact_manifold<double>, 4> flipped;
  REQUIRE(dispatch::collide(dispatch::ref(floor), floor_pose, dispatch::ref(c), pose, 0.0, flipped) == 1);
  CHECK(length(flipped[0].normal + from_compound[0].normal) < 1e-12);
}

TEST_CASE("two compounds touch child against child") {
  using dispatch = narrowphase::dispatcher<shape_list<sphere, box, compound>, double>;
  // A dumbbell of two balls lying across two cubes: each ball on a cube.
  const compound<double> cubes = two_cubes();
  compound<double>::builder b;
  b.add(sphere<double>{0.25}, tf{{-0.5, 0, 0}, upright});
  b.add(sphere<double>{0.25}, tf{{0.5, 0, 0}, upright});
  const compound<double> balls = b.build();
  const tf on_top{{0, 0.74, 0}, upright};  // 1 cm into the cubes' top
  std::array<contact_manifold<double>, 4> out;
  const std::size_t n = dispatch::collide(dispatch::ref(cubes), tf::identity(), dispatch::ref(balls), on_top, 0.0, out);
  REQUIRE(n == 1);  // both balls on the one top face: one normal
  CHECK(length(out[0].normal - vec3<double>{0, 1, 0}) < 1e-12);
  REQUIRE(out[0].count == 2);
  for (const contact_point<double>& p : out[0].contacts()) {
    CHECK(p.depth == doctest::Approx(0.01).epsilon(1e-9));
    CHECK(std::abs(std::abs(p.position.x) - 0.5) < 1e-12);
  }
  CHECK(out[0].points[0].feature != out[0].points[1].feature);
  // Lifted 2 cm clear: nothing, but within a 3 cm margin, both.
  const tf above{{0, 0.77, 0}, upright};
  CHECK(dispatch::collide(dispatch::ref(cubes), tf::identity(), dispatch::ref(balls), above, 0.0, out) == 0);
  CHECK(dispatch::collide(dispatch::ref(cubes), tf::identity(), dispatch::ref(balls), above, 0.03, out) == 1);
}

TEST_CASE("bad compounds are refused") {
  compound<double>::builder b;
  CHECK(error_code_of([&] { (void)b.build(); }) == error_code::degenerate_shape);
  CHECK(error_code_of([&] { b.add(box<double>{{0.5, -1, 0.5}}); }) == error_code::degenerate_shape);
  CHECK(error_code_of([&] { b.add(sphere<double>{1}, tf{{std::nan(""), 0, 0}, upright}); }) == error_code::non_finite);
  CHECK(error_code_of([&] { b.add(sphere<double>{1}, tf{{}, quat<double>{0, 0, 0, 2}}); }) ==
        error_code::not_normalized);
  CHECK(error_code_of([&] { b.add(sphere<double>{1}, tf::identity(), 0.0); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { b.add(sphere<double>{1}, tf::identity(), std::nan("")); }) ==
        error_code::invalid_parameter);
  // The refused children were not added: the builder still has none.
  CHECK(error_code_of([&] { (void)b.build(); }) == error_code::degenerate_shape);
  b.add(sphere<double>{1});
  compound<double> one = b.build();
  CHECK(one.child_count() == 1);
  const compound<double> taken = std::move(one);
  CHECK(taken.child_count() == 1);
  CHECK(error_code_of([&] { one.validate(); }) == error_code::degenerate_shape);  // NOLINT: moved from on purpose
  CHECK(error_code_of([&] { (void)mass_properties_of(taken, -1.0); }) == error_code::non_positive_mass);
}

}  // namespace shapes_compound_tests
