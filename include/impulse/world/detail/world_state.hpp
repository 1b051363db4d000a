// impulse/world/detail/world_state.hpp — what a world is: its records (bodies,
// contacts, joints), its broad phase and shapes, its events and clock, as
// plain data, with the queries every stage asks of them; and the scratch
// one step rebuilds. The stages of the step (docs/architecture.md, "The
// step") are functions over these two: contact_update.hpp, islands.hpp,
// solve.hpp, continuous.hpp; debug_drawing.hpp reads the state.
//
// The state is everything a step reads: world_snapshot copies it, and the
// same state stepped twice gives the same bits. The scratch holds nothing
// a step needs from the last one; it is kept only so that a warm world
// allocates nothing.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <span>
#include <vector>

#include "../../broadphase/broad_phase.hpp"
#include "../../config.hpp"
#include "../../core/error.hpp"
#include "../../core/detail/pooled_state.hpp"
#include "../../core/detail/stopwatch.hpp"
#include "../../core/slot_map.hpp"
#include "../../dynamics/contact_constraint.hpp"
#include "../../dynamics/detail/island.hpp"
#include "../../dynamics/body_motion.hpp"
#include "../../dynamics/body_spring.hpp"
#include "../../dynamics/joint.hpp"
#include "../../dynamics/rigid_body.hpp"
#include "../../narrowphase/dispatch.hpp"
#include "../body_def.hpp"
#include "../world_events.hpp"
#include "../contact_hooks.hpp"
#include "../world_settings.hpp"
#include "shape_store.hpp"
#include "world_traits.hpp"

namespace impulse::detail {

/// Manifolds one pair can have: one for two convex shapes, one per
/// distinct normal against a mesh (a box in a corner of it: two or three).
inline constexpr int max_manifolds = 4;

/// The sleep_set of a body in no sleeping island: awake, or made asleep
/// (body_def::awake false) and not yet grouped.
inline constexpr std::uint32_t no_sleep_set = 0xffffffffu;

/// Where a kinematic body is with its set_target_pose: none, moving there
/// in the coming step, or arrived (its velocities kept until the next step
/// begins, then zeroed unless a new target came).
enum class target_state : std::uint8_t { none, armed, arrived };

template <scalar_type T>
struct body_record {
  rigid_body<T> body;
  impulse::material<T> material;
  shape_handle shape;
  vec3<T> center{};      ///< center of mass in shape space
  proxy_id proxy;
  transform<T> previous;  ///< the center-of-mass pose at the start of the last step
  T sleep_timer = T(0);   ///< s spent below the sleep speeds
  bool awake = true;
  std::uint32_t sleep_set = no_sleep_set;  ///< asleep: its island (world_state::sleep_sets)
  std::uint64_t user_data = 0;
  collision_filter filter{};
  bool sensor = false;  ///< reports overlaps, makes no contacts (body_def::sensor)
  target_state target = target_state::none;  ///< kinematic: moving to a set_target_pose
  bool bullet = false;
  T thinnest = T(0);  ///< m: the shape's thinnest half-extent, what a step may cross before it is swept
  /// How far it may move in the coming step, while it moves (is_moving):
  /// its center's path and its farthest point's turn, m, each at most the
  /// solver's max_speculative_distance (world_state::set_reach).
  vec3<T> reach_path{};
  T reach_turn = T(0);
};

/// A sensor body and the bodies its shape overlapped at the end of the
/// last step, ascending by index (sensors.hpp).
struct sensor_record {
  body_id sensor;
  std::vector<body_id> inside;
};

/// One manifold of a touching pair: where it touches, the impulses the
/// solver carries to the next step, and what the last full pair test
/// found, in A's shape frame (contact_update.hpp, reuse_manifolds, carries
/// it with the bodies).
template <scalar_type T>
struct manifold_slot {
  contact_manifold<T> manifold;
  manifold_impulse<T> impulse;
  contact_manifold<T> tested_local;
};

/// A pair of bodies whose boxes overlap, and what the narrow phase and the
/// solver know of it. Kept sorted by proxy pair, the broad phase's order,
/// so that each step's pairs merge with the last step's in one pass, with
/// no lookup. Its manifolds live in world_state::manifolds, so that a pair
/// whose boxes overlap but whose shapes do not touch (most pairs in a heap)
/// costs this record alone: 80 bytes in float, where it cost 1 KB with
/// four manifolds inline.
template <scalar_type T>
struct contact_record {
  proxy_pair key;
  body_id a, b;  ///< a owns key.a
  T friction = T(0), restitution = T(0);
  std::uint8_t manifold_count = 0;
  bool touching = false;
  bool tested = false;              ///< whether tested_relative holds a full pair test's
  transform<T> tested_relative{};  ///< B's shape frame in A's at the last full test
  std::array<std::uint32_t, max_manifolds> slots{};  ///< the first manifold_count name its manifolds
};

/// A joint, with the impulses it carries between steps and what it
/// applied in the last one.
template <scalar_type T>
struct joint_record {
  joint_constraint<T> constraint;  ///< in the bodies' frames; body places set each step
  joint_def<T> def;                ///< as created
  body_id a, b;
  vec3<T> force{}, torque{};  ///< on B in the last step, N and N·m
  bool broken = false;
};

/// A spring of the world (world::create_spring): what it was made as, and
/// what it carries between steps.
template <scalar_type T>
struct spring_record {
  body_spring<T> def;    ///< end b none: point_b is a world anchor
  T impulse = T(0);      ///< along it, N·s: the last step's, its warm start
  T tension = T(0);      ///< N pulling its ends together in the last step
  [[nodiscard]] bool anchored() const noexcept { return def.body_b.is_none(); }
};

// ---- what every stage asks of a record ----

template <scalar_type T>
[[nodiscard]] transform<T> shape_pose_of(const body_record<T>& r) noexcept {
  return {r.body.position - rotate(r.body.orientation, r.center), r.body.orientation};
}
/// Whether the body moves this step: dynamic and awake, or kinematic with a
/// velocity.
template <scalar_type T>
[[nodiscard]] bool is_moving(const body_record<T>& r) noexcept {
  if (r.body.type == body_type::dynamic) return r.awake;
  if (r.body.type == body_type::kinematic)
    return r.body.kinematic_velocity != vec3<T>{} || r.body.kinematic_angular_velocity != vec3<T>{};
  return false;
}
/// Whether a step works on the body (world_state::awake_bodies): dynamic
/// and awake, or kinematic, moving or not.
template <scalar_type T>
[[nodiscard]] bool is_active(const body_record<T>& r) noexcept {
  return r.body.type == body_type::kinematic || (r.body.type == body_type::dynamic && r.awake);
}
/// Whether the solver moves the body: dynamic and awake.
template <scalar_type T>
[[nodiscard]] bool is_solved(const body_record<T>& r) noexcept {
  return r.body.type == body_type::dynamic && r.awake;
}

/// A body id as a broad-phase proxy's user data (world_state::unpack
/// turns it back, with the world's owner).
[[nodiscard]] inline std::uint64_t pack(body_id id) noexcept {
  return std::uint64_t(id.index) | (std::uint64_t(id.generation) << 32);
}

/// A number for a new world, stamped on its ids (core/slot_map.hpp): the
/// count of worlds constructed in the process, 0 skipped. Copies and
/// restored snapshots keep the number of the world they copy, since they
/// hold the same bodies; a world constructed afresh never answers to
/// another's ids (until 2³² worlds later).
[[nodiscard]] inline std::uint32_t next_world_owner() noexcept {
  static std::atomic<std::uint32_t> count{0};
  std::uint32_t owner = ++count;
  while (owner == 0) owner = ++count;
  return owner;
}
/// The key of an unordered pair of bodies.
[[nodiscard]] inline std::uint64_t pair_key(body_id a, body_id b) noexcept {
  const std::uint32_t low = std::min(a.index, b.index), high = std::max(a.index, b.index);
  return (std::uint64_t(high) << 32) | low;
}

/// The rigid body `def` makes of `shape`: its exact mass properties at
/// def.material.density, or scaled to def.mass; def.inertia, if given,
/// replaces the shape's inertia (rigid_body checks it). Refuses a mass that is not
/// finite and non-negative, and a dynamic plane or mesh.
template <scalar_type T, class Shape>
[[nodiscard]] rigid_body<T> make_body(const body_def<T>& def, const Shape& shape) {
  if (!std::isfinite(def.mass) || def.mass < T(0))
    report_error(error_code::non_finite,
                 "world::create_body: mass must be finite and >= 0 (a body that cannot move is static)");
  if (def.type != body_type::dynamic) return rigid_body<T>::fixed(def.type, def.pose);
  if constexpr (requires { mass_properties_of(shape, T(1)); }) {
    mass_properties<T> p = mass_properties_of(shape, def.material.density);
    if (def.mass > T(0)) {
      p.inertia = p.inertia * (def.mass / p.mass);
      p.mass = def.mass;
    }
    if (!(def.inertia == mat3<T>::zero())) p.inertia = def.inertia;
    return rigid_body<T>::dynamic({p.mass, vec3<T>{}, p.inertia}, def.pose);
  } else {
    report_error(error_code::invalid_parameter,
                 "world::create_body: planes, triangle meshes and heightfields can only be static or kinematic");
  }
}
/// Where a dynamic body of `shape` has its center of mass, in shape space.
template <scalar_type T, class Shape>
[[nodiscard]] vec3<T> center_of_mass(const body_def<T>& def, const Shape& shape) {
  if constexpr (requires { mass_properties_of(shape, T(1)); }) {
    return mass_properties_of(shape, def.material.density).center;
  } else {
    return {};
  }
}

/// A world's state: everything a step reads and writes.
template <class Config>
struct world_state {
  using T = typename Config::scalar;
  using shapes = typename world_shapes<Config>::type;
  using broad_phase_type = typename world_broadphase<Config>::type::template type<T>;
  using dispatcher = narrowphase::dispatcher<shapes, T>;

  using settings_type = typename world_solver_settings<Config>::type;
  settings_type settings{};
  slot_map<body_record<T>, body_id> bodies;
  slot_map<joint_record<T>, joint_id> joints;
  slot_map<spring_record<T>, spring_id> springs;
  /// The body pairs joined without collide_connected (pair_key), sorted,
  /// once per such joint: their proxies' pairs make no contact.
  std::vector<std::uint64_t> joined;
  std::vector<joint_broken_event<T>> broken;
  std::vector<body_id> held;      ///< held in the last step (world::step)
  std::vector<body_id> targeted;  ///< kinematic bodies with a target_state other than none
  using store_type = impulse::detail::shape_store<shapes, T>;
  store_type shape_store;
  broad_phase_type broad;
  std::vector<contact_record<T>> contacts;
  std::vector<manifold_slot<T>> manifolds;    ///< the touching pairs' manifolds
  std::vector<std::uint32_t> free_manifolds;  ///< slots of manifolds no pair holds
  std::size_t pairs_over_limit = 0;          ///< in the last step: see world::pairs_over_limit
  std::vector<contact_event> begun, ended;
  std::vector<sensor_record> sensors;  ///< in the order they were made
  std::vector<sensor_event> sensor_begun, sensor_ended;
  step_counts counts{};  ///< the last step's
  T time = T(0), accumulator = T(0), last_dt = T(0);
  std::uint64_t step_count = 0;

  // ---- the awake set: what a step works on ----

  /// The dense places of the active bodies (is_active: awake dynamic ones
  /// and every kinematic one), ascending; and the places of the contacts
  /// (in `contacts`), joints and springs (in their values()) with an active body,
  /// ascending. A step visits these and nothing else, so a sleeping body
  /// costs it nothing. Rebuilt by refresh_awake() once awake_stale says a
  /// body woke or slept, or a record came or went.
  std::vector<std::uint32_t> awake_bodies, awake_contacts, awake_joints, awake_springs;
  bool awake_stale = true;
  /// The contact records must be merged with the broad phase's pairs at
  /// the next step though the pairs did not change: a record was dropped,
  /// or a joint that kept two bodies apart went (contact_update.hpp).
  bool pairs_stale = true;
  /// The sleeping islands, each as the bodies it had when it fell asleep
  /// (a body's sleep_set names its own): touching one body wakes them all,
  /// at once. Sets go to free_sleep_sets when they wake.
  std::vector<std::vector<body_id>> sleep_sets;
  std::vector<std::uint32_t> free_sleep_sets;
  /// Bodies were made asleep (body_def::awake false) and are in no island
  /// yet: the next step groups every sleeping body afresh (islands.hpp).
  bool ungrouped_sleepers = false;
  /// The bodies that fell asleep in the last step: their `previous` is
  /// still that step's start, and becomes their pose at the next.
  std::vector<body_id> fell_asleep;

  // ---- bodies ----

  /// Stamps the ids this world makes with `owner` (a new, empty world).
  void set_owner(std::uint32_t owner) noexcept {
    bodies.set_owner(owner);
    joints.set_owner(owner);
    springs.set_owner(owner);
  }
  /// The body whose proxy carries `data` (pack).
  [[nodiscard]] body_id unpack(std::uint64_t data) const noexcept {
    return bodies.id_at(std::uint32_t(data & 0xffffffffu), std::uint32_t(data >> 32));
  }
  /// A body's place in the dense arrays (bodies.values(), the solver's).
  [[nodiscard]] std::uint32_t dense(body_id id) const noexcept { return std::uint32_t(bodies.dense_index(id)); }
  [[nodiscard]] aabb<T> bounds_of(const body_record<T>& r) const {
    const transform<T> pose = shape_pose_of(r);
    return shape_store.visit(r.shape, [&](const auto& s) { return s.world_aabb(pose); });
  }
  /// ‖I⁻¹‖, 1/(kg·m²): the largest row sum of a body's inverse inertia,
  /// which bounds its largest eigenvalue, so |ω| ≤ |L|·‖I⁻¹‖ without the
  /// rotation matrix and two products that ω itself costs.
  [[nodiscard]] static T inverse_inertia_bound(const rigid_body<T>& b) noexcept {
    const mat3<T>& i = b.inverse_inertia;
    T bound = T(0);
    for (int r = 0; r < 3; ++r) bound = std::max(bound, std::abs(i(r, 0)) + std::abs(i(r, 1)) + std::abs(i(r, 2)));
    return bound;
  }
  /// A bound on |ω|, rad/s (inverse_inertia_bound).
  [[nodiscard]] static T spin_bound(const rigid_body<T>& b) noexcept {
    if (b.type != body_type::dynamic) return length(b.angular_velocity());
    return length(b.angular_momentum) * inverse_inertia_bound(b);
  }
  /// Sets how far a moving body may move in a step of h, for the contacts
  /// that reach ahead with speed (contact_update.hpp, speculative_margin):
  /// its center's path, with the step's gravity (the solver adds it before
  /// the contacts act), and |ω|·h times its farthest point from the center,
  /// each at most max_speculative_distance. Returns its shape's box.
  aabb<T> set_reach(body_record<T>& r, T h) const {
    const aabb<T> bounds = bounds_of(r);
    const rigid_body<T>& b = r.body;
    const T limit = settings.solver.max_speculative_distance;
    vec3<T> path = b.linear_velocity() * h;
    if (b.type == body_type::dynamic) path += settings.gravity * (h * h);
    const T distance = length(path);
    r.reach_path = distance > limit ? path * (limit / distance) : path;
    const T farthest = length(max(abs(bounds.upper - b.position), abs(bounds.lower - b.position)));
    r.reach_turn = std::min(spin_bound(b) * h * farthest, limit);
    if (!std::isfinite(r.reach_turn) || !is_finite(r.reach_path)) r.reach_path = {}, r.reach_turn = limit;
    return bounds;
  }
  /// The box the broad phase keeps: the shape's, grown by the speculative
  /// distance and swept over the body's reach (set_reach), so that a pair
  /// that can meet within the step is a pair.
  [[nodiscard]] aabb<T> proxy_box(const body_record<T>& r) const { return proxy_box(r, bounds_of(r)); }
  [[nodiscard]] aabb<T> proxy_box(const body_record<T>& r, const aabb<T>& bounds) const {
    aabb<T> box = expand(bounds, settings.solver.speculative_distance + r.reach_turn);
    box.lower += min(r.reach_path, vec3<T>{});
    box.upper += max(r.reach_path, vec3<T>{});
    // A plane's box spans every finite value already: grown, it must not
    // overflow into infinities the broad phase refuses.
    const vec3<T> big = vec3<T>::splat(std::numeric_limits<T>::max());
    return {max(box.lower, -big), min(box.upper, big)};
  }
  [[nodiscard]] typename dispatcher::shape_ref shape_ref_of(const body_record<T>& r) const noexcept {
    return {shape_store.address(r.shape), r.shape.type};
  }
  /// Moves a kinematic body through a step of dt: its motion is
  /// prescribed, so it is placed exactly (not where an integrator's
  /// approximation would put it). Stopped at the world's bounds instead,
  /// it returns false and the caller holds it.
  bool move_kinematic(body_record<T>& r, T dt) {
    rigid_body<T>& b = r.body;
    if (r.target == target_state::armed) r.target = target_state::arrived;
    const vec3<T> moved = b.position + b.kinematic_velocity * dt;
    if (!within_bounds(moved)) {
      b.kinematic_velocity = b.kinematic_angular_velocity = vec3<T>{};
      return false;
    }
    b.position = moved;
    b.orientation = integrate(b.orientation, b.kinematic_angular_velocity, dt);
    return true;
  }
  /// Wakes a body, and every body of its sleeping island with it.
  void wake(body_record<T>& r) {
    r.sleep_timer = T(0);
    if (r.awake) return;
    r.awake = true;
    awake_stale = true;
    if (r.sleep_set != no_sleep_set) wake_set(r.sleep_set);
  }
  /// Wakes the bodies of a sleeping island that are still in it.
  void wake_set(std::uint32_t set) {
    for (const body_id id : sleep_sets[set]) {
      if (!bodies.contains(id)) continue;
      body_record<T>& r = bodies[id];
      if (r.sleep_set != set) continue;
      r.awake = true;
      r.sleep_timer = T(0);
      r.sleep_set = no_sleep_set;
    }
    sleep_sets[set].clear();
    free_sleep_sets.push_back(set);
    awake_stale = true;
  }
  void wake_all() {
    for (body_record<T>& r : bodies.values()) {
      r.awake = true;
      r.sleep_timer = T(0);
      r.sleep_set = no_sleep_set;
    }
    sleep_sets.clear();
    free_sleep_sets.clear();
    fell_asleep.clear();
    ungrouped_sleepers = false;
    awake_stale = true;
  }
  /// Brings awake_bodies, awake_contacts and awake_joints up to date.
  void refresh_awake() {
    if (!awake_stale) return;
    awake_stale = false;
    const std::vector<body_record<T>>& all = bodies.values();
    awake_bodies.clear();
    for (std::uint32_t i = 0; i < all.size(); ++i)
      if (is_active(all[i])) awake_bodies.push_back(i);
    awake_contacts.clear();
    for (std::uint32_t k = 0; k < contacts.size(); ++k)
      if (is_active(bodies[contacts[k].a]) || is_active(bodies[contacts[k].b])) awake_contacts.push_back(k);
    awake_joints.clear();
    const std::vector<joint_record<T>>& js = joints.values();
    for (std::uint32_t k = 0; k < js.size(); ++k)
      if (is_active(bodies[js[k].a]) || is_active(bodies[js[k].b])) awake_joints.push_back(k);
    awake_springs.clear();
    const std::vector<spring_record<T>>& ss = springs.values();
    for (std::uint32_t k = 0; k < ss.size(); ++k)
      if (is_active(bodies[ss[k].def.body_a]) || (!ss[k].anchored() && is_active(bodies[ss[k].def.body_b])))
        awake_springs.push_back(k);
  }
  /// Calls f(a, b) for every awake contact touching, unbroken joint and
  /// spring between two bodies: what joins bodies into an island.
  template <class F>
  void for_each_awake_link(F&& f) const {
    for (const std::uint32_t k : awake_contacts)
      if (contacts[k].touching) f(contacts[k].a, contacts[k].b);
    for (const std::uint32_t k : awake_joints)
      if (!joints.values()[k].broken) f(joints.values()[k].a, joints.values()[k].b);
    for (const std::uint32_t k : awake_springs)
      if (!springs.values()[k].anchored()) f(springs.values()[k].def.body_a, springs.values()[k].def.body_b);
  }
  /// Whether a point is within max_coordinate of the origin on every axis
  /// (false for NaN).
  [[nodiscard]] bool within_bounds(const vec3<T>& p) const noexcept {
    const T m = settings.max_coordinate;
    return std::abs(p.x) <= m && std::abs(p.y) <= m && std::abs(p.z) <= m;
  }
  /// Whether both speeds are within the world's limits (false for NaN).
  [[nodiscard]] bool within_speed_limits(const vec3<T>& linear, const vec3<T>& angular) const noexcept {
    const T v = settings.max_linear_speed, w = settings.max_angular_speed;
    return length_squared(linear) <= v * v && length_squared(angular) <= w * w;
  }

  /// Refuses a finite point farther than max_coordinate from the origin.
  void require_within_bounds(const vec3<T>& p, const char* message, body_id id = body_id{}) const {
    if (is_finite(p) && !within_bounds(p)) report_error(error_code::invalid_parameter, message, id.index);
  }
  /// Refuses finite speeds past the world's limits.
  void require_speeds(const vec3<T>& linear, const vec3<T>& angular, const char* message,
                      body_id id = body_id{}) const {
    if (is_finite(linear) && is_finite(angular) && !within_speed_limits(linear, angular))
      report_error(error_code::invalid_parameter, message, id.index);
  }
  /// Refuses a joint anchor farther from a dynamic body's center of mass
  /// than world_settings::max_joint_lever radii of gyration.
  void require_lever(const rigid_body<T>& b, const vec3<T>& anchor, body_id id) const {
    if (b.type != body_type::dynamic) return;
    const T smallest = std::min({b.inertia(0, 0), b.inertia(1, 1), b.inertia(2, 2)});
    const T reach = settings.max_joint_lever;
    if (!(length_squared(anchor - b.position) * b.mass <= reach * reach * smallest))
      report_error(error_code::invalid_parameter,
                   "world::create_joint: an anchor is farther from a dynamic body than max_joint_lever radii of "
                   "gyration",
                   id.index);
  }

  // ---- contacts ----

  [[nodiscard]] manifold_slot<T>& slot_of(const contact_record<T>& c, int m) noexcept {
    return manifolds[c.slots[std::size_t(m)]];
  }
  [[nodiscard]] const manifold_slot<T>& slot_of(const contact_record<T>& c, int m) const noexcept {
    return manifolds[c.slots[std::size_t(m)]];
  }
  /// A record that is dropped: its pair ends, its manifolds are freed.
  void end_contact(const contact_record<T>& c) {
    awake_stale = true;
    if (c.touching) ended.push_back({c.a, c.b});
    for (int m = 0; m < c.manifold_count; ++m) free_manifolds.push_back(c.slots[std::size_t(m)]);
  }

  // ---- joints ----

  /// Whether a joint between the two keeps them from colliding.
  [[nodiscard]] bool joined_apart(body_id a, body_id b) const noexcept {
    return !joined.empty() && std::binary_search(joined.begin(), joined.end(), pair_key(a, b));
  }
  /// Whether two bodies may make contact, the types apart: no joint keeps
  /// them apart, their filters let them touch, and so does the user's rule.
  [[nodiscard]] bool may_collide(body_id a, body_id b, const pair_filter& rule) const {
    return !joined_apart(a, b) && should_collide(bodies[a].filter, bodies[b].filter) &&
           (rule.test == nullptr || rule.test(a, b, rule.context));
  }
  /// Lets the joint's bodies collide again (if it had stopped them).
  void unjoin(const joint_record<T>& r) {
    if (r.def.collide_connected) return;
    const auto at = std::lower_bound(joined.begin(), joined.end(), pair_key(r.a, r.b));
    if (at != joined.end() && *at == pair_key(r.a, r.b)) joined.erase(at);
    pairs_stale = true;  // the pair makes contact again
  }
  void wake_joint(const joint_record<T>& r) {
    wake(bodies[r.a]);
    wake(bodies[r.b]);
  }
  /// The joint's parts and errors at the bodies' present poses.
  [[nodiscard]] joint_constraint<T> measure(const joint_record<T>& r) const {
    std::array<solver_body<T>, 2> ends{};
    const rigid_body<T>& a = bodies[r.a].body;
    const rigid_body<T>& b = bodies[r.b].body;
    ends[0].position = a.position, ends[0].orientation = a.orientation;
    ends[1].position = b.position, ends[1].orientation = b.orientation;
    joint_constraint<T> c = r.constraint;
    c.body_a = 0, c.body_b = 1;
    prepare_joint(std::span<const solver_body<T>>(ends), c);
    return c;
  }
};

/// What one worker's pair tests leave for the calling thread to do in the
/// records' order (contact_update.hpp, collide_all): the records whose
/// count of manifolds changed, with what goes in their slots, and the
/// records that began or stopped touching. A cache line of its own: the
/// workers count into theirs at every record.
template <scalar_type T>
struct alignas(64) worker_pairs {
  struct resized_record {
    std::uint32_t record, count;
    std::uint32_t worker, first;  ///< its manifolds: fresh and carried of work[worker], from first
    transform<T> pose_a;
  };
  struct touch_event {
    std::uint32_t record;
    bool begun;
  };
  std::vector<resized_record> resized;
  std::vector<contact_manifold<T>> fresh;
  std::vector<manifold_impulse<T>> carried;
  std::vector<touch_event> events;
  std::size_t updated = 0;  ///< records tested or carried
  std::uint32_t worker = 0;
  /// The only worker: resizes the slots and reports the events itself, in
  /// the records' order, and keeps nothing here.
  bool direct = false;

  void clear(std::uint32_t index) noexcept {
    resized.clear();
    fresh.clear();
    carried.clear();
    events.clear();
    updated = 0;
    worker = index;
    direct = false;
  }
};

/// What one step rebuilds: the solver and its arrays, the next contact
/// records, the islands. Not part of the state (a snapshot leaves it out);
/// kept to allocate nothing once warm.
template <class Config>
struct step_scratch {
  using T = typename Config::scalar;
  using solver_type = typename world_solver<Config>::type::template type<T>;

  /// A solved manifold's record and its place among the record's manifolds.
  struct constraint_source {
    std::uint32_t record;
    std::uint32_t manifold;
  };
  /// A new contact holding a body up (solve.hpp, estimate_cold_loads).
  struct support {
    T height;  ///< of the upper body, along −gravity
    std::uint32_t upper, lower, constraint;
    T lift;  ///< the normal's component along −gravity
  };

  solver_type solver{};
  /// The workers a step may spread over (world::set_task_system).
  task_system tasks{};
  /// The user's rule for pairs (world::set_pair_filter); like the tasks,
  /// the world's, not its state's.
  pair_filter pair_rule{};
  pre_solve_hook<T> pre_solve{};    ///< world::set_pre_solve; the world's, as the tasks
  post_solve_hook<T> post_solve{};  ///< world::set_post_solve
  /// Per solved manifold, what the pre-solve hook left (solve.hpp), when there is one.
  std::vector<contact_settings<T>> source_settings;
  /// The first pair a pre-solve hook gave settings out of range in this step.
  body_id refused_settings{};
  std::exception_ptr hook_error;  ///< what a hook threw in this step (contact_hooks.hpp, call_hook)
  step_profile profile;  ///< the last step's (world::last_step_profile)
  std::vector<contact_record<T>> next_contacts;
  std::vector<worker_pairs<T>> pair_work;  ///< one per worker (contact_update.hpp)
  std::vector<aabb<T>> proxy_boxes;        ///< each awake body's, when it moves (contact_update.hpp)
  std::vector<std::uint8_t> proxy_moves;   ///< each awake body's proxy_move (contact_update.hpp)
  /// The bodies the solver sees (solve.hpp): the active ones and the static
  /// ones their solved contacts and joints reach, in dense order.
  std::vector<solver_body<T>> solver_bodies;
  std::vector<std::uint32_t> solver_dense;  ///< each solver body's dense place
  std::vector<std::uint32_t> solver_place;  ///< per dense body: its solver place, if it has one
  std::vector<std::uint32_t> reached;       ///< the static bodies among them
  std::vector<std::uint32_t> gathered;      ///< per dense body: the gather that last took it
  std::uint32_t gather = 0;                 ///< this step's gather
  std::vector<contact_constraint<T>> constraints;
  std::vector<constraint_source> sources;
  std::vector<joint_constraint<T>> joints;
  std::vector<std::uint32_t> joint_sources;  ///< each solved joint's dense place
  std::vector<std::uint32_t> spring_sources;  ///< each solved spring's dense place (its row follows the joints')
  bool anchored = false;                      ///< a solved spring has a world anchor: the solver body past the others
  std::vector<joint_id> doomed_joints;       ///< world::destroy_body's
  std::vector<spring_id> doomed_springs;     ///< world::destroy_body's
  /// step(dt, field)'s loads, checked before any is applied.
  struct field_load {
    std::uint32_t body;
    wrench<T> load;
  };
  std::vector<field_load> field_loads;
  std::vector<support> supports;
  std::vector<T> load;
  union_find islands;  ///< over awake_bodies' places (islands.hpp)
  std::vector<std::uint32_t> awake_place;  ///< per dense body: its place in awake_bodies, if it has one
  std::vector<std::uint8_t> island_flag;
  std::vector<T> island_timer;
  std::vector<std::uint32_t> island_set;
  std::vector<std::uint8_t> held;  ///< per solver body: held in this step (hold)
  // Continuous collision's (continuous.hpp): per worker, what it saw; per
  // awake body, whether it left its broad-phase box; the bodies that did.
  std::vector<std::uint8_t> sweep_seen, sweep_left;
  std::vector<std::uint32_t> sweep_movers;
  std::vector<std::vector<body_id>> sensor_next;  ///< per sensor: what it overlaps now (sensors.hpp)

  /// A world without collision's (force_motion.hpp).
  struct motion_scratch {
    /// A spring's ends as dense places; b none: a world anchor.
    struct spring_ends {
      std::uint32_t a, b;
    };
    std::vector<spring_ends> ends;
    std::vector<std::uint32_t> first_spring, springs_of, fill;  ///< each body's springs
    bool coupled = false;  ///< a spring joins two moving bodies
    buffer_pool<body_pose<T>> pose_pool;
    buffer_pool<body_momentum<T>> momentum_pool;
    std::vector<body_kinematics<T>> stage_kinematics;
    std::vector<wrench<T>> stage_wrenches;
  };
  motion_scratch motion;

  /// Holds solver body i for this step: it keeps its pose, loses its
  /// velocity, and its contacts and joints are left out (world::step).
  void hold(world_state<Config>& state, std::size_t i) {
    hold_quietly(i);
    held[i] = 1;
    state.held.push_back(state.bodies.ids()[solver_dense[i]]);
  }
  /// Holds solver body i as hold() does, touching nothing but its own,
  /// so that bodies are held side by side; report_holds lists them.
  void hold_quietly(std::size_t i) {
    held[i] = 2;
    solver_body<T>& s = solver_bodies[i];
    s.inverse_mass = T(0);
    s.inverse_inertia = mat3<T>{};
    s.linear_velocity = s.angular_velocity = s.force_linear = s.force_angular = vec3<T>{};
  }
  /// Adds the bodies held quietly since the last call to the world's
  /// held list, in solver order.
  void report_holds(world_state<Config>& state) {
    for (std::size_t i = 0; i < held.size(); ++i)
      if (held[i] == 2) held[i] = 1, state.held.push_back(state.bodies.ids()[solver_dense[i]]);
  }
  [[nodiscard]] bool is_held(std::uint32_t i) const noexcept { return held[i] != 0; }
};

}  // namespace impulse::detail
