// impulse/dynamics/fwd.hpp — the dynamics module's names.
#pragma once

#include <cstdint>

#include "../core/policy.hpp"
#include "../core/slot_map.hpp"

namespace impulse {

enum class body_type : std::uint8_t;
template <scalar_type T> struct rigid_body;
template <scalar_type T> struct body_pose;
template <scalar_type T> struct body_momentum;
template <scalar_type T> struct body_kinematics;
template <scalar_type T> struct wrench;
template <scalar_type T> struct body_spring;
enum class joint_type : std::uint8_t;
template <scalar_type T> struct joint_def;
template <scalar_type T> struct joint_constraint;
template <scalar_type T> struct solver_settings;
template <scalar_type T> struct sequential_impulse_settings;
template <scalar_type T> struct soft_step_settings;

// A world's ids carry the world that made them (core/slot_map.hpp).
struct body_tag {
  static constexpr bool owned = true;
};
struct spring_tag {
  static constexpr bool owned = true;
};
struct joint_tag {
  static constexpr bool owned = true;
};
/// Names a body of a world.
using body_id = object_id<body_tag>;
/// Names a spring of a world.
using spring_id = object_id<spring_tag>;
/// Names a joint of a world.
using joint_id = object_id<joint_tag>;

struct default_config;

}  // namespace impulse
