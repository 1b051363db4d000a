// Compound bodies in a world: two cubes rest as the hull around them does,
// their contact points keep their ids (warm starting) and carry the weight,
// an L stands or topples as its center of mass says, compounds land on
// meshes, fields and each other at the heights their children say, fast
// compounds and bullets do not tunnel, queries and sensors see children
// and not the gaps between them, and a world refuses a child it cannot test.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <set>
#include <vector>

#include "../error_code_of.hpp"
#include "../shapes/two_cubes.hpp"
#include "impulse/world.hpp"
#include "scenes.hpp"

namespace world_compound_tests {

using namespace impulse;
using impulse::test::error_code_of;

namespace {

using tf = transform<float>;
const quat<float> upright = quat<float>::identity();

/// Two unit cubes side by side along x.
compound<float> two_cubes() { return test::two_cubes<float>(); }

/// The hull around them: the 2 × 1 × 1 box's corners.
convex_hull<float> hull_of_two_cubes() {
  std::vector<vec3<float>> corners;
  for (float x : {-1.0f, 1.0f})
    for (float y : {-0.5f, 0.5f})
      for (float z : {-0.5f, 0.5f}) corners.push_back({x, y, z});
  return convex_hull<float>::from_points(corners);
}

/// Two balls of radius 0.25 half a metre either side of a thin bar.
compound<float> dumbbell() {
  compound<float>::builder b;
  b.add(sphere<float>{0.25f}, tf{{-0.5f, 0, 0}, upright});
  b.add(sphere<float>{0.25f}, tf{{0.5f, 0, 0}, upright});
  b.add(capsule<float>{0.05f, 0.5f}, tf{{}, quat<float>::from_axis_angle({0, 0, 1}, std::numbers::pi_v<float> / 2)});
  return b.build();
}

/// A body at rest on its contacts sits within the solver's slop of them.
constexpr float rest_tolerance = 0.01f;

template <class World, class Shape>
body_id drop(World& w, const Shape& shape, vec3<float> at, quat<float> turn = upright) {
  body_def<float> d;
  d.pose = {at, turn};
  d.material.friction = 0.6f;
  return w.create_body(d, shape);
}

/// The angle between a body's y axis and the world's, rad.
float tilt(const quat<float>& q) { return std::acos(std::min(1.0f, rotate(q, vec3<float>{0, 1, 0}).y)); }

}  // namespace

TEST_CASE("two cubes as one compound rest as the hull around them does with sleeping off and on") {
  impulse::test::with_sleeping_off_and_on([](auto& w) {
    impulse::test::add_ground(w);
    const quat<float> turn = quat<float>::from_axis_angle(normalize(vec3<float>{1, 0, 2}), 0.05f);
    const body_id c = drop(w, two_cubes(), {0, 0.6f, 0}, turn);
    const body_id h = drop(w, hull_of_two_cubes(), {0, 0.6f, 5}, turn);
    impulse::test::run(w, 300);
    const rigid_body<float>& bc = w.body(c);
    const rigid_body<float>& bh = w.body(h);
    CHECK(bc.position.y == doctest::Approx(0.5f).epsilon(rest_tolerance));
    CHECK(length(bc.position - (bh.position - vec3<float>{0, 0, 5})) < 1e-3f);
    CHECK(tilt(bc.orientation) < 1e-3f);
    CHECK(tilt(bh.orientation) < 1e-3f);
    CHECK(length(bc.linear_velocity()) < 1e-3f);
    // One manifold of four corners under each, as for any flat face.
    int manifolds = 0;
    w.for_each_contact([&](body_id a, body_id b, std::span<const contact_manifold<float>> m) {
      if (a != c && b != c) return;
      manifolds += int(m.size());
      for (const contact_manifold<float>& one : m) CHECK(one.count == 4);
    });
    CHECK(manifolds == 1);
  });
}

TEST_CASE("a resting compound's contact points keep their ids and carry its weight every step") {
  // Sleeping off: the solve runs every step, and warm starting carries each
  // point's impulse by its id. Once settled, the normal impulses of a step
  // sum to m·g·dt (the body does not accelerate) and the ids never change.
  world<impulse::test::awake_config> w;
  impulse::test::add_ground(w);
  const body_id c = drop(w, two_cubes(), {0, 0.5f, 0});
  struct record {
    float sum = 0;
    std::set<std::uint32_t> ids;
  } step;
  post_solve_hook<float> hook;
  hook.context = &step;
  hook.call = [](body_id, body_id, const contact_manifold<float>& m, const manifold_impulse<float>& impulse,
                 void* context) {
    auto& r = *static_cast<record*>(context);
    for (int p = 0; p < m.count; ++p) {
      r.sum += impulse.normal[std::size_t(p)];
      r.ids.insert(m.points[std::size_t(p)].feature);
    }
  };
  w.set_post_solve(hook);
  impulse::test::run(w, 60);
  const float weight = w.body(c).mass * 9.81f * impulse::test::step_dt<float>;
  std::set<std::uint32_t> first;
  for (int i = 0; i < 300; ++i) {
    step = record{};
    w.step(impulse::test::step_dt<float>);
    CHECK(step.sum == doctest::Approx(weight).epsilon(0.005));
    REQUIRE(step.ids.size() == 4);
    if (i == 0) first = step.ids;
    CHECK(step.ids == first);
  }
}

TEST_CASE("an L stands while its center of mass is over its foot and topples once it is past") {
  // A post 0.2 m square and 1 m tall on the ground, an arm 0.1 m thick and
  // 0.2 m deep on its top reaching out along +x by r past the post's face
  // x = 0.1. Volumes 0.04 at x = 0 and 0.02·r at x = 0.1 + r/2: the center
  // of mass is over the foot (x < 0.1) while 0.02·r·(0.1 + r/2) <
  // 0.1·(0.04 + 0.02·r), that is r² < 0.4, r < 0.632. So 0.4 stands and
  // 1.2 topples.
  for (const float reach : {0.4f, 1.2f}) {
    impulse::test::with_sleeping_off_and_on([&](auto& w) {
      impulse::test::add_ground(w);
      compound<float>::builder b;
      b.add(box<float>{{0.1f, 0.5f, 0.1f}}, tf{{0, 0.5f, 0}, upright});
      b.add(box<float>{{reach / 2, 0.05f, 0.1f}}, tf{{0.1f + reach / 2, 0.95f, 0}, upright});
      const body_id l = drop(w, b.build(), {0, 0.001f, 0});
      impulse::test::run(w, 180);
      // Toppled, it comes to rest on its foot's edge (0.1, 0) and the arm's
      // lower tip (0.1 + r, 0.9): turned by atan(0.9 / r).
      if (reach < 0.632f) CHECK(tilt(w.body(l).orientation) < 0.01f);
      else CHECK(tilt(w.body(l).orientation) == doctest::Approx(std::atan2(0.9f, reach)).epsilon(0.01));
    });
  }
}

TEST_CASE("a dumbbell lands on a plane a triangle mesh and a heightfield with its balls on the surface") {
  // Its balls, radius 0.25, rest on the surface y = 0: their centers, and
  // the body's, at 0.25; the bar 0.05 thick never touches.
  for (int ground = 0; ground < 3; ++ground) {
    impulse::test::with_sleeping_off_and_on([&](auto& w) {
      body_def<float> d;
      d.type = body_type::static_body;
      if (ground == 0) {
        w.create_body(d, plane<float>::make({0, 1, 0}, 0));
      } else if (ground == 1) {
        const vec3<float> corners[] = {{-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}};
        const std::uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
        w.create_body(d, triangle_mesh<float>::make(corners, triangles));
      } else {
        const std::vector<float> flat(21 * 21, 0.0f);
        d.pose.position = {-5, 0, -5};
        w.create_body(d, heightfield<float>::make(21, 21, 0.5f, 0.5f, flat, {}));
      }
      const body_id bell = drop(w, dumbbell(), {0.3f, 1, 0.2f}, quat<float>::from_axis_angle({0, 0, 1}, 0.3f));
      impulse::test::run(w, 240);
      CHECK(w.body(bell).position.y == doctest::Approx(0.25f).epsilon(0.02));
      // Its bar level: both balls down (it may roll about the bar).
      CHECK(std::abs(rotate(w.body(bell).orientation, vec3<float>{1, 0, 0}).y) < 0.01f);
      CHECK(impulse::test::all_finite(w));
    });
  }
}

TEST_CASE("a compound rests on a compound child on child") {
  // The dumbbell across two cubes lying along x: each ball on a cube's top
  // (y = 1), the dumbbell's center at 1.25. The cubes are static: on a
  // dynamic box a ball at rest starts to roll after a few seconds with
  // sleeping off, one body or several (a solver matter, not a compound's);
  // dynamic compounds on compounds are the crosswise stack's.
  impulse::test::with_sleeping_off_and_on([](auto& w) {
    body_def<float> fixed;
    fixed.type = body_type::static_body;
    fixed.pose.position = {0, 0.5f, 0};
    w.create_body(fixed, two_cubes());
    const body_id bell = drop(w, dumbbell(), {0, 1.3f, 0});
    impulse::test::run(w, 240);
    CHECK(w.body(bell).position.y == doctest::Approx(1.25f).epsilon(0.02));
    CHECK(std::abs(w.body(bell).position.x) < 0.01f);
    CHECK(length(w.body(bell).linear_velocity()) < 0.01f);
  });
}

TEST_CASE("a stack of ten compounds laid crosswise stands for 10 s with sleeping off") {
  // Each layer the two-cube bar, turned a quarter from the one below, so
  // that it rests on the middle cube-face of it: an unstable stack if the
  // compound's four corners of contact flickered or lost their impulses.
  world<impulse::test::awake_config> w;
  impulse::test::add_ground(w);
  std::vector<body_id> bars;
  const quat<float> quarter = quat<float>::from_axis_angle({0, 1, 0}, std::numbers::pi_v<float> / 2);
  for (int k = 0; k < 10; ++k)
    bars.push_back(drop(w, two_cubes(), {0, 0.5f + float(k), 0}, k % 2 == 0 ? upright : quarter));
  const std::vector<vec3<float>> start = impulse::test::positions(w, bars);
  impulse::test::run(w, impulse::test::long_run(600));
  const vec3<float> moved = impulse::test::largest_displacement(w, bars, start);
  // As still as the same stack of 2 × 1 × 1 boxes (3e-7 m across, 8e-5 m
  // down as it settles): the compound's contacts are the box's.
  CHECK(std::max(moved.x, moved.z) < 1e-3f);
  CHECK(moved.y < 1e-3f);
  for (const body_id id : bars) CHECK(tilt(w.body(id).orientation) < 1e-3f);
}

TEST_CASE("a fast compound with a thin plate does not pass a thin wall and a bullet does not pass a thin child") {
  world_settings<float> weightless;
  weightless.gravity = {};
  {
    // A plate 2 cm thick and a ball, flying edge-on at 150 m/s (2.5 m a
    // step) at a wall 1 cm thick whose near face is x = 5.
    world<impulse::test::ccd_config> w(weightless);
    body_def<float> wall;
    wall.type = body_type::static_body;
    wall.pose.position = {5.005f, 0, 0};
    w.create_body(wall, box<float>::make({0.005f, 50, 50}));
    compound<float>::builder b;
    b.add(box<float>{{0.01f, 0.5f, 0.5f}}, tf{{0.3f, 0, 0}, upright});
    b.add(sphere<float>{0.1f}, tf{{-0.3f, 0, 0}, upright});
    body_def<float> d;
    d.linear_velocity = {150, 0, 0};
    const body_id plate = w.create_body(d, b.build());
    for (int i = 0; i < 30; ++i) {
      w.step(impulse::test::step_dt<float>);
      // The plate's far face, 0.31 m ahead of the compound's origin, never
      // past the wall's near face.
      CHECK(w.shape_pose(plate).position.x + 0.31f < 5.0f + 1e-3f);
    }
  }
  {
    // A static compound: a thick block and a plate 1 cm thick in front of
    // it, with a gap; a bullet ball at 300 m/s meets the plate.
    world<impulse::test::ccd_config> w(weightless);
    compound<float>::builder b;
    b.add(box<float>{{0.005f, 2, 2}}, tf{{5.005f, 0, 0}, upright});
    b.add(box<float>{{1, 2, 2}}, tf{{8, 0, 0}, upright});
    body_def<float> fixed;
    fixed.type = body_type::static_body;
    w.create_body(fixed, b.build());
    body_def<float> d;
    d.linear_velocity = {300, 0, 0};
    d.bullet = true;
    const body_id ball = w.create_body(d, sphere<float>::make(0.05f));
    for (int i = 0; i < 30; ++i) {
      w.step(impulse::test::step_dt<float>);
      CHECK(w.body(ball).position.x < 5.0f - 0.05f + 1e-3f);
    }
  }
}

TEST_CASE("queries and sensors see a compound's children and not the gap between them") {
  // Two boxes 1 m apart: x in [-2, -1] and [1, 2], y in [0, 1].
  compound<float>::builder b;
  b.add(box<float>{{0.5f, 0.5f, 0.5f}}, tf{{-1.5f, 0.5f, 0}, upright});
  b.add(box<float>{{0.5f, 0.5f, 0.5f}}, tf{{1.5f, 0.5f, 0}, upright});
  const compound<float> pair = b.build();
  impulse::test::with_sleeping_off_and_on([&](auto& w) {
    body_def<float> fixed;
    fixed.type = body_type::static_body;
    const body_id gate = w.create_body(fixed, pair);
    // Rays down at x = 1.5 (onto a box top, y = 1) and x = 0 (the gap).
    const auto top = w.ray_cast(ray<float>{{1.5f, 3, 0}, {0, -4, 0}});
    REQUIRE(top);
    CHECK(top->body == gate);
    CHECK(top->fraction == doctest::Approx(0.5f).epsilon(1e-5));
    CHECK_FALSE(w.ray_cast(ray<float>{{0, 3, 0}, {0, -4, 0}}));
    // A ball of radius 0.25 cast down onto the box top stops 0.25 above it
    // (within the cast's tolerance, 0.5 mm); through the gap it meets nothing.
    const auto cast = w.shape_cast(sphere<float>{0.25f}, tf{{-1.5f, 3, 0}, upright}, {0, -4, 0});
    REQUIRE(cast);
    CHECK(cast->fraction * 4 == doctest::Approx(1.75f).epsilon(0.001));
    CHECK(length(cast->normal - vec3<float>{0, 1, 0}) < 1e-3f);
    CHECK_FALSE(w.shape_cast(sphere<float>{0.25f}, tf{{0, 3, 0}, upright}, {0, -4, 0}));
    int seen = 0;
    w.shape_overlap(sphere<float>{0.4f}, tf{{0, 0.5f, 0}, upright}, [&](body_id) { ++seen; });
    CHECK(seen == 0);
    w.shape_overlap(sphere<float>{1.1f}, tf{{0, 0.5f, 0}, upright}, [&](body_id) { ++seen; });
    CHECK(seen == 1);
    // As a sensor: a ball falling through the gap is never inside; one
    // falling onto a box is, once it reaches it.
    body_def<float> s = fixed;
    s.sensor = true;
    s.pose.position = {0, 0, 10};
    const body_id sensor = w.create_body(s, pair);
    body_def<float> d;
    d.pose.position = {0, 3, 10};
    const body_id through = w.create_body(d, sphere<float>::make(0.2f));
    d.pose.position = {1.5f, 3, 10};
    const body_id onto = w.create_body(d, sphere<float>::make(0.2f));
    bool through_seen = false, onto_seen = false;
    for (int i = 0; i < 60; ++i) {
      w.step(impulse::test::step_dt<float>);
      for (const sensor_event& e : w.sensor_begin_events()) {
        CHECK(e.sensor == sensor);
        through_seen = through_seen || e.visitor == through;
        onto_seen = onto_seen || e.visitor == onto;
      }
    }
    CHECK_FALSE(through_seen);
    CHECK(onto_seen);
  });
}

TEST_CASE("a spinning compound keeps its angular momentum and energy without gravity") {
  // An uneven compound spun about an axis that is not principal: it
  // tumbles, and its angular momentum, in world axes, stays put.
  world_settings<float> weightless;
  weightless.gravity = {};
  world<impulse::test::awake_double_config> w([] {
    world_settings<double> s;
    s.gravity = {};
    return s;
  }());
  compound<double>::builder b;
  b.add(box<double>{{0.5, 0.1, 0.2}}, transform<double>::identity());
  b.add(sphere<double>{0.3}, transform<double>{{0.4, 0.3, 0.1}, quat<double>::identity()});
  b.add(capsule<double>{0.1, 0.4}, transform<double>{{-0.3, 0, 0.3}, quat<double>::from_axis_angle({1, 0, 0}, 1.0)});
  body_def<double> d;
  d.angular_velocity = {1, 2, 0.5};
  const body_id id = w.create_body(d, b.build());
  const vec3<double> before = w.angular_momentum();
  const double energy = w.body(id).kinetic_energy();
  for (int i = 0; i < 600; ++i) w.step(1.0 / 60);
  CHECK(length(w.angular_momentum() - before) < 1e-6 * length(before));
  CHECK(w.body(id).kinetic_energy() == doctest::Approx(energy).epsilon(1e-4));
}

TEST_CASE("a world refuses a compound with a child it does not compile and is left unchanged") {
  struct spheres_and_boxes : impulse::test::awake_config {
    using shapes = shape_list<sphere, box, compound>;
  };
  world<spheres_and_boxes> w;
  compound<float>::builder b;
  b.add(box<float>{{0.5f, 0.5f, 0.5f}});
  b.add(capsule<float>{0.2f, 0.5f}, tf{{0, 1, 0}, upright});
  const compound<float> with_capsule = b.build();
  CHECK(error_code_of([&] { (void)w.create_body(body_def<float>{}, with_capsule); }) == error_code::invalid_parameter);
  CHECK(w.body_count() == 0);
  b.add(box<float>{{0.5f, 0.5f, 0.5f}});
  b.add(sphere<float>{0.5f}, tf{{0, 1, 0}, upright});
  const body_id ok = w.create_body(body_def<float>{}, b.build());
  CHECK(w.body_count() == 1);
  const float start = w.body(ok).position.y;
  w.step(1.0f / 60);
  CHECK(w.body(ok).position.y < start);  // it falls
  // A moved-from compound is refused too.
  compound<float> taken = two_cubes();
  const compound<float> kept = std::move(taken);
  CHECK(kept.child_count() == 2);
  CHECK(error_code_of([&] { (void)w.create_body(body_def<float>{}, taken); }) == error_code::degenerate_shape);
  CHECK(w.body_count() == 1);
}

}  // namespace world_compound_tests
