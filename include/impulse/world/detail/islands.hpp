// impulse/world/detail/islands.hpp — the step's islands and sleeping (with
// `sleeping` on in the config): union–find over touching contacts and
// joints before the solve, waking an island with any body awake; after the
// bodies have moved, an island whose every body has been slow for
// sleep_time goes to sleep: no forces, no contacts solved, no narrow phase,
// until something wakes it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "world_state.hpp"

namespace impulse::detail {

template <class Config>
struct island_update {
  using T = typename Config::scalar;

  world_state<Config>& state;
  step_scratch<Config>& scratch;

  /// Before the solve: dynamic bodies touching or joined are one island,
  /// and an island with any body awake wakes entirely.
  void wake() {
    std::vector<body_record<T>>& bodies = state.bodies.values();
    scratch.islands.reset(bodies.size());
    // Dynamic bodies touching or joined are one island; one resting on (or
    // joined to) a kinematic body that moves wakes.
    const auto link = [&](std::uint32_t a, std::uint32_t b) {
      const body_type ta = bodies[a].body.type, tb = bodies[b].body.type;
      if (ta == body_type::dynamic && tb == body_type::dynamic) {
        scratch.islands.unite(a, b);
      } else if (ta == body_type::kinematic && tb == body_type::dynamic && is_moving(bodies[a])) {
        wake_record(bodies[b]);
      } else if (tb == body_type::kinematic && ta == body_type::dynamic && is_moving(bodies[b])) {
        wake_record(bodies[a]);
      }
    };
    for (const contact_record<T>& c : state.contacts)
      if (c.touching) link(state.dense(c.a), state.dense(c.b));
    for (const joint_record<T>& j : state.joints.values())
      if (!j.broken) link(state.dense(j.a), state.dense(j.b));
    scratch.island_flag.assign(bodies.size(), 0);
    for (std::uint32_t i = 0; i < bodies.size(); ++i)
      if (bodies[i].body.type == body_type::dynamic && bodies[i].awake) scratch.island_flag[scratch.islands.find(i)] = 1;
    for (std::uint32_t i = 0; i < bodies.size(); ++i)
      if (bodies[i].body.type == body_type::dynamic && !bodies[i].awake && scratch.island_flag[scratch.islands.find(i)])
        wake_record(bodies[i]);
  }

  /// After the bodies have moved: an island whose every body has been slow
  /// for sleep_time goes to sleep.
  void sleep(T dt) {
    std::vector<body_record<T>>& bodies = state.bodies.values();
    const world_settings<T>& s = state.settings;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      body_record<T>& r = bodies[i];
      if (r.body.type != body_type::dynamic || !r.awake) continue;
      // A body still being pushed out of a penetration is not at rest,
      // though its velocity is: it would sleep sunk in.
      // The correction speed is held to a tenth of the sleep speeds: 5 mm/s
      // is 0.4 mm of penetration beyond the slop at the default rate.
      const solver_body<T>& motion = scratch.solver_bodies[i];
      const T linear = s.sleep_linear_speed, angular = s.sleep_angular_speed;
      const bool slow = length_squared(r.body.linear_velocity()) <= linear * linear &&
                        length_squared(r.body.angular_velocity()) <= angular * angular &&
                        length_squared(motion.bias_linear) <= T(0.01) * linear * linear &&
                        length_squared(motion.bias_angular) <= T(0.01) * angular * angular;
      r.sleep_timer = slow ? r.sleep_timer + dt : T(0);
    }
    // A body carried by (or joined to) a moving kinematic body stays awake.
    for (const contact_record<T>& c : state.contacts) {
      if (!c.touching) continue;
      body_record<T>& a = state.bodies[c.a];
      body_record<T>& b = state.bodies[c.b];
      if (a.body.type == body_type::kinematic && is_moving(a)) b.sleep_timer = T(0);
      if (b.body.type == body_type::kinematic && is_moving(b)) a.sleep_timer = T(0);
    }
    for (const joint_record<T>& j : state.joints.values()) {
      if (j.broken) continue;
      body_record<T>& a = state.bodies[j.a];
      body_record<T>& b = state.bodies[j.b];
      if (a.body.type == body_type::kinematic && is_moving(a)) b.sleep_timer = T(0);
      if (b.body.type == body_type::kinematic && is_moving(b)) a.sleep_timer = T(0);
    }
    scratch.island_timer.assign(bodies.size(), std::numeric_limits<T>::infinity());
    for (std::uint32_t i = 0; i < bodies.size(); ++i)
      if (bodies[i].body.type == body_type::dynamic && bodies[i].awake) {
        T& t = scratch.island_timer[scratch.islands.find(i)];
        t = std::min(t, bodies[i].sleep_timer);
      }
    for (std::uint32_t i = 0; i < bodies.size(); ++i) {
      body_record<T>& r = bodies[i];
      if (r.body.type != body_type::dynamic || !r.awake || scratch.island_timer[scratch.islands.find(i)] < s.sleep_time) continue;
      r.awake = false;
      r.body.linear_momentum = {};
      r.body.angular_momentum = {};
    }
  }
};

}  // namespace impulse::detail
