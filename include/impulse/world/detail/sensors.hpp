// impulse/world/detail/sensors.hpp — the step's last collision stage: what
// each sensor body overlaps at the end of the step, and the bodies that
// came in or went out since the last, as events.
//
// A sensor makes no contacts (contact_update.hpp never pairs it), so it
// costs the solver nothing. Each step it asks the broad phase for the
// bodies whose boxes meet its shape's box, and tests each one its filters
// let through (world_state::may_collide) with the pair test at no margin:
// the two overlap when a point of it is at depth zero or more. Every body
// type counts, asleep or awake; another sensor does not.
//
// The sensors are tested across the world's workers, each writing only its
// own sensor's list; the events are then found on the calling thread, the
// sensors in the order they were made and each list ascending by body
// index. So the events are the same for any number of workers.
//
// The broad phase's boxes cover each body's motion over the step, except
// one that went farther than the solver's max_speculative_distance: its
// overlap with a sensor is then found a step late.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "world_state.hpp"

namespace impulse::detail {

/// Whether two shapes (the dispatcher's references) at their poses overlap
/// or touch: their pair test at no margin has a point at depth zero or
/// more. A sensor's test, and world::shape_overlap's.
template <class Dispatcher, scalar_type T>
[[nodiscard]] bool shapes_overlap(const typename Dispatcher::shape_ref& a, const transform<T>& pose_a,
                                  const typename Dispatcher::shape_ref& b, const transform<T>& pose_b) {
  std::array<contact_manifold<T>, max_manifolds> found;
  const std::size_t n =
      Dispatcher::collide(a, pose_a, b, pose_b, T(0), std::span<contact_manifold<T>>(found.data(), found.size()));
  for (std::size_t m = 0; m < n; ++m)
    for (const contact_point<T>& p : found[m].contacts())
      if (p.depth >= T(0)) return true;
  return false;
}

template <class Config>
struct sensor_update {
  using T = typename Config::scalar;
  using dispatcher = typename world_state<Config>::dispatcher;
  /// Sensors a worker takes at a time: a query and a few pair tests each.
  static constexpr std::uint32_t min_sensors_per_range = 8;

  world_state<Config>& state;
  step_scratch<Config>& scratch;

  void run() {
    std::vector<sensor_record>& sensors = state.sensors;
    if (sensors.empty()) return;
    std::vector<std::vector<body_id>>& next = scratch.sensor_next;
    if (next.size() < sensors.size()) next.resize(sensors.size());
    auto gather = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      for (std::uint32_t k = begin; k < end; ++k) find_inside(sensors[k].sensor, next[k]);
    };
    parallel_for(scratch.tasks, std::uint32_t(sensors.size()), min_sensors_per_range, gather);
    for (std::size_t k = 0; k < sensors.size(); ++k) {
      report(sensors[k], next[k]);
      sensors[k].inside.swap(next[k]);
    }
  }

 private:
  /// The bodies the sensor's shape overlaps, ascending by index.
  void find_inside(body_id sensor, std::vector<body_id>& inside) const {
    inside.clear();
    const body_record<T>& rs = state.bodies[sensor];
    const transform<T> pose = shape_pose_of(rs);
    state.broad.query(state.bounds_of(rs), [&](proxy_id proxy) {
      const body_id other = state.unpack(state.broad.user_data(proxy));
      if (other == sensor) return;
      const body_record<T>& ro = state.bodies[other];
      if (ro.sensor || !state.may_collide(sensor, other, scratch.pair_rule)) return;
      if (shapes_overlap<dispatcher>(state.shape_ref_of(rs), pose, state.shape_ref_of(ro), shape_pose_of(ro)))
        inside.push_back(other);
    });
    std::ranges::sort(inside, {}, &body_id::index);
  }

  /// Events for the bodies in one list and not the other (both ascending).
  void report(const sensor_record& was, const std::vector<body_id>& now) const {
    std::size_t i = 0, j = 0;
    const std::vector<body_id>& before = was.inside;
    while (i < before.size() || j < now.size()) {
      if (j == now.size() || (i < before.size() && before[i].index < now[j].index)) {
        state.sensor_ended.push_back({was.sensor, before[i++]});
      } else if (i == before.size() || now[j].index < before[i].index) {
        state.sensor_begun.push_back({was.sensor, now[j++]});
      } else {
        // The same slot: the same body, or one made in a destroyed one's
        // place (world::destroy_body ends the destroyed one's overlaps).
        if (before[i] != now[j]) {
          state.sensor_ended.push_back({was.sensor, before[i]});
          state.sensor_begun.push_back({was.sensor, now[j]});
        }
        ++i, ++j;
      }
    }
  }
};

}  // namespace impulse::detail
