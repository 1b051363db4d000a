// impulse/world/fwd.hpp — the world module's names.
#pragma once

#include "../core/policy.hpp"
#include "../dynamics/fwd.hpp"

namespace impulse {

template <scalar_type T> struct body_def;
template <scalar_type T, class SolverSettings = sequential_impulse_settings<T>> struct world_settings;
template <scalar_type T> struct world_ray_hit;
struct contact_event;
template <scalar_type T> struct joint_broken_event;
struct debug_color;
struct debug_draw_flags;
template <class Config> class world_snapshot;
template <class Config = default_config> class world;

}  // namespace impulse
