// impulse/world/world_events.hpp — what a step reports: contacts that began
// or ended, joints that broke, and how much of the world it visited.
#pragma once

#include <cstddef>

#include "../dynamics/fwd.hpp"

namespace impulse {

/// Two bodies that began or stopped touching in the last step (touching:
/// their shapes are within the solver's speculative distance).
struct contact_event {
  body_id a;
  body_id b;
  friend constexpr bool operator==(const contact_event&, const contact_event&) = default;
};

/// A body that began or stopped overlapping a sensor (body_def::sensor) in
/// the last step, or that lost the sensor, or the sensor it, since.
struct sensor_event {
  body_id sensor;
  body_id visitor;
  friend constexpr bool operator==(const sensor_event&, const sensor_event&) = default;
};

/// A joint that broke in the last step: the impulse it applied exceeded
/// its break_force or break_torque times the step.
template <scalar_type T>
struct joint_broken_event {
  joint_id joint;
  body_id a;
  body_id b;
  T time = T(0);    ///< the world's time at the end of the step it broke in, s
  T force = T(0);   ///< what it applied in that step, N
  T torque = T(0);  ///< N·m
  friend constexpr bool operator==(const joint_broken_event&, const joint_broken_event&) = default;
};

/// How long the last step took, stage by stage, in milliseconds of the
/// monotonic clock (world::last_step_profile). Always measured: a few clock
/// reads a step. The stages run in this order; with a task hook
/// (world::set_task_system) each runs across the workers, but for the
/// parts docs/world.md ("Across workers") names, which stay on the thread
/// that called step().
struct step_profile {
  double broad = 0;       ///< the moving bodies' boxes into the broad phase, and its pairs
  double narrow = 0;      ///< the contact records merged with the pairs, and the pair tests
  double prepare = 0;     ///< the solver's bodies, contacts, joints and springs, and the contacts' masses
  double solve = 0;       ///< the contact and joint solver
  double integrate = 0;   ///< impulses kept, bodies moved (or held), joints projected (the first two in `solve`
                          ///< when it went by groups of islands, step_counts::solver_groups)
  double continuous = 0;  ///< continuous collision of fast bodies
  double sensors = 0;     ///< the sensors' overlaps
  double sleep = 0;       ///< islands woken, then put to sleep
  double total = 0;       ///< the whole step, these and what lies between them
};

/// How much of the world the last step worked on (world::last_step_counts):
/// what a profile needs beside the times, and what shows that sleeping
/// bodies cost nothing (docs/world.md, "Sleeping costs nothing").
struct step_counts {
  std::size_t active_bodies = 0;     ///< awake dynamic bodies and kinematic ones: those the step moved or could have
  std::size_t solver_bodies = 0;     ///< those the solver saw: the active ones and the static ones they touch
  std::size_t updated_contacts = 0;  ///< contact records the narrow phase updated (tested, or carried with their bodies)
  std::size_t solved_manifolds = 0;  ///< touching manifolds the solver solved
  std::size_t solved_joints = 0;
  std::size_t solved_springs = 0;
  /// Groups of islands the solver shared among the workers, each solved
  /// whole on one; 0 when it shared each color's batches instead, or ran
  /// on one thread (docs/world.md, "Across workers").
  std::size_t solver_groups = 0;
  std::size_t colors = 0;   ///< colors of the solver's contact graph (its batches of one color share no moving body)
  std::size_t islands = 0;  ///< awake islands, with sleeping on (0 with it off: the step makes none)
  bool pairs_merged = false;  ///< a pair began or ended, and the records were merged with the broad phase's pairs
  friend constexpr bool operator==(const step_counts&, const step_counts&) = default;
};

/// The last step at a glance (world::profile): its stage times and counts,
/// and what the world holds after it.
struct world_profile {
  step_profile times;
  step_counts counts;
  std::size_t bodies = 0;
  std::size_t pairs = 0;     ///< the broad phase's: bodies whose boxes overlap
  std::size_t contacts = 0;  ///< contact records: pairs that may touch
  std::size_t touching = 0;  ///< of those, touching
  std::size_t joints = 0;
  std::size_t sensors = 0;
};

}  // namespace impulse
