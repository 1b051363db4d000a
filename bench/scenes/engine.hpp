// bench/scenes/engine.hpp — what an engine adapter of the scenes benchmark
// provides, so that main.cpp runs every engine through the same loop and
// metrics.hpp judges them all from the same numbers.
//
// An adapter is a default-constructible type, built once per scene run:
//
//   static constexpr std::string_view name;  // the CSV's engine column
//   std::string config() const;             // the CSV's config column (no commas)
//   void build(const scene_spec&);          // create the bodies, in order
//   void step();                            // exactly one step of spec.dt
//   std::span<const body_state> states();   // every body, in spec order
//
// An adapter may also report the last step's time per stage, in ms:
//
//   stage_times profile() const;            // after step(), outside the clock
//
// step() is the only call that is timed, so it must hold the whole of an
// engine's step (collision detection, solving, integration) and nothing
// else; states() may copy, it is called outside the clock. Adding an
// engine is one header with such a type and one line in main.cpp's engine
// list, or, for a peer library, in peers.cpp's (impulse_engine.hpp is
// impulse's own).
#pragma once

#include <concepts>
#include <span>
#include <string>
#include <string_view>

#include "scene_spec.hpp"

namespace bench::scenes {

/// A body's state as an engine reports it after a step, in double whatever
/// the engine's own scalar.
struct body_state {
  vec3 position;          ///< m, center of mass
  quat orientation;       ///< body to world
  vec3 linear_velocity;   ///< m/s
  vec3 angular_velocity;  ///< rad/s, world frame
  bool awake = false;     ///< simulated this step (not asleep, not static)
};

/// The stages of a step an engine may report (impulse's step_profile),
/// in ms, in this order.
inline constexpr const char* stage_names[] = {"broad", "narrow", "prepare", "solve", "integrate", "continuous", "sleep"};
inline constexpr int stage_count = 7;
struct stage_times {
  double ms[stage_count] = {};
};

template <class E>
concept profiled_engine = requires(const E& ce) {
  { ce.profile() } -> std::convertible_to<stage_times>;
};

template <class E>
concept scene_engine = std::default_initializable<E> && requires(E& e, const E& ce, const scene_spec& s) {
  { E::name } -> std::convertible_to<std::string_view>;
  { ce.config() } -> std::convertible_to<std::string>;
  e.build(s);
  e.step();
  { e.states() } -> std::convertible_to<std::span<const body_state>>;
};

}  // namespace bench::scenes
