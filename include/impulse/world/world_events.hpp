// impulse/world/world_events.hpp — what a step reports: contacts that began
// or ended, joints that broke.
#pragma once

#include "../dynamics/fwd.hpp"

namespace impulse {

/// Two bodies that began or stopped touching in the last step (touching:
/// their shapes are within the solver's speculative distance).
struct contact_event {
  body_id a;
  body_id b;
  friend constexpr bool operator==(const contact_event&, const contact_event&) = default;
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

}  // namespace impulse
