// impulse/world/world.hpp — impulse::world<Config>: bodies with shapes and
// materials, stepped through the pipeline of docs/architecture.md.
//
// One step, in order (Box2D v3's order: collide from where the bodies are,
// then solve and move):
//
//   broad phase   each moving body's box, grown by the speculative
//                 distance, is moved; the broad phase reports the pairs.
//   narrow phase  each pair with a dynamic body gets its manifolds, from
//                 the dispatcher of the config's shape_list; points that
//                 keep their feature id keep their impulses (warm start).
//                 Pairs that start or stop touching become events.
//   islands       (sleeping on) union–find over touching contacts and
//                 joints; an island with any body awake is awake entirely.
//   solver        the config's solver (sequential_impulse, soft_step)
//                 applies this step's forces, solves the contacts and the
//                 joints (joint.hpp; trees of joints exactly,
//                 joint_tree.hpp) and moves the awake bodies, then moves
//                 them back onto their joints (project_joints); joints
//                 that pulled harder than their thresholds break.
//   continuous    (ccd on) fast bodies and bullets are swept from where
//                 they started the step and put back short of what they
//                 would have passed (continuous()).
//   sleeping      (sleeping on) an island whose every body has been slow
//                 for sleep_time goes to sleep: no forces, no contacts
//                 solved, no narrow phase, until something wakes it.
//
// Bodies keep Baraff's state (rigid_body.hpp): the solver works on
// velocities v = P/m, ω = I_w⁻¹·L taken at the start of the step; the world
// writes back P = m·v, and L changed by the torque's impulse and by I_w
// times what the contacts did to ω, so that with no contact L is constant
// to the bit. The bodies then move by the config's integrator policy with
// L held and ω = R·I⁻¹·Rᵀ·L at each stage: a free body precesses as
// accurately as the integrator (RK4: fourth order). Forces are held
// constant over a step, so every integrator gives the same velocity
// change, F·dt/m; the integrator matters for the rotation, and for forces
// that depend on the state within a step (springs). A solver that moves the
// bodies itself (soft_step) holds ω through its substeps: ω is then the
// state, written back as L = I_w·ω at the pose reached, and the gyroscopic
// term is taken once a step, implicitly (gyroscopic_turn).
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
#include <limits>
#include <optional>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "../broadphase/broad_phase.hpp"
#include "../config.hpp"
#include "../core/error.hpp"
#include "../core/slot_map.hpp"
#include "../dynamics/body_motion.hpp"
#include "../dynamics/contact_constraint.hpp"
#include "../dynamics/island.hpp"
#include "../dynamics/joint.hpp"
#include "../dynamics/rigid_body.hpp"
#include "../narrowphase/dispatch.hpp"
#include "../narrowphase/epa.hpp"
#include "../narrowphase/ray_cast.hpp"
#include "../narrowphase/time_of_impact.hpp"
#include "body_def.hpp"
#include "debug_draw.hpp"
#include "fwd.hpp"
#include "shape_store.hpp"
#include "world_traits.hpp"

namespace impulse {

template <class Config>
class world {
  static_assert(check_config<Config>());

 public:
  using config = Config;
  using scalar = typename Config::scalar;
  using T = scalar;
  using shapes = typename detail::world_shapes<Config>::type;
  using broad_phase_type = typename detail::world_broadphase<Config>::type::template type<T>;
  using solver_policy = typename detail::world_solver<Config>::type;
  using solver_type = typename solver_policy::template type<T>;
  using integrator = typename Config::integrator;
  static constexpr bool sleeping = detail::world_sleeping<Config>();
  /// Whether fast bodies and bullets are swept (continuous collision); off,
  /// the sweeping code is not compiled.
  static constexpr bool ccd = detail::world_ccd<Config>();
  /// Manifolds one pair can have: one for two convex shapes, one per
  /// distinct normal against a mesh (a box in a corner of it: two or three).
  static constexpr int max_manifolds = 4;
  /// The longest step, s: a step is a small piece of motion, and one of a
  /// thousand years (finite) would carry every body out of finite numbers.
  static constexpr T max_dt = T(1);

  static_assert(broadphase::broad_phase<broad_phase_type, T>,
                "impulse world: the config's broadphase is not a broad phase for its scalar");

  explicit world(const world_settings<T>& settings = {});
  // Declared here and defaulted after the class, so that an explicit
  // instantiation declaration (IMPULSE_DECLARE_WORLD) keeps them, and all
  // that the members' destructors instantiate, out of other translation units.
  world(const world& other);
  world(world&& other) noexcept;
  world& operator=(const world& other);
  world& operator=(world&& other) noexcept;
  ~world();

  // ---- settings ----

  [[nodiscard]] const world_settings<T>& settings() const noexcept { return state_.settings; }
  void set_settings(const world_settings<T>& settings) {
    settings.validate();
    state_.settings = settings;
  }
  /// Refused: gravity that is not finite, or stronger than
  /// max_linear_speed per second (world_settings::validate).
  void set_gravity(const vec3<T>& g) {
    if (!is_finite(g)) detail::report_error(error_code::non_finite, "world::set_gravity: gravity is not finite");
    world_settings<T> changed = state_.settings;
    changed.gravity = g;
    changed.validate();
    state_.settings = changed;
    wake_all();
  }

  // ---- bodies ----

  /// Makes a body of `shape` (one of the config's shapes) as `def` says.
  /// A dynamic body takes the shape's exact mass properties at
  /// def.material.density, or scaled to def.mass. Bad input (a degenerate
  /// shape, a non-finite or non-unit pose, a dynamic plane or mesh, an
  /// infinite or negative mass) is refused and the world is unchanged.
  template <class Shape>
  body_id create_body(const body_def<T>& def, const Shape& shape) {
    static_assert(detail::shape_store<shapes, T>::template index_of<Shape>() < shapes::size,
                  "impulse world: this shape is not in the config's shape_list");
    refuse_in_callback("world::create_body: called from inside a world callback (for_each_contact, overlap, "
                       "visit_shape, draw); make the change after it returns");
    // Every shape is checked here; a hull or mesh only for being empty
    // (moved from), since their factories checked the rest.
    if constexpr (requires { shape.validate(); }) shape.validate();
    def.material.validate();
    const rigid_body<T> body = make_body(def, shape);  // checks the pose, the mass and the type
    const vec3<T> center = def.type == body_type::dynamic ? centre_of_mass(def, shape) : vec3<T>{};
    body_record record = prepare_body(def, body, center);  // checks the velocities
    if constexpr (!std::is_same_v<Shape, plane<T>>) {  // a plane is unbounded by nature
      const aabb<T> box = shape.world_aabb(def.pose);
      if (!within_bounds(box.lower) || !within_bounds(box.upper))
        detail::report_error(error_code::invalid_parameter,
                             "world::create_body: the shape reaches farther than max_coordinate from the origin");
    }
    // Nothing below can fail on the input.
    record.shape = state_.shape_store.add(shape);
    record.thinnest = thinnest_half_extent(shape);
    return insert_body(record);
  }

  /// Removes a body, its contacts and its joints; the bodies it touched or
  /// was joined to wake. A stale or destroyed id is refused.
  void destroy_body(body_id id);

  [[nodiscard]] bool contains(body_id id) const noexcept { return state_.bodies.contains(id); }
  [[nodiscard]] std::size_t body_count() const noexcept { return state_.bodies.size(); }
  /// Every live body, in storage order.
  [[nodiscard]] std::span<const body_id> body_ids() const noexcept { return state_.bodies.ids(); }
  /// A body's state (position of its centre of mass, orientation, momenta,
  /// mass properties).
  [[nodiscard]] const rigid_body<T>& body(body_id id) const {
    require(id, "world::body: no such body");
    return state_.bodies[id].body;
  }
  /// Where the body's shape is: its origin and orientation.
  [[nodiscard]] transform<T> shape_pose(body_id id) const {
    require(id, "world::shape_pose: no such body");
    return shape_pose_of(state_.bodies[id]);
  }
  /// The shape pose between the last two steps: alpha 0 at the start of
  /// the last step, 1 at its end (advance() returns the alpha of the time
  /// left over). Rendering at it hides the fixed step's stutter. Refused:
  /// alpha outside [0, 1] or NaN.
  [[nodiscard]] transform<T> interpolated_pose(body_id id, T alpha) const {
    require(id, "world::interpolated_pose: no such body");
    if (!(alpha >= T(0) && alpha <= T(1)))
      detail::report_error(error_code::invalid_parameter, "world::interpolated_pose: alpha must be within [0, 1]",
                           id.index);
    const body_record& r = state_.bodies[id];
    const transform<T> now = r.body.pose();
    quat<T> q1 = now.rotation;
    if (dot(r.previous.rotation, q1) < T(0)) q1 = q1 * T(-1);  // the short way round
    const transform<T> centre{lerp(r.previous.position, now.position, alpha),
                              normalize(r.previous.rotation * (T(1) - alpha) + q1 * alpha)};
    return {centre.position - rotate(centre.rotation, r.center), centre.rotation};
  }
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
    std::size_t n = 0;
    for (const body_record& r : state_.bodies.values()) n += r.body.type == body_type::dynamic && r.awake;
    return n;
  }

  /// Sets a body's velocities (a dynamic or kinematic body) and wakes it.
  /// Refused: speeds above world_settings::max_linear_speed or
  /// max_angular_speed, and velocities whose momenta overflow.
  void set_velocity(body_id id, const vec3<T>& linear, const vec3<T>& angular) {
    require(id, "world::set_velocity: no such body");
    body_record& r = state_.bodies[id];
    require_speeds(linear, angular, "world::set_velocity: faster than max_linear_speed or max_angular_speed", id);
    r.body.set_velocity(linear, angular);  // refuses non-finite values and static bodies
    wake_record(r);
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
  /// A force through the centre of mass for the next step, N.
  void apply_force(body_id id, const vec3<T>& force) {
    body_record& r = dynamic_record(id, "world::apply_force: no such body");
    r.body.apply_force(force);
    wake_record(r);
  }
  /// A force at a world point for the next step, N.
  void apply_force_at(body_id id, const vec3<T>& force, const vec3<T>& point) {
    body_record& r = dynamic_record(id, "world::apply_force_at: no such body");
    r.body.apply_force_at(force, point);
    wake_record(r);
  }
  void apply_torque(body_id id, const vec3<T>& torque) {
    body_record& r = dynamic_record(id, "world::apply_torque: no such body");
    r.body.apply_torque(torque);
    wake_record(r);
  }
  /// An impulse at a world point, now, N·s.
  void apply_impulse_at(body_id id, const vec3<T>& impulse, const vec3<T>& point) {
    body_record& r = dynamic_record(id, "world::apply_impulse_at: no such body");
    r.body.apply_impulse_at(impulse, point);
    wake_record(r);
  }
  void wake(body_id id) {
    require(id, "world::wake: no such body");
    wake_record(state_.bodies[id]);
  }

  // ---- joints ----

  /// Joins two bodies as `def` says (joint.hpp). The anchors and axis are
  /// taken in the bodies' frames as they are now. Refused, with the world
  /// unchanged: a body given twice, a missing or destroyed body, two bodies
  /// neither of which is dynamic, non-finite anchors or axis, and the
  /// other bad values joint_def::validate names. Both bodies wake; unless
  /// def.collide_connected, their contacts with each other end.
  joint_id create_joint(const joint_def<T>& def);

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
    return measure(state_.joints[id]).position;
  }
  /// How far apart the joint's anchors on A and B are now, m: its error
  /// for a ball, hinge or fixed joint (a slider's anchors part along the
  /// axis, a distance joint's by its length).
  [[nodiscard]] T joint_separation(joint_id id) const {
    require(id, "world::joint_separation: no such joint");
    return length(measure(state_.joints[id]).separation);
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
  void set_joint_motor(joint_id id, bool enable, T speed, T max_force) {
    require(id, "world::set_joint_motor: no such joint");
    joint_record& r = state_.joints[id];
    joint_def<T> def = r.def;
    def.enable_motor = enable, def.motor_speed = speed, def.max_motor_force = max_force;
    def.validate();
    r.def = def;
    r.constraint.enable_motor = enable, r.constraint.motor_speed = speed, r.constraint.max_motor_force = max_force;
    if (!enable) r.constraint.motor_impulse = T(0);
    wake_joint(r);
  }
  /// Keeps a hinge's angle or a slider's translation within [lower, upper];
  /// enable false frees it. Wakes the bodies.
  void set_joint_limits(joint_id id, bool enable, T lower, T upper) {
    require(id, "world::set_joint_limits: no such joint");
    joint_record& r = state_.joints[id];
    joint_def<T> def = r.def;
    def.enable_limit = enable, def.lower = lower, def.upper = upper;
    def.validate();
    r.def = def;
    r.constraint.enable_limit = enable, r.constraint.lower = lower, r.constraint.upper = upper;
    if (!enable) r.constraint.lower_impulse = r.constraint.upper_impulse = T(0);
    wake_joint(r);
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

  /// Runs as many fixed steps (settings().fixed_dt) as the frame time and
  /// what was left over from the last call allow, at most
  /// max_steps_per_advance; returns the fraction of a step left over, the
  /// alpha for interpolated_pose.
  T advance(T frame_dt);

  [[nodiscard]] T time() const noexcept { return state_.time; }
  [[nodiscard]] std::uint64_t step_count() const noexcept { return state_.step_count; }

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
      for (int m = 0; m < count; ++m) manifolds[std::size_t(m)] = slot_of(c, m).manifold;
      f(c.a, c.b, std::span<const contact_manifold<T>>(manifolds.data(), std::size_t(count)));
    }
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

  /// The nearest body along the ray within max_fraction of its translation.
  [[nodiscard]] std::optional<world_ray_hit<T>> ray_cast(const ray<T>& r, T max_fraction = T(1)) const;

  /// f(body) for every body whose shape's bounding box overlaps `box`.
  template <class F>
  void overlap(const aabb<T>& box, F&& f) const {
    if (!is_finite(box.lower) || !is_finite(box.upper) || !is_valid(box))
      detail::report_error(error_code::invalid_parameter, "world::overlap: the box is not finite and ordered");
    const in_callback scope(*this);
    state_.broad.query(box, [&](proxy_id proxy) {
      const body_id id = unpack(state_.broad.user_data(proxy));
      if (overlaps(bounds_of(state_.bodies[id]), box)) f(id);
    });
  }

  // ---- drawing ----

  template <class D>
    requires debug_drawer<D, T>
  void draw(D& d, const debug_draw_flags& flags = {}) const {
    const in_callback scope(*this);
    if (flags.aabbs)
      for (const body_record& r : state_.bodies.values()) draw_box(d, bounds_of(r), colour_of(r));
    for (const contact_record& c : state_.contacts) {
      if (!c.touching) continue;
      for (int m = 0; m < c.manifold_count; ++m) {
        const contact_manifold<T>& manifold = slot_of(c, m).manifold;
        for (int i = 0; i < manifold.count; ++i) {
          const vec3<T>& p = manifold.points[std::size_t(i)].position;
          if (flags.contacts) d.point(p, debug_color{1, 0.2f, 0.2f});
          if (flags.normals) d.arrow(p, p + manifold.normal * T(0.2), debug_color{1, 1, 0.2f});
          if (flags.forces && state_.last_dt > T(0)) {
            const T force = slot_of(c, m).impulse.normal[std::size_t(i)] / state_.last_dt;
            d.arrow(p, p + manifold.normal * (force * T(0.01)), debug_color{1, 0.5f, 0});
          }
        }
      }
    }
    if (flags.velocities)
      for (const body_record& r : state_.bodies.values())
        if (r.body.type != body_type::static_body)
          d.arrow(r.body.position, r.body.position + r.body.linear_velocity() * T(0.1), debug_color{0.2f, 0.6f, 1});
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

  [[nodiscard]] T kinetic_energy() const noexcept {
    T e = T(0);
    for (const body_record& r : state_.bodies.values()) e += r.body.kinetic_energy();
    return e;
  }

 private:
  friend class world_snapshot<Config>;
  using dispatcher = narrowphase::dispatcher<shapes, T>;

  /// Where a kinematic body is with its set_target_pose: none, moving
  /// there in the coming step, or arrived (its velocities kept until the
  /// next step begins, then zeroed unless a new target came).
  enum class target_state : std::uint8_t { none, armed, arrived };

  struct body_record {
    rigid_body<T> body;
    impulse::material<T> material;
    detail::shape_handle shape;
    vec3<T> center{};      ///< centre of mass in shape space
    proxy_id proxy;
    transform<T> previous;  ///< the centre-of-mass pose at the start of the last step
    T sleep_timer = T(0);   ///< s spent below the sleep speeds
    bool awake = true;
    std::uint64_t user_data = 0;
    target_state target = target_state::none;  ///< kinematic: moving to a set_target_pose
    bool bullet = false;
    T thinnest = T(0);  ///< m: the shape's thinnest half-extent, what a step may cross before it is swept
  };

  /// One manifold of a touching pair: where it touches, the impulses the
  /// solver carries to the next step, and what the last full pair test
  /// found, in A's shape frame (reuse_manifolds carries it with the bodies).
  struct manifold_slot {
    contact_manifold<T> manifold;
    manifold_impulse<T> impulse;
    contact_manifold<T> tested_local;
  };

  /// A pair of bodies whose boxes overlap, and what the narrow phase and
  /// the solver know of it. Kept sorted by proxy pair, the broad phase's
  /// order, so that each step's pairs merge with the last step's in one
  /// pass, with no lookup. Its manifolds live in state::manifolds, so that
  /// a pair whose boxes overlap but whose shapes do not touch (most pairs
  /// in a heap) costs this record alone: 80 bytes in float, where it cost
  /// 1 KB with four manifolds inline.
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
  struct joint_record {
    joint_constraint<T> constraint;  ///< in the bodies' frames; body places set each step
    joint_def<T> def;                ///< as created
    body_id a, b;
    vec3<T> force{}, torque{};  ///< on B in the last step, N and N·m
    bool broken = false;
  };

  struct state {
    world_settings<T> settings{};
    slot_map<body_record, body_id> bodies;
    slot_map<joint_record, joint_id> joints;
    /// The body pairs joined without collide_connected (pair_key), sorted,
    /// once per such joint: their proxies' pairs make no contact.
    std::vector<std::uint64_t> joined;
    std::vector<joint_broken_event<T>> broken;
    std::vector<body_id> held;      ///< held in the last step (step())
    std::vector<body_id> targeted;  ///< kinematic bodies with a target_state other than none
    detail::shape_store<shapes, T> shape_store;
    broad_phase_type broad;
    std::vector<contact_record> contacts;
    std::vector<manifold_slot> manifolds;      ///< the touching pairs' manifolds
    std::vector<std::uint32_t> free_manifolds;  ///< slots of manifolds no pair holds
    std::size_t pairs_over_limit = 0;          ///< in the last step: see pairs_over_limit()
    std::vector<contact_event> begun, ended;
    T time = T(0), accumulator = T(0), last_dt = T(0);
    std::uint64_t step_count = 0;
  };

  // ---- bodies ----

  void require(body_id id, const char* message) const {
    if (!state_.bodies.contains(id)) detail::report_error(error_code::out_of_range, message, id.index);
  }
  void require(joint_id id, const char* message) const {
    if (!state_.joints.contains(id)) detail::report_error(error_code::out_of_range, message, id.index);
  }

  /// Stops the kinematic bodies that arrived at their targets last step and
  /// were given no new one.
  void expire_targets() {
    std::erase_if(state_.targeted, [&](body_id id) {
      if (!state_.bodies.contains(id)) return true;
      body_record& r = state_.bodies[id];
      if (r.target != target_state::arrived) return false;
      r.body.set_velocity({}, {});
      r.target = target_state::none;
      return true;
    });
  }

  // ---- joints ----

  static std::uint64_t pair_key(body_id a, body_id b) noexcept {
    const std::uint32_t low = std::min(a.index, b.index), high = std::max(a.index, b.index);
    return (std::uint64_t(high) << 32) | low;
  }
  bool joined(body_id a, body_id b) const noexcept {
    return !state_.joined.empty() && std::binary_search(state_.joined.begin(), state_.joined.end(), pair_key(a, b));
  }
  /// Lets the joint's bodies collide again (if it had stopped them).
  void unjoin(const joint_record& r) {
    if (r.def.collide_connected) return;
    const auto at = std::lower_bound(state_.joined.begin(), state_.joined.end(), pair_key(r.a, r.b));
    if (at != state_.joined.end() && *at == pair_key(r.a, r.b)) state_.joined.erase(at);
  }
  void end_contacts_between(body_id a, body_id b) {
    std::erase_if(state_.contacts, [&](const contact_record& c) {
      if (!((c.a == a && c.b == b) || (c.a == b && c.b == a))) return false;
      end_contact(c);
      return true;
    });
  }
  void wake_joint(const joint_record& r) {
    wake_record(state_.bodies[r.a]);
    wake_record(state_.bodies[r.b]);
  }
  /// The joint's parts and errors at the bodies' present poses.
  joint_constraint<T> measure(const joint_record& r) const {
    std::array<solver_body<T>, 2> ends{};
    const rigid_body<T>& a = state_.bodies[r.a].body;
    const rigid_body<T>& b = state_.bodies[r.b].body;
    ends[0].position = a.position, ends[0].orientation = a.orientation;
    ends[1].position = b.position, ends[1].orientation = b.orientation;
    joint_constraint<T> c = r.constraint;
    c.body_a = 0, c.body_b = 1;
    detail::prepare_joint(std::span<const solver_body<T>>(ends), c);
    return c;
  }
  /// Whether a point is within max_coordinate of the origin on every axis
  /// (false for NaN).
  bool within_bounds(const vec3<T>& p) const noexcept {
    const T m = state_.settings.max_coordinate;
    return std::abs(p.x) <= m && std::abs(p.y) <= m && std::abs(p.z) <= m;
  }
  void require_within_bounds(const vec3<T>& p, const char* message, body_id id = body_id{}) const {
    if (is_finite(p) && !within_bounds(p)) detail::report_error(error_code::invalid_parameter, message, id.index);
  }
  /// Refuses a joint anchor farther from a dynamic body's centre of mass
  /// than world_settings::max_joint_lever radii of gyration.
  void require_lever(const rigid_body<T>& b, const vec3<T>& anchor, body_id id) const {
    if (b.type != body_type::dynamic) return;
    const T smallest = std::min({b.inertia(0, 0), b.inertia(1, 1), b.inertia(2, 2)});
    const T reach = state_.settings.max_joint_lever;
    if (!(length_squared(anchor - b.position) * b.mass <= reach * reach * smallest))
      detail::report_error(error_code::invalid_parameter,
                           "world::create_joint: an anchor is farther from a dynamic body than max_joint_lever "
                           "radii of gyration",
                           id.index);
  }
  /// Whether both speeds are within the world's limits (false for NaN).
  bool within_speed_limits(const vec3<T>& linear, const vec3<T>& angular) const noexcept {
    const T v = state_.settings.max_linear_speed, w = state_.settings.max_angular_speed;
    return length_squared(linear) <= v * v && length_squared(angular) <= w * w;
  }
  void require_speeds(const vec3<T>& linear, const vec3<T>& angular, const char* message,
                      body_id id = body_id{}) const {
    if (is_finite(linear) && is_finite(angular) && !within_speed_limits(linear, angular))
      detail::report_error(error_code::invalid_parameter, message, id.index);
  }
  body_record& dynamic_record(body_id id, const char* message) {
    require(id, message);
    body_record& r = state_.bodies[id];
    if (r.body.type != body_type::dynamic)
      detail::report_error(error_code::invalid_parameter, "world: forces and impulses move dynamic bodies only",
                           id.index);
    return r;
  }

  /// create_body's part that does not depend on the shape, defined outside
  /// the class: the record of a body made from `def`, its centre of mass
  /// at `center` in shape space; refuses non-finite or impossible velocities.
  body_record prepare_body(const body_def<T>& def, rigid_body<T> body, const vec3<T>& center) const;
  /// Adds the record made by prepare_body, with its shape, and its proxy.
  body_id insert_body(const body_record& record);

  template <class Shape>
  static rigid_body<T> make_body(const body_def<T>& def, const Shape& shape) {
    if (!std::isfinite(def.mass) || def.mass < T(0))
      detail::report_error(error_code::non_finite,
                           "world::create_body: mass must be finite and >= 0 (a body that cannot move is static)");
    if (def.type != body_type::dynamic) return rigid_body<T>::fixed(def.type, def.pose);
    if constexpr (requires { mass_properties_of(shape, T(1)); }) {
      mass_properties<T> p = mass_properties_of(shape, def.material.density);
      if (def.mass > T(0)) {
        p.inertia = p.inertia * (def.mass / p.mass);
        p.mass = def.mass;
      }
      rigid_body<T> b = rigid_body<T>::dynamic({p.mass, vec3<T>{}, p.inertia}, def.pose);
      return b;
    } else {
      detail::report_error(error_code::invalid_parameter,
                           "world::create_body: planes and triangle meshes can only be static or kinematic");
    }
  }
  template <class Shape>
  static vec3<T> centre_of_mass(const body_def<T>& def, const Shape& shape) {
    if constexpr (requires { mass_properties_of(shape, T(1)); }) {
      return mass_properties_of(shape, def.material.density).center;
    } else {
      return {};
    }
  }

  static transform<T> shape_pose_of(const body_record& r) noexcept {
    return {r.body.position - rotate(r.body.orientation, r.center), r.body.orientation};
  }
  aabb<T> bounds_of(const body_record& r) const {
    const transform<T> pose = shape_pose_of(r);
    return state_.shape_store.visit(r.shape, [&](const auto& s) { return s.world_aabb(pose); });
  }
  aabb<T> proxy_box(const body_record& r) const {
    const aabb<T> box = expand(bounds_of(r), state_.settings.solver.speculative_distance);
    // A plane's box spans every finite value already: grown, it must not
    // overflow into infinities the broad phase refuses.
    const vec3<T> big = vec3<T>::splat(std::numeric_limits<T>::max());
    return {max(box.lower, -big), min(box.upper, big)};
  }
  typename dispatcher::shape_ref shape_ref_of(const body_record& r) const noexcept {
    return {state_.shape_store.address(r.shape), r.shape.type};
  }

  static std::uint64_t pack(body_id id) noexcept { return std::uint64_t(id.index) | (std::uint64_t(id.generation) << 32); }
  static body_id unpack(std::uint64_t data) noexcept {
    return body_id{std::uint32_t(data & 0xffffffffu), std::uint32_t(data >> 32)};
  }

  static void wake_record(body_record& r) noexcept {
    r.awake = true;
    r.sleep_timer = T(0);
  }
  void wake_all() noexcept {
    for (body_record& r : state_.bodies.values()) wake_record(r);
  }
  static bool is_moving(const body_record& r) noexcept {
    if (r.body.type == body_type::dynamic) return r.awake;
    if (r.body.type == body_type::kinematic)
      return r.body.kinematic_velocity != vec3<T>{} || r.body.kinematic_angular_velocity != vec3<T>{};
    return false;
  }

  // ---- broad phase ----

  void update_broad_phase() {
    for (const body_record& r : state_.bodies.values())
      if (is_moving(r)) state_.broad.move(r.proxy, proxy_box(r));
    state_.broad.update();
  }

  // ---- narrow phase ----

  /// How far a pair may move before its pair test runs again
  /// (world_settings::contact_reuse_distance and _angle), as collide
  /// compares them.
  struct reuse_limits {
    T distance_squared;
    T cos_half_angle;
  };

  void update_contacts() {
    const std::span<const proxy_pair> pairs = state_.broad.pairs();
    std::vector<contact_record>& old = state_.contacts;
    const world_settings<T>& s = state_.settings;
    const reuse_limits limits{s.contact_reuse_distance * s.contact_reuse_distance,
                              std::cos(s.contact_reuse_angle / T(2))};
    // Most steps have the last step's pairs: then the records are updated
    // where they are, rather than copied over.
    if (same_pairs(pairs)) {
      for (contact_record& c : old) collide(c, limits);
      return;
    }
    next_contacts_.clear();
    next_contacts_.reserve(std::min(pairs.size(), std::size_t(s.max_contact_pairs)));
    // New pairs are taken while the records, old and new, stay within
    // max_contact_pairs; those past it wait, and are counted.
    const std::size_t room = std::size_t(s.max_contact_pairs) > old.size() ? s.max_contact_pairs - old.size() : 0;
    std::size_t created = 0;
    state_.pairs_over_limit = 0;
    std::size_t i = 0;
    for (const proxy_pair& pair : pairs) {
      while (i < old.size() && old[i].key < pair) end_contact(old[i++]);
      if (i < old.size() && old[i].key == pair) {
        next_contacts_.push_back(old[i++]);
      } else {
        if (!may_touch(pair)) continue;
        if (created == room) {
          ++state_.pairs_over_limit;
          continue;
        }
        ++created;
        const body_id a = unpack(state_.broad.user_data(pair.a)), b = unpack(state_.broad.user_data(pair.b));
        const body_record& ra = state_.bodies[a];
        const body_record& rb = state_.bodies[b];
        contact_record c{};
        c.key = pair;
        c.a = a, c.b = b;
        c.friction = combine_friction(ra.material.friction, rb.material.friction);
        c.restitution = combine_restitution(ra.material.restitution, rb.material.restitution);
        next_contacts_.push_back(c);
      }
      collide(next_contacts_.back(), limits);
    }
    while (i < old.size()) end_contact(old[i++]);
    old.swap(next_contacts_);
  }

  /// Whether a pair of proxies can make contact: one of its bodies is
  /// dynamic, and no joint between them keeps them apart.
  bool may_touch(const proxy_pair& pair) const {
    const body_id a = unpack(state_.broad.user_data(pair.a)), b = unpack(state_.broad.user_data(pair.b));
    const body_record& ra = state_.bodies[a];
    const body_record& rb = state_.bodies[b];
    return (ra.body.type == body_type::dynamic || rb.body.type == body_type::dynamic) && !joined(a, b);
  }

  /// Whether the broad phase's pairs, less those that cannot touch, are
  /// the records' pairs.
  bool same_pairs(std::span<const proxy_pair> pairs) const {
    const std::vector<contact_record>& old = state_.contacts;
    std::size_t i = 0;
    for (const proxy_pair& pair : pairs) {
      if (i < old.size() && old[i].key == pair) ++i;
      else if (may_touch(pair)) return false;
    }
    return i == old.size();
  }

  /// A record that is dropped: its pair ends, its manifolds are freed.
  void end_contact(const contact_record& c) {
    if (c.touching) state_.ended.push_back({c.a, c.b});
    for (int m = 0; m < c.manifold_count; ++m) state_.free_manifolds.push_back(c.slots[std::size_t(m)]);
  }

  manifold_slot& slot_of(const contact_record& c, int m) noexcept { return state_.manifolds[c.slots[std::size_t(m)]]; }
  const manifold_slot& slot_of(const contact_record& c, int m) const noexcept {
    return state_.manifolds[c.slots[std::size_t(m)]];
  }
  /// Gives the record n manifold slots, keeping its first ones: freed
  /// slots are reused before the pool grows.
  void resize_slots(contact_record& c, int n) {
    while (c.manifold_count > n) state_.free_manifolds.push_back(c.slots[std::size_t(--c.manifold_count)]);
    while (c.manifold_count < n) {
      std::uint32_t slot;
      if (!state_.free_manifolds.empty()) {
        slot = state_.free_manifolds.back();
        state_.free_manifolds.pop_back();
      } else {
        slot = std::uint32_t(state_.manifolds.size());
        state_.manifolds.emplace_back();
      }
      c.slots[std::size_t(c.manifold_count++)] = slot;
    }
  }

  void collide(contact_record& c, const reuse_limits& limits) {
    const body_record& ra = state_.bodies[c.a];
    const body_record& rb = state_.bodies[c.b];
    // Two bodies that are not moving keep their manifolds: sleeping ones
    // wake with the contacts they slept on.
    if (!is_moving(ra) && !is_moving(rb) && c.manifold_count > 0) return;
    const transform<T> pose_a = shape_pose_of(ra), pose_b = shape_pose_of(rb);
    const transform<T> relative{inverse_apply(pose_a, pose_b.position), conjugate(pose_a.rotation) * pose_b.rotation};
    if (c.tested && reuse_manifolds(c, pose_a, relative, limits)) return;
    std::array<contact_manifold<T>, max_manifolds> fresh;
    const std::size_t n = dispatcher::collide(shape_ref_of(ra), pose_a, shape_ref_of(rb), pose_b,
                                              state_.settings.solver.speculative_distance,
                                              std::span<contact_manifold<T>>(fresh.data(), fresh.size()));
    std::array<manifold_impulse<T>, max_manifolds> carried{};
    for (std::size_t m = 0; m < n; ++m) {
      // The old manifold with the nearest normal (a mesh's several keep
      // theirs apart), then each point by its feature id.
      int match = -1;
      T best = T(0.95);  // normals within 18° count as the same face
      for (int k = 0; k < c.manifold_count; ++k) {
        const T d = dot(slot_of(c, k).manifold.normal, fresh[m].normal);
        if (d > best) best = d, match = k;
      }
      if (match < 0) continue;
      const contact_manifold<T>& before = slot_of(c, match).manifold;
      const manifold_impulse<T>& had = slot_of(c, match).impulse;
      carried[m].friction = had.friction;
      carried[m].twist = had.twist;
      for (int p = 0; p < fresh[m].count; ++p)
        for (int q = 0; q < before.count; ++q)
          if (before.points[std::size_t(q)].feature == fresh[m].points[std::size_t(p)].feature) {
            carried[m].normal[std::size_t(p)] = had.normal[std::size_t(q)];
            break;
          }
    }
    resize_slots(c, int(n));
    c.tested = true;
    c.tested_relative = relative;
    for (std::size_t m = 0; m < n; ++m) {
      manifold_slot& slot = slot_of(c, int(m));
      slot.manifold = fresh[m];
      slot.impulse = carried[m];
      contact_manifold<T>& local = slot.tested_local;
      local = fresh[m];
      local.normal = inverse_rotate(pose_a.rotation, fresh[m].normal);
      for (int p = 0; p < local.count; ++p)
        local.points[std::size_t(p)].position = inverse_apply(pose_a, fresh[m].points[std::size_t(p)].position);
    }
    const bool touching = n > 0;
    if (touching && !c.touching) state_.begun.push_back({c.a, c.b});
    if (!touching && c.touching) state_.ended.push_back({c.a, c.b});
    c.touching = touching;
  }

  /// Keeps the manifolds of the pair's last full test while B has moved
  /// less than the reuse limits relative to A since then (a resting stack
  /// skips its pair tests), and returns whether it did. Each point lies
  /// midway between a point of A's surface and one of B's, `depth` apart
  /// along the normal: the one on A and the normal stay with A, the one on
  /// B is carried with B, and the depth and midpoint follow. For a corner
  /// of B on a face of A the depth is exact, and the midpoint lags the
  /// fresh one by half the corner's slide; a point clipped at the edge of
  /// A's face is carried past it by as much. (Bullet refreshes its
  /// persistent manifolds' points the same way; Jolt's body pair cache
  /// reuses manifolds within the same limits.)
  bool reuse_manifolds(contact_record& c, const transform<T>& pose_a, const transform<T>& relative,
                       const reuse_limits& limits) noexcept {
    const vec3<T> shift = relative.position - c.tested_relative.position;
    if (!(length_squared(shift) < limits.distance_squared)) return false;
    // B's turn in A's frame since the test; |w| = cos(angle / 2).
    const quat<T> turn = relative.rotation * conjugate(c.tested_relative.rotation);
    if (!(std::abs(turn.w) > limits.cos_half_angle)) return false;
    for (int m = 0; m < c.manifold_count; ++m) {
      manifold_slot& slot = slot_of(c, m);
      const contact_manifold<T>& local = slot.tested_local;
      contact_manifold<T>& out = slot.manifold;
      out.normal = rotate(pose_a.rotation, local.normal);
      for (int p = 0; p < local.count; ++p) {
        const contact_point<T>& tested = local.points[std::size_t(p)];
        const vec3<T> on_b = tested.position - local.normal * (tested.depth * T(0.5));
        const vec3<T> moved = rotate(turn, on_b - c.tested_relative.position) + relative.position - on_b;
        contact_point<T>& point = out.points[std::size_t(p)];
        point.depth = tested.depth - dot(moved, local.normal);
        point.position = apply(pose_a, tested.position + moved * T(0.5));
      }
    }
    return true;
  }

  // ---- continuous collision ----

  template <class Shape>
  static T thinnest_half_extent(const Shape& shape) noexcept {
    if constexpr (requires { shape.radius; }) {
      return shape.radius;  // a ball's, and a capsule's across
    } else if constexpr (requires { shape.local_aabb(); }) {
      const aabb<T> box = shape.local_aabb();
      const vec3<T> half = (box.upper - box.lower) * T(0.5);
      return std::min({half.x, half.y, half.z});
    } else {
      return std::numeric_limits<T>::infinity();  // planes and meshes are static or kinematic: never swept
    }
  }

  /// After the bodies have moved: each bullet, and each body that crossed
  /// more than ccd_motion_fraction of its thinnest half-extent, is swept
  /// from where it started the step to where it ended, and stopped ccd_gap
  /// short of the first body it would have met (Box2D v3's continuous
  /// stage: the rest of its step is lost, and the next step's speculative
  /// contact resolves the impact; its velocity is kept for that).
  void continuous() {
    std::vector<body_record>& bodies = state_.bodies.values();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const body_record& r = bodies[i];
      if (!is_solved(r) || held(std::uint32_t(i))) continue;
      const T moved = length(r.body.position - r.previous.position);
      if (r.bullet || moved > state_.settings.ccd_motion_fraction * r.thinnest) sweep_back(i);
    }
  }

  void sweep_back(std::size_t i) {
    body_record& r = state_.bodies.values()[i];
    const body_id id = state_.bodies.ids()[i];
    const narrowphase::sweep<T> path{{r.previous.position - rotate(r.previous.rotation, r.center), r.previous.rotation},
                                     shape_pose_of(r), r.center};
    const aabb<T> swept = state_.shape_store.visit(r.shape, [&](const auto& s) {
      return merge(s.world_aabb(path.start), s.world_aabb(path.end));
    });
    T first = T(1);
    state_.broad.query(swept, [&](proxy_id proxy) {
      const body_id other = unpack(state_.broad.user_data(proxy));
      if (other == id || joined(id, other)) return;
      const body_record& o = state_.bodies[other];
      // Fast bodies meet the world; bullets meet moving bodies too, but
      // not each other (each is already swept).
      if (o.body.type == body_type::dynamic && (!r.bullet || o.bullet)) return;
      const narrowphase::sweep<T> other_path{
          {o.previous.position - rotate(o.previous.rotation, o.center), o.previous.rotation}, shape_pose_of(o),
          o.center};
      first = std::min(first, impact_time(r, path, o, other_path));
    });
    if (!(first < T(1))) return;
    const transform<T> at = narrowphase::sweep_motion<T>(path).at(first);
    r.body.position = apply(at, r.center);
    r.body.orientation = at.rotation;
  }

  /// When r, moving along path, first comes within ccd_gap of o moving along
  /// its own; 1 if not within the step. Convex pairs by convex_impact_time;
  /// a mesh triangle by triangle (mesh_impact_time). Planes are
  /// half-spaces, which nothing can cross unseen.
  T impact_time(const body_record& r, const narrowphase::sweep<T>& path, const body_record& o,
                const narrowphase::sweep<T>& other_path) const {
    return state_.shape_store.visit(r.shape, [&](const auto& mover) {
      return state_.shape_store.visit(o.shape, [&](const auto& target) {
        using M = std::decay_t<decltype(mover)>;
        using O = std::decay_t<decltype(target)>;
        constexpr bool convex_mover = requires(const M& m, vec3<T> d) { m.support(d); };
        constexpr bool convex_target = requires(const O& t, vec3<T> d) { t.support(d); };
        if constexpr (convex_mover && std::is_same_v<O, triangle_mesh<T>>) {
          return mesh_impact_time(mover, path, target, other_path);
        } else if constexpr (convex_mover && convex_target) {
          return convex_impact_time(mover, path, target, other_path);
        } else {
          return T(1);
        }
      });
    });
  }

  /// A convex pair. A ball against a body that does not turn is a sphere
  /// cast, exact; other pairs are conservative advancement
  /// (narrowphase/time_of_impact.hpp).
  template <class M, class O>
  T convex_impact_time(const M& mover, const narrowphase::sweep<T>& path, const O& target,
                       const narrowphase::sweep<T>& other_path) const {
    const T gap = state_.settings.ccd_gap;
    if constexpr (std::is_same_v<M, sphere<T>>) {
      if (other_path.start == other_path.end) {
        // The ball's centre against the body grown by its radius.
        const vec3<T> from = path.start.position, to = path.end.position;
        const T distance = length(to - from);
        const narrowphase::ray_hit<T> hit =
            narrowphase::sphere_cast(ray<T>{from, to - from}, mover.radius, target, other_path.start);
        // Starting within the grown body: the discrete contact has it (a
        // ball rolling fast on the ground is not stopped by it).
        if (!hit.hit || !(hit.fraction > T(0))) return T(1);
        const T t = hit.fraction - gap / distance;
        if (t > T(0)) return t;
        return passed(mover, path, target, other_path, -hit.normal) ? T(0) : T(1);
      }
    }
    narrowphase::toi_options<T> options;
    options.target = gap;
    options.tolerance = gap * T(0.25);
    const narrowphase::toi_result<T> hit = narrowphase::time_of_impact(mover, path, target, other_path, options);
    if (hit.state == narrowphase::toi_state::overlapping) return T(1);  // the discrete contacts have it
    if (hit.state == narrowphase::toi_state::separated) return T(1);
    if (hit.t > T(0)) return hit.t;
    return passed(mover, path, target, other_path, hit.normal) ? T(0) : T(1);
  }

  /// The earliest impact on any triangle of the mesh near the mover's
  /// sweep, each triangle a convex shape of its own.
  template <class M>
  T mesh_impact_time(const M& mover, const narrowphase::sweep<T>& path, const triangle_mesh<T>& mesh,
                     const narrowphase::sweep<T>& other_path) const {
    const aabb<T> swept = merge(mover.world_aabb(path.start), mover.world_aabb(path.end));
    aabb<T> near = transform_aabb(swept, inverse(other_path.start));
    if (!(other_path.start == other_path.end)) near = merge(near, transform_aabb(swept, inverse(other_path.end)));
    const vec3<T> gap = vec3<T>::splat(state_.settings.ccd_gap);
    T first = T(1);
    mesh.for_each_overlapping({near.lower - gap, near.upper + gap}, [&](std::size_t t) {
      narrowphase::detail::convex_triangle<T> triangle;
      mesh.triangle(t, triangle.v[0], triangle.v[1], triangle.v[2]);
      first = std::min(first, convex_impact_time(mover, path, triangle, other_path));
    });
    return first;
  }

  /// For a pair that starts the step within ccd_gap (normal: from the
  /// mover towards the other), whether the step ended with the mover
  /// through the other or deeper in it than ccd_gap. Such a pair is the
  /// discrete contacts' to handle, and they nearly always hold it; a body
  /// that turns fast under the contact's impulse can still swing through
  /// (a 2 cm plate hitting a wall at 150 m/s, spinning at 10 rad/s), and is
  /// then put back where it started the step.
  template <class M, class O>
  bool passed(const M& mover, const narrowphase::sweep<T>& path, const O& target,
              const narrowphase::sweep<T>& other_path, const vec3<T>& normal) const {
    const narrowphase::gjk_result<T> end = narrowphase::gjk_distance(mover, path.end, target, other_path.end);
    if (!end.overlapping) return dot(end.on_b - end.on_a, normal) < T(0);
    return narrowphase::epa_penetration(mover, path.end, target, other_path.end).depth > state_.settings.ccd_gap;
  }

  // ---- islands and sleeping ----

  void wake_islands() {
    std::vector<body_record>& bodies = state_.bodies.values();
    islands_.reset(bodies.size());
    // Dynamic bodies touching or joined are one island; one resting on (or
    // joined to) a kinematic body that moves wakes.
    const auto link = [&](std::uint32_t a, std::uint32_t b) {
      const body_type ta = bodies[a].body.type, tb = bodies[b].body.type;
      if (ta == body_type::dynamic && tb == body_type::dynamic) {
        islands_.unite(a, b);
      } else if (ta == body_type::kinematic && tb == body_type::dynamic && is_moving(bodies[a])) {
        wake_record(bodies[b]);
      } else if (tb == body_type::kinematic && ta == body_type::dynamic && is_moving(bodies[b])) {
        wake_record(bodies[a]);
      }
    };
    for (const contact_record& c : state_.contacts)
      if (c.touching) link(dense(c.a), dense(c.b));
    for (const joint_record& j : state_.joints.values())
      if (!j.broken) link(dense(j.a), dense(j.b));
    island_flag_.assign(bodies.size(), 0);
    for (std::uint32_t i = 0; i < bodies.size(); ++i)
      if (bodies[i].body.type == body_type::dynamic && bodies[i].awake) island_flag_[islands_.find(i)] = 1;
    for (std::uint32_t i = 0; i < bodies.size(); ++i)
      if (bodies[i].body.type == body_type::dynamic && !bodies[i].awake && island_flag_[islands_.find(i)])
        wake_record(bodies[i]);
  }

  void update_sleep(T dt) {
    std::vector<body_record>& bodies = state_.bodies.values();
    const world_settings<T>& s = state_.settings;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      body_record& r = bodies[i];
      if (r.body.type != body_type::dynamic || !r.awake) continue;
      // A body still being pushed out of a penetration is not at rest,
      // though its velocity is: it would sleep sunk in.
      // The correction speed is held to a tenth of the sleep speeds: 5 mm/s
      // is 0.4 mm of penetration beyond the slop at the default rate.
      const solver_body<T>& motion = solver_bodies_[i];
      const T linear = s.sleep_linear_speed, angular = s.sleep_angular_speed;
      const bool slow = length_squared(r.body.linear_velocity()) <= linear * linear &&
                        length_squared(r.body.angular_velocity()) <= angular * angular &&
                        length_squared(motion.bias_linear) <= T(0.01) * linear * linear &&
                        length_squared(motion.bias_angular) <= T(0.01) * angular * angular;
      r.sleep_timer = slow ? r.sleep_timer + dt : T(0);
    }
    // A body carried by (or joined to) a moving kinematic body stays awake.
    for (const contact_record& c : state_.contacts) {
      if (!c.touching) continue;
      body_record& a = state_.bodies[c.a];
      body_record& b = state_.bodies[c.b];
      if (a.body.type == body_type::kinematic && is_moving(a)) b.sleep_timer = T(0);
      if (b.body.type == body_type::kinematic && is_moving(b)) a.sleep_timer = T(0);
    }
    for (const joint_record& j : state_.joints.values()) {
      if (j.broken) continue;
      body_record& a = state_.bodies[j.a];
      body_record& b = state_.bodies[j.b];
      if (a.body.type == body_type::kinematic && is_moving(a)) b.sleep_timer = T(0);
      if (b.body.type == body_type::kinematic && is_moving(b)) a.sleep_timer = T(0);
    }
    island_timer_.assign(bodies.size(), std::numeric_limits<T>::infinity());
    for (std::uint32_t i = 0; i < bodies.size(); ++i)
      if (bodies[i].body.type == body_type::dynamic && bodies[i].awake) {
        T& t = island_timer_[islands_.find(i)];
        t = std::min(t, bodies[i].sleep_timer);
      }
    for (std::uint32_t i = 0; i < bodies.size(); ++i) {
      body_record& r = bodies[i];
      if (r.body.type != body_type::dynamic || !r.awake || island_timer_[islands_.find(i)] < s.sleep_time) continue;
      r.awake = false;
      r.body.linear_momentum = {};
      r.body.angular_momentum = {};
    }
  }

  // ---- solver ----

  std::uint32_t dense(body_id id) const noexcept { return std::uint32_t(state_.bodies.dense_index(id)); }

  static bool is_solved(const body_record& r) noexcept { return r.body.type == body_type::dynamic && r.awake; }

  /// Holds body i for this step: it keeps its pose, loses its velocity,
  /// and its contacts and joints are left out (step()).
  void hold(std::size_t i) {
    held_[i] = 1;
    solver_body<T>& s = solver_bodies_[i];
    s.inverse_mass = T(0);
    s.inverse_inertia = mat3<T>{};
    s.linear_velocity = s.angular_velocity = s.force_linear = s.force_angular = vec3<T>{};
    state_.held.push_back(state_.bodies.ids()[i]);
  }
  bool held(std::uint32_t i) const noexcept { return held_[i] != 0; }

  void solve(T dt) {
    std::vector<body_record>& bodies = state_.bodies.values();
    const vec3<T> gravity_step = state_.settings.gravity * dt;
    solver_bodies_.resize(bodies.size());
    held_.assign(bodies.size(), 0);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const rigid_body<T>& b = bodies[i].body;
      solver_body<T>& s = solver_bodies_[i];
      s = solver_body<T>{};
      s.position = b.position;
      s.orientation = b.orientation;
      if (is_solved(bodies[i])) {
        s.inverse_mass = b.inverse_mass;
        s.inverse_inertia = b.inverse_inertia_world();
        s.linear_velocity = b.linear_momentum * b.inverse_mass;
        s.angular_velocity = s.inverse_inertia * b.angular_momentum;
        s.force_linear = gravity_step + b.force * (b.inverse_mass * dt);
        s.force_angular = s.inverse_inertia * (b.torque * dt);
        if constexpr (solver_policy::moves_bodies) s.force_angular += gyroscopic_turn(b, s.angular_velocity, dt);
        // A body its loads would take out of finite numbers, or past the
        // speed limits, is held before anything couples it to another: a
        // joint solved with it would carry the overflow into its partner.
        if (!within_speed_limits(s.linear_velocity + s.force_linear, s.angular_velocity + s.force_angular)) hold(i);
      } else if (b.type == body_type::kinematic) {
        s.linear_velocity = b.kinematic_velocity;
        s.angular_velocity = b.kinematic_angular_velocity;
      }
    }
    // How long the bodies move in a straight line at a time.
    const T move_dt = solver_policy::moves_bodies ? dt / T(state_.settings.solver.substeps) : dt;
    constraints_.clear();
    sources_.clear();
    // Reserved exactly: grown by doubling, the largest per-step array
    // would hold up to twice what it needs, and three times while it moves.
    std::size_t manifold_count = 0;
    for (const contact_record& c : state_.contacts) manifold_count += c.manifold_count;
    constraints_.reserve(manifold_count);
    sources_.reserve(manifold_count);
    for (std::uint32_t k = 0; k < state_.contacts.size(); ++k) {
      const contact_record& c = state_.contacts[k];
      if (!c.touching) continue;
      const std::uint32_t ia = dense(c.a), ib = dense(c.b);
      if (held(ia) || held(ib) || (!is_solved(bodies[ia]) && !is_solved(bodies[ib]))) continue;
      for (int m = 0; m < c.manifold_count; ++m) {
        const contact_manifold<T>& manifold = slot_of(c, m).manifold;
        contact_constraint<T> cc;
        cc.body_a = ia, cc.body_b = ib;
        cc.normal = manifold.normal;
        cc.friction = c.friction;
        cc.restitution = c.restitution;
        cc.count = manifold.count;
        // Friction acts at the middle of the patch, with the mean distance
        // of the points from it, times 2/3, as the lever of its twist: the
        // mean radius of a uniformly pressed disc through its points.
        vec3<T> middle{};
        for (int p = 0; p < manifold.count; ++p) middle += manifold.points[std::size_t(p)].position;
        middle = middle * (T(1) / T(manifold.count));
        T spread = T(0);
        for (int p = 0; p < manifold.count; ++p) spread += length(manifold.points[std::size_t(p)].position - middle);
        cc.twist_radius = spread * (T(2) / T(3)) / T(manifold.count);
        cc.anchor_a = middle - bodies[ia].body.position;
        cc.anchor_b = middle - bodies[ib].body.position;
        // The slip at the middle of the patch chooses the tangents.
        const vec3<T> slip = relative_velocity(solver_bodies_[ia], solver_bodies_[ib], cc.anchor_a, cc.anchor_b);
        slip_tangents(cc.normal, slip, state_.settings.solver.rest_slip_speed, cc.tangent1, cc.tangent2);
        // The positions move each centre in a straight line while each body
        // turns exactly, so two points that move together at the velocity
        // level part over the step by ½dt²·(ω_B×(ω_B×r_B) − ω_A×(ω_A×r_A)):
        // a box stuck 2 m out on a platform turning at 1 rad/s crept
        // outward 1.7 cm/s. Friction holds the patch at the relative
        // velocity that cancels it (per substep, for a substepping solver,
        // which moves the bodies in straight lines that much shorter).
        const solver_body<T>& sa = solver_bodies_[ia];
        const solver_body<T>& sb = solver_bodies_[ib];
        const vec3<T> curving = cross(sb.angular_velocity, cross(sb.angular_velocity, cc.anchor_b)) -
                                cross(sa.angular_velocity, cross(sa.angular_velocity, cc.anchor_a));
        cc.slip_target1 = dot(curving, cc.tangent1) * (-move_dt / T(2));
        cc.slip_target2 = dot(curving, cc.tangent2) * (-move_dt / T(2));
        const manifold_impulse<T>& carried = slot_of(c, m).impulse;
        cc.tangent_impulse1 = dot(carried.friction, cc.tangent1);
        cc.tangent_impulse2 = dot(carried.friction, cc.tangent2);
        cc.twist_impulse = carried.twist;
        for (int p = 0; p < manifold.count; ++p) {
          const contact_point<T>& point = manifold.points[std::size_t(p)];
          contact_constraint_point<T>& cp = cc.points[p];
          cp.offset_a = point.position - bodies[ia].body.position;
          cp.offset_b = point.position - bodies[ib].body.position;
          cp.depth = point.depth;
          cp.normal_impulse = carried.normal[std::size_t(p)];
        }
        constraints_.push_back(cc);
        sources_.push_back({k, std::uint32_t(m)});
      }
    }
    if (state_.settings.solver.warm_starting) {
      // A substepping solver's impulses are per substep.
      estimate_cold_loads(solver_policy::moves_bodies ? dt / T(state_.settings.solver.substeps) : dt);
    }
    joints_.clear();
    joint_sources_.clear();
    for (std::uint32_t k = 0; k < state_.joints.size(); ++k) {
      const joint_record& r = state_.joints.values()[k];
      if (r.broken) continue;
      const std::uint32_t ia = dense(r.a), ib = dense(r.b);
      if (held(ia) || held(ib) || (!is_solved(bodies[ia]) && !is_solved(bodies[ib]))) continue;
      joints_.push_back(r.constraint);
      joints_.back().body_a = ia, joints_.back().body_b = ib;
      joint_sources_.push_back(k);
    }
    solver_.prepare(solver_bodies_, constraints_);
    solver_.solve(solver_bodies_, constraints_, joints_, state_.settings.solver, dt);
    keep_joint_impulses(dt);
    for (std::size_t j = 0; j < constraints_.size(); ++j) {
      contact_record& c = state_.contacts[sources_[j].record];
      const contact_constraint<T>& cc = constraints_[j];
      manifold_impulse<T>& kept = slot_of(c, int(sources_[j].manifold)).impulse;
      for (int p = 0; p < cc.count; ++p) kept.normal[std::size_t(p)] = cc.points[p].normal_impulse;
      kept.friction = cc.tangent1 * cc.tangent_impulse1 + cc.tangent2 * cc.tangent_impulse2;
      kept.twist = cc.twist_impulse;
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      body_record& r = bodies[i];
      rigid_body<T>& b = r.body;
      r.previous = b.pose();
      if (held(std::uint32_t(i))) {
        b.linear_momentum = {};
        b.angular_momentum = {};
      } else if (is_solved(r)) {
        const solver_body<T>& s = solver_bodies_[i];
        body_pose<T> x{b.position, b.orientation};
        // L changes by the torque's impulse and by what the contacts did to
        // ω; written as that change rather than as I_w·ω, it stays constant
        // to the bit when nothing acts on the body.
        const vec3<T> free_spin = s.inverse_inertia * b.angular_momentum + s.force_angular;
        body_momentum<T> momentum{s.linear_velocity * b.mass,
                                  b.angular_momentum + b.torque * dt + b.inertia_world() * (s.angular_velocity - free_spin)};
        if constexpr (!solver_policy::moves_bodies) {
          // Free motion under the solved momenta, by the integrator policy:
          // with L held, ω = R·I⁻¹·Rᵀ·L turns with the body at each stage,
          // so the gyroscopic motion is as accurate as the integrator.
          integrator::advance(x, momentum, dt, free_motion{b, s.bias_linear, s.bias_angular});
        } else {
          // The solver held ω through each substep while the body turned,
          // so ω is its state: L = I_w·ω at the pose it reached. Kept as
          // the change of L instead, a tumbling link's energy grew at each
          // step (the tail of a swinging chain spun up to 3 000 rad/s).
          x = {s.position, s.orientation};
          const mat3<T> turn = to_mat3(s.orientation);
          momentum.angular = turn * b.inertia * transpose(turn) * s.angular_velocity;
        }
        // What the solve gave it can still overflow (or pass the limits):
        // the body is then held after all, where it started the step.
        const bool finite = is_finite(x.position) && is_finite(x.orientation) && is_finite(momentum.linear) &&
                            is_finite(momentum.angular) && length_squared(x.orientation) > T(0) &&
                            within_speed_limits(s.linear_velocity, s.angular_velocity) && within_bounds(x.position);
        if (finite) {
          b.linear_momentum = momentum.linear;
          b.angular_momentum = momentum.angular;
          b.position = x.position;
          b.orientation = normalize(x.orientation);
        } else {
          b.linear_momentum = {};
          b.angular_momentum = {};
          hold(i);
        }
      } else if (b.type == body_type::kinematic) {
        // A kinematic body's motion is prescribed: placed exactly, and
        // stopped at the world's bounds.
        const vec3<T> moved = b.position + b.kinematic_velocity * dt;
        if (within_bounds(moved)) {
          b.position = moved;
          b.orientation = integrate(b.orientation, b.kinematic_angular_velocity, dt);
        } else {
          b.kinematic_velocity = b.kinematic_angular_velocity = vec3<T>{};
          hold(i);
        }
        if (r.target == target_state::armed) r.target = target_state::arrived;
      }
      b.clear_loads();
    }
    if (!joints_.empty()) project_joints();
  }

  /// For a solver that moves the bodies itself, holding ω over each
  /// substep: the change of ω over the step that keeps L = I_w·ω as the
  /// body turns (ω × I·ω, the gyroscopic term), taken implicitly by one
  /// Newton step on I·(ω₂ − ω₁) + dt·ω₂ × I·ω₂ = 0 (Catto, "Numerical
  /// Methods", GDC 2015). Explicitly, the term adds energy: a thin link
  /// whipped at the end of a chain spun itself up to 3 000 rad/s.
  static vec3<T> gyroscopic_turn(const rigid_body<T>& b, const vec3<T>& omega, T dt) noexcept {
    const mat3<T> inertia = b.inertia_world();
    const vec3<T> spin = inertia * omega;
    const mat3<T> slope = inertia + (skew(omega) * inertia - skew(spin)) * dt;
    const std::optional<mat3<T>> inverse = try_inverse(slope);
    return inverse ? -(*inverse * (cross(omega, spin) * dt)) : vec3<T>{};
  }

  /// The joints' drift removed from where the bodies have moved to
  /// (joint_tree::project_joints), by either solver; velocities are left as
  /// solved.
  /// A body held after its solve (hold() made it immovable) stays put,
  /// and a projection that would leave a body non-finite is undone for it.
  void project_joints() {
    std::vector<body_record>& bodies = state_.bodies.values();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      solver_bodies_[i].position = bodies[i].body.position;
      solver_bodies_[i].orientation = bodies[i].body.orientation;
    }
    solver_.project_joints(solver_bodies_, joints_, state_.settings.solver);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (!is_solved(bodies[i]) || held(std::uint32_t(i))) continue;
      const solver_body<T>& s = solver_bodies_[i];
      if (within_bounds(s.position) && is_finite(s.orientation) && length_squared(s.orientation) > T(0)) {
        bodies[i].body.position = s.position;
        bodies[i].body.orientation = normalize(s.orientation);
      } else {
        rigid_body<T>& b = bodies[i].body;
        b.position = bodies[i].previous.position;
        b.orientation = bodies[i].previous.rotation;
        b.linear_momentum = {};
        b.angular_momentum = {};
        hold(i);
      }
    }
  }

  /// Keeps what each solved joint accumulated, and breaks those whose
  /// impulse this step (per substep, for a substepping solver, whose
  /// impulses are per substep) exceeded their thresholds.
  void keep_joint_impulses(T dt) {
    const T h = solver_policy::moves_bodies ? dt / T(state_.settings.solver.substeps) : dt;
    for (std::size_t n = 0; n < joints_.size(); ++n) {
      joint_record& r = state_.joints.values()[joint_sources_[n]];
      r.constraint = joints_[n];
      const detail::joint_reaction<T> applied = detail::reaction_of(joints_[n]);
      r.force = applied.linear * (T(1) / h);
      r.torque = applied.angular * (T(1) / h);
      const T force = length(r.force), torque = length(r.torque);
      if (force > r.def.break_force || torque > r.def.break_torque) {
        r.broken = true;
        unjoin(r);
        wake_joint(r);
        state_.broken.push_back({state_.joints.ids()[joint_sources_[n]], r.a, r.b, state_.time + dt, force, torque});
      }
    }
  }

  template <class D>
  static void draw_box(D& d, const aabb<T>& box, const debug_color& colour) {
    const vec3<T>& l = box.lower;
    const vec3<T>& u = box.upper;
    const vec3<T> c[8] = {{l.x, l.y, l.z}, {u.x, l.y, l.z}, {u.x, u.y, l.z}, {l.x, u.y, l.z},
                          {l.x, l.y, u.z}, {u.x, l.y, u.z}, {u.x, u.y, u.z}, {l.x, u.y, u.z}};
    for (int i = 0; i < 4; ++i) {
      d.line(c[i], c[(i + 1) % 4], colour);
      d.line(c[i + 4], c[(i + 1) % 4 + 4], colour);
      d.line(c[i], c[i + 4], colour);
    }
  }
  static debug_color colour_of(const body_record& r) noexcept {
    if (r.body.type == body_type::static_body) return {0.5f, 0.5f, 0.5f};
    if (r.body.type == body_type::kinematic) return {0.5f, 0.5f, 1};
    return r.awake ? debug_color{0.3f, 1, 0.3f} : debug_color{0.2f, 0.4f, 0.2f};
  }

  /// A first guess of the normal impulses of touching contacts that have
  /// none to carry over: the weight they hold up.
  ///
  /// Warm starting makes each step's iterations continue the last step's,
  /// but a new contact starts from nothing, and Gauss–Seidel moves a load
  /// only so far per sweep: down a stack one contact per sweep, and from a
  /// heavy body into a light one beneath it by about the mass ratio's
  /// inverse per sweep. A 100 kg box set on a 1 kg one sinks 4 cm in the
  /// first ten steps before the carried-over impulses catch up (200 sweeps
  /// in the first step still leave 6 mm). So when a contact is new and
  /// holds a body up against gravity (its normal within 45° of vertical),
  /// its first impulse is that body's weight over the step, plus what rests
  /// on the body through other new contacts, shared evenly among the
  /// contacts holding it: loads are passed down from the highest body. The
  /// iterations then correct the guess like any carried-over impulse; it
  /// only sets where they start.
  void estimate_cold_loads(T dt) {
    const T g = length(state_.settings.gravity);
    if (!(g > T(0))) return;
    const vec3<T> up = state_.settings.gravity * (T(-1) / g);
    supports_.clear();
    for (std::uint32_t j = 0; j < constraints_.size(); ++j) {
      const contact_constraint<T>& c = constraints_[j];
      bool cold = true, touching = false;
      for (int p = 0; p < c.count; ++p) {
        cold = cold && c.points[p].normal_impulse == T(0);
        touching = touching || c.points[p].depth >= -state_.settings.solver.linear_slop;
      }
      if (!cold || !touching) continue;  // a gap still to close carries no load yet
      T lift = dot(c.normal, up);
      std::uint32_t upper = c.body_b, lower = c.body_a;
      if (lift < T(0)) std::swap(upper, lower), lift = -lift;
      if (lift < T(0.7071) || solver_bodies_[upper].inverse_mass == T(0)) continue;
      supports_.push_back({dot(solver_bodies_[upper].position, up), upper, lower, j, lift});
    }
    if (supports_.empty()) return;
    std::sort(supports_.begin(), supports_.end(), [](const support& x, const support& y) {
      return x.height != y.height ? x.height > y.height : x.upper < y.upper;
    });
    load_.assign(solver_bodies_.size(), T(0));
    for (std::size_t first = 0; first < supports_.size();) {
      const std::uint32_t upper = supports_[first].upper;
      std::size_t last = first;
      while (last < supports_.size() && supports_[last].upper == upper) ++last;
      const T share = (g * dt / solver_bodies_[upper].inverse_mass + load_[upper]) / T(last - first);
      for (std::size_t k = first; k < last; ++k) {
        contact_constraint<T>& c = constraints_[supports_[k].constraint];
        const T per_point = share / (supports_[k].lift * T(c.count));
        for (int p = 0; p < c.count; ++p) c.points[p].normal_impulse = per_point;
        if (solver_bodies_[supports_[k].lower].inverse_mass > T(0)) load_[supports_[k].lower] += share;
      }
      first = last;
    }
  }

  struct support {
    T height;  ///< of the upper body, along −gravity
    std::uint32_t upper, lower, constraint;
    T lift;  ///< the normal's component along −gravity
  };

  /// A body moving freely with the momenta the solver left it, plus the
  /// position pass's pseudo-velocities, as the integrator policy's system
  /// (body_motion.hpp): momentum constant over the step.
  struct free_motion {
    const rigid_body<T>& body;
    vec3<T> bias_linear, bias_angular;
    body_pose<T> position_rate(const body_pose<T>& x, const body_momentum<T>& p) const {
      body_kinematics<T> k = kinematics_of(body, x, p);
      k.linear_velocity += bias_linear;
      k.angular_velocity += bias_angular;
      return pose_rate(k, x.orientation);
    }
    body_momentum<T> momentum_rate(const body_pose<T>&, const body_momentum<T>&) const { return {}; }
  };

  struct constraint_source {
    std::uint32_t record;
    std::uint32_t manifold;
  };

  state state_;
  // Per-step scratch, kept to allocate nothing once warm; not part of the
  // state (each step rebuilds it).
  solver_type solver_{};
  std::vector<contact_record> next_contacts_;
  std::vector<solver_body<T>> solver_bodies_;
  std::vector<contact_constraint<T>> constraints_;
  std::vector<constraint_source> sources_;
  std::vector<joint_constraint<T>> joints_;
  std::vector<std::uint32_t> joint_sources_;  ///< each solved joint's dense place
  std::vector<joint_id> doomed_joints_;
  std::vector<support> supports_;
  std::vector<T> load_;
  detail::union_find islands_;
  std::vector<std::uint8_t> island_flag_;
  std::vector<T> island_timer_;
  std::vector<std::uint8_t> held_;  ///< per dense body: held in this step (hold())

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
world<Config>::world(const world_settings<T>& settings) {
  settings.validate();
  state_.settings = settings;
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
auto world<Config>::prepare_body(const body_def<T>& def, rigid_body<T> body, const vec3<T>& center) const
    -> body_record {
  if (def.type == body_type::dynamic) body.position = apply(def.pose, center);
  if (!is_finite(def.linear_velocity) || !is_finite(def.angular_velocity))
    detail::report_error(error_code::non_finite, "world::create_body: velocity is not finite");
  require_speeds(def.linear_velocity, def.angular_velocity,
                 "world::create_body: faster than max_linear_speed or max_angular_speed");
  require_within_bounds(body.position, "world::create_body: the body is farther than max_coordinate from the origin");
  if (def.type == body_type::static_body && (def.linear_velocity != vec3<T>{} || def.angular_velocity != vec3<T>{}))
    detail::report_error(error_code::invalid_parameter, "world::create_body: a static body cannot move");
  if (def.type != body_type::static_body) body.set_velocity(def.linear_velocity, def.angular_velocity);
  body_record record{};
  record.body = body;
  record.material = def.material;
  record.center = center;
  record.awake = def.awake || def.type != body_type::dynamic;
  record.user_data = def.user_data;
  record.bullet = def.bullet;
  record.previous = body.pose();
  return record;
}

template <class Config>
body_id world<Config>::insert_body(const body_record& record) {
  const body_id id = state_.bodies.insert(record);
  body_record& r = state_.bodies[id];
  r.proxy = state_.broad.create(proxy_box(r), pack(id));
  return id;
}

template <class Config>
void world<Config>::destroy_body(body_id id) {
  refuse_in_callback("world::destroy_body: called from inside a world callback (for_each_contact, overlap, "
                     "visit_shape, draw); make the change after it returns");
  require(id, "world::destroy_body: no such body (destroyed already?)");
  doomed_joints_.clear();
  for (std::size_t k = 0; k < state_.joints.size(); ++k) {
    const joint_record& j = state_.joints.values()[k];
    if (j.a == id || j.b == id) doomed_joints_.push_back(state_.joints.ids()[k]);
  }
  for (const joint_id j : doomed_joints_) destroy_joint(j);
  std::erase_if(state_.contacts, [&](const contact_record& c) {
    if (c.a != id && c.b != id) return false;
    end_contact(c);
    const body_id other = c.a == id ? c.b : c.a;
    wake_record(state_.bodies[other]);
    return true;
  });
  body_record& r = state_.bodies[id];
  state_.broad.destroy(r.proxy);
  state_.shape_store.remove(r.shape);
  state_.bodies.erase(id);
}

template <class Config>
void world<Config>::set_pose(body_id id, const transform<T>& pose) {
  refuse_in_callback("world::set_pose: called from inside a world callback (for_each_contact, overlap, "
                     "visit_shape, draw); make the change after it returns");
  require(id, "world::set_pose: no such body");
  body_record& r = state_.bodies[id];
  body_record moved = r;
  moved.body.set_pose({apply(pose, r.center), pose.rotation});  // refuses a bad pose
  moved.previous = moved.body.pose();
  const aabb<T> box = proxy_box(moved);
  const bool plane_shape = r.shape.type == detail::shape_store<shapes, T>::template index_of<plane<T>>();
  if (!within_bounds(moved.body.position) || (!plane_shape && (!within_bounds(box.lower) || !within_bounds(box.upper))))
    detail::report_error(error_code::invalid_parameter,
                         "world::set_pose: the body would reach farther than max_coordinate from the origin", id.index);
  r = moved;
  state_.broad.move(r.proxy, box);
  wake_record(r);
}

template <class Config>
void world<Config>::set_target_pose(body_id id, const transform<T>& target, T dt) {
  require(id, "world::set_target_pose: no such body");
  body_record& r = state_.bodies[id];
  if (r.body.type != body_type::kinematic)
    detail::report_error(error_code::invalid_parameter, "world::set_target_pose: the body is not kinematic",
                         id.index);
  if (!std::isfinite(dt) || !(dt > T(0)))
    detail::report_error(error_code::invalid_parameter, "world::set_target_pose: dt must be positive and finite");
  if (!is_finite(target.position) || !is_finite(target.rotation))
    detail::report_error(error_code::non_finite, "world::set_target_pose: the pose is not finite");
  if (!is_normalized(target.rotation))
    detail::report_error(error_code::not_normalized, "world::set_target_pose: the rotation is not a unit quaternion");
  require_within_bounds(target.position, "world::set_target_pose: farther than max_coordinate from the origin", id);
  const vec3<T> rotation = rotation_between(r.body.orientation, target.rotation);
  const vec3<T> linear = (target.position - shape_pose_of(r).position) * (T(1) / dt), angular = rotation * (T(1) / dt);
  if (!is_finite(linear) || !is_finite(angular) || !within_speed_limits(linear, angular))
    detail::report_error(error_code::invalid_parameter,
                         "world::set_target_pose: reaching the target in dt is faster than max_linear_speed or "
                         "max_angular_speed",
                         id.index);
  r.body.set_velocity(linear, angular);
  if (r.target == target_state::none) state_.targeted.push_back(id);
  r.target = target_state::armed;
}

template <class Config>
joint_id world<Config>::create_joint(const joint_def<T>& def) {
  refuse_in_callback("world::create_joint: called from inside a world callback (for_each_contact, overlap, "
                     "visit_shape, draw); make the change after it returns");
  require(def.body_a, "world::create_joint: body_a does not exist (destroyed?)");
  require(def.body_b, "world::create_joint: body_b does not exist (destroyed?)");
  if (def.body_a == def.body_b)
    detail::report_error(error_code::invalid_parameter, "world::create_joint: a joint needs two different bodies",
                         def.body_a.index);
  def.validate();
  require_within_bounds(def.anchor_a, "world::create_joint: anchor_a is farther than max_coordinate from the origin");
  require_within_bounds(def.anchor_b, "world::create_joint: anchor_b is farther than max_coordinate from the origin");
  body_record& ra = state_.bodies[def.body_a];
  body_record& rb = state_.bodies[def.body_b];
  if (ra.body.type != body_type::dynamic && rb.body.type != body_type::dynamic)
    detail::report_error(error_code::invalid_parameter, "world::create_joint: at least one body must be dynamic",
                         def.body_a.index);

  const bool two_ends = def.type == joint_type::distance;
  require_lever(ra.body, def.anchor_a, def.body_a);
  require_lever(rb.body, two_ends ? def.anchor_b : def.anchor_a, def.body_b);

  // Nothing below can fail on the input.
  const rigid_body<T>& a = ra.body;
  const rigid_body<T>& b = rb.body;
  joint_constraint<T> c;
  c.type = def.type;
  c.local_anchor_a = inverse_rotate(a.orientation, def.anchor_a - a.position);
  c.local_anchor_b = inverse_rotate(b.orientation, (two_ends ? def.anchor_b : def.anchor_a) - b.position);
  vec3<T> axis = def.axis;
  if (two_ends) axis = def.anchor_b - def.anchor_a;
  c.local_axis_a = length_squared(axis) > T(0) ? inverse_rotate(a.orientation, normalize(axis)) : vec3<T>{1, 0, 0};
  c.reference = conjugate(a.orientation) * b.orientation;
  c.enable_limit = def.enable_limit, c.lower = def.lower, c.upper = def.upper;
  c.enable_motor = def.enable_motor, c.motor_speed = def.motor_speed, c.max_motor_force = def.max_motor_force;
  c.length = def.length, c.spring_hertz = def.spring_hertz, c.spring_damping_ratio = def.spring_damping_ratio;
  joint_record record{};
  record.constraint = c;
  record.def = def;
  record.a = def.body_a, record.b = def.body_b;
  if (!def.collide_connected) {
    const std::uint64_t key = pair_key(def.body_a, def.body_b);
    state_.joined.insert(std::upper_bound(state_.joined.begin(), state_.joined.end(), key), key);
    end_contacts_between(def.body_a, def.body_b);
  }
  wake_record(ra);
  wake_record(rb);
  return state_.joints.insert(record);
}

template <class Config>
void world<Config>::destroy_joint(joint_id id) {
  refuse_in_callback("world::destroy_joint: called from inside a world callback (for_each_contact, overlap, "
                     "visit_shape, draw); make the change after it returns");
  require(id, "world::destroy_joint: no such joint (destroyed already?)");
  const joint_record& r = state_.joints[id];
  if (!r.broken) unjoin(r);
  wake_record(state_.bodies[r.a]);
  wake_record(state_.bodies[r.b]);
  state_.joints.erase(id);
}

template <class Config>
void world<Config>::step(T dt) {
  refuse_in_callback("world::step: called from inside a world callback (for_each_contact, overlap, "
                     "visit_shape, draw); make the change after it returns");
  if (!(dt > T(0) && dt <= max_dt))
    detail::report_error(error_code::invalid_parameter, "world::step: dt must be positive and at most max_dt (1 s)");
  state_.begun.clear();
  state_.ended.clear();
  state_.broken.clear();
  state_.held.clear();
  expire_targets();
  update_broad_phase();
  update_contacts();
  if constexpr (sleeping) wake_islands();
  solve(dt);
  if constexpr (ccd) continuous();
  if constexpr (sleeping) update_sleep(dt);
  state_.time += dt;
  state_.last_dt = dt;
  ++state_.step_count;
  if (!state_.held.empty())
    detail::report_error(error_code::non_finite,
                         "world::step: a body's motion overflowed (not finite, past max_linear_speed or "
                         "max_angular_speed, or beyond max_coordinate); it was held where it was, its contacts and joints left out of the "
                         "step, and the other bodies stepped on (held_bodies() lists every one)",
                         state_.held.front().index);
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

template <class Config>
auto world<Config>::ray_cast(const ray<T>& r, T max_fraction) const -> std::optional<world_ray_hit<T>> {
  std::optional<world_ray_hit<T>> best;
  T reach = max_fraction;
  state_.broad.ray_cast(r, max_fraction, [&](proxy_id proxy, T) {
    const body_id id = unpack(state_.broad.user_data(proxy));
    const body_record& rec = state_.bodies[id];
    const transform<T> pose = shape_pose_of(rec);
    const narrowphase::ray_hit<T> hit =
        state_.shape_store.visit(rec.shape, [&](const auto& s) { return narrowphase::ray_cast(r, s, pose, reach); });
    if (hit.hit && hit.fraction <= reach) {
      reach = hit.fraction;
      best = world_ray_hit<T>{id, hit.fraction, hit.point, hit.normal};
    }
    return reach;
  });
  return best;
}

/// A world's whole state, to restore it later exactly.
template <class Config>
class world_snapshot {
 public:
  world_snapshot() = default;

 private:
  friend class world<Config>;
  explicit world_snapshot(const typename world<Config>::state& s) : state_(s) {}
  typename world<Config>::state state_;
};

}  // namespace impulse

#if IMPULSE_EXTERN_TEMPLATES
IMPULSE_DECLARE_WORLD(impulse::default_config);
IMPULSE_DECLARE_WORLD(impulse::default_double_config);
#endif
