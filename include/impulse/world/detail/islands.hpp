// impulse/world/detail/islands.hpp — the step's islands and sleeping (with
// `sleeping` on in the config). Before the solve, a sleeping body touching
// or joined to a moving one wakes, with its whole island, and the awake
// bodies are joined into islands by their touching contacts, joints and
// springs; after the bodies have moved, an island whose every body has
// been slow for sleep_time falls asleep: no forces, no contacts solved, no
// narrow phase, until something wakes it.
//
// A sleeping island keeps its bodies (world_state::sleep_sets), as Box2D's
// solver sets do, so that waking it needs no search, and the step visits
// only the awake set (world_state::awake_bodies, and the contacts, joints
// and springs that have an awake body): with everything asleep, it visits
// nothing. An island falls asleep whole, with every body touching its
// bodies, so a sleeping island touches only itself and static bodies, and
// wakes only from outside it: by a moving body's contact, joint or spring,
// or by the world's API (world_state::wake). Bodies made asleep
// (body_def::awake false) are in no island until the next step groups
// every sleeping body afresh.
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

  /// The fewest bodies a worker times at a time (sleep).
  static constexpr std::uint32_t min_bodies = 256;

  /// Before the solve: a sleeping island touching or joined to a moving
  /// body wakes; then the awake bodies' islands.
  void wake() {
    if (state.ungrouped_sleepers) group_sleepers();
    state.refresh_awake();
    // A woken island brings its contacts into the awake set, and they touch
    // only itself and static bodies: the second pass finds nothing to wake.
    while (wake_touched()) state.refresh_awake();
    find_islands();
  }

  /// After the bodies have moved: an island whose every body has been slow
  /// for sleep_time goes to sleep. The bodies' timers run across the
  /// workers; the islands' least timers and their sleep follow in order.
  void sleep(T dt) {
    std::vector<body_record<T>>& bodies = state.bodies.values();
    const auto& s = state.settings;
    const std::vector<std::uint32_t>& awake = state.awake_bodies;
    // Each body's timer, across the workers: it reads and writes only its own.
    auto time = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      for (std::uint32_t k = begin; k < end; ++k) {
        const std::uint32_t i = awake[k];
        body_record<T>& r = bodies[i];
        if (r.body.type != body_type::dynamic) continue;
        // A body still being pushed out of a penetration is not at rest,
        // though its velocity is: it would sleep sunk in.
        // The correction speed is held to a tenth of the sleep speeds: 5 mm/s
        // is 0.4 mm of penetration beyond the slop at the default rate.
        const solver_body<T>& motion = scratch.solver_bodies[scratch.solver_place[i]];
        const T linear = s.sleep_linear_speed, angular = s.sleep_angular_speed;
        const bool slow = length_squared(r.body.linear_velocity()) <= linear * linear &&
                          length_squared(r.body.angular_velocity()) <= angular * angular &&
                          length_squared(motion.bias_linear) <= T(0.01) * linear * linear &&
                          length_squared(motion.bias_angular) <= T(0.01) * angular * angular;
        r.sleep_timer = slow ? r.sleep_timer + dt : T(0);
      }
    };
    parallel_for(scratch.tasks, std::uint32_t(awake.size()), min_bodies, time);
    // A body carried by (or joined to) a moving kinematic body stays awake.
    const auto carried = [&](body_id ia, body_id ib) {
      body_record<T>& a = state.bodies[ia];
      body_record<T>& b = state.bodies[ib];
      if (a.body.type == body_type::kinematic && is_moving(a)) b.sleep_timer = T(0);
      if (b.body.type == body_type::kinematic && is_moving(b)) a.sleep_timer = T(0);
    };
    state.for_each_awake_link(carried);
    const std::size_t n = state.awake_bodies.size();
    scratch.island_timer.assign(n, std::numeric_limits<T>::infinity());
    for (std::uint32_t p = 0; p < n; ++p) {
      const body_record<T>& r = bodies[state.awake_bodies[p]];
      if (r.body.type != body_type::dynamic) continue;
      T& t = scratch.island_timer[scratch.islands.find(p)];
      t = std::min(t, r.sleep_timer);
    }
    scratch.island_set.assign(n, no_sleep_set);
    for (std::uint32_t p = 0; p < n; ++p) {
      const std::uint32_t i = state.awake_bodies[p];
      body_record<T>& r = bodies[i];
      const std::uint32_t root = scratch.islands.find(p);
      if (r.body.type != body_type::dynamic) continue;
      if (root == p) ++state.counts.islands;
      if (scratch.island_timer[root] < s.sleep_time) continue;
      std::uint32_t& set = scratch.island_set[root];
      if (set == no_sleep_set) set = new_sleep_set();
      put_to_sleep(r, state.bodies.ids()[i], set);
      state.fell_asleep.push_back(state.bodies.ids()[i]);
    }
  }

 private:
  /// Wakes each sleeping body that a moving one touches or is joined to
  /// (and so its island); returns whether any woke.
  bool wake_touched() {
    bool woke = false;
    const auto wake_by = [&](const body_record<T>& mover, body_record<T>& sleeper) {
      if (!is_moving(mover) || sleeper.body.type != body_type::dynamic || sleeper.awake) return;
      state.wake(sleeper);
      woke = true;
    };
    const auto link = [&](body_id a, body_id b) {
      wake_by(state.bodies[a], state.bodies[b]);
      wake_by(state.bodies[b], state.bodies[a]);
    };
    state.for_each_awake_link(link);
    return woke;
  }

  /// The awake dynamic bodies touching or joined are one island
  /// (scratch.islands, over their places in awake_bodies).
  void find_islands() {
    scratch.awake_place.resize(state.bodies.size());
    for (std::uint32_t p = 0; p < state.awake_bodies.size(); ++p) scratch.awake_place[state.awake_bodies[p]] = p;
    scratch.islands.reset(state.awake_bodies.size());
    const auto link = [&](body_id a, body_id b) {
      if (state.bodies[a].body.type == body_type::dynamic && state.bodies[b].body.type == body_type::dynamic)
        scratch.islands.unite(scratch.awake_place[state.dense(a)], scratch.awake_place[state.dense(b)]);
    };
    state.for_each_awake_link(link);
  }

  /// Every body's island found afresh over all touching contacts and
  /// joints: an island with a body awake (or resting on a moving kinematic
  /// body) wakes whole, and each other one becomes a sleeping island. Run
  /// when bodies were made asleep, which are in no island until then.
  void group_sleepers() {
    state.ungrouped_sleepers = false;
    std::vector<body_record<T>>& bodies = state.bodies.values();
    for (body_record<T>& r : bodies) r.sleep_set = no_sleep_set;
    state.sleep_sets.clear();
    state.free_sleep_sets.clear();
    scratch.islands.reset(bodies.size());
    scratch.island_flag.assign(bodies.size(), 0);
    const auto link = [&](std::uint32_t a, std::uint32_t b) {
      const body_type ta = bodies[a].body.type, tb = bodies[b].body.type;
      if (ta == body_type::dynamic && tb == body_type::dynamic) {
        scratch.islands.unite(a, b);
      } else if (ta == body_type::kinematic && tb == body_type::dynamic && is_moving(bodies[a])) {
        scratch.island_flag[b] = 1;
      } else if (tb == body_type::kinematic && ta == body_type::dynamic && is_moving(bodies[b])) {
        scratch.island_flag[a] = 1;
      }
    };
    for (const contact_record<T>& c : state.contacts)
      if (c.touching) link(state.dense(c.a), state.dense(c.b));
    for (const joint_record<T>& j : state.joints.values())
      if (!j.broken) link(state.dense(j.a), state.dense(j.b));
    for (const spring_record<T>& r : state.springs.values())
      if (!r.anchored()) link(state.dense(r.def.body_a), state.dense(r.def.body_b));
    for (std::uint32_t i = 0; i < bodies.size(); ++i)
      if (bodies[i].body.type == body_type::dynamic && (bodies[i].awake || scratch.island_flag[i]))
        scratch.island_flag[scratch.islands.find(i)] = 1;
    scratch.island_set.assign(bodies.size(), no_sleep_set);
    for (std::uint32_t i = 0; i < bodies.size(); ++i) {
      body_record<T>& r = bodies[i];
      if (r.body.type != body_type::dynamic || r.awake) continue;
      const std::uint32_t root = scratch.islands.find(i);
      if (scratch.island_flag[root]) {
        state.wake(r);
        continue;
      }
      std::uint32_t& set = scratch.island_set[root];
      if (set == no_sleep_set) set = new_sleep_set();
      r.sleep_set = set;
      state.sleep_sets[set].push_back(state.bodies.ids()[i]);
    }
    state.awake_stale = true;
  }

  std::uint32_t new_sleep_set() {
    if (!state.free_sleep_sets.empty()) {
      const std::uint32_t set = state.free_sleep_sets.back();
      state.free_sleep_sets.pop_back();
      return set;
    }
    state.sleep_sets.emplace_back();
    return std::uint32_t(state.sleep_sets.size() - 1);
  }

  void put_to_sleep(body_record<T>& r, body_id id, std::uint32_t set) {
    r.awake = false;
    r.body.linear_momentum = {};
    r.body.angular_momentum = {};
    r.sleep_set = set;
    state.sleep_sets[set].push_back(id);
    state.awake_stale = true;
  }
};

}  // namespace impulse::detail
