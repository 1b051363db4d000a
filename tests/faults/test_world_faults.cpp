// The world under faults: a body that overflows is held and the others,
// its joint partners too, step on; finite input that would overflow is
// refused at the call; shapes are checked where the world takes them;
// callbacks cannot change what they walk; a destroyed id never names
// another body; and heaped bodies stay within the pair limit.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "../error_code_of.hpp"
#include "../world/scenes.hpp"
#include "impulse/core/slot_map.hpp"

namespace faults_world_faults_tests {

using namespace impulse;
using impulse::test::error_code_of;

namespace {

// The shared test worlds (tests/world/scenes.hpp), compiled once.
using gauss_seidel_solver_config = impulse::test::awake_config;
using soft_step_config = impulse::test::soft_config;
using double_config = impulse::test::awake_double_config;

/// Everything a refused call must leave as it was: each body's pose and
/// momenta, bit for bit, and the counts.
template <class World>
std::uint64_t state_hash(const World& w) {
  std::uint64_t h = impulse::test::transform_hash(w);
  const auto mix = [&](const void* data, std::size_t n) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ bytes[i]) * 1099511628211ull;
  };
  for (const body_id id : w.body_ids()) {
    const auto& b = w.body(id);
    mix(&b.linear_momentum, sizeof b.linear_momentum);
    mix(&b.angular_momentum, sizeof b.angular_momentum);
    mix(&b.force, sizeof b.force);
    mix(&b.torque, sizeof b.torque);
  }
  const std::size_t counts[] = {w.body_count(), w.joint_count(), w.touching_pair_count()};
  mix(counts, sizeof counts);
  return h;
}

/// An id with an 8-bit generation: it wraps after 256 reuses of a slot,
/// where impulse's 32-bit one would after 2³².
struct small_id {
  std::uint32_t index = no_object;
  std::uint8_t generation = 0;
  friend constexpr bool operator==(const small_id&, const small_id&) = default;
};

using impulse::test::all_finite;

template <class T>
body_id add_box(world<T>& w, vec3<typename world<T>::scalar> at) {
  using S = typename world<T>::scalar;
  body_def<S> d;
  d.pose.position = at;
  d.mass = 1;
  return w.create_body(d, box<S>::make({S(0.5), S(0.25), S(0.25)}));
}

/// Two boxes side by side at height 5, joined at x = 0.5 by a joint of
/// `type`, and a ball far away with nothing to do with them.
template <class World>
struct joined_pair {
  using T = typename World::scalar;
  World w;
  body_id a, b, bystander;
  joint_id joint;

  joined_pair(joint_type type, bool exact_trees) {
    typename World::settings_type settings;
    settings.solver.exact_joint_trees = exact_trees;
    w.set_settings(settings);
    a = add_box(w, vec3<T>{0, 5, 0});
    b = add_box(w, vec3<T>{1, 5, 0});
    body_def<T> d;
    d.pose.position = {20, 5, 0};
    bystander = w.create_body(d, sphere<T>::make(T(0.5)));
    const vec3<T> anchor{T(0.5), 5, 0}, axis{0, 0, 1};
    switch (type) {
      case joint_type::ball: joint = w.create_joint(joint_def<T>::ball(a, b, anchor)); break;
      case joint_type::hinge: joint = w.create_joint(joint_def<T>::hinge(a, b, anchor, axis)); break;
      case joint_type::slider: joint = w.create_joint(joint_def<T>::slider(a, b, anchor, {1, 0, 0})); break;
      case joint_type::fixed: joint = w.create_joint(joint_def<T>::fixed(a, b, anchor)); break;
      case joint_type::distance:
        joint = w.create_joint(joint_def<T>::distance(a, b, vec3<T>{T(0.4), 5, 0}, vec3<T>{T(0.6), 5, 0}));
        break;
    }
  }
};

/// The overflow defect's scene for every joint kind: a force of 1e29 N
/// on A (1.7e27 m/s after one step, far past max_linear_speed; in float
/// the joint's products of it overflow). A is held where it was, named by
/// the step's error; B, joined to it, and the bystander fall freely for
/// that step, exactly as gravity alone moves them; and the joint holds
/// them together again over the next second.
template <class World>
void check_overflow_is_held(joint_type type, bool exact_trees) {
  using T = typename World::scalar;
  joined_pair<World> scene(type, exact_trees);
  World& w = scene.w;
  const vec3<T> a_start = w.body(scene.a).position, b_start = w.body(scene.b).position;
  const vec3<T> far_start = w.body(scene.bystander).position;
  w.apply_force(scene.a, {T(1e29), 0, 0});
  const error_code code = error_code_of([&] { w.step(impulse::test::step_dt<T>); });
  CHECK(code == error_code::non_finite);
  REQUIRE(w.held_bodies().size() == 1);
  CHECK(w.held_bodies()[0] == scene.a);
  CHECK(w.body(scene.a).position == a_start);
  CHECK(w.body(scene.a).linear_velocity() == vec3<T>{});
  // One step of free fall, as the same solver moves a lone body (soft_step's
  // substeps fall less far in the first step than one Euler step).
  World alone;
  const body_id lone = add_box(alone, b_start);
  const T dt = impulse::test::step_dt<T>;
  alone.step(dt);
  const T fall = b_start.y - alone.body(lone).position.y;
  CHECK(fall > T(0.0015));  // g·dt²·(5/8) for soft_step's 4 substeps, g·dt² for one step: 1.7 and 2.7 mm
  CHECK(all_finite(w));
  CHECK(w.body(scene.b).position.y == doctest::Approx(double(b_start.y - fall)).epsilon(1e-6));
  CHECK(w.body(scene.b).position.x == doctest::Approx(double(b_start.x)).epsilon(1e-6));
  CHECK(w.body(scene.bystander).position.y == doctest::Approx(double(far_start.y - fall)).epsilon(1e-6));
  for (int i = 0; i < 60; ++i) w.step(dt);  // nothing is held any more: no error
  CHECK(w.held_bodies().empty());
  CHECK(all_finite(w));
  // A joint's anchors part along a slider's axis and by a distance joint's
  // rod; the others' anchors meet.
  if (type != joint_type::slider && type != joint_type::distance) CHECK(w.joint_separation(scene.joint) < T(0.01));
  if (type == joint_type::distance) CHECK(std::abs(w.joint_position(scene.joint) - T(0.2)) < T(0.01));
}

template <class World>
void check_every_joint_kind() {
  for (const joint_type type :
       {joint_type::ball, joint_type::hinge, joint_type::slider, joint_type::fixed, joint_type::distance})
    for (const bool exact_trees : {true, false}) {
      CAPTURE(int(type));
      CAPTURE(exact_trees);
      check_overflow_is_held<World>(type, exact_trees);
    }
}

}  // namespace

// ---- a body that overflows is held; the others step on ----

TEST_CASE("a jointed body pushed by 1e29 N is held and named, and its partner steps on (every joint, Gauss–Seidel)") {
  check_every_joint_kind<world<gauss_seidel_solver_config>>();
}

TEST_CASE("a jointed body pushed by 1e29 N is held and named, and its partner steps on (every joint, soft_step)") {
  check_every_joint_kind<world<soft_step_config>>();
}

TEST_CASE("a jointed body pushed by 1e29 N is held and named, and its partner steps on (every joint, double)") {
  check_every_joint_kind<world<double_config>>();
}

TEST_CASE("a body spun past max_angular_speed by a torque is held, and a body resting on it stays on the ground") {
  world<gauss_seidel_solver_config> w;
  impulse::test::add_ground(w);
  const body_id bottom = impulse::test::add_cube(w, {0, 0.5f, 0});
  const body_id top = impulse::test::add_cube(w, {0, 1.5f, 0});
  impulse::test::run(w, 30);
  const vec3<float> bottom_at = w.body(bottom).position;
  w.apply_torque(bottom, {0, 1e30f, 0});
  CHECK(error_code_of([&] { w.step(impulse::test::step_dt<float>); }) == error_code::non_finite);
  CHECK(w.held_bodies().size() == 1);
  CHECK(w.body(bottom).position == bottom_at);
  CHECK(w.body(bottom).angular_velocity() == vec3<float>{});
  // The top box lost its support for one step: it fell at most g·dt².
  CHECK(w.body(top).position.y > 1.5f - 0.01f);
  impulse::test::run(w, 60);
  CHECK(std::abs(w.body(top).position.y - 1.5f) < 0.01f);
  CHECK(all_finite(w));
}

TEST_CASE("a body that gravity would take past max_linear_speed is held with no velocity, and falls again") {
  world_settings<float> settings;
  settings.max_linear_speed = 10;
  world<gauss_seidel_solver_config> w(settings);
  const body_id box_id = add_box(w, vec3<float>{0, 100, 0});
  // Each step adds 9.81/60 = 0.1635 m/s: 61 steps reach 9.97 m/s, the 62nd
  // would pass 10 m/s.
  std::vector<int> held_at;
  for (int i = 0; i < 90; ++i) {
    if (error_code_of([&] { w.step(impulse::test::step_dt<float>); }) == error_code::non_finite) {
      held_at.push_back(i);
      CHECK(w.held_bodies()[0] == box_id);
      CHECK(w.body(box_id).linear_velocity() == vec3<float>{});
    }
    CHECK(length(w.body(box_id).linear_velocity()) <= 10.0f);
  }
  CHECK(held_at == std::vector<int>{61});
  CHECK(all_finite(w));
}

// ---- finite input that would overflow is refused at the call ----

TEST_CASE("forces, torques and impulses whose sums overflow are refused, and the world is unchanged") {
  world<gauss_seidel_solver_config> w;
  const body_id b = add_box(w, vec3<float>{0, 1, 0});
  w.apply_force(b, {3e38f, 0, 0});
  const std::uint64_t before = state_hash(w);
  CHECK(error_code_of([&] { w.apply_force(b, {3e38f, 0, 0}); }) == error_code::non_finite);
  CHECK(error_code_of([&] { w.apply_force_at(b, {3e38f, 0, 0}, {0, 1, 0}); }) == error_code::non_finite);
  // A finite force whose moment about the center overflows.
  CHECK(error_code_of([&] { w.apply_force_at(b, {0, 3e30f, 0}, {3e30f, 1, 0}); }) == error_code::non_finite);
  w.apply_torque(b, {0, 0, 3e38f});
  const std::uint64_t with_torque = state_hash(w);
  CHECK(error_code_of([&] { w.apply_torque(b, {0, 0, 3e38f}); }) == error_code::non_finite);
  CHECK(state_hash(w) == with_torque);
  CHECK(with_torque != before);
  world<gauss_seidel_solver_config> v;
  const body_id c = add_box(v, vec3<float>{0, 1, 0});
  const std::uint64_t still = state_hash(v);
  // Impulses change the momenta at once: 2e38 + 2e38 N·s overflows.
  v.apply_impulse_at(c, {2e38f, 0, 0}, {0, 1, 0});
  const std::uint64_t pushed = state_hash(v);
  CHECK(pushed != still);
  CHECK(error_code_of([&] { v.apply_impulse_at(c, {2e38f, 0, 0}, {0, 1, 0}); }) == error_code::non_finite);
  CHECK(state_hash(v) == pushed);
}

TEST_CASE("a velocity past the speed limits or whose momentum overflows is refused, and the world is unchanged") {
  world<gauss_seidel_solver_config> w;
  body_def<float> d;
  d.mass = 8000;
  const body_id heavy = w.create_body(d, box<float>::make({1, 1, 1}));
  const std::uint64_t before = state_hash(w);
  CHECK(error_code_of([&] { w.set_velocity(heavy, {1e35f, 0, 0}, {}); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { w.set_velocity(heavy, {}, {0, 2e4f, 0}); }) == error_code::invalid_parameter);
  d.linear_velocity = {0, 0, 2e4f};
  CHECK(error_code_of([&] { w.create_body(d, box<float>::make({1, 1, 1})); }) == error_code::invalid_parameter);
  world_settings<float> raised;
  raised.max_linear_speed = 1e30f;  // past the ceiling of 1e6 m/s
  CHECK(error_code_of([&] { w.set_settings(raised); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { w.set_gravity({0, -2e4f, 0}); }) == error_code::invalid_parameter);
  CHECK(state_hash(w) == before);
  w.set_velocity(heavy, {1e4f, 0, 0}, {});  // at the default limit: taken
  CHECK(w.body(heavy).linear_velocity().x == 1e4f);
}

TEST_CASE("a rigid body refuses a velocity whose momentum overflows, and keeps its own") {
  // The world's speed limits keep its bodies far from this, with or without
  // collision; a rigid_body used on its own, outside any world (stepped by
  // hand through body_motion.hpp and an integrator), has no limits and is
  // guarded here.
  rigid_body<float> b = rigid_body<float>::dynamic({8000, {}, mat3<float>::diagonal({1e4f, 1e4f, 1e4f})});
  b.set_velocity({1, 0, 0}, {});
  CHECK(error_code_of([&] { b.set_velocity({1e35f, 0, 0}, {}); }) == error_code::non_finite);
  CHECK(error_code_of([&] { b.set_velocity({}, {0, 0, 1e35f}); }) == error_code::non_finite);
  CHECK(b.linear_momentum == vec3<float>{8000, 0, 0});
  CHECK(b.angular_momentum == vec3<float>{});
}

TEST_CASE("a kinematic target too far to reach within the speed limit in dt is refused") {
  world<gauss_seidel_solver_config> w;
  body_def<float> d;
  d.type = body_type::kinematic;
  const body_id platform = w.create_body(d, box<float>::make({1, 0.1f, 1}));
  const std::uint64_t before = state_hash(w);
  CHECK(error_code_of([&] {
          w.set_target_pose(platform, {{1e30f, 0, 0}, quat<float>::identity()}, 1.0f / 60);
        }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] {
          w.set_target_pose(platform, {{1, 0, 0}, quat<float>::identity()}, 1e-30f);
        }) == error_code::invalid_parameter);
  CHECK(state_hash(w) == before);
  w.set_target_pose(platform, {{1, 0, 0}, quat<float>::identity()}, 1.0f / 60);  // 60 m/s: taken
  CHECK(w.body(platform).kinematic_velocity.x == doctest::Approx(60.0f).epsilon(1e-5));
}

TEST_CASE("interpolated_pose refuses alpha outside [0, 1] or NaN") {
  world<gauss_seidel_solver_config> w;
  const body_id b = add_box(w, vec3<float>{0, 1, 0});
  w.step(impulse::test::step_dt<float>);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  CHECK(error_code_of([&] { (void)w.interpolated_pose(b, nan); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { (void)w.interpolated_pose(b, -0.5f); }) == error_code::invalid_parameter);
  CHECK(error_code_of([&] { (void)w.interpolated_pose(b, 1e30f); }) == error_code::invalid_parameter);
  CHECK(w.interpolated_pose(b, 1).position == w.shape_pose(b).position);
}

// ---- shapes are checked where the world takes them ----

TEST_CASE("an empty triangle mesh or a moved-from hull is refused by create_body, and the world is unchanged") {
  world<gauss_seidel_solver_config> w;  // the default shapes: meshes and hulls among them
  const body_id ball = w.create_body({}, sphere<float>::make(0.5f));
  const std::uint64_t before = state_hash(w);
  body_def<float> ground;
  ground.type = body_type::static_body;
  CHECK(error_code_of([&] { w.create_body(ground, triangle_mesh<float>{}); }) == error_code::degenerate_shape);
  const std::vector<vec3<float>> corners{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  convex_hull<float> hull = convex_hull<float>::from_points(corners);
  const convex_hull<float> taken = std::move(hull);
  CHECK(error_code_of([&] { w.create_body({}, hull); }) == error_code::degenerate_shape);  // NOLINT: moved from on purpose
  CHECK(w.body_count() == 1);
  CHECK(state_hash(w) == before);
  CHECK(w.contains(ball));
  w.create_body({}, taken);
  impulse::test::run(w, 10);
  CHECK(all_finite(w));
}

// ---- callbacks cannot change what they walk ----

TEST_CASE("calls that would change the world's containers are refused from inside its callbacks") {
  world<gauss_seidel_solver_config> w;
  impulse::test::add_ground(w);
  const body_id a = impulse::test::add_cube(w, {0, 0.5f, 0});
  const body_id b = impulse::test::add_cube(w, {3, 0.5f, 0});
  impulse::test::run(w, 2);
  REQUIRE(w.touching_pair_count() == 2);
  const world_snapshot<gauss_seidel_solver_config> saved = w.snapshot();
  const std::uint64_t before = state_hash(w);
  const auto refused_calls = [&] {
    std::vector<error_code> codes;
    codes.push_back(error_code_of([&] { w.step(impulse::test::step_dt<float>); }));
    codes.push_back(error_code_of([&] { (void)w.advance(1.0f); }));
    codes.push_back(error_code_of([&] { impulse::test::add_cube(w, {9, 3, 0}); }));
    codes.push_back(error_code_of([&] { w.destroy_body(b); }));
    codes.push_back(error_code_of([&] { w.set_pose(b, {{5, 1, 0}, quat<float>::identity()}); }));
    codes.push_back(error_code_of([&] { (void)w.create_joint(joint_def<float>::ball(a, b, {1, 1, 0})); }));
    codes.push_back(error_code_of([&] { w.restore(saved); }));
    return codes;
  };
  const auto all_refused = [](const std::vector<error_code>& codes) {
    for (const error_code c : codes)
      if (c != error_code::invalid_parameter) return false;
    return true;
  };
  int calls = 0;
  w.for_each_contact([&](body_id, body_id, std::span<const contact_manifold<float>>) {
    ++calls;
    CHECK(all_refused(refused_calls()));
  });
  CHECK(calls == 2);
  w.overlap({{-10, -10, -10}, {10, 10, 10}}, [&](body_id) { CHECK(all_refused(refused_calls())); });
  w.visit_shape(a, [&](const auto&) { CHECK(all_refused(refused_calls())); });
  CHECK(state_hash(w) == before);
  // What does not touch the containers is allowed: a force, a velocity.
  w.for_each_contact([&](body_id first, body_id second, std::span<const contact_manifold<float>>) {
    for (const body_id id : {first, second})
      if (id == a) w.apply_force(a, {0, 1, 0});
  });
  CHECK(w.body(a).force.y == 1.0f);  // a is in one pair, with the ground
  // A callback that throws leaves the world usable.
  CHECK_THROWS(w.for_each_contact([](body_id, body_id, std::span<const contact_manifold<float>>) { throw 1; }));
  w.step(impulse::test::step_dt<float>);
  w.destroy_body(b);
  CHECK(w.body_count() == 2);
}

// ---- a destroyed id never names another body ----

TEST_CASE("a destroyed body's id never names a later body, over a thousand reuses of its slot") {
  world<gauss_seidel_solver_config> w;
  std::vector<body_id> destroyed;
  for (int i = 0; i < 1000; ++i) {
    const body_id id = add_box(w, vec3<float>{0, 1, 0});
    for (const body_id old : destroyed) REQUIRE_FALSE(old == id);
    w.destroy_body(id);
    destroyed.push_back(id);
  }
  const body_id live = add_box(w, vec3<float>{0, 1, 0});
  for (const body_id old : destroyed) CHECK_FALSE(w.contains(old));
  CHECK(error_code_of([&] { w.apply_force(destroyed.front(), {1, 0, 0}); }) == error_code::out_of_range);
  CHECK(w.body(live).force == vec3<float>{});
}

TEST_CASE("a slot whose generation would wrap is retired, so its first id never names a new object") {
  // The same slot_map code as the world's ids', with a generation that
  // wraps sooner (small_id).
  slot_map<int, small_id> map;
  const small_id first = map.insert(0);
  small_id id = first;
  for (int i = 1; i < 256; ++i) {
    map.erase(id);
    id = map.insert(i);
    REQUIRE(id.index == first.index);  // the slot is reused while its generation lasts
    REQUIRE_FALSE(id == first);
  }
  CHECK(id.generation == 255);
  map.erase(id);  // generation 255 → would be 0 again: the slot retires
  const small_id next = map.insert(256);
  CHECK(next.index != first.index);
  CHECK_FALSE(map.contains(first));
  CHECK_FALSE(map.contains(id));
  CHECK(map.contains(next));
  CHECK(map.size() == 1);
}

// ---- heaped bodies stay within the pair limit ----

TEST_CASE("bodies heaped in one spot get contacts up to max_contact_pairs, the rest wait, and none is lost") {
  world_settings<float> settings;
  settings.max_contact_pairs = 100;
  settings.gravity = {};
  world<gauss_seidel_solver_config> w(settings);
  for (int i = 0; i < 30; ++i) add_box(w, vec3<float>{0.01f * float(i), 0, 0});  // 435 pairs
  w.step(impulse::test::step_dt<float>);
  CHECK(w.touching_pair_count() <= 100);
  CHECK(w.touching_pair_count() + w.pairs_over_limit() == 435);
  // They push apart; as pairs separate, those waiting get their turn, and
  // the heap spreads until no box overlaps another.
  for (int i = 0; i < 600 && w.pairs_over_limit() > 0; ++i) w.step(impulse::test::step_dt<float>);
  CHECK(w.pairs_over_limit() == 0);
  CHECK(all_finite(w));
}

}  // namespace faults_world_faults_tests
