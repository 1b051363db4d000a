// A world stepped across workers (world::set_task_system): the same bits as
// one thread, whatever the worker count and however the scheduler cuts and
// orders the ranges. The scenes reach every stage that runs across workers:
// the pair tests (boxes, spheres, walls), manifold counts that change and
// contacts that begin and end, the solver's colors, and joints beside
// them, under either contact solver.
#include <doctest/doctest.h>

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "../core/schedulers.hpp"
#include "../error_code_of.hpp"
#include "impulse/core/random.hpp"
#include "impulse/thread_pool.hpp"
#include "scenes.hpp"

namespace world_workers_tests {

namespace {

using namespace impulse;
using impulse::test::awake_config;
using world_type = world<awake_config>;
using impulse::test::soft_config;
using soft_world = world<soft_config>;
using sleeping_world = world<impulse::test::sleeping_config>;
using ccd_world = world<impulse::test::ccd_config>;

/// What a run leaves: every body's transform (transform_hash), and the
/// contact events of every step, their pairs in the order given (FNV-1a).
struct outcome {
  std::uint64_t transforms = 0, events = 1469598103934665603ull;
  std::size_t begun = 0, ended = 0, sensed = 0;
  bool operator==(const outcome&) const = default;

  void add(std::span<const contact_event> list, std::uint64_t kind) {
    for (const contact_event& e : list)
      for (const std::uint64_t word : {kind, std::uint64_t(e.a.index), std::uint64_t(e.b.index)})
        events = (events ^ word) * 1099511628211ull;
  }
  void add(std::span<const sensor_event> list, std::uint64_t kind) {
    for (const sensor_event& e : list)
      for (const std::uint64_t word : {kind, std::uint64_t(e.sensor.index), std::uint64_t(e.visitor.index)})
        events = (events ^ word) * 1099511628211ull;
  }
};

/// Builds a scene with `build`, steps it `steps` times across `tasks` (none:
/// on this thread) and reports what it left.
template <class World>
outcome run(const std::function<void(World&)>& build, int steps, const task_system* tasks) {
  World w;
  if (tasks != nullptr) w.set_task_system(*tasks);
  build(w);
  outcome out;
  for (int i = 0; i < steps; ++i) {
    w.step(impulse::test::step_dt<float>);
    out.begun += w.contact_begin_events().size();
    out.ended += w.contact_end_events().size();
    out.add(w.contact_begin_events(), 1);
    out.add(w.contact_end_events(), 2);
    out.add(w.sensor_begin_events(), 3);
    out.add(w.sensor_end_events(), 4);
    out.sensed += w.sensor_begin_events().size();
  }
  out.transforms = impulse::test::transform_hash(w);
  return out;
}

/// The scene at 1 worker, then at 2, 3 and 8 (8 more than this machine's
/// cores) on impulse::thread_pool, and on a scheduler that runs the ranges
/// back to front: all the same.
template <class World = world_type>
void check_any_worker_count(const std::function<void(World&)>& build, int steps) {
  const outcome one = run(build, steps, nullptr);
  CHECK(one.begun > 0);
  for (const std::uint32_t workers : {2u, 3u, 8u}) {
    CAPTURE(workers);
    thread_pool pool{workers};
    const task_system tasks = pool.tasks();
    CHECK(run(build, steps, &tasks) == one);
  }
  const task_system backwards = impulse::test::backwards_scheduler::tasks();
  CHECK(run(build, steps, &backwards) == one);
}

/// Builds a scene in `w` with `build` and steps it `steps` times at 2
/// workers, then hands the world back to its own thread (the pool ends).
template <class World>
void step_on_two_workers(World& w, const std::function<void(World&)>& build, int steps) {
  thread_pool pool{2};
  w.set_task_system(pool.tasks());
  build(w);
  impulse::test::run(w, steps);
  w.set_task_system(task_system{});
}

/// `spheres` (docs/standard_scenes.md), its first `layers` of 25 layers:
/// 400 balls of radius 0.25 a layer on a jittered grid, dropped into a box
/// of four walls.
template <class World>
void add_spheres(World& w, int layers) {
  impulse::test::add_ground(w);
  const auto wall = [&](vec3<float> half, vec3<float> at) {
    body_def<float> d;
    d.type = body_type::static_body;
    d.pose.position = at;
    d.material.friction = 0.6f;
    w.create_body(d, box<float>::make(half));
  };
  wall({0.5f, 10, 8}, {7.5f, 10, 0});
  wall({0.5f, 10, 8}, {-7.5f, 10, 0});
  wall({8, 10, 0.5f}, {0, 10, 7.5f});
  wall({8, 10, 0.5f}, {0, 10, -7.5f});
  lcg32 random{12345};
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < layers; ++j)
      for (int k = 0; k < 20; ++k) {
        const float jitter_x = (random.uniform<float>() - 0.5f) * 0.1f;
        const float jitter_z = (random.uniform<float>() - 0.5f) * 0.1f;
        body_def<float> d;
        d.pose.position = {(float(i) - 9.5f) * 0.6f + jitter_x, 1 + 0.6f * float(j), (float(k) - 9.5f) * 0.6f + jitter_z};
        d.material.friction = 0.6f;
        w.create_body(d, sphere<float>::make(0.25f));
      }
}

/// `large_pyramid`: a 100-box base, 5 050 boxes of 100 kg.
template <class World>
void add_large_pyramid(World& w) {
  impulse::test::add_ground(w, 0.6f, {}, 400.0f);
  for (int k = 0; k < 100; ++k) {
    const int n = 100 - k;
    for (int i = 0; i < n; ++i) impulse::test::add_cube(w, {float(i) - float(n - 1) / 2, 0.5f + float(k), 0}, 100.0f);
  }
}

/// Eight chains of ten boxes on ball joints, hung from static posts and
/// let go from horizontal, swinging into a row of boxes on the ground.
template <class World>
void add_chains(World& w) {
  impulse::test::add_ground(w);
  for (int c = 0; c < 8; ++c) {
    const float z = 1.5f * float(c);
    body_def<float> post;
    post.type = body_type::static_body;
    post.pose.position = {0, 12, z};
    body_id above = w.create_body(post, box<float>::make({0.1f, 0.1f, 0.1f}));
    vec3<float> anchor{0, 12, z};
    for (int i = 0; i < 10; ++i) {
      const body_id link = impulse::test::add_cube(w, anchor + vec3<float>{0.55f, 0, 0}, 1.0f);
      w.create_joint(joint_def<float>::ball(above, link, anchor));
      anchor += vec3<float>{1.1f, 0, 0};
      above = link;
    }
    for (int i = 0; i < 6; ++i) impulse::test::add_cube(w, {-3.0f + 1.2f * float(i), 0.5f, z});
  }
}

/// Islands the solver shares out among the workers, each group solved
/// whole on one, with what it must carry across: 24 stacks of a 1 kg box
/// under a 50 kg one (the support sweep), balls bouncing at e = 0.6 (the
/// restitution pass), a kinematic platform sliding at 0.5 m/s under two
/// boxes (a body no impulse moves that moves, and joins what it carries),
/// and one box bridging two stacks.
template <class World>
void add_islands(World& w) {
  impulse::test::add_ground(w);
  for (int s = 0; s < 24; ++s) {
    const vec3<float> at{float(s % 6) * 2.0f - 5.0f, 0.5f, float(s / 6) * 2.0f - 3.0f};
    impulse::test::add_cube(w, at, 1.0f);
    impulse::test::add_cube(w, at + vec3<float>{0, 1, 0}, s == 7 || s == 8 ? 1.0f : 50.0f);
  }
  body_def<float> bridge;  // on the tops of stacks 7 and 8, 2 m apart
  bridge.pose.position = {-2.0f, 2.25f, -1.0f};
  w.create_body(bridge, box<float>::make({1.3f, 0.25f, 0.4f}));
  for (int b = 0; b < 6; ++b) {
    body_def<float> d;
    d.pose.position = {float(b) * 2.0f - 5.0f, 3.0f, 6.0f};
    d.material.restitution = 0.6f;
    w.create_body(d, sphere<float>::make(0.3f));
  }
  body_def<float> platform;
  platform.type = body_type::kinematic;
  platform.pose.position = {-4.0f, 3.0f, -7.0f};
  platform.linear_velocity = {0.5f, 0, 0};
  w.create_body(platform, box<float>::make({2.0f, 0.1f, 1.0f}));
  impulse::test::add_cube(w, {-5.0f, 3.6f, -7.0f});
  impulse::test::add_cube(w, {-3.0f, 3.6f, -7.0f});
}


/// A field of 400 cubes on the ground, 20 by 20 and 1.5 m apart, every
/// fifth one in a stack of three: 560 bodies in 400 islands, which come to
/// rest within a second (enough bodies that a check over them splits into
/// ranges).
template <class World>
void add_field(World& w) {
  impulse::test::add_ground(w);
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) {
      const int height = (i + j) % 5 == 0 ? 3 : 1;
      for (int k = 0; k < height; ++k)
        impulse::test::add_cube(w, {(float(i) - 9.5f) * 1.5f, 0.52f + 1.02f * float(k), (float(j) - 9.5f) * 1.5f});
    }
}

/// Fast bodies and bullets, beside the field (add_field): 40 cubes of 20 cm at 240 m/s at a
/// 1 cm wall (each swept back), 20 bullets of 5 cm at 120 m/s down into
/// their paths, and a kinematic plate at 300 m/s through the lot, its reach
/// in the broad phase capped.
template <class World>
void add_shooting(World& w) {
  add_field(w);
  body_def<float> wall;
  wall.type = body_type::static_body;
  wall.pose.position = {15.005f, 4, 0};  // just past the field's edge (x = 14.75)
  w.create_body(wall, box<float>::make({0.005f, 4, 8}));
  for (int c = 0; c < 40; ++c) {
    body_def<float> d;
    d.pose.position = {12.5f - 0.03f * float(c), 1.0f + 0.15f * float(c % 8), -6.0f + 0.3f * float(c)};
    d.linear_velocity = {240, 0, 0};
    w.create_body(d, box<float>::make({0.1f, 0.1f, 0.1f}));
    if (c % 2 != 0) continue;
    body_def<float> shot;
    shot.pose.position = {14.89f, d.pose.position.y + 2, d.pose.position.z};
    shot.linear_velocity = {0, -120, 0};
    shot.bullet = true;
    w.create_body(shot, sphere<float>::make(0.05f));
  }
  body_def<float> plate;
  plate.type = body_type::kinematic;
  plate.pose.position = {14, 2, -10};
  plate.linear_velocity = {0, 0, 300};
  w.create_body(plate, box<float>::make({0.5f, 1, 0.01f}));
}

}  // namespace

TEST_CASE("islands solved whole on each worker are bit-identical for 1, 2, 3 and 8 workers, over 300 steps") {
  check_any_worker_count<world_type>(add_islands<world_type>, impulse::test::long_run(300));
  // And they were solved apart: two groups on two workers, none on one.
  thread_pool pool{2};
  world_type w;
  w.set_task_system(pool.tasks());
  add_islands(w);
  for (int i = 0; i < 60; ++i) w.step(impulse::test::step_dt<float>);
  CHECK(w.last_step_counts().solver_groups == 2);
  world_type alone;
  add_islands(alone);
  alone.step(impulse::test::step_dt<float>);
  CHECK(alone.last_step_counts().solver_groups == 0);
}

TEST_CASE("the pile is bit-identical for 1, 2, 3 and 8 workers, over 600 steps") {
  check_any_worker_count<world_type>([](world_type& w) {
    impulse::test::add_ground(w);
    impulse::test::add_pile(w);
  }, impulse::test::long_run(600));
}

// The standard scenes run 600 steps of 10 000 balls and 5 050 boxes;
// bench/scenes --threads compares those whole runs at each worker count
// (docs/performance.md). Here, the heap's first five layers until they
// have landed and piled up (the lowest lands at step 24), and the
// pyramid's first steps, in which all of its contacts begin.
TEST_CASE("the sphere heap's first 2 000 balls are bit-identical for 1, 2, 3 and 8 workers, over 60 steps") {
  check_any_worker_count<world_type>([](world_type& w) { add_spheres(w, 5); }, 60);
}

TEST_CASE("large_pyramid is bit-identical for 1, 2, 3 and 8 workers, over its first 10 steps") {
  check_any_worker_count<world_type>(add_large_pyramid<world_type>, impulse::test::long_run(10));
}

TEST_CASE("chains on joints swinging into boxes are bit-identical for 1, 2, 3 and 8 workers, over 300 steps") {
  check_any_worker_count<world_type>(add_chains<world_type>, impulse::test::long_run(300));
}

TEST_CASE("soft_step's pile and chains are bit-identical for 1, 2, 3 and 8 workers, over 300 steps") {
  check_any_worker_count<soft_world>([](soft_world& w) {
    impulse::test::add_ground(w);
    impulse::test::add_pile(w);
  }, impulse::test::long_run(300));
  check_any_worker_count<soft_world>(add_chains<soft_world>, impulse::test::long_run(300));
}

TEST_CASE("fast bodies and bullets swept beside a field of cubes are bit-identical for 1, 2, 3 and 8 workers, over 60 steps") {
  check_any_worker_count<ccd_world>(add_shooting<ccd_world>, 60);
  // And the sweeps ran: after the first step, at 2 workers, every cube
  // that would have passed the wall (its face at x = 15) is short of it.
  ccd_world w;
  step_on_two_workers<ccd_world>(w, add_shooting<ccd_world>, 1);
  int past = 0, short_of_wall = 0;
  for (const body_id id : w.body_ids()) {
    const rigid_body<float>& b = w.body(id);
    if (b.type != body_type::dynamic) continue;
    if (b.position.x >= 15.0f) ++past;
    if (b.position.x > 14.85f) ++short_of_wall;
  }
  CHECK(past == 0);
  CHECK(short_of_wall >= 40);
}

TEST_CASE("a field of cubes falling asleep is bit-identical for 1, 2, 3 and 8 workers, over 60 steps") {
  check_any_worker_count<sleeping_world>(add_field<sleeping_world>, 60);
  // And it does fall asleep within those steps (by step 36), at 2 workers.
  sleeping_world w;
  step_on_two_workers<sleeping_world>(w, add_field<sleeping_world>, 60);
  CHECK(w.awake_body_count() == 0);
}

TEST_CASE("sensors report the same events for 1, 2, 3 and 8 workers, over 90 steps") {
  // 64 static sensor slabs, 1 m square and 0.2 m thick, at y = 2 on a
  // 1.5 m grid; 400 balls dropped through them onto the ground.
  const auto build = [](world_type& w) {
    impulse::test::add_ground(w);
    body_def<float> d;
    d.type = body_type::static_body;
    d.sensor = true;
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 8; ++k) {
        d.pose.position = {(float(i) - 3.5f) * 1.5f, 2, (float(k) - 3.5f) * 1.5f};
        w.create_body(d, box<float>::make({0.5f, 0.1f, 0.5f}));
      }
    lcg32 random{11};
    body_def<float> ball;
    for (int n = 0; n < 400; ++n) {
      ball.pose.position = {random.uniform<float>(-6, 6), random.uniform<float>(4, 12), random.uniform<float>(-6, 6)};
      w.create_body(ball, sphere<float>::make(0.2f));
    }
  };
  check_any_worker_count<world_type>(build, 90);
  const outcome one = run<world_type>(build, 90, nullptr);
  CHECK(one.sensed > 100);  // most balls pass a slab
}

TEST_CASE("a snapshot restored into a world with workers steps on as it would have on one thread") {
  world_type one, many;
  impulse::test::add_ground(one);
  impulse::test::add_pile(one);
  impulse::test::run(one, 30);
  thread_pool pool{2};
  many.set_task_system(pool.tasks());
  many.restore(one.snapshot());
  CHECK(many.tasks().workers == 2);  // restore leaves the task system as it was
  impulse::test::run(one, 30);
  impulse::test::run(many, 30);
  CHECK(impulse::test::transform_hash(many) == impulse::test::transform_hash(one));
}

TEST_CASE("set_task_system refuses a hook with no worker or with one callback of two") {
  world_type w;
  task_system none;
  none.workers = 0;
  CHECK(impulse::test::error_code_of([&] { w.set_task_system(none); }) == error_code::invalid_parameter);
  thread_pool pool{2};
  task_system half = pool.tasks();
  half.finish = nullptr;
  CHECK(impulse::test::error_code_of([&] { w.set_task_system(half); }) == error_code::invalid_parameter);
  CHECK(w.tasks().workers == 1);  // the refused hooks left it on this thread
}

}  // namespace world_workers_tests
