// Sleeping islands (world/detail/islands.hpp): a step works on the awake
// set alone, so a world asleep costs it nothing; an island sleeps and
// wakes whole; bodies made asleep join the islands they touch. What the
// step visits is read from world::last_step_counts.
#include <doctest/doctest.h>

#include <cstdint>
#include <vector>

#include "scenes.hpp"

namespace world_sleeping_tests {

using namespace impulse;

namespace {

using sleeping_world = world<impulse::test::sleeping_config>;

/// Steps until no body is awake, at most `limit` steps; returns the steps taken.
template <class World>
int settle(World& w, int limit) {
  int steps = 0;
  while (w.awake_body_count() > 0 && steps < limit) w.step(impulse::test::step_dt<float>), ++steps;
  return steps;
}

/// A column of `height` unit cubes standing on the ground at (x, z).
template <class World>
std::vector<body_id> add_column(World& w, float x, float z, int height) {
  std::vector<body_id> ids;
  for (int k = 0; k < height; ++k) ids.push_back(impulse::test::add_cube(w, {x, 0.5f + float(k), z}));
  return ids;
}

template <class World>
int awake_among(const World& w, const std::vector<body_id>& ids) {
  int n = 0;
  for (const body_id id : ids) n += w.is_awake(id) ? 1 : 0;
  return n;
}

}  // namespace

TEST_CASE("a wholly asleep pile steps without visiting a body, a contact or a pair, and keeps every bit") {
  sleeping_world w;
  impulse::test::add_ground(w);
  impulse::test::add_pile(w);
  REQUIRE(settle(w, 1200) < 1200);
  const std::uint64_t before = impulse::test::transform_hash(w);
  for (int i = 0; i < 300; ++i) {
    w.step(impulse::test::step_dt<float>);
    REQUIRE(w.last_step_counts() == step_counts{});
  }
  CHECK(impulse::test::transform_hash(w) == before);
  CHECK(w.contact_begin_events().empty());
  CHECK(w.contact_end_events().empty());
}

TEST_CASE("a step works on the awake island alone: a poked column wakes whole, the other 99 sleep") {
  sleeping_world w;
  impulse::test::add_ground(w);
  std::vector<std::vector<body_id>> columns;
  for (int i = 0; i < 10; ++i)
    for (int k = 0; k < 10; ++k) columns.push_back(add_column(w, 3.0f * float(i), 3.0f * float(k), 3));
  REQUIRE(settle(w, 600) < 600);
  const std::vector<body_id>& poked = columns[37];
  w.apply_impulse_at(poked[0], {0.2f, 0, 0}, w.body(poked[0]).position);
  // The whole island wakes at once, before any step: its boxes touch.
  CHECK(awake_among(w, poked) == 3);
  CHECK(w.awake_body_count() == 3);
  w.step(impulse::test::step_dt<float>);
  const step_counts& c = w.last_step_counts();
  CHECK(c.active_bodies == 3);
  CHECK(c.solver_bodies == 4);     // the column and the ground
  CHECK(c.updated_contacts <= 3);  // the column's pairs: box–ground and box–box
  CHECK(c.solved_manifolds == 3);
  CHECK(w.awake_body_count() == 3);
}

TEST_CASE("a box landing on a sleeping column wakes it, and they fall asleep and wake again as one island") {
  sleeping_world w;
  impulse::test::add_ground(w);
  const std::vector<body_id> column = add_column(w, 0, 0, 4);
  REQUIRE(settle(w, 600) < 600);
  const body_id top = impulse::test::add_cube(w, {0.1f, 6, 0});
  bool woke = false;
  for (int i = 0; i < 120 && !woke; ++i) {
    w.step(impulse::test::step_dt<float>);
    woke = awake_among(w, column) == 4;
  }
  CHECK(woke);
  REQUIRE(settle(w, 600) < 600);
  CHECK(w.body(top).position.y == doctest::Approx(4.5f).epsilon(0.002));
  // One island now: waking the landed box wakes the column beneath it.
  w.wake(top);
  CHECK(awake_among(w, column) == 4);
}

TEST_CASE("bodies made asleep join the islands they touch: waking one wakes its stack and no other") {
  sleeping_world w;
  impulse::test::add_ground(w);
  std::vector<body_id> left, right;
  for (int k = 0; k < 5; ++k) {
    body_def<float> d;
    d.mass = 1;
    d.awake = false;
    d.pose.position = {0, 0.5f + float(k), 0};
    left.push_back(w.create_body(d, box<float>::make({0.5f, 0.5f, 0.5f})));
    d.pose.position = {5, 0.5f + float(k), 0};
    right.push_back(w.create_body(d, box<float>::make({0.5f, 0.5f, 0.5f})));
  }
  w.step(impulse::test::step_dt<float>);
  CHECK(w.awake_body_count() == 0);
  CHECK(w.last_step_counts().active_bodies == 0);
  w.wake(left[2]);
  CHECK(awake_among(w, left) == 5);
  CHECK(awake_among(w, right) == 0);
  // A stack made asleep exactly resting stays put once woken.
  impulse::test::run(w, 120);
  for (int k = 0; k < 5; ++k) CHECK(w.body(left[std::size_t(k)]).position.y == doctest::Approx(0.5f + float(k)).epsilon(1e-3));
}

TEST_CASE("destroying the middle box of a sleeping column wakes the other two, and the top one lands on the bottom one") {
  sleeping_world w;
  impulse::test::add_ground(w);
  const std::vector<body_id> column = add_column(w, 0, 0, 3);
  REQUIRE(settle(w, 600) < 600);
  w.destroy_body(column[1]);  // the middle box: the top one falls onto the bottom one
  CHECK(w.is_awake(column[0]));
  CHECK(w.is_awake(column[2]));
  REQUIRE(settle(w, 600) < 600);
  CHECK(w.body(column[2]).position.y == doctest::Approx(1.5f).epsilon(0.003));
}

TEST_CASE("with sleeping islands, a snapshot restores the world to the bit through pokes and landings") {
  // The bodies the poke and the landing woke, 40 steps after the landing
  // began.
  const auto run = [](sleeping_world& w, std::vector<body_id>& ids) {
    impulse::test::run(w, 40);
    w.apply_impulse_at(ids[5], {2, 0, 0}, w.body(ids[5]).position);
    impulse::test::run(w, 40);
    ids.push_back(impulse::test::add_cube(w, {0.3f, 15, 0.2f}, 5.0f));
    impulse::test::run(w, 40);
    const std::size_t woken = w.awake_body_count();
    impulse::test::run(w, impulse::test::long_run(160));
    return woken;
  };
  sleeping_world w;
  impulse::test::add_ground(w);
  std::vector<body_id> ids = impulse::test::add_pile(w);
  REQUIRE(settle(w, 1200) < 1200);
  const world_snapshot<impulse::test::sleeping_config> asleep = w.snapshot();
  std::vector<body_id> first = ids, second = ids;
  const std::size_t woken = run(w, first);
  CHECK(woken > 0);
  const std::uint64_t hash = impulse::test::transform_hash(w);
  w.restore(asleep);
  CHECK(w.awake_body_count() == 0);
  CHECK(run(w, second) == woken);
  CHECK(impulse::test::transform_hash(w) == hash);
}

TEST_CASE("with sleeping off, no body sleeps and the step works on every body") {
  world<impulse::test::awake_config> w;
  impulse::test::add_ground(w);
  add_column(w, 0, 0, 3);
  impulse::test::run(w, 120);
  CHECK(w.awake_body_count() == 3);
  CHECK(w.last_step_counts().active_bodies == 3);
  CHECK(w.last_step_counts().solved_manifolds == 3);
}

}  // namespace world_sleeping_tests
