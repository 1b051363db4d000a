// impulse/world/world.hpp — impulse::world<Config>: bodies with shapes and
// materials, joints between them, stepped through the pipeline of
// docs/architecture.md. This file is the world's interface and its step;
// the state it keeps is detail/world_state.hpp, and each stage of the step
// is a file of its own:
//
//   broad and narrow phase   detail/contact_update.hpp
//   islands, sleeping        detail/islands.hpp (sleeping on)
//   solve and write-back     detail/solve.hpp
//   continuous collision     detail/continuous.hpp (ccd on)
//
// A world without collision (config `collision = false`) steps through
// detail/force_motion.hpp alone: forces at every integrator stage.
// world_bodies.hpp, world_joints.hpp, world_forces.hpp and
// world_queries.hpp define the members that make and destroy bodies,
// joints and springs, and that answer queries.
//
// The world is a value: copying it copies every body, shape, contact and
// impulse, and snapshot() / restore() are that copy. A step is a pure
// function of the state (no clocks, no addresses, containers iterated in
// id order), so the same state stepped twice gives the same bits.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <optional>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "../config.hpp"
#include "../core/error.hpp"
#include "../core/floating_point.hpp"
#include "../core/task_system.hpp"
#include "../narrowphase/dispatch.hpp"
#include "../narrowphase/ray_cast.hpp"
#include "../narrowphase/time_of_impact.hpp"
#include "body_def.hpp"
#include "contact_hooks.hpp"
#include "world_events.hpp"
#include "world_ray_hit.hpp"
#include "world_settings.hpp"
#include "detail/contact_update.hpp"
#include "detail/continuous.hpp"
#include "detail/debug_drawing.hpp"
#include "detail/force_motion.hpp"
#include "fwd.hpp"
#include "detail/islands.hpp"
#include "detail/sensors.hpp"
#include "detail/shape_cast.hpp"
#include "detail/solve.hpp"
#include "detail/world_state.hpp"

namespace impulse {

template <class Config>
class world {
  static_assert(detail::check_world_config<Config>());
  static_assert(detail::check_determinism_build<Config>());

 public:
  using config = Config;
  using scalar = typename Config::scalar;
  using T = scalar;
  using state_type = detail::world_state<Config>;
  using shapes = typename state_type::shapes;
  using broad_phase_type = typename state_type::broad_phase_type;
  using solver_policy = typename detail::world_solver<Config>::type;
  using solver_type = typename solver_policy::template type<T>;
  using settings_type = typename state_type::settings_type;  ///< world_settings with its solver's
  using integrator = typename Config::integrator;
  /// Whether bodies collide (config `collision`, on by default). Off, the
  /// world has no broad phase, contacts, joints or solver: gravity, loads,
  /// springs and force fields move the bodies, each evaluated at every
  /// stage of the integrator (detail/force_motion.hpp).
  static constexpr bool collision = detail::world_collides<Config>();
  static constexpr bool sleeping = detail::world_sleeping<Config>();
  /// Whether fast bodies and bullets are swept (continuous collision); off,
  /// the sweeping code is not compiled.
  static constexpr bool ccd = detail::world_ccd<Config>();
  /// Whether every build of the program steps to the same bits (config
  /// `cross_platform_determinism`, off by default): the world then refuses
  /// to be made in a build that fuses multiplies and adds
  /// (core/floating_point.hpp; docs/world.md, "Lockstep determinism").
  static constexpr bool cross_platform_determinism = detail::cross_platform_determinism<Config>();
  /// Manifolds one pair can have (one per distinct normal against a mesh).
  static constexpr int max_manifolds = detail::max_manifolds;
  /// The longest step, s: a step is a small piece of motion, and one of a
  /// thousand years (finite) would carry every body out of finite numbers.
  static constexpr T max_dt = T(1);


  explicit world(const settings_type& settings = {});
  // Declared here and defaulted after the class, so that an explicit
  // instantiation declaration (IMPULSE_DECLARE_WORLD) keeps them, and all
  // that the members' destructors instantiate, out of other translation units.
  world(const world& other);
  world(world&& other) noexcept;
  world& operator=(const world& other);
  world& operator=(world&& other) noexcept;
  ~world();

  // ---- settings ----

  [[nodiscard]] const settings_type& settings() const noexcept { return state_.settings; }
  void set_settings(const settings_type& settings) {
    settings.validate();
    state_.settings = settings;
  }
  /// Refused: gravity that is not finite, or stronger than
  /// max_linear_speed per second (world_settings::validate).
  void set_gravity(const vec3<T>& g) {
    if (!is_finite(g)) detail::report_error(error_code::non_finite, "world::set_gravity: gravity is not finite");
    settings_type changed = state_.settings;
    changed.gravity = g;
    changed.validate();
    state_.settings = changed;
    state_.wake_all();
  }

  // ---- threads ----

  /// Spreads the step's stages across the hook's workers
  /// (core/task_system.hpp, impulse/thread_pool.hpp); the default runs
  /// everything on the calling thread, and the world never starts a thread
  /// of its own. A step gives the same bits for any worker count. Kept
  /// apart from the state: a snapshot neither saves nor restores it.
  void set_task_system(const task_system& tasks) {
    refuse_in_callback("world::set_task_system: called from inside a world callback");
    if (tasks.workers < 1)
      detail::report_error(error_code::invalid_parameter, "world::set_task_system: a task system needs at least one worker");
    if ((tasks.enqueue == nullptr) != (tasks.finish == nullptr))
      detail::report_error(error_code::invalid_parameter,
                           "world::set_task_system: a task system needs both enqueue and finish, or neither");
    scratch_.tasks = tasks;
  }
  [[nodiscard]] const task_system& tasks() const noexcept { return scratch_.tasks; }

  // ---- bodies ----

  /// Makes a body of `shape` (one of the config's shapes) as `def` says.
  /// A dynamic body takes the shape's exact mass properties at
  /// def.material.density, or scaled to def.mass. Bad input (a degenerate
  /// shape, a non-finite or non-unit pose, a dynamic plane or mesh, an
  /// infinite or negative mass) is refused and the world is unchanged.
  template <class Shape>
  body_id create_body(const body_def<T>& def, const Shape& shape);

  /// Removes a body, its contacts and its joints; the bodies it touched or
  /// was joined to wake. A stale or destroyed id is refused.
  void destroy_body(body_id id);

  [[nodiscard]] bool contains(body_id id) const noexcept { return state_.bodies.contains(id); }
  [[nodiscard]] std::size_t body_count() const noexcept { return state_.bodies.size(); }
  /// Every live body, in storage order.
  [[nodiscard]] std::span<const body_id> body_ids() const noexcept { return state_.bodies.ids(); }
  /// A body's state (position of its center of mass, orientation, momenta,
  /// mass properties).
  [[nodiscard]] const rigid_body<T>& body(body_id id) const {
    require(id, "world::body: no such body");
    return state_.bodies[id].body;
  }
  /// Where the body's shape is: its origin and orientation.
  [[nodiscard]] transform<T> shape_pose(body_id id) const {
    require(id, "world::shape_pose: no such body");
    return detail::shape_pose_of(state_.bodies[id]);
  }
  /// The shape pose between the last two steps: alpha 0 at the start of
  /// the last step, 1 at its end (advance() returns the alpha of the time
  /// left over). Rendering at it hides the fixed step's stutter. Refused:
  /// alpha outside [0, 1] or NaN.
  [[nodiscard]] transform<T> interpolated_pose(body_id id, T alpha) const;
  /// Calls f(shape) with the body's shape (one of the config's shape
  /// list, in the body's shape frame) and returns what f returns.
  template <class F>
  decltype(auto) visit_shape(body_id id, F&& f) const {
    require(id, "world::visit_shape: no such body");
    const in_callback scope(*this);
    return state_.shape_store.visit(state_.bodies[id].shape, std::forward<F>(f));
  }
  [[nodiscard]] const impulse::material<T>& material_of(body_id id) const {
    require(id, "world::material_of: no such body");
    return state_.bodies[id].material;
  }
  [[nodiscard]] std::uint64_t user_data(body_id id) const {
    require(id, "world::user_data: no such body");
    return state_.bodies[id].user_data;
  }
  [[nodiscard]] bool is_awake(body_id id) const {
    require(id, "world::is_awake: no such body");
    return state_.bodies[id].awake;
  }
  [[nodiscard]] std::size_t awake_body_count() const noexcept {
    return std::size_t(std::ranges::count_if(state_.bodies.values(), [](const body_record& r) { return detail::is_solved(r); }));
  }

  /// Sets a body's velocities (a dynamic or kinematic body) and wakes it.
  /// Refused: speeds above world_settings::max_linear_speed or
  /// max_angular_speed, and velocities whose momenta overflow.
  void set_velocity(body_id id, const vec3<T>& linear, const vec3<T>& angular) {
    require(id, "world::set_velocity: no such body");
    body_record& r = state_.bodies[id];
    state_.require_speeds(linear, angular, "world::set_velocity: faster than max_linear_speed or max_angular_speed", id);
    r.body.set_velocity(linear, angular);  // refuses non-finite values and static bodies
    state_.wake(r);
  }
  /// Moves a body (its shape's origin) at once, and wakes it. Contacts
  /// follow at the next step; nothing in between is swept.
  void set_pose(body_id id, const transform<T>& pose);
  /// Moves a kinematic body (its shape's origin) to `target` over the next
  /// step of dt seconds: its velocities are set so that it arrives there,
  /// carrying what rests on it by friction as a moving body would, and go
  /// back to zero after that step unless a new target is set. An animated
  /// platform calls this every step. Refused: a body that is not
  /// kinematic, a non-finite or non-unit pose, dt not positive.
  void set_target_pose(body_id id, const transform<T>& target, T dt);
  /// A force through the center of mass for the next step, N.
  void apply_force(body_id id, const vec3<T>& force) {
    body_record& r = dynamic_record(id, "world::apply_force: no such body");
    r.body.apply_force(force);
    state_.wake(r);
  }
  /// A force at a world point for the next step, N.
  void apply_force_at(body_id id, const vec3<T>& force, const vec3<T>& point) {
    body_record& r = dynamic_record(id, "world::apply_force_at: no such body");
    r.body.apply_force_at(force, point);
    state_.wake(r);
  }
  void apply_torque(body_id id, const vec3<T>& torque) {
    body_record& r = dynamic_record(id, "world::apply_torque: no such body");
    r.body.apply_torque(torque);
    state_.wake(r);
  }
  /// An impulse at a world point, now, N·s.
  void apply_impulse_at(body_id id, const vec3<T>& impulse, const vec3<T>& point) {
    body_record& r = dynamic_record(id, "world::apply_impulse_at: no such body");
    r.body.apply_impulse_at(impulse, point);
    state_.wake(r);
  }
  void wake(body_id id) {
    require(id, "world::wake: no such body");
    state_.wake(state_.bodies[id]);
  }

  // ---- filtering (collision_filter.hpp; world_bodies.hpp) ----

  [[nodiscard]] const collision_filter& filter(body_id id) const {
    require(id, "world::filter: no such body");
    return state_.bodies[id].filter;
  }
  /// Gives the body a new filter and wakes it. Its contacts with the
  /// bodies the filter now keeps it from end at once (with end events for
  /// those touching, and those bodies wake); the pairs it now lets through
  /// make contact from the next step.
  void set_filter(body_id id, const collision_filter& filter);
  /// The world's rule for the pairs the filters let through (pair_filter);
  /// a default pair_filter removes it. Contacts the new rule refuses end at
  /// once, as set_filter's do. Kept apart from the state: a snapshot
  /// neither saves nor restores it.
  void set_pair_filter(const pair_filter& rule);
  [[nodiscard]] const pair_filter& pair_rule() const noexcept { return scratch_.pair_rule; }
  /// Asks the filters and the rule again about the body's pairs, after the
  /// rule's answer for them changed; as set_filter does with the same filter.
  void refilter(body_id id);

  // ---- contact hooks (contact_hooks.hpp) ----

  /// Before each solve, the hook sees each touching manifold and may switch
  /// it off or change its friction, restitution and surface velocity for
  /// the step: one-way platforms, conveyor belts. A default hook removes
  /// it. Kept apart from the state, as the task system.
  void set_pre_solve(const pre_solve_hook<T>& hook) {
    refuse_in_callback("world::set_pre_solve: called from inside a world callback");
    scratch_.pre_solve = hook;
  }
  /// After each solve, the hook sees each solved manifold with the
  /// impulses it applied over the step.
  void set_post_solve(const post_solve_hook<T>& hook) {
    refuse_in_callback("world::set_post_solve: called from inside a world callback");
    scratch_.post_solve = hook;
  }
  [[nodiscard]] const pre_solve_hook<T>& pre_solve() const noexcept { return scratch_.pre_solve; }
  [[nodiscard]] const post_solve_hook<T>& post_solve() const noexcept { return scratch_.post_solve; }

  // ---- joints ----

  /// Joins two bodies as `def` says (joint.hpp). The anchors and axis are
  /// taken in the bodies' frames as they are now. Refused, with the world
  /// unchanged: a body given twice, a missing or destroyed body, two bodies
  /// neither of which is dynamic, non-finite anchors or axis, and the
  /// other bad values joint_def::validate names. Both bodies wake; unless
  /// def.collide_connected, their contacts with each other end.
  /// A world without collision has no solver, and so no joints.
  joint_id create_joint(const joint_def<T>& def)
    requires(detail::world_collides<Config>());

  /// Removes a joint; its bodies wake and, if they did not collide, may
  /// touch again from the next step. A broken joint stays until destroyed.
  void destroy_joint(joint_id id);

  [[nodiscard]] bool contains(joint_id id) const noexcept { return state_.joints.contains(id); }
  [[nodiscard]] std::size_t joint_count() const noexcept { return state_.joints.size(); }
  /// Every joint, broken ones too, in storage order.
  [[nodiscard]] std::span<const joint_id> joint_ids() const noexcept { return state_.joints.ids(); }
  /// The joint as it was created.
  [[nodiscard]] const joint_def<T>& joint(joint_id id) const {
    require(id, "world::joint: no such joint");
    return state_.joints[id].def;
  }
  [[nodiscard]] bool is_broken(joint_id id) const {
    require(id, "world::is_broken: no such joint");
    return state_.joints[id].broken;
  }
  /// What the joint measures now: a hinge's angle about its axis (rad) or
  /// a slider's translation along it (m), both 0 at creation; a distance
  /// joint's length (m); 0 for the others.
  [[nodiscard]] T joint_position(joint_id id) const {
    require(id, "world::joint_position: no such joint");
    return state_.measure(state_.joints[id]).position;
  }
  /// How far apart the joint's anchors on A and B are now, m: its error
  /// for a ball, hinge or fixed joint (a slider's anchors part along the
  /// axis, a distance joint's by its length).
  [[nodiscard]] T joint_separation(joint_id id) const {
    require(id, "world::joint_separation: no such joint");
    return length(state_.measure(state_.joints[id]).separation);
  }
  /// The force and torque the joint applied to B in the last step, N and
  /// N·m, world (A took the opposite).
  [[nodiscard]] vec3<T> joint_force(joint_id id) const {
    require(id, "world::joint_force: no such joint");
    return state_.joints[id].force;
  }
  [[nodiscard]] vec3<T> joint_torque(joint_id id) const {
    require(id, "world::joint_torque: no such joint");
    return state_.joints[id].torque;
  }
  /// Drives a hinge or slider at `speed` (rad/s or m/s) with at most
  /// `max_force` (N·m or N); enable false turns the motor off. Wakes the
  /// bodies.
  void set_joint_motor(joint_id id, bool enable, T speed, T max_force);
  /// Keeps a hinge's angle or a slider's translation within [lower, upper];
  /// enable false frees it. Wakes the bodies.
  void set_joint_limits(joint_id id, bool enable, T lower, T upper);
  // ---- springs (world_forces.hpp) ----

  /// Adds a damped spring (body_spring.hpp) from a point of one body to a
  /// point of another or to a world anchor (end b none), solved with the
  /// contacts and joints as a soft row of its stiffness and damping:
  /// stable at any stiffness, and the bodies still collide. (Without
  /// collision it is a force at every integrator stage instead.) Refused, the
  /// world unchanged: a missing body, both ends on one body, no end on a
  /// dynamic body, a value not finite or negative. Its bodies wake.
  spring_id create_spring(const body_spring<T>& def);
  /// Removes a spring; its bodies wake. destroy_body removes its springs.
  void destroy_spring(spring_id id);
  [[nodiscard]] bool contains(spring_id id) const noexcept { return state_.springs.contains(id); }
  [[nodiscard]] std::size_t spring_count() const noexcept { return state_.springs.size(); }
  [[nodiscard]] std::span<const spring_id> spring_ids() const noexcept { return state_.springs.ids(); }
  [[nodiscard]] const body_spring<T>& spring(spring_id id) const {
    require(id, "world::spring: no such spring");
    return state_.springs[id].def;
  }
  /// N the spring pulled its ends together with in the last step (< 0: pushed apart).
  [[nodiscard]] T spring_tension(spring_id id) const {
    require(id, "world::spring_tension: no such spring");
    return state_.springs[id].tension;
  }

  /// Bodies held in the last step (see step()), in storage order.
  [[nodiscard]] std::span<const body_id> held_bodies() const noexcept { return state_.held; }
  /// Joints that broke in the last step.
  [[nodiscard]] std::span<const joint_broken_event<T>> joint_broken_events() const noexcept { return state_.broken; }

  // ---- stepping ----

  /// Advances the world by dt seconds. Events of this step replace the
  /// last step's. A body that the step would take past the world's speed
  /// limits or out of finite numbers (finite input can still overflow: a
  /// force of 1e29 N on a kilogram) is held: it stays where it was with no
  /// velocity, its contacts and joints are left out of the step, and every
  /// other body, its joint partners too, steps on. (A body found only after
  /// the solve, which it took part in, is put back where it was, and the
  /// joint projection treats it as fixed.) The step then throws
  /// impulse::invalid_argument (non_finite) naming the first held body; held_bodies()
  /// lists them all.
  void step(T dt);
  /// A step with a force field: field(body_id, body_kinematics) -> wrench
  /// (force through the center of mass, torque), added to each awake
  /// dynamic body's loads for this step (world_forces.hpp). It wakes none.
  /// Without collision it is evaluated at every integrator stage instead,
  /// on the stage's state.
  template <class Field>
    requires body_force_field<Field, T>
  void step(T dt, Field&& field);

  /// Runs as many fixed steps (settings().fixed_dt) as the frame time and
  /// what was left over from the last call allow, at most
  /// max_steps_per_advance; returns the fraction of a step left over, the
  /// alpha for interpolated_pose.
  T advance(T frame_dt);

  [[nodiscard]] T time() const noexcept { return state_.time; }
  [[nodiscard]] std::uint64_t step_count() const noexcept { return state_.step_count; }
  /// How much of the world the last step worked on (step_counts).
  [[nodiscard]] const step_counts& last_step_counts() const noexcept { return state_.counts; }
  /// How long the last step took in each stage (step_profile).
  [[nodiscard]] const step_profile& last_step_profile() const noexcept { return scratch_.profile; }
  /// The last step's times and counts, and what the world holds: worked
  /// out when asked (a pass over the contact records), not by the step.
  [[nodiscard]] world_profile profile() const {
    world_profile p{scratch_.profile, state_.counts};
    p.bodies = state_.bodies.size();
    if constexpr (collision) p.pairs = state_.broad.pairs().size();
    p.contacts = state_.contacts.size();
    p.touching = touching_pair_count();
    p.joints = state_.joints.size();
    p.sensors = state_.sensors.size();
    return p;
  }

  // ---- events and contacts ----

  /// Pairs that began touching in the last step.
  [[nodiscard]] std::span<const contact_event> contact_begin_events() const noexcept { return state_.begun; }
  /// Pairs that stopped touching in the last step, or lost a body since.
  [[nodiscard]] std::span<const contact_event> contact_end_events() const noexcept { return state_.ended; }

  /// f(a, b, manifolds) for every touching pair; each manifold's normal
  /// points from a into b.
  ///
  /// Inside this callback, and those of overlap, visit_shape and draw, the
  /// world refuses what would change the containers the callback walks:
  /// step, advance, create_body, destroy_body, set_pose, create_joint,
  /// destroy_joint and restore throw impulse::invalid_argument (invalid_parameter).
  /// Velocities, forces, impulses, motors and limits may be set.
  template <class F>
  void for_each_contact(F&& f) const {
    const in_callback scope(*this);
    std::array<contact_manifold<T>, max_manifolds> manifolds;
    for (const contact_record& c : state_.contacts) {
      if (!c.touching) continue;
      const int count = std::min(int(c.manifold_count), max_manifolds);  // always the count; says so to the compiler
      for (int m = 0; m < count; ++m) manifolds[std::size_t(m)] = state_.slot_of(c, m).manifold;
      f(c.a, c.b, std::span<const contact_manifold<T>>(manifolds.data(), std::size_t(count)));
    }
  }
  /// Bodies that began overlapping a sensor in the last step.
  [[nodiscard]] std::span<const sensor_event> sensor_begin_events() const noexcept { return state_.sensor_begun; }
  /// Bodies that stopped overlapping a sensor in the last step, or since:
  /// a body destroyed inside a sensor, or a sensor destroyed with bodies
  /// inside.
  [[nodiscard]] std::span<const sensor_event> sensor_end_events() const noexcept { return state_.sensor_ended; }
  /// The bodies the sensor overlapped at the end of the last step,
  /// ascending by index. Refused: a body that is not there or not a sensor.
  [[nodiscard]] std::span<const body_id> sensor_overlaps(body_id sensor) const {
    require(sensor, "world::sensor_overlaps: no such body");
    for (const detail::sensor_record& s : state_.sensors)
      if (s.sensor == sensor) return s.inside;
    detail::report_error(error_code::invalid_parameter, "world::sensor_overlaps: the body is not a sensor",
                         sensor.index);
  }
  [[nodiscard]] bool is_sensor(body_id id) const {
    require(id, "world::is_sensor: no such body");
    return state_.bodies[id].sensor;
  }
  /// Pairs whose boxes overlapped in the last step but got no contact
  /// because the world held world_settings::max_contact_pairs already: 0
  /// unless a scene heaps that many bodies together. They get their
  /// contacts once there is room.
  [[nodiscard]] std::size_t pairs_over_limit() const noexcept { return state_.pairs_over_limit; }
  [[nodiscard]] std::size_t touching_pair_count() const noexcept {
    return std::size_t(std::count_if(state_.contacts.begin(), state_.contacts.end(),
                                     [](const contact_record& c) { return c.touching; }));
  }

  // ---- queries ----

  /// The nearest body that `filter` sees along the ray, within
  /// max_fraction of its translation.
  [[nodiscard]] std::optional<world_ray_hit<T>> ray_cast(const ray<T>& r, T max_fraction = T(1),
                                                         const query_filter& filter = {}) const;

  /// f(body) for every body that `filter` sees whose shape's bounding box
  /// overlaps `box`.
  template <class F>
  void overlap(const aabb<T>& box, F&& f, const query_filter& filter = {}) const;

  /// f(hit) for every body that `filter` sees along the ray, in no set
  /// order; f returns the fraction to go on to: its hit's own to see only
  /// nearer bodies from then on, 1 to see all, 0 (or NaN) to stop.
  template <class F>
  void ray_cast_all(const ray<T>& r, F&& f, const query_filter& filter = {}) const;

  /// The first body that `filter` sees which `shape` (a convex one: sphere,
  /// capsule, box, hull), at `pose` and moved by `translation` without
  /// turning, meets: the fraction of the translation it can move, the
  /// touching point, and the body's outward normal there. It stops within
  /// half a millimetre short of touching, never past; a shape that starts
  /// overlapping a body meets it at fraction 0 (world_queries.hpp).
  /// Refused: a pose or translation that is not finite, a rotation that
  /// is not unit.
  template <class Shape>
  [[nodiscard]] std::optional<world_ray_hit<T>> shape_cast(const Shape& shape, const transform<T>& pose,
                                                           const vec3<T>& translation,
                                                           const query_filter& filter = {}) const;

  /// f(body) for every body that `filter` sees whose shape overlaps
  /// `shape` (one of the config's shapes) at `pose`: touching counts.
  template <class Shape, class F>
  void shape_overlap(const Shape& shape, const transform<T>& pose, F&& f, const query_filter& filter = {}) const;

  // ---- drawing ----

  template <class D>
    requires debug_drawer<D, T>
  void draw(D& d, const debug_draw_flags& flags = {}) const {
    const in_callback scope(*this);
    detail::draw_world(state_, d, flags);
  }

  // ---- snapshot ----

  /// Everything a step reads: bodies, shapes, broad phase, contacts with
  /// their impulses, events, time and settings.
  [[nodiscard]] world_snapshot<Config> snapshot() const { return world_snapshot<Config>(state_); }
  void restore(const world_snapshot<Config>& s) {
    refuse_in_callback("world::restore: called from inside a world callback (for_each_contact, overlap, "
                       "visit_shape, draw); make the change after it returns");
    state_ = s.state_;
  }

  // ---- what is conserved, for tests and diagnostics ----

  /// Σ ½·m·v² + ½·ω·L over dynamic bodies, J.
  [[nodiscard]] T kinetic_energy() const noexcept {
    T e = T(0);
    for (const body_record& r : state_.bodies.values()) e += r.body.kinetic_energy();
    return e;
  }
  /// Gravitational (−m·g·x, zero at the origin) plus the springs' elastic
  /// energy, J (world_queries.hpp).
  [[nodiscard]] T potential_energy() const;
  /// Σ P over dynamic bodies, kg·m/s.
  [[nodiscard]] vec3<T> linear_momentum() const noexcept;
  /// Σ (x × P + L) over dynamic bodies, about the world origin, kg·m²/s.
  [[nodiscard]] vec3<T> angular_momentum() const noexcept;

 private:
  friend class world_snapshot<Config>;
  using body_record = detail::body_record<T>;
  using contact_record = detail::contact_record<T>;
  using joint_record = detail::joint_record<T>;

  void require(body_id id, const char* message) const {
    if (!state_.bodies.contains(id)) detail::report_error(error_code::out_of_range, message, id.index);
  }
  void require(joint_id id, const char* message) const {
    if (!state_.joints.contains(id)) detail::report_error(error_code::out_of_range, message, id.index);
  }
  void require(spring_id id, const char* message) const {
    if (!state_.springs.contains(id)) detail::report_error(error_code::out_of_range, message, id.index);
  }
  body_record& dynamic_record(body_id id, const char* message) {
    require(id, message);
    body_record& r = state_.bodies[id];
    if (r.body.type != body_type::dynamic)
      detail::report_error(error_code::invalid_parameter, "world: forces and impulses move dynamic bodies only",
                           id.index);
    return r;
  }

  /// create_body's part that does not depend on the shape: the record of a
  /// body made from `def`, its center of mass at `center` in shape space;
  /// refuses non-finite or impossible velocities.
  body_record prepare_body(const body_def<T>& def, rigid_body<T> body, const vec3<T>& center) const;
  /// Adds the record made by prepare_body, with its shape, and its proxy.
  body_id insert_body(const body_record& record);
  /// Stops the kinematic bodies that arrived at their targets last step and
  /// were given no new one.
  void expire_targets();

  void end_contacts_between(body_id a, body_id b);
  /// Where the ray meets the body within reach, if `filter` sees it.
  [[nodiscard]] std::optional<world_ray_hit<T>> ray_hit_of(body_id id, const ray<T>& r, T reach,
                                                            const query_filter& filter) const;
  /// A body about to go: its overlaps with sensors, or as a sensor, end.
  void end_sensor_overlaps(body_id id);
  /// Ends the contacts of `only` (of every body if none) that may_collide
  /// now refuses, waking their bodies, and has the next step pair anew.
  void end_filtered_contacts(body_id only);
  /// The step's start (checks dt, clears the last step's events) and its
  /// end (the clock, and the error naming a held body).
  void begin_step(T dt);
  void finish_step(T dt);

  state_type state_;
  detail::step_scratch<Config> scratch_;  ///< rebuilt by each step; not part of the state

  /// How many user callbacks are running (for_each_contact, overlap,
  /// visit_shape, draw). Not state: a copy of the world starts with none.
  struct callback_depth {
    int depth = 0;
    callback_depth() = default;
    callback_depth(const callback_depth&) noexcept {}
    callback_depth& operator=(const callback_depth&) noexcept { return *this; }
  };
  struct in_callback {
    const world& owner;
    explicit in_callback(const world& w) noexcept : owner(w) { ++owner.callbacks_.depth; }
    ~in_callback() { --owner.callbacks_.depth; }
    in_callback(const in_callback&) = delete;
    in_callback& operator=(const in_callback&) = delete;
  };
  mutable callback_depth callbacks_;
  void refuse_in_callback(const char* message) const {
    if (callbacks_.depth > 0) detail::report_error(error_code::invalid_parameter, message);
  }
};

// ---- the members defined outside the class ----
// They are not inline, so a translation unit that sees an explicit
// instantiation declaration of the world (IMPULSE_DECLARE_WORLD, or the
// default configs' under IMPULSE_EXTERN_TEMPLATES: world/extern_templates.hpp)
// neither instantiates nor compiles them, nor the pipeline they call: it
// only parses. Those kept in the class are short accessors.

template <class Config>
world<Config>::world(const settings_type& settings) {
  if constexpr (cross_platform_determinism)
    if (detail::contraction_in_effect() || detail::quat_product_fused())
      detail::report_error(error_code::invalid_parameter, detail::contraction_message);
  settings.validate();
  state_.settings = settings;
  state_.set_owner(detail::next_world_owner());
}
template <class Config>
world<Config>::world(const world&) = default;
template <class Config>
world<Config>::world(world&&) noexcept = default;
template <class Config>
world<Config>& world<Config>::operator=(const world&) = default;
template <class Config>
world<Config>& world<Config>::operator=(world&&) noexcept = default;
template <class Config>
world<Config>::~world() = default;

template <class Config>
void world<Config>::step(T dt) {
  detail::stopwatch whole, lap;
  step_profile& p = scratch_.profile;
  p = step_profile{};
  begin_step(dt);
  if constexpr (collision) {
    // The user's hooks and pair rule may read the world, and not change it.
    const in_callback scope(*this);
    detail::contact_update<Config>{state_, scratch_}.run(dt);  // broad and narrow
    lap.lap_ms();
    if constexpr (sleeping) detail::island_update<Config>{state_, scratch_}.wake();
    p.sleep = lap.lap_ms();
    detail::body_solve<Config>{state_, scratch_}.run(dt);  // prepare, solve and integrate
    lap.lap_ms();
    if constexpr (ccd) detail::continuous_collision<Config>{state_, scratch_}.run();
    p.continuous = lap.lap_ms();
    detail::sensor_update<Config>{state_, scratch_}.run();
    p.sensors = lap.lap_ms();
    if constexpr (sleeping) detail::island_update<Config>{state_, scratch_}.sleep(dt);
    p.sleep += lap.lap_ms();
  } else {
    detail::no_force_field none;
    detail::force_motion<Config>{state_, scratch_}.run(dt, none);
    p.integrate = lap.lap_ms();
  }
  finish_step(dt);
  p.total = whole.lap_ms();
}

template <class Config>
void world<Config>::begin_step(T dt) {
  refuse_in_callback("world::step: called from inside a world callback (for_each_contact, overlap, "
                     "visit_shape, draw); make the change after it returns");
  if (!(dt > T(0) && dt <= max_dt))
    detail::report_error(error_code::invalid_parameter, "world::step: dt must be positive and at most max_dt (1 s)");
  state_.begun.clear();
  state_.ended.clear();
  state_.sensor_begun.clear();
  state_.sensor_ended.clear();
  state_.broken.clear();
  state_.held.clear();
  scratch_.refused_settings = body_id{};
  scratch_.hook_error = nullptr;
  expire_targets();
}

template <class Config>
void world<Config>::finish_step(T dt) {
  state_.time += dt;
  state_.last_dt = dt;
  ++state_.step_count;
  if (!state_.held.empty())
    detail::report_error(error_code::non_finite,
                         "world::step: a body's motion overflowed (not finite, past max_linear_speed or "
                         "max_angular_speed, or beyond max_coordinate); it was held where it was, its contacts and joints left out of the "
                         "step, and the other bodies stepped on (held_bodies() lists every one)",
                         state_.held.front().index);
  if (scratch_.hook_error) {
    const std::exception_ptr caught = scratch_.hook_error;
    scratch_.hook_error = nullptr;
    std::rethrow_exception(caught);
  }
  if (!scratch_.refused_settings.is_none())
    detail::report_error(error_code::invalid_parameter,
                         "world::step: the pre-solve hook gave a contact a friction that is negative or not finite, a "
                         "restitution outside [0, 1] or a surface velocity that is not finite; the pair's own settings "
                         "were used and the step completed",
                         scratch_.refused_settings.index);
}

template <class Config>
auto world<Config>::advance(T frame_dt) -> T {
  if (!std::isfinite(frame_dt) || frame_dt < T(0))
    detail::report_error(error_code::invalid_parameter, "world::advance: frame_dt must be finite and >= 0");
  const T h = state_.settings.fixed_dt;
  state_.accumulator += frame_dt;
  int steps = 0;
  // A step is due once the time left is within rounding of h: 2.5 steps
  // and then 0.5 more make three, though the sum falls an ulp short.
  const T due = h * (T(1) - T(64) * std::numeric_limits<T>::epsilon());
  while (state_.accumulator >= due && steps < state_.settings.max_steps_per_advance) {
    step(h);
    state_.accumulator = std::max(state_.accumulator - h, T(0));
    ++steps;
  }
  // Past the cap the remaining time is dropped: the simulation falls
  // behind the clock rather than trying to catch up ever harder.
  if (state_.accumulator >= due) state_.accumulator = std::fmod(state_.accumulator, h);
  return state_.accumulator / h;
}

/// A world's whole state, to restore it later exactly.
template <class Config>
class world_snapshot {
 public:
  world_snapshot() = default;

 private:
  friend class world<Config>;
  explicit world_snapshot(const detail::world_state<Config>& s) : state_(s) {}
  detail::world_state<Config> state_;
};

}  // namespace impulse

#include "world_bodies.hpp"
#include "world_forces.hpp"
#include "world_joints.hpp"
#include "world_queries.hpp"

#if IMPULSE_EXTERN_TEMPLATES
IMPULSE_DECLARE_NARROW_PHASE(float);
IMPULSE_DECLARE_NARROW_PHASE(double);
IMPULSE_DECLARE_SCALAR_PARTS(float);
IMPULSE_DECLARE_SCALAR_PARTS(double);
IMPULSE_DECLARE_WORLD(impulse::default_config);
IMPULSE_DECLARE_WORLD(impulse::default_double_config);
#endif
