// impulse/world/detail/force_motion.hpp — the step of a world without
// collision: bodies moved by forces alone, every force at every stage.
//
// A config with `collision = false` (world_traits.hpp) has no broad phase,
// contacts, joints or solver. Its step is this stage: each dynamic body
// moves under gravity, its held loads, its springs and the step's force
// field, advanced by the config's integrator policy, and the forces are
// evaluated at every stage of the integrator, on the stage's speculative
// state: a spring sees where its bodies would be mid-step, and so does a
// field. RK4 then keeps its fourth order on a spring-coupled pair, which a
// constraint solver's step cannot (integrators compared in
// docs/rigid_motion.md).
//
// Two paths run the same integrator code. When no spring joins two moving
// bodies, each body is independent: it is advanced alone, with its state in
// registers (body_motion.hpp's pose and momenta as the integrator's x and
// p). When springs couple bodies, every stage needs every body's stage
// state, so the integrator is handed the whole set as one state
// (core/detail/pooled_state.hpp), as the particle system does for its
// springs.
//
// A body whose step comes out non-finite, past the speed limits or beyond
// max_coordinate is held as in a colliding world: it stays where it was
// with no velocity, the others keep their step, and world::step names it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "../../dynamics/body_motion.hpp"
#include "../../dynamics/body_spring.hpp"
#include "world_state.hpp"

namespace impulse::detail {

template <class Config>
struct force_motion {
  using T = typename Config::scalar;
  using integrator = typename Config::integrator;
  static constexpr std::uint32_t none = no_object;

  world_state<Config>& state;
  step_scratch<Config>& scratch;

  template <class Field>
  void run(T dt, Field& field) {
    for (body_record<T>& r : state.bodies.values()) r.previous = r.body.pose();
    resolve_springs();
    if (scratch.motion.coupled) {
      step_coupled(dt, field);
    } else {
      step_each(dt, field);
    }
    for (std::size_t i = 0; i < state.bodies.size(); ++i) {
      body_record<T>& r = state.bodies.values()[i];
      rigid_body<T>& b = r.body;
      if (b.type == body_type::kinematic && !state.move_kinematic(r, dt)) state.held.push_back(state.bodies.ids()[i]);
      b.clear_loads();
    }
    state.counts = {};
    state.counts.active_bodies = state.bodies.size();
  }

 private:
  using motion_scratch = typename step_scratch<Config>::motion_scratch;
  using spring_ends = typename motion_scratch::spring_ends;
  using poses = pooled_state<body_pose<T>>;
  using momenta = pooled_state<body_momentum<T>>;

  [[nodiscard]] const rigid_body<T>& body(std::size_t i) const noexcept { return state.bodies.values()[i].body; }
  [[nodiscard]] const body_spring<T>& spring(std::size_t s) const noexcept { return state.springs.values()[s].def; }

  // Each spring's ends as dense places, and each body's springs (counting
  // sort), for the independent path.
  void resolve_springs() {
    motion_scratch& m = scratch.motion;
    const std::size_t n = state.bodies.size();
    m.ends.resize(state.springs.size());
    m.coupled = false;
    m.first_spring.assign(n + 1, 0);
    for (std::size_t i = 0; i < state.springs.size(); ++i) {
      const body_spring<T>& s = spring(i);
      spring_ends& e = m.ends[i];
      e.a = state.dense(s.body_a);
      e.b = s.body_b.is_none() ? none : state.dense(s.body_b);
      const bool a_moves = body(e.a).type != body_type::static_body;
      const bool b_moves = e.b != none && body(e.b).type != body_type::static_body;
      m.coupled = m.coupled || (a_moves && b_moves);
      ++m.first_spring[e.a + 1];
      if (e.b != none) ++m.first_spring[e.b + 1];
    }
    for (std::size_t i = 0; i < n; ++i) m.first_spring[i + 1] += m.first_spring[i];
    m.springs_of.resize(m.first_spring[n]);
    m.fill.assign(m.first_spring.begin(), m.first_spring.end() - 1);
    for (std::uint32_t i = 0; i < m.ends.size(); ++i) {
      m.springs_of[m.fill[m.ends[i].a]++] = i;
      if (m.ends[i].b != none) m.springs_of[m.fill[m.ends[i].b]++] = i;
    }
  }

  // Gravity, the held loads and the field on body i at kinematics k.
  template <class Field>
  wrench<T> body_wrench(std::size_t i, const body_kinematics<T>& k, Field& field) const {
    const rigid_body<T>& b = body(i);
    if (b.type != body_type::dynamic) return {};
    wrench<T> w{b.force + state.settings.gravity * b.mass, b.torque};
    if constexpr (!std::is_same_v<std::remove_cvref_t<Field>, no_force_field>) w += field(state.bodies.ids()[i], k);
    return w;
  }

  static void add_at(wrench<T>& w, const body_kinematics<T>& k, const vec3<T>& f, const vec3<T>& p) noexcept {
    w.force += f;
    w.torque += cross(p - k.position, f);
  }

  // A body at the other end of a spring that does not move in the step.
  [[nodiscard]] body_kinematics<T> resting_kinematics(std::uint32_t i) const noexcept {
    return kinematics_of(body(i), pose_of(body(i)), momentum_of(body(i)));
  }

  // One dynamic body alone, its springs' other ends fixed for the step
  // (static bodies or world anchors).
  template <class Field>
  struct single_body {
    const force_motion& stage;
    std::size_t index;
    Field& field;
    // Most methods ask for both rates at the same stage state; the
    // kinematics (a rotation matrix and the world inverse inertia) are
    // worked out once for both.
    body_pose<T> cached_x{};
    body_momentum<T> cached_p{};
    body_kinematics<T> cached_k{};
    bool cached = false;

    const body_kinematics<T>& kinematics(const body_pose<T>& x, const body_momentum<T>& p) {
      if (!cached || !(x.position == cached_x.position && x.orientation == cached_x.orientation &&
                       p.linear == cached_p.linear && p.angular == cached_p.angular)) {
        cached_k = kinematics_of(stage.body(index), x, p);
        cached_x = x, cached_p = p, cached = true;
      }
      return cached_k;
    }
    body_pose<T> position_rate(const body_pose<T>& x, const body_momentum<T>& p) {
      return pose_rate(kinematics(x, p), x.orientation);
    }
    body_momentum<T> momentum_rate(const body_pose<T>& x, const body_momentum<T>& p) {
      const body_kinematics<T>& k = kinematics(x, p);
      wrench<T> w = stage.body_wrench(index, k, field);
      const motion_scratch& m = stage.scratch.motion;
      for (std::uint32_t j = m.first_spring[index]; j < m.first_spring[index + 1]; ++j) {
        const std::uint32_t s = m.springs_of[j];
        const spring_ends& e = m.ends[s];
        const body_spring<T>& spring = stage.spring(s);
        // This body may be either end; the other end does not move.
        if (e.a == index && e.b == none) {  // a world anchor
          const spring_load<T> load = spring_load_of<T>(spring, k, nullptr);
          add_at(w, k, load.force, load.point_a);
        } else if (e.a == index) {
          const body_kinematics<T> other = stage.resting_kinematics(e.b);
          const spring_load<T> load = spring_load_of(spring, k, &other);
          add_at(w, k, load.force, load.point_a);
        } else {
          const body_kinematics<T> other = stage.resting_kinematics(e.a);
          const spring_load<T> load = spring_load_of(spring, other, &k);
          add_at(w, k, -load.force, load.point_b);
        }
      }
      return {w.force, w.torque};
    }
  };

  template <class Field>
  void step_each(T dt, Field& field) {
    for (std::size_t i = 0; i < state.bodies.size(); ++i) {
      if (body(i).type != body_type::dynamic) continue;  // kinematic ones are placed exactly after
      body_pose<T> x = pose_of(body(i));
      body_momentum<T> p = momentum_of(body(i));
      integrator::advance(x, p, dt, single_body<Field>{*this, i, field});
      commit(i, x, p);
    }
  }

  // Every body at once: the whole set is the integrator's state.
  template <class Field>
  struct whole_set {
    force_motion& stage;
    Field& field;

    poses position_rate(const poses& x, const momenta& p) const {
      poses rate(stage.scratch.motion.pose_pool);
      for (std::size_t i = 0; i < stage.state.bodies.size(); ++i)
        rate[i] = pose_rate(kinematics_of(stage.body(i), x[i], p[i]), x[i].orientation);
      return rate;
    }
    momenta momentum_rate(const poses& x, const momenta& p) const {
      motion_scratch& m = stage.scratch.motion;
      const std::size_t n = stage.state.bodies.size();
      for (std::size_t i = 0; i < n; ++i) {
        m.stage_kinematics[i] = kinematics_of(stage.body(i), x[i], p[i]);
        m.stage_wrenches[i] = stage.body_wrench(i, m.stage_kinematics[i], field);
      }
      for (std::size_t s = 0; s < m.ends.size(); ++s) {
        const spring_ends& e = m.ends[s];
        const std::vector<body_kinematics<T>>& k = m.stage_kinematics;
        const spring_load<T> load = spring_load_of(stage.spring(s), k[e.a], e.b == none ? nullptr : &k[e.b]);
        if (stage.body(e.a).type == body_type::dynamic) add_at(m.stage_wrenches[e.a], k[e.a], load.force, load.point_a);
        if (e.b != none && stage.body(e.b).type == body_type::dynamic)
          add_at(m.stage_wrenches[e.b], k[e.b], -load.force, load.point_b);
      }
      momenta rate(m.momentum_pool);
      for (std::size_t i = 0; i < n; ++i)
        rate[i] = stage.body(i).type == body_type::dynamic
                      ? body_momentum<T>{m.stage_wrenches[i].force, m.stage_wrenches[i].torque}
                      : body_momentum<T>{};
      return rate;
    }
  };

  template <class Field>
  void step_coupled(T dt, Field& field) {
    motion_scratch& m = scratch.motion;
    const std::size_t n = state.bodies.size();
    m.pose_pool.resize(1, n, n);
    m.momentum_pool.resize(1, n, n);
    m.stage_kinematics.resize(n);
    m.stage_wrenches.resize(n);
    poses x(m.pose_pool);
    momenta p(m.momentum_pool);
    for (std::size_t i = 0; i < n; ++i) x[i] = pose_of(body(i)), p[i] = momentum_of(body(i));
    integrator::advance(x, p, dt, whole_set<Field>{*this, field});
    for (std::size_t i = 0; i < n; ++i) commit(i, x[i], p[i]);
  }

  // Whether the body's speeds after its step are within the world's
  // limits. |ω| ≤ |L|·‖I⁻¹‖ (world_state::inverse_inertia_bound), so ω
  // itself, a rotation matrix and two products, is worked out only when
  // that bound passes the limit: done for every body, it cost a third of a
  // symplectic Euler step.
  [[nodiscard]] bool within_speed_limits(const rigid_body<T>& b, const body_pose<T>& x,
                                         const body_momentum<T>& p) const noexcept {
    const T bound = world_state<Config>::inverse_inertia_bound(b);
    const T w = state.settings.max_angular_speed;
    const vec3<T> v = p.linear * b.inverse_mass;
    if (length_squared(p.angular) * bound * bound <= w * w) return state.within_speed_limits(v, vec3<T>{});
    return state.within_speed_limits(v, kinematics_of(b, x, p).angular_velocity);
  }

  // Writes a dynamic body's step or, if it overflowed, holds the body where
  // it was with no velocity. Nothing reads a body's stored state after its
  // step is computed, so no copy of the start is needed.
  void commit(std::size_t i, const body_pose<T>& x, const body_momentum<T>& p) {
    body_record<T>& r = state.bodies.values()[i];
    rigid_body<T>& b = r.body;
    if (b.type != body_type::dynamic) return;
    const bool finite = is_finite(x.position) && is_finite(x.orientation) && is_finite(p.linear) &&
                        is_finite(p.angular) && length_squared(x.orientation) > scalar_traits<T>::zero_length_squared;
    const bool kept = finite && state.within_bounds(x.position) && within_speed_limits(b, x, p);
    if (!kept) {
      b.linear_momentum = b.angular_momentum = vec3<T>{};
      state.held.push_back(state.bodies.ids()[i]);
      return;
    }
    b.position = x.position;
    b.orientation = normalize(x.orientation);
    b.linear_momentum = p.linear;
    b.angular_momentum = p.angular;
  }
};

}  // namespace impulse::detail
