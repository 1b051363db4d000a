// impulse::world's interface: bodies and their ids, bad input, events,
// queries, the fixed-step accumulator, sleeping, snapshots, determinism,
// drawing.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "../error_code_of.hpp"
#include "scenes.hpp"

namespace world_world_tests {

using namespace impulse;
using impulse::test::error_code_of;

namespace {

using awake_world = world<impulse::test::awake_config>;
using sleeping_world = world<impulse::test::sleeping_config>;

body_id add_ball(awake_world& w, vec3<float> at, float radius = 0.5f) {
  body_def<float> d;
  d.pose.position = at;
  d.mass = 1;
  return w.create_body(d, sphere<float>::make(radius));
}

struct draw_recorder {
  int lines = 0, points = 0, arrows = 0;
  void line(const vec3<float>&, const vec3<float>&, const debug_color&) { ++lines; }
  void point(const vec3<float>&, const debug_color&) { ++points; }
  void arrow(const vec3<float>&, const vec3<float>&, const debug_color&) { ++arrows; }
};

}  // namespace

TEST_CASE("bodies keep their ids while others come and go and a destroyed id is refused") {
  awake_world w;
  const body_id a = add_ball(w, {0, 1, 0}), b = add_ball(w, {3, 1, 0}), c = add_ball(w, {6, 1, 0});
  w.destroy_body(b);
  CHECK(w.body_count() == 2);
  CHECK(w.contains(a));
  CHECK_FALSE(w.contains(b));
  CHECK(w.body(c).position.x == 6.0f);
  const std::uint64_t before = impulse::test::transform_hash(w);
  CHECK(error_code_of([&] { w.destroy_body(b); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { (void)w.body(b); }) == error_code::out_of_range);
  CHECK(w.body_count() == 2);
  CHECK(impulse::test::transform_hash(w) == before);
  const body_id d = add_ball(w, {9, 1, 0});  // takes b's slot, with a new generation
  CHECK(d.index == b.index);
  CHECK_FALSE(d == b);
  CHECK_FALSE(w.contains(b));
}

TEST_CASE("bad input is refused with its error and leaves the world unchanged") {
  awake_world w;
  impulse::test::add_ground(w);
  const body_id ball = add_ball(w, {0, 2, 0});
  impulse::test::run(w, 10);
  const std::uint64_t hash = impulse::test::transform_hash(w);
  const std::size_t count = w.body_count();
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();

  body_def<float> d;
  d.pose.position = {nan, 0, 0};
  CHECK(error_code_of([&] { w.create_body(d, sphere<float>{0.5f}); }) == error_code::non_finite);
  d = {};
  d.pose.rotation = {0, 0, 0, 2};
  CHECK(error_code_of([&] { w.create_body(d, sphere<float>{0.5f}); }) == error_code::not_normalized);
  d = {};
  CHECK(error_code_of([&] { w.create_body(d, box<float>{{0.5f, 0, 0.5f}}); }) == error_code::degenerate_shape);
  CHECK(error_code_of([&] { w.create_body(d, sphere<float>{-1}); }) == error_code::degenerate_shape);
  d.mass = inf;  // a dynamic body of infinite mass: it should be static
  CHECK(error_code_of([&] { w.create_body(d, sphere<float>{0.5f}); }) == error_code::non_finite);
  d.mass = -1;
  CHECK(error_code_of([&] { w.create_body(d, sphere<float>{0.5f}); }) == error_code::non_finite);
  d = {};
  d.material.restitution = 1.5f;
  CHECK(error_code_of([&] { w.create_body(d, sphere<float>{0.5f}); }) == error_code::invalid_parameter);
  d = {};
  d.material.density = 0;
  CHECK(error_code_of([&] { w.create_body(d, sphere<float>{0.5f}); }) == error_code::non_positive_mass);
  d = {};
  CHECK(error_code_of([&] { w.create_body(d, plane<float>::make({0, 1, 0}, 0)); }) == error_code::invalid_parameter);
  d.type = body_type::static_body;
  d.linear_velocity = {1, 0, 0};
  CHECK(error_code_of([&] { w.create_body(d, sphere<float>{0.5f}); }) == error_code::invalid_parameter);
  d = {};
  d.linear_velocity = {0, inf, 0};
  CHECK(error_code_of([&] { w.create_body(d, sphere<float>{0.5f}); }) == error_code::non_finite);

  CHECK(error_code_of([&] { w.set_velocity(ball, {nan, 0, 0}, {}); }) == error_code::non_finite);
  CHECK(error_code_of([&] { w.apply_force(ball, {0, inf, 0}); }) == error_code::non_finite);
  CHECK(error_code_of([&] { w.set_pose(ball, {{0, 0, 0}, {0, 0, 0, 0}}); }) == error_code::not_normalized);
  CHECK(error_code_of([&] { w.step(0); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { w.step(nan); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { w.set_gravity({0, nan, 0}); }) == error_code::non_finite);
  world_settings<float> bad;
  bad.solver.velocity_iterations = 0;
  CHECK(error_code_of([&] { w.set_settings(bad); }) == error_code::invalid_parameter);
  bad = {};
  bad.solver.rest_depth = -1e-5f;
  CHECK(error_code_of([&] { w.set_settings(bad); }) == error_code::invalid_parameter);
  bad = {};
  bad.contact_reuse_distance = nan;
  CHECK(error_code_of([&] { w.set_settings(bad); }) == error_code::invalid_parameter);
  bad = {};
  bad.contact_reuse_angle = -0.1f;
  CHECK(error_code_of([&] { w.set_settings(bad); }) == error_code::invalid_parameter);
  CHECK(w.settings().contact_reuse_angle == world_settings<float>{}.contact_reuse_angle);

  CHECK(w.body_count() == count);
  CHECK(impulse::test::transform_hash(w) == hash);
  CHECK(w.body(ball).linear_velocity() == w.body(ball).linear_velocity());  // finite, unchanged
}

TEST_CASE("a body whose state overflows in a step is named and left where it was; the others step") {
  world_settings<float> settings;
  settings.gravity = {0, 0, 0};
  awake_world w(settings);
  body_def<float> d;
  d.mass = 1e-6f;
  const body_id tiny = w.create_body(d, sphere<float>::make(0.5f));
  const body_id other = add_ball(w, {5, 0, 0});
  w.set_velocity(other, {1, 0, 0}, {});
  w.apply_force(tiny, {3e38f, 0, 0});  // finite, but F·dt/m (5e42) is not, in float
  try {
    w.step(impulse::test::step_dt<float>);
    FAIL("the overflow was not reported");
  } catch (const invalid_argument& e) {
    CHECK(e.code() == error_code::non_finite);
    CHECK(e.object() == tiny.index);
  }
  CHECK(w.body(tiny).position == vec3<float>{});
  CHECK(w.body(tiny).linear_velocity() == vec3<float>{});
  CHECK(w.body(other).position.x == doctest::Approx(5.0f + impulse::test::step_dt<float>));
}

TEST_CASE("a ball landing on the ground begins one contact, and lifting it away ends it") {
  awake_world w;
  const body_id ground = impulse::test::add_ground(w);
  const body_id ball = add_ball(w, {0, 1, 0});
  int begun = 0, ended = 0;
  for (int i = 0; i < 60; ++i) {
    w.step(impulse::test::step_dt<float>);
    for (const contact_event& e : w.contact_begin_events()) {
      ++begun;
      CHECK(((e.a == ground && e.b == ball) || (e.a == ball && e.b == ground)));
    }
    ended += int(w.contact_end_events().size());
  }
  CHECK(begun == 1);
  CHECK(ended == 0);
  CHECK(w.touching_pair_count() == 1);
  w.set_pose(ball, {{0, 5, 0}, quat<float>::identity()});
  w.step(impulse::test::step_dt<float>);
  CHECK(w.contact_end_events().size() == 1);
  CHECK(w.touching_pair_count() == 0);
  // Destroying a body ends its contacts at once.
  impulse::test::run(w, 120);
  REQUIRE(w.touching_pair_count() == 1);
  w.destroy_body(ball);
  CHECK(w.contact_end_events().size() == 1);
}

TEST_CASE("a pair that moved within the reuse limits keeps its manifold carried with the bodies: the depths of a fresh test") {
  // A small box resting on a cube, so that every contact point is one of
  // its corners; then placed anew, moved and turned a little. One world
  // reuses the manifold, the other (limits 0) tests the pair again.
  struct seen {
    vec3<float> normal;
    std::vector<contact_point<float>> points;
  };
  const auto manifold_after = [](float reuse_distance, vec3<float> shift, float angle) {
    world_settings<float> settings;
    settings.contact_reuse_distance = reuse_distance;
    awake_world w(settings);
    impulse::test::add_ground(w);
    const body_id base = impulse::test::add_cube(w, {0, 0.5f, 0});
    body_def<float> d;
    d.pose.position = {0.1f, 1.3f, -0.05f};
    d.mass = 1;
    const body_id top = w.create_body(d, box<float>::make({0.3f, 0.3f, 0.3f}));
    w.step(impulse::test::step_dt<float>);
    const quat<float> turn = quat<float>::from_axis_angle(normalize(vec3<float>{0.6f, 0.3f, 0.8f}), angle);
    w.set_pose(top, {vec3<float>{0.1f, 1.3f, -0.05f} + shift, turn});
    w.step(impulse::test::step_dt<float>);
    seen out{};
    w.for_each_contact([&](body_id a, body_id b, std::span<const contact_manifold<float>> m) {
      if (a == base && b == top) out = {m[0].normal, {m[0].points.begin(), m[0].points.begin() + m[0].count}};
    });
    return out;
  };
  const float near = world_settings<float>{}.contact_reuse_distance;
  // Within the limits (0.5 mm, 0.4°): the corners' depths as a fresh test
  // finds them, and each point within half its corner's slide of it (a
  // corner 0.52 m from the center slides 3.6 mm at 0.4°, the shift
  // 0.5 mm).
  const seen reused = manifold_after(near, {0.0004f, -0.0002f, 0.0002f}, 0.007f);
  const seen fresh = manifold_after(0, {0.0004f, -0.0002f, 0.0002f}, 0.007f);
  REQUIRE(reused.points.size() == 4);
  REQUIRE(fresh.points.size() == 4);
  CHECK(length(reused.normal - fresh.normal) < 1e-6f);
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(reused.points[i].feature == fresh.points[i].feature);
    CHECK(std::abs(reused.points[i].depth - fresh.points[i].depth) < 1e-6f);
    CHECK(length(reused.points[i].position - fresh.points[i].position) < 0.0022f);
  }
  // Past the distance limit the pair is tested again: the fresh manifold.
  const seen moved = manifold_after(near, {0.002f, 0, 0}, 0);
  const seen tested = manifold_after(0, {0.002f, 0, 0}, 0);
  REQUIRE(moved.points.size() == tested.points.size());
  for (std::size_t i = 0; i < moved.points.size(); ++i) {
    CHECK(moved.points[i].position == tested.points[i].position);
    CHECK(moved.points[i].depth == tested.points[i].depth);
  }
}

TEST_CASE("a ray cast finds the nearest body and an overlap query the bodies in a box") {
  awake_world w;
  const body_id ground = impulse::test::add_ground(w);
  const body_id cube = impulse::test::add_cube(w, {0, 0.5f, 0});
  const body_id ball = add_ball(w, {4, 0.5f, 0});
  const auto hit = w.ray_cast({{0, 10, 0}, {0, -20, 0}});
  REQUIRE(hit.has_value());
  CHECK(hit->body == cube);
  CHECK(hit->fraction == doctest::Approx(9.0f / 20.0f));
  CHECK(hit->normal.y == doctest::Approx(1.0f));
  const auto floor = w.ray_cast({{2, 10, 0}, {0, -20, 0}});
  REQUIRE(floor.has_value());
  CHECK(floor->body == ground);
  CHECK(floor->point.y == doctest::Approx(0.0f).epsilon(1e-5));
  CHECK_FALSE(w.ray_cast({{0, 10, 0}, {0, 20, 0}}).has_value());

  std::vector<body_id> found;
  w.overlap({{3, -0.5f, -1}, {5, 2, 1}}, [&](body_id id) { found.push_back(id); });
  CHECK(found.size() == 2);  // the ball and the ground
  CHECK(std::count(found.begin(), found.end(), ball) == 1);
  CHECK(std::count(found.begin(), found.end(), cube) == 0);
}

TEST_CASE("advance takes fixed steps, returns the fraction left over and caps the steps per call") {
  awake_world w;
  add_ball(w, {0, 100, 0});
  const float h = w.settings().fixed_dt;
  float alpha = w.advance(2.5f * h);
  CHECK(w.step_count() == 2);
  CHECK(alpha == doctest::Approx(0.5f).epsilon(1e-4));
  alpha = w.advance(0.5f * h);  // the half step left over makes a whole one
  CHECK(w.step_count() == 3);
  CHECK(alpha == doctest::Approx(0.0f).epsilon(1e-4));
  w.advance(100 * h);  // a long stall: 8 steps, not 100
  CHECK(w.step_count() == 3 + std::uint64_t(w.settings().max_steps_per_advance));
}

TEST_CASE("interpolated poses run from the last step's start to its end") {
  awake_world w;
  const body_id ball = add_ball(w, {0, 10, 0});
  w.set_velocity(ball, {6, 0, 0}, {});
  w.step(impulse::test::step_dt<float>);
  const float start = w.interpolated_pose(ball, 0).position.x, end = w.interpolated_pose(ball, 1).position.x;
  CHECK(start == doctest::Approx(0.0f));
  CHECK(end == doctest::Approx(0.1f));
  CHECK(w.interpolated_pose(ball, 0.5f).position.x == doctest::Approx(0.05f));
}

TEST_CASE("a resting box falls asleep and wakes on a force, an impulse and a body landing on it") {
  sleeping_world w;
  impulse::test::add_ground(w);
  const body_id cube = impulse::test::add_cube(w, {0, 0.5f, 0});
  impulse::test::run(w, 60);
  CHECK_FALSE(w.is_awake(cube));
  w.apply_force(cube, {0, 1, 0});
  CHECK(w.is_awake(cube));
  impulse::test::run(w, 60);
  REQUIRE_FALSE(w.is_awake(cube));
  w.apply_impulse_at(cube, {0.1f, 0, 0}, w.body(cube).position);
  CHECK(w.is_awake(cube));
  impulse::test::run(w, 120);
  REQUIRE_FALSE(w.is_awake(cube));
  body_def<float> d;
  d.pose.position = {0, 3, 0};
  d.mass = 1;
  w.create_body(d, sphere<float>::make(0.25f));
  bool woke = false;
  for (int i = 0; i < 60 && !woke; ++i) {
    w.step(impulse::test::step_dt<float>);
    woke = w.is_awake(cube);
  }
  CHECK(woke);
}

TEST_CASE("a snapshot restores the world to the bit, and the same state steps to the same bits") {
  // The determinism check: 600 steps of `pile` (150 in debug builds,
  // test::long_run), twice from the start and once from a snapshot taken
  // halfway, hash alike.
  const int half = impulse::test::long_run(300);
  sleeping_world first, second;
  impulse::test::add_ground(first);
  impulse::test::add_ground(second);
  impulse::test::add_pile(first);
  impulse::test::add_pile(second);
  impulse::test::run(first, half);
  const world_snapshot<impulse::test::sleeping_config> halfway = first.snapshot();
  impulse::test::run(first, half);
  impulse::test::run(second, 2 * half);
  const std::uint64_t hash = impulse::test::transform_hash(first);
  CHECK(impulse::test::transform_hash(second) == hash);
  first.restore(halfway);
  CHECK(first.step_count() == std::uint64_t(half));
  impulse::test::run(first, half);
  CHECK(impulse::test::transform_hash(first) == hash);
}

TEST_CASE("debug drawing shows each body's box, each contact point and normal, and each velocity") {
  awake_world w;
  impulse::test::add_ground(w);
  impulse::test::add_cube(w, {0, 0.5f, 0});
  impulse::test::run(w, 30);
  draw_recorder r;
  debug_draw_flags flags;
  flags.aabbs = flags.velocities = true;
  flags.shapes = flags.joints = false;  // (tests/world/test_debug_draw.cpp)
  w.draw(r, flags);
  CHECK(r.lines == 2 * 12);  // two boxes
  CHECK(r.points == 4);      // a face on the ground: four points
  CHECK(r.arrows == 4 + 1);  // their normals, and the cube's velocity
}

TEST_CASE("every shape rests where it should: a hull, a capsule and a sphere on a mesh floor and on a plane") {
  // A unit-cube hull whose points are all off-center (its center of mass
  // is at (2, 2, 2) in its own frame), a capsule lying down and a ball,
  // dropped on a two-triangle mesh and on a plane: each comes to rest with
  // its lowest point at the floor, within the slop.
  for (const bool mesh : {true, false}) {
    awake_world w;
    body_def<float> floor;
    floor.type = body_type::static_body;
    if (mesh) {
      const vec3<float> corners[] = {{-20, 0, -20}, {20, 0, -20}, {20, 0, 20}, {-20, 0, 20}};
      const std::uint32_t triangles[] = {0, 2, 1, 0, 3, 2};
      w.create_body(floor, triangle_mesh<float>::make(corners, triangles));
    } else {
      w.create_body(floor, plane<float>::make({0, 1, 0}, 0));
    }
    std::vector<vec3<float>> points;
    for (int i = 0; i < 8; ++i) points.push_back({1.5f + float(i & 1), 1.5f + float((i >> 1) & 1), 1.5f + float(i >> 2)});
    body_def<float> d;
    d.mass = 1;
    d.pose.position = {-2, -1, -2};  // the hull's points then span y = 0.5 .. 1.5
    const body_id hull = w.create_body(d, convex_hull<float>::from_points(points));
    CHECK(w.body(hull).position.y == doctest::Approx(1.0f));  // the center of mass, not the origin
    d.pose = {{3, 1, 0}, quat<float>::from_axis_angle({0, 0, 1}, 1.5707963f)};
    const body_id capsule_body = w.create_body(d, capsule<float>::make(0.25f, 0.5f));
    d.pose = {{-3, 1, 0}, quat<float>::identity()};
    const body_id ball = w.create_body(d, sphere<float>::make(0.5f));
    impulse::test::run(w, 180);
    const float slop = w.settings().solver.linear_slop;
    CHECK(w.body(hull).position.y == doctest::Approx(0.5f).epsilon(2 * slop));
    CHECK(w.shape_pose(hull).position.y == doctest::Approx(-1.5f).epsilon(4 * slop));
    CHECK(w.body(capsule_body).position.y == doctest::Approx(0.25f).epsilon(4 * slop));
    CHECK(w.body(ball).position.y == doctest::Approx(0.5f).epsilon(2 * slop));
    CHECK(w.kinetic_energy() < 1e-6f);
  }
}

TEST_CASE("a kinematic body moves at its velocity and is not pushed by what it hits") {
  world_settings<float> settings;
  settings.gravity = {0, 0, 0};
  awake_world w(settings);
  body_def<float> d;
  d.type = body_type::kinematic;
  d.linear_velocity = {1, 0, 0};
  const body_id pusher = w.create_body(d, box<float>::make({0.5f, 0.5f, 0.5f}));
  const body_id ball = add_ball(w, {1.5f, 0, 0});
  impulse::test::run(w, 60);
  CHECK(w.body(pusher).position.x == doctest::Approx(1.0f).epsilon(1e-5));
  CHECK(w.body(pusher).linear_velocity().x == 1.0f);
  // Pushed ahead of it: its face reached x = 1.5, the ball's center 0.5 beyond.
  CHECK(w.body(ball).position.x >= 2.0f - w.settings().solver.linear_slop);
  CHECK(w.body(ball).linear_velocity().x == doctest::Approx(1.0f).epsilon(1e-3));
}

TEST_CASE("a step's profile times each stage once: none negative, together within the whole step") {
  awake_world w;
  impulse::test::add_ground(w);
  impulse::test::add_pyramid(w, 10);
  CHECK(w.last_step_profile().total == 0);  // no step yet
  for (int step = 0; step < 30; ++step) {
    w.step(1.0f / 60);
    const step_profile& p = w.last_step_profile();
    const double stages[] = {p.broad, p.narrow, p.prepare, p.solve, p.integrate, p.continuous, p.sensors, p.sleep};
    double sum = 0;
    for (const double ms : stages) {
      CHECK(ms >= 0);
      sum += ms;
    }
    // The stages are disjoint parts of the step, read off the same clock:
    // their sum is at most the whole, up to the rounding of the sums.
    CHECK(sum <= p.total + 1e-9);
    CHECK(p.total > 0);
    CHECK(p.solve > 0);  // the pyramid stands on its contacts
  }
}

TEST_CASE("the profile counts a stack of three and four lone cubes: pairs, touching contacts, colors and islands") {
  const auto check = [](auto& w, bool sleeping) {
    impulse::test::add_ground(w);
    for (int k = 0; k < 3; ++k) impulse::test::add_cube(w, {0, 0.5f + float(k), 0});
    for (int k = 0; k < 4; ++k) impulse::test::add_cube(w, {3 + 3 * float(k), 0.5f, 0});
    impulse::test::run(w, 10);  // 1/6 s: all still awake
    const world_profile p = w.profile();
    CHECK(p.bodies == 8);
    // The stack's two pairs and its base on the ground, and each lone cube's.
    CHECK(p.pairs == 7);
    CHECK(p.contacts == 7);
    CHECK(p.touching == 7);
    CHECK(p.counts.solved_manifolds == 7);
    CHECK(p.counts.active_bodies == 7);
    // The stack's contacts chain through its two lower cubes: two colors.
    CHECK(p.counts.colors == 2);
    // The stack and the four cubes, each an island of its own.
    CHECK(p.counts.islands == (sleeping ? 5u : 0u));
    CHECK(p.joints == 0);
    CHECK(p.sensors == 0);
    CHECK(p.times.total == w.last_step_profile().total);
  };
  awake_world awake;
  check(awake, false);
  world<impulse::test::sleeping_config> sleeping;
  check(sleeping, true);
}

}  // namespace world_world_tests
