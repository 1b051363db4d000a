// Ids name the world that made them (core/slot_map.hpp): an id of one world
// is refused by another even at the same slot and generation, while a copy
// of a world, or one restored from its snapshot, answers to its ids. And a
// body's mass properties may be given instead of the shape's
// (body_def::inertia).
#include <doctest/doctest.h>

#include <optional>
#include <vector>

#include "../error_code_of.hpp"
#include "../dynamics/motion_test.hpp"
#include "scenes.hpp"

namespace world_world_ids_tests {

using namespace impulse;
using impulse::test::error_code_of;

namespace {

using awake_world = world<impulse::test::awake_config>;

}  // namespace

TEST_CASE("an id of one world is refused by another, though both have a body at its slot and generation") {
  awake_world first, second;
  const body_id a = impulse::test::add_cube(first, {0, 0.5f, 0});
  const body_id b = impulse::test::add_cube(second, {3, 0.5f, 0});
  REQUIRE(a.index == b.index);
  REQUIRE(a.generation == b.generation);
  CHECK_FALSE(a == b);
  CHECK(first.contains(a));
  CHECK_FALSE(first.contains(b));
  CHECK_FALSE(second.contains(a));
  CHECK(error_code_of([&] { (void)second.body(a); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { second.apply_force(a, {1, 0, 0}); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { second.destroy_body(a); }) == error_code::out_of_range);
  CHECK(second.body(b).force == vec3<float>{});  // nothing reached b
  CHECK(second.body_count() == 1);
  // Nor can a joint or a spring of one world name another's body.
  const body_id c = impulse::test::add_cube(second, {5, 0.5f, 0});
  CHECK(error_code_of([&] { second.create_joint(joint_def<float>::ball(a, c, {4, 0.5f, 0})); }) ==
        error_code::out_of_range);
  CHECK(error_code_of([&] { second.create_spring(body_spring<float>::between(c, {}, a, {}, 10, 1, 1)); }) ==
        error_code::out_of_range);
  CHECK(second.joint_count() == 0);
  CHECK(second.spring_count() == 0);
  // A joint id and a spring id carry their world as well.
  const spring_id s = first.create_spring(body_spring<float>::to_anchor(a, {}, {0, 3, 0}, 10, 1, 1));
  const spring_id t = second.create_spring(body_spring<float>::to_anchor(c, {}, {5, 3, 0}, 10, 1, 1));
  REQUIRE(s.index == t.index);
  CHECK_FALSE(second.contains(s));
  CHECK(error_code_of([&] { second.destroy_spring(s); }) == error_code::out_of_range);
  CHECK(second.spring_count() == 1);
}

TEST_CASE("every id a world reports is the id it gave: body_ids, events, contacts, ray hits and overlaps") {
  awake_world w;
  const body_id ground = impulse::test::add_ground(w);
  const body_id cube = impulse::test::add_cube(w, {0, 0.5f, 0});
  w.step(impulse::test::step_dt<float>);
  CHECK(w.body_ids()[0] == ground);
  CHECK(w.body_ids()[1] == cube);
  REQUIRE(w.contact_begin_events().size() == 1);
  const contact_event e = w.contact_begin_events()[0];
  CHECK(((e.a == ground && e.b == cube) || (e.a == cube && e.b == ground)));
  int pairs = 0;
  w.for_each_contact([&](body_id a, body_id b, auto) {
    CHECK(w.contains(a));
    CHECK(w.contains(b));
    ++pairs;
  });
  CHECK(pairs == 1);
  const std::optional<world_ray_hit<float>> hit = w.ray_cast(ray<float>{{0, 5, 0}, {0, -10, 0}});
  REQUIRE(hit.has_value());
  CHECK(hit->body == cube);
  std::vector<body_id> found;
  w.overlap(aabb<float>{{-0.1f, 0.4f, -0.1f}, {0.1f, 0.6f, 0.1f}}, [&](body_id id) { found.push_back(id); });
  CHECK(found == std::vector<body_id>{cube});
}

TEST_CASE("a copy of a world, and a world restored from another's snapshot, answer to the ids they copied") {
  awake_world original;
  impulse::test::add_ground(original);
  const body_id cube = impulse::test::add_cube(original, {0, 2, 0});
  awake_world copy = original;  // a prediction run: the same bodies under the same ids
  copy.step(impulse::test::step_dt<float>);
  CHECK(copy.body(cube).position.y < 2.0f);
  CHECK(original.body(cube).position.y == 2.0f);
  awake_world other;
  const body_id own = impulse::test::add_cube(other, {7, 7, 7});
  other.restore(original.snapshot());  // other is now a copy of original
  CHECK(other.contains(cube));
  CHECK_FALSE(other.contains(own));
  CHECK(other.body(cube).position.y == 2.0f);
}

TEST_CASE("a body's inertia may be given: a box spun about x with I = 2 instead of its own keeps L = I·omega") {
  world_settings<double> settings;
  settings.gravity = {};
  world<impulse::test::awake_double_config> w(settings);
  body_def<double> d;
  d.mass = 3;
  d.inertia = mat3<double>::diagonal({2, 4, 5});  // a box of mass 3 and half-extent 0.5 has 0.5 about each axis
  d.angular_velocity = {1.5, 0, 0};
  const body_id id = w.create_body(d, box<double>::make({0.5, 0.5, 0.5}));
  CHECK(w.body(id).mass == 3.0);
  CHECK(w.body(id).inertia(0, 0) == 2.0);
  CHECK(w.body(id).angular_momentum.x == doctest::Approx(3.0).epsilon(1e-15));
  CHECK(w.kinetic_energy() == doctest::Approx(0.5 * 2 * 1.5 * 1.5).epsilon(1e-15));
  // Refused, with the world unchanged: a tensor that is not symmetric, not
  // positive definite, not finite, or one no solid has (4 + 1 < 6).
  const auto refused = [&](const mat3<double>& inertia) {
    body_def<double> bad = d;
    bad.inertia = inertia;
    return error_code_of([&] { w.create_body(bad, box<double>::make({0.5, 0.5, 0.5})); });
  };
  mat3<double> skew = mat3<double>::diagonal({2, 2, 2});
  skew(0, 1) = 0.5;
  CHECK(refused(skew) != error_code::none);
  CHECK(refused(mat3<double>::diagonal({2, -1, 2})) != error_code::none);
  CHECK(refused(mat3<double>::diagonal({2, std::numeric_limits<double>::infinity(), 2})) == error_code::non_finite);
  CHECK(refused(mat3<double>::diagonal({4, 1, 6})) != error_code::none);
  CHECK(w.body_count() == 1);
}

// ---- a world without collision ----

namespace {

/// Double, no collision (and so no sleeping): a world the tests compile once.
using motion_config = impulse::test::motion_config<double, impulse::default_config::integrator>;

}  // namespace

TEST_CASE("without collision two bodies pass through each other, and ray casts and overlaps still find them") {
  world_settings<double> settings;
  settings.gravity = {};
  world<motion_config> w(settings);
  static_assert(!world<motion_config>::collision && !world<motion_config>::sleeping && !world<motion_config>::ccd);
  body_def<double> d;
  d.pose.position = {-2, 0, 0};
  d.linear_velocity = {1, 0, 0};
  const body_id a = w.create_body(d, sphere<double>{0.5});
  d.pose.position = {2, 0, 0};
  d.linear_velocity = {-1, 0, 0};
  const body_id b = w.create_body(d, sphere<double>{0.5});
  for (int i = 0; i < 240; ++i) w.step(1.0 / 60);  // 4 s: they meet at 2 s and go on
  CHECK(w.body(a).position.x == doctest::Approx(2.0).epsilon(1e-12));
  CHECK(w.body(b).position.x == doctest::Approx(-2.0).epsilon(1e-12));
  CHECK(w.contact_begin_events().empty());
  CHECK(w.touching_pair_count() == 0);
  CHECK(w.last_step_counts().active_bodies == 2);
  // Queries test every body, there being no broad phase.
  const std::optional<world_ray_hit<double>> hit = w.ray_cast(ray<double>{{-10, 0, 0}, {20, 0, 0}});
  REQUIRE(hit.has_value());
  CHECK(hit->body == b);
  CHECK(hit->point.x == doctest::Approx(-2.5).epsilon(1e-12));
  int found = 0;
  w.overlap(aabb<double>{{1.9, -0.1, -0.1}, {2.1, 0.1, 0.1}}, [&](body_id id) { found += id == a ? 1 : 100; });
  CHECK(found == 1);
}

TEST_CASE("without collision a body that overflows is held, named, and the others keep their step") {
  world<motion_config> w;
  body_def<double> d;
  const body_id calm = w.create_body(d, sphere<double>{0.5});
  d.pose.position = {5, 0, 0};
  const body_id wild = w.create_body(d, sphere<double>{0.5});
  w.apply_force(wild, {1e30, 0, 0});  // a kilogram-ish ball past max_linear_speed in one step
  CHECK(error_code_of([&] { w.step(1.0 / 60); }) == error_code::non_finite);
  REQUIRE(w.held_bodies().size() == 1);
  CHECK(w.held_bodies()[0] == wild);
  CHECK(w.body(wild).position == vec3<double>{5, 0, 0});
  CHECK(w.body(wild).linear_momentum == vec3<double>{});
  CHECK(w.body(calm).position.y == doctest::Approx(-9.81 / 3600).epsilon(1e-12));  // one symplectic Euler step
  w.step(1.0 / 60);
  CHECK(w.held_bodies().empty());
}

}  // namespace world_world_ids_tests
