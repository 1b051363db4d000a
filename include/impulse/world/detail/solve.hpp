// impulse/world/detail/solve.hpp — the step's solve: the awake bodies and their
// touching contacts and joints handed to the config's solver
// (sequential_impulse, soft_step), which applies this step's forces, solves
// the contacts and the joints (joint.hpp; trees of joints exactly,
// joint_tree.hpp) and, if it moves the bodies itself, moves them; then the
// write-back: the bodies left where the solver moved them (or moved, for a
// user's solver that leaves the motion to the world),
// moved back onto their joints (project_joints), the impulses
// kept for the next step's warm start, and the joints that pulled harder
// than their thresholds broken.
//
// Bodies keep Baraff's state (rigid_body.hpp): the solver works on
// velocities v = P/m, ω = I_w⁻¹·L taken at the start of the step; the
// write-back sets P = m·v, and L changed by the torque's impulse and by I_w
// times what the contacts did to ω, so that with no contact L is constant
// to the bit. The bodies then move in a straight line and turn freely with
// L held (free_rotation.hpp: exact for a symmetric body, second order for
// any other, fourth under a fourth-order integrator policy), so the
// gyroscopic motion, ω turning as the body turns, needs no term of its
// own. Forces are held constant over a step, so every integrator gives the
// same velocity change, F·dt/m; a world without collision (force_motion.hpp)
// is where the policies differ. Both shipped solvers move the bodies
// themselves (sequential_impulse part by part, soft_step substep by
// substep), turning them the same way and keeping each body's L in step
// with the ω their rows change; the world takes that L.
//
// A body that the step would take past the world's speed limits or out of
// finite numbers is held (step_scratch::hold): before the solve if its
// loads would, after it if what the solve gave it does.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "../../dynamics/body_motion.hpp"
#include "contact_update.hpp"
#include "world_state.hpp"

namespace impulse::detail {

template <class Config>
struct body_solve {
  using T = typename Config::scalar;
  using solver_type = typename step_scratch<Config>::solver_type;
  using integrator = typename Config::integrator;
  using support = typename step_scratch<Config>::support;

  /// Constraints a worker builds or keeps at a time: a few hundred ns each.
  static constexpr std::uint32_t min_constraints = 128;
  /// Bodies a worker gathers or moves at a time.
  static constexpr std::uint32_t min_bodies = 256;

  world_state<Config>& state;
  step_scratch<Config>& scratch;

  /// Solves and moves the bodies over dt (above).
  void run(T dt) {
    stopwatch lap;
    std::vector<body_record<T>>& bodies = state.bodies.values();
    state.refresh_awake();
    settle_sleepers();
    gather_bodies();
    const vec3<T> gravity_step = state.settings.gravity * dt;
    // The bodies' solver places, then the world anchor of springs that have
    // one: a static body at the origin, so that an anchor is its own point.
    const std::size_t count = scratch.solver_dense.size();
    scratch.solver_bodies.resize(count + (scratch.anchored ? 1 : 0));
    scratch.held.assign(scratch.solver_bodies.size(), 0);
    if (scratch.anchored) scratch.solver_bodies[count] = solver_body<T>{};
    auto gather = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      for (std::size_t i = begin; i < end; ++i) gather_body(bodies[scratch.solver_dense[i]], i, gravity_step, dt);
    };
    parallel_for(scratch.tasks, std::uint32_t(count), min_bodies, gather);
    scratch.report_holds(state);
    // How long the bodies move in a straight line at a time: the solver's
    // impulse step (a part's or substep's length).
    const T move_dt = solver_type::impulse_step(state.settings.solver, dt);
    // The solved manifolds first, in the records' order; then their
    // constraints, built across the workers: each writes only its own.
    // Reserved exactly: grown by doubling, the largest per-step array
    // would hold up to twice what it needs, and three times while it moves.
    std::size_t manifold_count = 0;
    for (const std::uint32_t k : state.awake_contacts) manifold_count += state.contacts[k].manifold_count;
    scratch.sources.clear();
    scratch.sources.reserve(manifold_count);
    const pre_solve_hook<T>& hook = scratch.pre_solve;
    scratch.source_settings.clear();
    if (hook.call != nullptr) scratch.source_settings.reserve(manifold_count);
    for (const std::uint32_t k : state.awake_contacts) {
      const contact_record<T>& c = state.contacts[k];
      if (!c.touching) continue;
      if (!is_solved(state.bodies[c.a]) && !is_solved(state.bodies[c.b])) continue;
      const std::uint32_t ia = scratch.solver_place[state.dense(c.a)], ib = scratch.solver_place[state.dense(c.b)];
      if (scratch.is_held(ia) || scratch.is_held(ib)) continue;
      for (int m = 0; m < c.manifold_count; ++m) {
        if (hook.call != nullptr && !offer(c, m, hook)) continue;
        scratch.sources.push_back({k, std::uint32_t(m)});
      }
    }
    // Not cleared: every constraint is written whole below, and a vector
    // that keeps its size between steps is not zeroed twice.
    scratch.constraints.reserve(scratch.sources.size());
    scratch.constraints.resize(scratch.sources.size());
    auto build = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      for (std::uint32_t j = begin; j < end; ++j) {
        const std::uint32_t k = scratch.sources[j].record;
        const int m = int(scratch.sources[j].manifold);
        const contact_record<T>& c = state.contacts[k];
        const body_record<T>& ra = state.bodies[c.a];
        const body_record<T>& rb = state.bodies[c.b];
        const std::uint32_t ia = scratch.solver_place[state.dense(c.a)], ib = scratch.solver_place[state.dense(c.b)];
        const contact_manifold<T>& manifold = state.slot_of(c, m).manifold;
        contact_constraint<T>& cc = scratch.constraints[j];
        cc = contact_constraint<T>{};
        cc.body_a = ia, cc.body_b = ib;
        cc.normal = manifold.normal;
        cc.friction = c.friction;
        cc.restitution = c.restitution;
        vec3<T> surface{};  // the relative velocity friction holds the patch at, from a pre-solve hook
        if (!scratch.source_settings.empty()) {
          const contact_settings<T>& set = scratch.source_settings[j];
          cc.friction = set.friction, cc.restitution = set.restitution, surface = set.surface_velocity;
        }
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
        // Apart (a speculative contact), each body's friction acts where it
        // will touch, its own surface: at the middle of the gap a ball
        // landing 30 cm a step from the ground would be spun through a
        // lever 15 cm too long (and roll off 1.7 % too fast at 20 m/s).
        T gap = T(0);
        for (int p = 0; p < manifold.count; ++p) gap -= manifold.points[std::size_t(p)].depth;
        const vec3<T> half_gap = manifold.normal * (std::max(gap, T(0)) / T(2 * manifold.count));
        cc.anchor_a = middle - half_gap - ra.body.position;
        cc.anchor_b = middle + half_gap - rb.body.position;
        // The slip at the middle of the patch chooses the tangents.
        const vec3<T> slip =
            relative_velocity(scratch.solver_bodies[ia], scratch.solver_bodies[ib], cc.anchor_a, cc.anchor_b) - surface;
        slip_tangents(cc.normal, slip, state.settings.solver.rest_slip_speed, cc.tangent1, cc.tangent2);
        // The positions move each center in a straight line while each body
        // turns exactly, so two points that move together at the velocity
        // level part over the step by ½dt²·(ω_B×(ω_B×r_B) − ω_A×(ω_A×r_A)):
        // a box stuck 2 m out on a platform turning at 1 rad/s crept
        // outward 1.7 cm/s. Friction holds the patch at the relative
        // velocity that cancels it, over the solver's impulse step (a part
        // or substep: sequential_impulse turns the levers between its
        // parts, contact_batch.hpp, retarget_batch).
        const solver_body<T>& sa = scratch.solver_bodies[ia];
        const solver_body<T>& sb = scratch.solver_bodies[ib];
        const vec3<T> curving = cross(sb.angular_velocity, cross(sb.angular_velocity, cc.anchor_b)) -
                                cross(sa.angular_velocity, cross(sa.angular_velocity, cc.anchor_a));
        cc.slip_target1 = dot(curving, cc.tangent1) * (-move_dt / T(2)) + dot(surface, cc.tangent1);
        cc.slip_target2 = dot(curving, cc.tangent2) * (-move_dt / T(2)) + dot(surface, cc.tangent2);
        const manifold_impulse<T>& carried = state.slot_of(c, m).impulse;
        cc.tangent_impulse1 = dot(carried.friction, cc.tangent1);
        cc.tangent_impulse2 = dot(carried.friction, cc.tangent2);
        cc.twist_impulse = carried.twist;
        for (int p = 0; p < manifold.count; ++p) {
          const contact_point<T>& point = manifold.points[std::size_t(p)];
          contact_constraint_point<T>& cp = cc.points[p];
          cp.offset_a = point.position - ra.body.position;
          cp.offset_b = point.position - rb.body.position;
          cp.depth = point.depth;
          cp.normal_impulse = carried.normal[std::size_t(p)];
        }
      }
    };
    parallel_for(scratch.tasks, std::uint32_t(scratch.sources.size()), min_constraints, build);
    if (state.settings.solver.warm_starting) {
      estimate_cold_loads(solver_type::impulse_step(state.settings.solver, dt));
    }
    scratch.joints.clear();
    scratch.joint_sources.clear();
    scratch.spring_sources.clear();
    for (const std::uint32_t k : state.awake_joints) {
      const joint_record<T>& r = state.joints.values()[k];
      if (r.broken || (!is_solved(state.bodies[r.a]) && !is_solved(state.bodies[r.b]))) continue;
      const std::uint32_t ia = scratch.solver_place[state.dense(r.a)], ib = scratch.solver_place[state.dense(r.b)];
      if (scratch.is_held(ia) || scratch.is_held(ib)) continue;
      scratch.joints.push_back(r.constraint);
      scratch.joints.back().body_a = ia, scratch.joints.back().body_b = ib;
      scratch.joint_sources.push_back(k);
    }
    add_springs(count);
    state.counts.active_bodies = state.awake_bodies.size();
    state.counts.solver_bodies = count;
    state.counts.solved_manifolds = scratch.constraints.size();
    state.counts.solved_joints = scratch.joint_sources.size();
    state.counts.solved_springs = scratch.spring_sources.size();
    if constexpr (requires { scratch.solver.set_fourth_order_turns(true); })
      scratch.solver.set_fourth_order_turns(integrator::order >= 4);
    if constexpr (requires { scratch.solver.set_task_system(scratch.tasks); })
      scratch.solver.set_task_system(scratch.tasks);
    scratch.solver.prepare(scratch.solver_bodies, scratch.constraints);
    scratch.profile.prepare = lap.lap_ms();
    // Each manifold's impulses kept for the next step, and each body's
    // solved motion put back: by the worker that solved its group of
    // islands, when the solve goes by groups (its data still in that
    // worker's cache; two loops fewer), else in two loops afterwards.
    const auto keep_one = [&](std::uint32_t j) {
      contact_record<T>& c = state.contacts[scratch.sources[j].record];
      const contact_constraint<T>& cc = scratch.constraints[j];
      manifold_impulse<T>& kept = state.slot_of(c, int(scratch.sources[j].manifold)).impulse;
      for (int p = 0; p < cc.count; ++p) kept.normal[std::size_t(p)] = cc.points[p].normal_impulse;
      kept.friction = cc.tangent1 * cc.tangent_impulse1 + cc.tangent2 * cc.tangent_impulse2;
      kept.twist = cc.twist_impulse;
    };
    const auto move_one = [&](std::uint32_t i) {
      if (i < count) finish_body(bodies[scratch.solver_dense[i]], i, dt);
    };
    bool handed = false;
    if constexpr (requires { typename solver_type::group_results; }) {
      auto take = [&](std::span<const std::uint32_t> contacts, std::span<const std::uint32_t> moved) {
        for (const std::uint32_t j : contacts) keep_one(j);
        for (const std::uint32_t i : moved) move_one(i);
      };
      const typename solver_type::group_results results{
          [](void* context, std::span<const std::uint32_t> contacts, std::span<const std::uint32_t> moved) {
            (*static_cast<decltype(take)*>(context))(contacts, moved);
          },
          &take};
      scratch.solver.solve(scratch.solver_bodies, scratch.constraints, scratch.joints, state.settings.solver, dt,
                           results);
      handed = scratch.solver.solved_groups() > 0;
    } else {
      scratch.solver.solve(scratch.solver_bodies, scratch.constraints, scratch.joints, state.settings.solver, dt);
    }
    scratch.profile.solve = lap.lap_ms();
    if constexpr (requires { scratch.solver.solved_groups(); })
      state.counts.solver_groups = scratch.solver.solved_groups();
    if constexpr (requires { scratch.solver.color_count(); }) state.counts.colors = scratch.solver.color_count();
    keep_joint_impulses(dt);
    if (!handed) {
      auto keep = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
        for (std::uint32_t j = begin; j < end; ++j) keep_one(j);
      };
      parallel_for(scratch.tasks, std::uint32_t(scratch.constraints.size()), min_constraints, keep);
      auto move = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
        for (std::uint32_t i = begin; i < end; ++i) move_one(i);
      };
      parallel_for(scratch.tasks, std::uint32_t(count), min_bodies, move);
    }
    scratch.report_holds(state);
    if (!scratch.joints.empty()) project_joints();
    scratch.profile.integrate = lap.lap_ms();
    if (const post_solve_hook<T>& after = scratch.post_solve; after.call != nullptr) {
      // A solver in parts keeps the last part's impulses: scaled to the
      // step, as a force held over it (world::joint_force does the same).
      const T scale = dt / solver_type::impulse_step(state.settings.solver, dt);
      for (const auto& [k, m] : scratch.sources) {
        const contact_record<T>& c = state.contacts[k];
        const manifold_slot<T>& slot = state.slot_of(c, int(m));
        manifold_impulse<T> step_impulse = slot.impulse;
        for (T& n : step_impulse.normal) n *= scale;
        step_impulse.friction = step_impulse.friction * scale;
        step_impulse.twist *= scale;
        call_hook(scratch.hook_error, [&] { after.call(c.a, c.b, slot.manifold, step_impulse, after.context); });
      }
    }
  }

 private:
  /// Offers manifold m of record c to the pre-solve hook: whether it is
  /// solved, and if so its settings in scratch.source_settings. A
  /// manifold switched off loses its impulses; settings out of range are
  /// replaced by the pair's own, and the first such pair is kept for the
  /// step to report.
  bool offer(const contact_record<T>& c, int m, const pre_solve_hook<T>& hook) {
    const contact_settings<T> own{true, c.friction, c.restitution, {}};
    contact_settings<T> set = own;
    manifold_slot<T>& slot = state.slot_of(c, m);
    call_hook(scratch.hook_error, [&] { hook.call(c.a, c.b, slot.manifold, set, hook.context); });
    if (scratch.hook_error) set = own;
    if (!valid_settings(set)) {
      if (scratch.refused_settings.is_none()) scratch.refused_settings = c.a;
      set = own;
    }
    if (!set.enabled) {
      slot.impulse = manifold_impulse<T>{};
      return false;
    }
    scratch.source_settings.push_back(set);
    return true;
  }

  /// Solver body i from the body record r (held, quietly, if its loads
  /// would take it out of finite numbers or past the speed limits).
  void gather_body(const body_record<T>& r, std::size_t i, const vec3<T>& gravity_step, T dt) {
    const rigid_body<T>& b = r.body;
    solver_body<T>& s = scratch.solver_bodies[i];
    s = solver_body<T>{};
    s.position = b.position;
    s.orientation = b.orientation;
    if (is_solved(r)) {
      s.inverse_mass = b.inverse_mass;
      s.inverse_inertia = b.inverse_inertia_world();
      s.angular_momentum = b.angular_momentum;
      s.principal = b.principal;
      s.linear_velocity = b.linear_momentum * b.inverse_mass;
      s.angular_velocity = s.inverse_inertia * b.angular_momentum;
      s.force_linear = gravity_step + b.force * (b.inverse_mass * dt);
      s.force_angular = s.inverse_inertia * (b.torque * dt);
      // A body its loads would take out of finite numbers, or past the
      // speed limits, is held before anything couples it to another: a
      // joint solved with it would carry the overflow into its partner.
      if (!state.within_speed_limits(s.linear_velocity + s.force_linear, s.angular_velocity + s.force_angular)) scratch.hold_quietly(i);
    } else if (b.type == body_type::kinematic) {
      // + 0 turns a −0 into +0: the contact solver's lanes write a body
      // that does not move back as v + 0·p, which must be v to the bit
      // (contact_batch.hpp, lanes_written).
      s.linear_velocity = b.kinematic_velocity + vec3<T>{};
      s.angular_velocity = b.kinematic_angular_velocity + vec3<T>{};
    }
  }

  /// Moves the body of record r, solver body i, by what the solve gave it
  /// (held, quietly, if that overflows), and clears its loads.
  void finish_body(body_record<T>& r, std::size_t i, T dt) {
    rigid_body<T>& b = r.body;
    r.previous = b.pose();
    if (scratch.is_held(std::uint32_t(i))) {
      b.linear_momentum = {};
      b.angular_momentum = {};
    } else if (is_solved(r)) {
      const solver_body<T>& s = scratch.solver_bodies[i];
      body_pose<T> x{b.position, b.orientation};
      // L changes by the torque's impulse and by what the contacts did to
      // ω; written as that change rather than as I_w·ω, it stays constant
      // to the bit when nothing acts on the body.
      const vec3<T> free_spin = s.inverse_inertia * b.angular_momentum + s.force_angular;
      body_momentum<T> momentum{s.linear_velocity * b.mass,
                                b.angular_momentum + b.torque * dt + b.inertia_world() * (s.angular_velocity - free_spin)};
      if constexpr (!solver_type::moves_bodies) {
        // Free motion under the solved momenta: a straight line, and the
        // torque-free turn with L held (free_rotation.hpp), to fourth
        // order under a fourth-order policy; the position pass's
        // pseudo-velocities with them.
        x.position += (s.linear_velocity + s.bias_linear) * dt;
        x.orientation = free_turn(x.orientation, b.principal, momentum.angular, dt, integrator::order >= 4, s.bias_angular);
      } else {
        // The solver turned the body substep by substep, with its L.
        x = {s.position, s.orientation};
        momentum.angular = s.angular_momentum;
      }
      // What the solve gave it can still overflow (or pass the limits):
      // the body is then held after all, where it started the step.
      const bool finite = is_finite(x.position) && is_finite(x.orientation) && is_finite(momentum.linear) &&
                          is_finite(momentum.angular) && length_squared(x.orientation) > T(0) &&
                          state.within_speed_limits(s.linear_velocity, s.angular_velocity) && state.within_bounds(x.position);
      if (finite) {
        b.linear_momentum = momentum.linear;
        b.angular_momentum = momentum.angular;
        b.position = x.position;
        b.orientation = normalize(x.orientation);
      } else {
        b.linear_momentum = {};
        b.angular_momentum = {};
        scratch.hold_quietly(i);
      }
    } else if (b.type == body_type::kinematic) {
      if (!state.move_kinematic(r, dt)) scratch.hold_quietly(i);
    }
    b.clear_loads();
  }

  /// The springs with a solved body, after the joints: each a distance row
  /// of its stiffness and damping (joint.hpp, soften_absolute), from its
  /// point on A to its point on B or, anchored, to the anchor on the
  /// static body at `anchor`, the origin.
  void add_springs(std::size_t anchor) {
    for (const std::uint32_t k : state.awake_springs) {
      spring_record<T>& r = state.springs.values()[k];
      const bool solved_b = !r.anchored() && is_solved(state.bodies[r.def.body_b]);
      if (!is_solved(state.bodies[r.def.body_a]) && !solved_b) continue;
      // With neither stiffness nor damping it pulls with nothing; as a
      // distance row it would be a rigid rod (joint_constraint::is_spring).
      if (!(r.def.stiffness > T(0)) && !(r.def.damping > T(0))) {
        r.impulse = r.tension = T(0);
        continue;
      }
      const std::uint32_t ia = scratch.solver_place[state.dense(r.def.body_a)];
      const std::uint32_t ib = r.anchored() ? std::uint32_t(anchor) : scratch.solver_place[state.dense(r.def.body_b)];
      if (scratch.is_held(ia) || scratch.is_held(ib)) continue;
      joint_constraint<T> c{};
      c.type = joint_type::distance;
      c.body_a = ia, c.body_b = ib;
      c.local_anchor_a = r.def.point_a;
      c.local_anchor_b = r.def.point_b;
      c.length = r.def.rest_length;
      c.spring_stiffness = r.def.stiffness;
      c.spring_damping = r.def.damping;
      c.axial_impulse = r.impulse;
      scratch.joints.push_back(c);
      scratch.spring_sources.push_back(k);
    }
  }

  /// Bodies that fell asleep in the last step have stood still since: the
  /// pose at this step's start is where they are.
  void settle_sleepers() {
    for (const body_id id : state.fell_asleep)
      if (state.bodies.contains(id) && !state.bodies[id].awake) state.bodies[id].previous = state.bodies[id].body.pose();
    state.fell_asleep.clear();
  }

  /// The bodies the solver sees, in dense order: the active ones, and the
  /// static ones that their solved contacts and joints reach. A sleeping
  /// body is none of these (it would have woken, islands.hpp), so the
  /// solver and the write-back never visit one.
  void gather_bodies() {
    const std::size_t n = state.bodies.size();
    scratch.solver_place.resize(n);
    scratch.gathered.resize(n);
    if (++scratch.gather == 0) {  // the stamps wrapped: forget them all
      std::fill(scratch.gathered.begin(), scratch.gathered.end(), 0u);
      scratch.gather = 1;
    }
    for (const std::uint32_t i : state.awake_bodies) scratch.gathered[i] = scratch.gather;
    scratch.reached.clear();
    const auto reach = [&](body_id a, body_id b) {
      if (!is_solved(state.bodies[a]) && !is_solved(state.bodies[b])) return;
      for (const body_id id : {a, b}) {
        const std::uint32_t i = state.dense(id);
        if (scratch.gathered[i] == scratch.gather) continue;
        scratch.gathered[i] = scratch.gather;
        scratch.reached.push_back(i);
      }
    };
    for (const std::uint32_t k : state.awake_contacts)
      if (state.contacts[k].touching) reach(state.contacts[k].a, state.contacts[k].b);
    for (const std::uint32_t k : state.awake_joints)
      if (!state.joints.values()[k].broken) reach(state.joints.values()[k].a, state.joints.values()[k].b);
    scratch.anchored = false;
    for (const std::uint32_t k : state.awake_springs) {
      const spring_record<T>& r = state.springs.values()[k];
      if (!r.anchored()) reach(r.def.body_a, r.def.body_b);
      else scratch.anchored = scratch.anchored || is_solved(state.bodies[r.def.body_a]);
    }
    std::sort(scratch.reached.begin(), scratch.reached.end());
    scratch.solver_dense.resize(state.awake_bodies.size() + scratch.reached.size());
    std::merge(state.awake_bodies.begin(), state.awake_bodies.end(), scratch.reached.begin(), scratch.reached.end(),
               scratch.solver_dense.begin());
    for (std::uint32_t i = 0; i < scratch.solver_dense.size(); ++i) scratch.solver_place[scratch.solver_dense[i]] = i;
  }

  /// The joints' drift removed from where the bodies have moved to
  /// (joint_tree::project_joints), by either solver; velocities are left as
  /// solved.
  /// A body held after its solve (hold() made it immovable) stays put,
  /// and a projection that would leave a body non-finite is undone for it.
  void project_joints() {
    std::vector<body_record<T>>& bodies = state.bodies.values();
    for (std::size_t i = 0; i < scratch.solver_dense.size(); ++i) {
      scratch.solver_bodies[i].position = bodies[scratch.solver_dense[i]].body.position;
      scratch.solver_bodies[i].orientation = bodies[scratch.solver_dense[i]].body.orientation;
    }
    scratch.solver.project_joints(scratch.solver_bodies, scratch.joints, state.settings.solver);
    for (std::size_t i = 0; i < scratch.solver_dense.size(); ++i) {
      body_record<T>& r = bodies[scratch.solver_dense[i]];
      if (!is_solved(r) || scratch.is_held(std::uint32_t(i))) continue;
      const solver_body<T>& s = scratch.solver_bodies[i];
      if (state.within_bounds(s.position) && is_finite(s.orientation) && length_squared(s.orientation) > T(0)) {
        r.body.position = s.position;
        r.body.orientation = normalize(s.orientation);
      } else {
        rigid_body<T>& b = r.body;
        b.position = r.previous.position;
        b.orientation = r.previous.rotation;
        b.linear_momentum = {};
        b.angular_momentum = {};
        scratch.hold(state, i);
      }
    }
  }

  /// Keeps what each solved joint accumulated, and breaks those whose
  /// impulse this step (per substep, for a substepping solver, whose
  /// impulses are per substep) exceeded their thresholds.
  void keep_joint_impulses(T dt) {
    const T h = solver_type::impulse_step(state.settings.solver, dt);
    for (std::size_t n = 0; n < scratch.spring_sources.size(); ++n) {
      spring_record<T>& r = state.springs.values()[scratch.spring_sources[n]];
      r.impulse = scratch.joints[scratch.joint_sources.size() + n].axial_impulse;
      r.tension = -r.impulse * (T(1) / h);  // a positive impulse pushes B away from A
    }
    for (std::size_t n = 0; n < scratch.joint_sources.size(); ++n) {
      joint_record<T>& r = state.joints.values()[scratch.joint_sources[n]];
      r.constraint = scratch.joints[n];
      const joint_reaction<T> applied = reaction_of(scratch.joints[n]);
      r.force = applied.linear * (T(1) / h);
      r.torque = applied.angular * (T(1) / h);
      const T force = length(r.force), torque = length(r.torque);
      if (force > r.def.break_force || torque > r.def.break_torque) {
        r.broken = true;
        state.unjoin(r);
        state.wake_joint(r);
        state.broken.push_back({state.joints.ids()[scratch.joint_sources[n]], r.a, r.b, state.time + dt, force, torque});
      }
    }
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
    const T g = length(state.settings.gravity);
    if (!(g > T(0))) return;
    const vec3<T> up = state.settings.gravity * (T(-1) / g);
    scratch.supports.clear();
    for (std::uint32_t j = 0; j < scratch.constraints.size(); ++j) {
      const contact_constraint<T>& c = scratch.constraints[j];
      bool cold = true, touching = false;
      for (int p = 0; p < c.count; ++p) {
        cold = cold && c.points[p].normal_impulse == T(0);
        touching = touching || c.points[p].depth >= -state.settings.solver.linear_slop;
      }
      if (!cold || !touching) continue;  // a gap still to close carries no load yet
      T lift = dot(c.normal, up);
      std::uint32_t upper = c.body_b, lower = c.body_a;
      if (lift < T(0)) std::swap(upper, lower), lift = -lift;
      if (lift < T(0.7071) || scratch.solver_bodies[upper].inverse_mass == T(0)) continue;
      scratch.supports.push_back({dot(scratch.solver_bodies[upper].position, up), upper, lower, j, lift});
    }
    if (scratch.supports.empty()) return;
    std::sort(scratch.supports.begin(), scratch.supports.end(), [](const support& x, const support& y) {
      return x.height != y.height ? x.height > y.height : x.upper < y.upper;
    });
    scratch.load.assign(scratch.solver_bodies.size(), T(0));
    for (std::size_t first = 0; first < scratch.supports.size();) {
      const std::uint32_t upper = scratch.supports[first].upper;
      std::size_t last = first;
      while (last < scratch.supports.size() && scratch.supports[last].upper == upper) ++last;
      const T share = (g * dt / scratch.solver_bodies[upper].inverse_mass + scratch.load[upper]) / T(last - first);
      for (std::size_t k = first; k < last; ++k) {
        contact_constraint<T>& c = scratch.constraints[scratch.supports[k].constraint];
        const T per_point = share / (scratch.supports[k].lift * T(c.count));
        for (int p = 0; p < c.count; ++p) c.points[p].normal_impulse = per_point;
        if (scratch.solver_bodies[scratch.supports[k].lower].inverse_mass > T(0)) scratch.load[scratch.supports[k].lower] += share;
      }
      first = last;
    }
  }
};

}  // namespace impulse::detail
