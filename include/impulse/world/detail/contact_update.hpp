// impulse/world/detail/contact_update.hpp — the step's collision stages: each
// moving body's proxy moved in the broad phase, then the narrow phase over
// the pairs it reports (docs/architecture.md, "The step").
//
// Each pair with a dynamic body gets its manifolds from the dispatcher of
// the config's shape_list; points that keep their feature id keep their
// impulses (warm start); a pair that has moved less than the reuse limits
// since its last full test keeps that test's manifolds, carried with its
// bodies. Pairs that start or stop touching become events. The records
// stay sorted by proxy pair, merged with the broad phase's pairs in one
// pass.
//
// The pair tests run across the world's workers (world::set_task_system):
// each record is tested by one worker, which writes only that record and
// the manifolds it holds. What is shared is done afterwards on the calling
// thread in the records' order: the manifold slots of a record whose count
// of manifolds changed, and the begin and end events. So a step gives the
// same bits for any number of workers.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "../../narrowphase/time_of_impact.hpp"
#include "world_state.hpp"

namespace impulse::detail {

template <class Config>
struct contact_update {
  using T = typename Config::scalar;
  using dispatcher = typename world_state<Config>::dispatcher;
  using pair_work = worker_pairs<T>;
  using resized_record = typename pair_work::resized_record;
  using touch_event = typename pair_work::touch_event;
  /// Records a worker tests at a time: a pair test takes 0.1 to a few µs.
  static constexpr std::uint32_t min_pairs_per_range = 64;
  /// Bodies whose boxes a worker works out at a time: about 100 ns each.
  static constexpr std::uint32_t min_bodies_per_range = 512;
  /// What a body's proxy took in update_broad_phase: nothing (the body
  /// stands still), a move within its fat box (done across the workers),
  /// or a move by move() on the calling thread.
  enum proxy_move : std::uint8_t { still, within, by_move };

  world_state<Config>& state;
  step_scratch<Config>& scratch;
  T step = T(0);  ///< s: the step's length

  /// The broad phase, then the narrow phase, for a step of h.
  void run(T h) {
    step = h;
    state.counts = step_counts{};
    state.refresh_awake();
    stopwatch lap;
    update_broad_phase(h);
    scratch.profile.broad = lap.lap_ms();
    update_contacts();
    scratch.profile.narrow = lap.lap_ms();
  }

 private:
  /// The moving bodies' boxes, worked out across the workers (each its own
  /// body's reach and box), then moved into the broad phase in order. A
  /// broad phase that can move a proxy within what it already holds, with
  /// no shared change (dynamic_bvh::move_within), takes those moves across
  /// the workers too, and the calling thread moves only the rest: in
  /// `pile`, about one box in a hundred a step, where the thousand moves
  /// took 90 µs on the calling thread.
  void update_broad_phase(T h) {
    const std::span<const std::uint32_t> awake = state.awake_bodies;
    std::vector<aabb<T>>& boxes = scratch.proxy_boxes;
    std::vector<std::uint8_t>& way = scratch.proxy_moves;
    boxes.resize(awake.size());
    way.resize(awake.size());
    auto reach = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      for (std::uint32_t k = begin; k < end; ++k) {
        body_record<T>& r = state.bodies.values()[awake[k]];
        way[k] = still;
        if (!is_moving(r)) continue;
        boxes[k] = state.proxy_box(r, state.set_reach(r, h));
        way[k] = by_move;
        if constexpr (requires { state.broad.move_within(r.proxy, boxes[k]); })
          if (state.broad.move_within(r.proxy, boxes[k])) way[k] = within;
      }
    };
    parallel_for(scratch.tasks, std::uint32_t(awake.size()), min_bodies_per_range, reach);
    bool any_within = false;
    for (std::size_t k = 0; k < awake.size(); ++k) {
      any_within = any_within || way[k] == within;
      if (way[k] == by_move) state.broad.move(state.bodies.values()[awake[k]].proxy, boxes[k]);
    }
    if constexpr (requires { state.broad.moved_within(); })
      if (any_within) state.broad.moved_within();
    if constexpr (requires { state.broad.update(scratch.tasks); })
      state.broad.update(scratch.tasks);
    else
      state.broad.update();
  }


  /// How far a pair may move before its pair test runs again
  /// (world_settings::contact_reuse_distance and _angle), as collide
  /// compares them.
  struct reuse_limits {
    T distance_squared;
    T cos_half_angle;
  };

  void update_contacts() {
    const std::span<const proxy_pair> pairs = state.broad.pairs();
    std::vector<contact_record<T>>& old = state.contacts;
    const auto& s = state.settings;
    const reuse_limits limits{s.contact_reuse_distance * s.contact_reuse_distance,
                              portable_cos(s.contact_reuse_angle / T(2))};
    // With the broad phase's pairs as they were, the records are too (but
    // for pairs waiting for room, and those a joint no longer keeps apart),
    // and only the pairs of bodies that move can change: a sleeping pile
    // costs nothing here.
    const bool quiet = !state.pairs_stale && state.pairs_over_limit == 0 && state.broad.begun().empty() &&
                       state.broad.ended().empty();
    state.pairs_stale = false;
    if (quiet) {
      const std::span<const std::uint32_t> awake = state.awake_contacts;
      collide_all(std::uint32_t(awake.size()), [&](std::uint32_t i) { return awake[i]; }, limits);
      return;
    }
    state.counts.pairs_merged = true;
    // Most steps have the last step's pairs: then the records are updated
    // where they are, rather than copied over.
    if (same_pairs(pairs)) {
      collide_all(std::uint32_t(old.size()), [](std::uint32_t i) { return i; }, limits);
      return;
    }
    scratch.next_contacts.clear();
    scratch.next_contacts.reserve(std::min(pairs.size(), std::size_t(s.max_contact_pairs)));
    // New pairs are taken while the records, old and new, stay within
    // max_contact_pairs; those past it wait, and are counted.
    const std::size_t room = std::size_t(s.max_contact_pairs) > old.size() ? s.max_contact_pairs - old.size() : 0;
    std::size_t created = 0;
    state.pairs_over_limit = 0;
    std::size_t i = 0;
    for (const proxy_pair& pair : pairs) {
      while (i < old.size() && old[i].key < pair) state.end_contact(old[i++]);
      if (i < old.size() && old[i].key == pair) {
        scratch.next_contacts.push_back(old[i++]);
      } else {
        if (!may_touch(pair)) continue;
        if (created == room) {
          ++state.pairs_over_limit;
          continue;
        }
        ++created;
        const body_id a = state.unpack(state.broad.user_data(pair.a)), b = state.unpack(state.broad.user_data(pair.b));
        const body_record<T>& ra = state.bodies[a];
        const body_record<T>& rb = state.bodies[b];
        contact_record<T> c{};
        c.key = pair;
        c.a = a, c.b = b;
        c.friction = combine_friction(ra.material.friction, rb.material.friction);
        c.restitution = combine_restitution(ra.material.restitution, rb.material.restitution);
        scratch.next_contacts.push_back(c);
      }
    }
    while (i < old.size()) state.end_contact(old[i++]);
    old.swap(scratch.next_contacts);
    state.awake_stale = true;
    collide_all(std::uint32_t(old.size()), [](std::uint32_t i) { return i; }, limits);
  }

  /// Tests the records index(0), …, index(count − 1) (collide), across
  /// the workers, then does in the records' order what they share. One
  /// worker does it as it goes, in the same order, so that it keeps no
  /// copy of the manifolds: the slots it takes are the same.
  template <class Index>
  void collide_all(std::uint32_t count, Index index, const reuse_limits& limits) {
    const task_system& tasks = scratch.tasks;
    std::vector<pair_work>& work = scratch.pair_work;
    work.resize(tasks.parallel() ? tasks.workers : 1);
    for (std::size_t k = 0; k < work.size(); ++k) work[k].clear(std::uint32_t(k));
    work[0].direct = work.size() == 1;
    auto range = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t worker) {
      pair_work& w = work[worker];
      for (std::uint32_t i = begin; i < end; ++i) collide(index(i), limits, w);
    };
    parallel_for(tasks, count, min_pairs_per_range, range);
    // Gathered in the records' order, whichever worker tested which.
    pair_work& all = work[0];
    for (std::size_t k = 1; k < work.size(); ++k) {
      all.resized.insert(all.resized.end(), work[k].resized.begin(), work[k].resized.end());
      all.events.insert(all.events.end(), work[k].events.begin(), work[k].events.end());
      all.updated += work[k].updated;
    }
    if (work.size() > 1) {
      std::sort(all.resized.begin(), all.resized.end(),
                [](const resized_record& x, const resized_record& y) { return x.record < y.record; });
      std::sort(all.events.begin(), all.events.end(),
                [](const touch_event& x, const touch_event& y) { return x.record < y.record; });
    }
    for (const resized_record& r : all.resized) {
      contact_record<T>& c = state.contacts[r.record];
      const pair_work& from = work[r.worker];
      resize_slots(c, int(r.count));
      for (std::size_t m = 0; m < r.count; ++m)
        keep(c, m, from.fresh[r.first + m], from.carried[r.first + m], r.pose_a);
    }
    for (const touch_event& e : all.events) touch(state.contacts[e.record], e.begun);
    state.counts.updated_contacts += all.updated;
  }

  /// The record's bodies began (or stopped) touching: an event for them.
  void touch(const contact_record<T>& c, bool begun) const {
    (begun ? state.begun : state.ended).push_back({c.a, c.b});
  }

  /// Whether a pair of proxies can make contact: one of its bodies is
  /// dynamic, neither is a sensor, no joint between them keeps them apart, and the filters let
  /// them touch (world_state::may_collide).
  bool may_touch(const proxy_pair& pair) const {
    const body_id a = state.unpack(state.broad.user_data(pair.a)), b = state.unpack(state.broad.user_data(pair.b));
    const body_record<T>& ra = state.bodies[a];
    const body_record<T>& rb = state.bodies[b];
    return (ra.body.type == body_type::dynamic || rb.body.type == body_type::dynamic) && !ra.sensor && !rb.sensor &&
           state.may_collide(a, b, scratch.pair_rule);
  }

  /// Whether the broad phase's pairs, less those that cannot touch, are
  /// the records' pairs.
  bool same_pairs(std::span<const proxy_pair> pairs) const {
    const std::vector<contact_record<T>>& old = state.contacts;
    std::size_t i = 0;
    for (const proxy_pair& pair : pairs) {
      if (i < old.size() && old[i].key == pair) ++i;
      else if (may_touch(pair)) return false;
    }
    return i == old.size();
  }

  /// Gives the record n manifold slots, keeping its first ones: freed
  /// slots are reused before the pool grows.
  void resize_slots(contact_record<T>& c, int n) const {
    while (c.manifold_count > n) state.free_manifolds.push_back(c.slots[std::size_t(--c.manifold_count)]);
    while (c.manifold_count < n) {
      std::uint32_t slot;
      if (!state.free_manifolds.empty()) {
        slot = state.free_manifolds.back();
        state.free_manifolds.pop_back();
      } else {
        slot = std::uint32_t(state.manifolds.size());
        state.manifolds.emplace_back();
      }
      c.slots[std::size_t(c.manifold_count++)] = slot;
    }
  }

  /// The record `record` tested again, or its manifolds carried (below).
  /// Writes only the record and the manifolds it holds; a change in their
  /// count, and an event, go to the worker's `w` for collide_all, unless
  /// it is the only worker.
  void collide(std::uint32_t record, const reuse_limits& limits, pair_work& w) const {
    contact_record<T>& c = state.contacts[record];
    const body_record<T>& ra = state.bodies[c.a];
    const body_record<T>& rb = state.bodies[c.b];
    // Two bodies that are not moving keep their manifolds: sleeping ones
    // wake with the contacts they slept on.
    if (!is_moving(ra) && !is_moving(rb) && c.manifold_count > 0) return;
    ++w.updated;
    const transform<T> pose_a = shape_pose_of(ra), pose_b = shape_pose_of(rb);
    const transform<T> relative{inverse_apply(pose_a, pose_b.position), conjugate(pose_a.rotation) * pose_b.rotation};
    if (c.tested && reuse_manifolds(c, pose_a, relative, limits)) return;
    std::array<contact_manifold<T>, max_manifolds> fresh;
    const T near = state.settings.solver.speculative_distance;
    const T margin = speculative_margin(ra, rb);
    std::size_t n = dispatcher::collide(state.shape_ref_of(ra), pose_a, state.shape_ref_of(rb), pose_b, margin,
                                        std::span<contact_manifold<T>>(fresh.data(), fresh.size()));
    if (n > 0 && margin > near && nearest_gap(fresh, n) > near && !meet_within_step(ra, rb, pose_a, pose_b)) n = 0;
    std::array<manifold_impulse<T>, max_manifolds> carried{};
    for (std::size_t m = 0; m < n; ++m) {
      // The old manifold with the nearest normal (a mesh's several keep
      // theirs apart), then each point by its feature id.
      int match = -1;
      T best = T(0.95);  // normals within 18° count as the same face
      for (int k = 0; k < c.manifold_count; ++k) {
        const T d = dot(state.slot_of(c, k).manifold.normal, fresh[m].normal);
        if (d > best) best = d, match = k;
      }
      if (match < 0) continue;
      const contact_manifold<T>& before = state.slot_of(c, match).manifold;
      const manifold_impulse<T>& had = state.slot_of(c, match).impulse;
      carried[m].friction = had.friction;
      carried[m].twist = had.twist;
      for (int p = 0; p < fresh[m].count; ++p)
        for (int q = 0; q < before.count; ++q)
          if (before.points[std::size_t(q)].feature == fresh[m].points[std::size_t(p)].feature) {
            carried[m].normal[std::size_t(p)] = had.normal[std::size_t(q)];
            break;
          }
    }
    c.tested = true;
    c.tested_relative = relative;
    if (n != std::size_t(c.manifold_count) && !w.direct) {
      w.resized.push_back({record, std::uint32_t(n), w.worker, std::uint32_t(w.fresh.size()), pose_a});
      w.fresh.insert(w.fresh.end(), fresh.begin(), fresh.begin() + std::ptrdiff_t(n));
      w.carried.insert(w.carried.end(), carried.begin(), carried.begin() + std::ptrdiff_t(n));
    } else {
      resize_slots(c, int(n));
      for (std::size_t m = 0; m < n; ++m) keep(c, m, fresh[m], carried[m], pose_a);
    }
    const bool touching = n > 0;
    if (touching != c.touching) {
      if (w.direct) touch(c, touching);
      else w.events.push_back({record, touching});
    }
    c.touching = touching;
  }

  /// A fresh manifold and the impulses carried to it, in the record's
  /// m-th slot, with the manifold in A's frame for reuse_manifolds.
  void keep(contact_record<T>& c, std::size_t m, const contact_manifold<T>& fresh,
            const manifold_impulse<T>& carried, const transform<T>& pose_a) const noexcept {
    manifold_slot<T>& slot = state.slot_of(c, int(m));
    slot.manifold = fresh;
    slot.impulse = carried;
    contact_manifold<T>& local = slot.tested_local;
    local = fresh;
    local.normal = inverse_rotate(pose_a.rotation, fresh.normal);
    for (int p = 0; p < local.count; ++p)
      local.points[std::size_t(p)].position = inverse_apply(pose_a, fresh.points[std::size_t(p)].position);
  }

  /// How far ahead the pair's contacts reach: speculative_distance, or as
  /// far as their surfaces can close in the step if that is farther (each
  /// body's path and turn, set_reach), up to max_speculative_distance.
  T speculative_margin(const body_record<T>& ra, const body_record<T>& rb) const noexcept {
    const auto& solver = state.settings.solver;
    const bool moving_a = is_moving(ra), moving_b = is_moving(rb);
    const vec3<T> path = (moving_b ? rb.reach_path : vec3<T>{}) - (moving_a ? ra.reach_path : vec3<T>{});
    const T closing = length(path) + (moving_a ? ra.reach_turn : T(0)) + (moving_b ? rb.reach_turn : T(0));
    return std::max(solver.speculative_distance, std::min(closing, solver.max_speculative_distance));
  }

  static T nearest_gap(const std::array<contact_manifold<T>, max_manifolds>& manifolds, std::size_t n) noexcept {
    T gap = std::numeric_limits<T>::infinity();
    for (std::size_t m = 0; m < n; ++m)
      for (int p = 0; p < manifolds[m].count; ++p) gap = std::min(gap, -manifolds[m].points[std::size_t(p)].depth);
    return gap;
  }

  /// Whether the pair comes within speculative_distance in the step, each
  /// body swept along its reach (narrowphase/time_of_impact.hpp): a
  /// contact found farther ahead than that is kept only if so, or a fast
  /// body passing an edge would be stopped by it. Pairs without a support
  /// function (planes, meshes) have no edge to pass by and are kept.
  bool meet_within_step(const body_record<T>& ra, const body_record<T>& rb, const transform<T>& pose_a,
                        const transform<T>& pose_b) const {
    const narrowphase::sweep<T> path_a = sweep_of(ra, pose_a), path_b = sweep_of(rb, pose_b);
    return state.shape_store.visit(ra.shape, [&](const auto& a) {
      return state.shape_store.visit(rb.shape, [&](const auto& b) {
        if constexpr (requires(vec3<T> d) { a.support(d); b.support(d); }) {
          narrowphase::toi_options<T> options;
          options.target = state.settings.solver.speculative_distance;
          options.tolerance = options.target * T(0.25);
          return narrowphase::time_of_impact(a, path_a, b, path_b, options).state != narrowphase::toi_state::separated;
        } else {
          return true;
        }
      });
    });
  }
  /// A body's motion over the step as its reach says: its center along
  /// reach_path, turning at its angular velocity.
  narrowphase::sweep<T> sweep_of(const body_record<T>& r, const transform<T>& pose) const noexcept {
    if (!is_moving(r)) return {pose, pose, r.center};
    const quat<T> turned = integrate(pose.rotation, r.body.angular_velocity(), step);
    const vec3<T> center = r.body.position + r.reach_path;
    return {pose, {center - rotate(turned, r.center), turned}, r.center};
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
  bool reuse_manifolds(contact_record<T>& c, const transform<T>& pose_a, const transform<T>& relative,
                       const reuse_limits& limits) const noexcept {
    const vec3<T> shift = relative.position - c.tested_relative.position;
    if (!(length_squared(shift) < limits.distance_squared)) return false;
    // B's turn in A's frame since the test; |w| = cos(angle / 2).
    const quat<T> turn = relative.rotation * conjugate(c.tested_relative.rotation);
    if (!(std::abs(turn.w) > limits.cos_half_angle)) return false;
    for (int m = 0; m < c.manifold_count; ++m) {
      manifold_slot<T>& slot = state.slot_of(c, m);
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
};

}  // namespace impulse::detail
