// Collision filtering: category and mask bits, groups, the world's pair
// rule, changing a filter on a live world, and queries that see only what
// their filter sees. Each case against what the filter's rule says and the
// motion a body has when nothing touches it.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "../error_code_of.hpp"
#include "impulse/world.hpp"
#include "scenes.hpp"

namespace world_filter_tests {

using namespace impulse;
using impulse::test::error_code_of;
using impulse::test::step_dt;

namespace {

constexpr float g = 9.81f;

world_settings<float> weightless() {
  world_settings<float> s;
  s.gravity = {0, 0, 0};
  return s;
}

/// A unit cube at `at` with the given filter, user data and velocity.
template <class World>
body_id add_filtered_cube(World& w, vec3<float> at, const collision_filter& filter, std::uint64_t user_data = 0,
                          vec3<float> velocity = {}) {
  body_def<float> d;
  d.pose.position = at;
  d.filter = filter;
  d.user_data = user_data;
  d.linear_velocity = velocity;
  return w.create_body(d, box<float>::make({0.5f, 0.5f, 0.5f}));
}

/// Whether the last step's begin events hold the pair a–b.
template <class World>
bool began(const World& w, body_id a, body_id b) {
  return std::ranges::any_of(w.contact_begin_events(), [&](const contact_event& e) {
    return (e.a == a && e.b == b) || (e.a == b && e.b == a);
  });
}
template <class World>
bool ended(const World& w, body_id a, body_id b) {
  return std::ranges::any_of(w.contact_end_events(), [&](const contact_event& e) {
    return (e.a == a && e.b == b) || (e.a == b && e.b == a);
  });
}

/// The speed of a body falling freely from rest for `steps` steps: every
/// step adds g·dt, whatever the integrator does with the position.
float free_fall_speed(int steps) { return g * float(steps) * step_dt<float>; }

/// A pair rule that keeps apart two bodies whose user data are both odd,
/// counting the pairs it was asked about.
struct odd_pairs_apart {
  const world<impulse::test::awake_config>* w = nullptr;
  int asked = 0;
  static bool test(body_id a, body_id b, void* context) {
    auto& self = *static_cast<odd_pairs_apart*>(context);
    ++self.asked;
    return !(self.w->user_data(a) % 2 == 1 && self.w->user_data(b) % 2 == 1);
  }
};

}  // namespace

TEST_CASE("the filter rule: groups decide alone, otherwise each mask must hold the other's category") {
  const collision_filter any{};
  CHECK(should_collide(any, any));
  CHECK(should_collide(collision_filter{2, 1, 0}, collision_filter{1, 2, 0}));
  CHECK_FALSE(should_collide(collision_filter{2, 1, 0}, collision_filter{1, 4, 0}));  // 1 does not collide with 2
  CHECK_FALSE(should_collide(collision_filter{2, 0, 0}, any));                        // a mask of nothing
  CHECK(should_collide(collision_filter{2, 0, 5}, collision_filter{4, 0, 5}));        // a positive group overrides
  CHECK_FALSE(should_collide(collision_filter{1, all_categories, -5}, collision_filter{1, all_categories, -5}));
  CHECK(should_collide(collision_filter{1, all_categories, -5}, collision_filter{1, all_categories, -6}));
  // The rule is symmetric.
  for (const collision_filter& a : {any, collision_filter{2, 1, 0}, collision_filter{1, 6, -3}, collision_filter{4, 5, 3}})
    for (const collision_filter& b : {any, collision_filter{1, 2, 0}, collision_filter{2, 3, -3}, collision_filter{1, 0, 3}})
      CHECK(should_collide(a, b) == should_collide(b, a));
}

TEST_CASE("a box whose mask leaves out the ground's category falls through it freely, beside one that lands") {
  impulse::test::with_sleeping_off_and_on([](auto& w) {
    const body_id ground = impulse::test::add_ground(w);
    const body_id ghost = add_filtered_cube(w, {-2, 2, 0}, collision_filter{2, all_categories & ~1u, 0});
    const body_id lander = add_filtered_cube(w, {2, 2, 0}, collision_filter{2, all_categories, 0});
    const int steps = 120;
    for (int i = 0; i < steps; ++i) {
      w.step(step_dt<float>);
      CHECK_FALSE(began(w, ghost, ground));
    }
    // Nothing touched the ghost: its speed is the free fall's (2 s at
    // 60 Hz: 19.62 m/s, to float rounding of 120 sums), and it is below
    // the 2 m slab.
    CHECK(std::abs(w.body(ghost).linear_velocity().y + free_fall_speed(steps)) < 1e-4f * free_fall_speed(steps));
    CHECK(w.body(ghost).position.y < -2.5f);
    // The other rests on the top face, y = 0.
    CHECK(std::abs(w.body(lander).position.y - 0.5f) < 0.01f);
    CHECK(length(w.body(lander).linear_velocity()) < 0.01f);
    CHECK(w.touching_pair_count() == 1);
  });
}

TEST_CASE("two boxes of one negative group pass through each other; a positive group collides against the masks") {
  // Weightless, head-on at 2 m/s each from 4 m apart: 2 s later, with
  // nothing between them, each is where the other started.
  for (const int group : {-1, 1}) {
    CAPTURE(group);
    world<impulse::test::awake_config> w(weightless());
    // Masks of nothing: only a positive group makes them collide.
    const collision_filter f{1, 0, group};
    const body_id a = add_filtered_cube(w, {-2, 0, 0}, f, 0, {2, 0, 0});
    const body_id b = add_filtered_cube(w, {2, 0, 0}, f, 0, {-2, 0, 0});
    bool touched = false;
    for (int i = 0; i < 120; ++i) {
      w.step(step_dt<float>);
      touched = touched || began(w, a, b);
    }
    // Momentum is conserved either way.
    CHECK(length(w.linear_momentum()) < 1e-5f);
    if (group < 0) {
      CHECK_FALSE(touched);
      CHECK(std::abs(w.body(a).position.x - 2) < 1e-4f);
      CHECK(std::abs(w.body(b).position.x + 2) < 1e-4f);
      CHECK(std::abs(w.body(a).linear_velocity().x - 2) < 1e-6f);
    } else {
      CHECK(touched);
      // They met and did not pass: still side by side, a box's width apart.
      CHECK(w.body(a).position.x < w.body(b).position.x);
      CHECK(w.body(b).position.x - w.body(a).position.x > 1 - 0.01f);
    }
  }
  // Different groups fall back on the bits, which let these two collide.
  world<impulse::test::awake_config> w(weightless());
  const body_id a = add_filtered_cube(w, {-2, 0, 0}, collision_filter{1, all_categories, -1}, 0, {2, 0, 0});
  const body_id b = add_filtered_cube(w, {2, 0, 0}, collision_filter{1, all_categories, -2}, 0, {-2, 0, 0});
  impulse::test::run(w, 120);
  CHECK(w.body(b).position.x - w.body(a).position.x > 1 - 0.01f);
}

TEST_CASE("a new filter on a resting box wakes it and ends its contact at once, and a snapshot keeps the filter") {
  world<impulse::test::sleeping_config> w;
  const body_id ground = impulse::test::add_ground(w);
  const body_id box_id = add_filtered_cube(w, {0, 0.5f, 0}, collision_filter{});
  impulse::test::run(w, 180);
  REQUIRE_FALSE(w.is_awake(box_id));  // settled and asleep
  const world_snapshot<impulse::test::sleeping_config> resting = w.snapshot();

  const collision_filter ghost{2, all_categories & ~1u, 0};
  w.set_filter(box_id, ghost);
  CHECK(w.filter(box_id) == ghost);
  CHECK(w.is_awake(box_id));
  CHECK(ended(w, box_id, ground));  // reported before the next step
  CHECK(w.touching_pair_count() == 0);
  const float y0 = w.body(box_id).position.y;
  impulse::test::run(w, 30);
  CHECK(w.body(box_id).position.y < y0 - 0.5f * g * 0.25f * 0.25f * 0.9f);  // falling (½·g·t² at t = 0.5 s, less 10 %)
  CHECK(std::abs(w.body(box_id).linear_velocity().y + free_fall_speed(30)) < 1e-4f);

  // The snapshot from before has the old filter and the contact.
  w.restore(resting);
  CHECK(w.filter(box_id) == collision_filter{});
  impulse::test::run(w, 30);
  CHECK(std::abs(w.body(box_id).position.y - 0.5f) < 0.01f);

  // A filter for a body that is not there is refused, the world unchanged.
  const body_id gone = add_filtered_cube(w, {5, 5, 5}, collision_filter{});
  w.destroy_body(gone);
  CHECK(error_code_of([&] { w.set_filter(gone, ghost); }) == error_code::out_of_range);
  CHECK(error_code_of([&] { (void)w.filter(gone); }) == error_code::out_of_range);
  // Nor may a callback change one.
  bool refused = false;
  w.for_each_contact([&](body_id, body_id, auto) {
    refused = error_code_of([&] { w.set_filter(box_id, ghost); }) == error_code::invalid_parameter;
  });
  CHECK(refused);
  CHECK(w.filter(box_id) == collision_filter{});
}

TEST_CASE("two boxes made overlapping in one negative group push apart once one leaves the group") {
  world<impulse::test::awake_config> w(weightless());
  // Overlapping by 0.4 m along x.
  const body_id a = add_filtered_cube(w, {0, 0, 0}, collision_filter{1, all_categories, -7});
  const body_id b = add_filtered_cube(w, {0.6f, 0, 0}, collision_filter{1, all_categories, -7});
  impulse::test::run(w, 30);
  CHECK(w.touching_pair_count() == 0);
  CHECK(w.body(b).position.x - w.body(a).position.x == doctest::Approx(0.6f));
  w.set_filter(b, collision_filter{});
  w.step(step_dt<float>);
  CHECK(began(w, a, b));
  impulse::test::run(w, 120);
  // Pushed apart until the faces touch, and no farther than the solver's
  // push-out speed carries them; momentum stays zero.
  CHECK(w.body(b).position.x - w.body(a).position.x > 1 - 0.01f);
  CHECK(length(w.linear_momentum()) < 1e-5f);
}

TEST_CASE("the world's pair rule keeps apart the pairs it refuses, and refilter asks it again") {
  world<impulse::test::awake_config> w;
  odd_pairs_apart rule{&w};
  // The ground's user data is 1: odd.
  body_def<float> gd;
  gd.type = body_type::static_body;
  gd.pose.position = {0, -1, 0};
  gd.user_data = 1;
  const body_id ground = w.create_body(gd, box<float>::make({100, 1, 100}));
  const body_id odd = add_filtered_cube(w, {-2, 0.5f, 0}, collision_filter{}, 3);
  const body_id even = add_filtered_cube(w, {2, 0.5f, 0}, collision_filter{}, 4);
  impulse::test::run(w, 10);
  CHECK(w.touching_pair_count() == 2);

  // The rule ends the odd box's contact at once; the even one stays.
  w.set_pair_filter({&odd_pairs_apart::test, &rule});
  CHECK(rule.asked >= 2);
  CHECK(ended(w, odd, ground));
  CHECK_FALSE(ended(w, even, ground));
  CHECK(w.pair_rule().context == &rule);
  impulse::test::run(w, 60);
  CHECK(w.body(odd).position.y < -2.5f);
  CHECK(std::abs(w.body(odd).linear_velocity().y + free_fall_speed(60)) < 1e-4f * free_fall_speed(60));
  CHECK(std::abs(w.body(even).position.y - 0.5f) < 0.01f);

  // The even box's number turns odd: the rule would now refuse it, which
  // the world learns from refilter.
  w.set_filter(even, w.filter(even));  // the same filter: nothing changes
  CHECK(w.touching_pair_count() == 1);
  rule.asked = 0;
  w.destroy_body(odd);
  body_def<float> d;
  d.pose.position = {-2, 0.5f, 0};
  d.user_data = 5;
  const body_id other_odd = w.create_body(d, box<float>::make({0.5f, 0.5f, 0.5f}));
  w.step(step_dt<float>);
  CHECK(rule.asked >= 1);  // asked about the new pair
  CHECK(w.touching_pair_count() == 1);
  // Without the rule, the new odd box touches the ground again.
  w.set_pair_filter({});
  CHECK(!w.pair_rule().test);
  impulse::test::run(w, 2);
  CHECK(w.touching_pair_count() == 2);
  CHECK(std::abs(w.body(other_odd).position.y - 0.5f) < 0.02f);
}

TEST_CASE("refilter asks the pair rule again about a body's pairs after its answer changed") {
  struct ghosts {
    std::array<bool, 8> ghost{};
    const world<impulse::test::awake_config>* w = nullptr;
    static bool test(body_id a, body_id b, void* context) {
      const auto& self = *static_cast<const ghosts*>(context);
      return !self.ghost[self.w->user_data(a)] && !self.ghost[self.w->user_data(b)];
    }
  };
  world<impulse::test::awake_config> w;
  ghosts rule;
  rule.w = &w;
  w.set_pair_filter({&ghosts::test, &rule});
  const body_id ground = impulse::test::add_ground(w);
  const body_id cube = add_filtered_cube(w, {0, 0.5f, 0}, collision_filter{}, 2);
  impulse::test::run(w, 10);
  REQUIRE(w.touching_pair_count() == 1);
  rule.ghost[2] = true;
  impulse::test::run(w, 2);
  CHECK(w.touching_pair_count() == 1);  // the world has not been told
  w.refilter(cube);
  CHECK(ended(w, cube, ground));
  CHECK(w.touching_pair_count() == 0);
  impulse::test::run(w, 30);
  CHECK(w.body(cube).position.y < 0);
}

TEST_CASE("ray casts and overlaps see only the bodies their filter sees") {
  world<impulse::test::awake_config> w(weightless());
  body_def<float> d;
  d.pose.position = {2, 0, 0};
  d.filter = {2, all_categories, 7};
  const body_id near = w.create_body(d, sphere<float>::make(0.5f));
  d.pose.position = {5, 0, 0};
  d.filter = {4, all_categories, 0};
  const body_id far = w.create_body(d, sphere<float>::make(0.5f));
  const ray<float> r{{0, 0, 0}, {10, 0, 0}};
  // The near sphere's surface at x = 1.5 (fraction 0.15), the far one's at 4.5 (0.45).
  const auto hit = w.ray_cast(r);
  REQUIRE(hit);
  CHECK(hit->body == near);
  CHECK(hit->fraction == doctest::Approx(0.15f).epsilon(1e-5));
  const auto past = w.ray_cast(r, 1, query_filter{4, 0});
  REQUIRE(past);
  CHECK(past->body == far);
  CHECK(past->fraction == doctest::Approx(0.45f).epsilon(1e-5));
  const auto skipping = w.ray_cast(r, 1, query_filter{all_categories, 7});
  REQUIRE(skipping);
  CHECK(skipping->body == far);
  CHECK_FALSE(w.ray_cast(r, 1, query_filter{8, 0}));

  std::vector<body_id> found;
  const aabb<float> both{{0, -1, -1}, {6, 1, 1}};
  w.overlap(both, [&](body_id id) { found.push_back(id); });
  CHECK(found.size() == 2);
  found.clear();
  w.overlap(both, [&](body_id id) { found.push_back(id); }, query_filter{2, 0});
  CHECK(found == std::vector<body_id>{near});
}

}  // namespace world_filter_tests
