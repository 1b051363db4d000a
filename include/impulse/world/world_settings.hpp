// impulse/world/world_settings.hpp — a world's runtime settings (the
// compile-time ones are in its config): gravity, its solver's settings, the
// fixed step, sleeping, contact reuse, continuous collision, and the limits
// bad input is refused at.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "../core/error.hpp"
#include "../dynamics/solver_settings.hpp"
#include "../math/vec3.hpp"
#include "fwd.hpp"

namespace impulse {

namespace detail {

/// Every runtime setting of a world but its solver's: world_settings below.
template <scalar_type T>
struct world_settings_base {
  vec3<T> gravity{T(0), T(-9.81), T(0)};  ///< m/s²
  /// The step advance() takes, s: physics at a fixed rate whatever the
  /// frame rate, so that a scene behaves the same on every machine.
  T fixed_dt = T(1) / T(60);
  /// The most steps one advance() takes. A frame that took longer than
  /// this many steps (a debugger stop, a loading hitch) slows the
  /// simulation down instead of making the next frame slower still (the
  /// "spiral of death").
  int max_steps_per_advance = 8;
  /// A body whose speed stays below these for sleep_time seconds, with
  /// every body of its island, sleeps (when the config has `sleeping`).
  /// 5 cm/s and 2°/s are Box2D's: a settled box jitters at under 1 mm/s.
  T sleep_linear_speed = T(0.05);   ///< m/s
  T sleep_angular_speed = T(0.035);  ///< rad/s
  T sleep_time = T(0.5);            ///< s
  /// A pair whose relative pose has moved less than these since its last
  /// full test keeps that test's manifolds, carried with the bodies, and
  /// skips the pair test (world.hpp, reuse_manifolds); either at 0 tests
  /// every pair every step. Jolt's body pair cache takes 1 mm and 2°; a
  /// point carried with its body may lie past the edge of the face under
  /// it by as much as it slid, 17 mm at 2° for a corner 0.5 m from the
  /// center, so the angle here is 0.5° (4.4 mm): a box tipping over an
  /// edge is tested again before it has turned far.
  T contact_reuse_distance = T(0.001);  ///< m
  T contact_reuse_angle = T(0.0087);    ///< rad
  /// With ccd on in the config, a body whose center moves farther in a step
  /// than this fraction of its thinnest half-extent (a ball's radius) is
  /// swept against static and kinematic bodies. Below it the speculative
  /// contacts (solver.speculative_distance) already catch what it meets.
  T ccd_motion_fraction = T(0.5);
  /// How far short of the impact a swept body is stopped, m: the next
  /// step's speculative contact then meets it apart, not overlapping by
  /// rounding. Box2D's linear slop.
  T ccd_gap = T(0.005);
  /// The fastest a body may move, linearly and turning. These are bounds
  /// against overflow, not physical limits: 10 km/s is 170 m in a step of
  /// 1/60 s, beyond what any step resolves, and well inside what the
  /// solver's products of speeds, masses and lengths keep finite in float.
  /// A velocity above them is refused where it is set (set_velocity,
  /// create_body, set_target_pose); a body that a step's forces or its
  /// solve would take past them is held (step(), held_bodies()).
  T max_linear_speed = T(1e4);   ///< m/s
  T max_angular_speed = T(1e4);  ///< rad/s
  /// How far the limits above may be raised: past 1e6, squares of speeds
  /// times masses and lengths leave float's range.
  static constexpr T speed_ceiling = T(1e6);
  /// The most body pairs the world keeps contacts for; a pair past it gets
  /// none until there is room (world::pairs_over_limit counts them). A
  /// touching pair costs about 1.1 KB in float and 2 KB in double at its
  /// peak in a step, solver included (bench/contact_memory, 1 000 boxes in
  /// one spot), so the default bounds a step's contacts at about 1.1 GB and
  /// 2.1 GB. A thousand bodies dropped in one spot make 500 000 pairs.
  std::uint32_t max_contact_pairs = 1u << 20;
  /// How far from the origin, along any axis, the world places bodies,
  /// anchors and targets, m: a bound against overflow like the speeds. In
  /// float, 1e6 m is where neighbouring floats are 6 cm apart, already too
  /// coarse for contacts (Box2D's bound is 1e5 m); in double, 1e12 m (0.1 mm
  /// apart). A pose or anchor beyond it is refused; a body that a step would
  /// carry past it is held.
  T max_coordinate = std::is_same_v<T, float> ? T(1e6) : T(1e12);
  static constexpr T coordinate_ceiling = std::is_same_v<T, float> ? T(1e8) : T(1e15);
  /// How far a joint's anchor may be from a dynamic body's center of mass,
  /// in multiples of the body's smallest radius of gyration (√(I_min / m):
  /// 0.41 m for a unit cube, 6 mm for a 1 cm ball). Farther, the joint's
  /// effective mass along the lever is lost in rounding (its part 1/m is
  /// below the lever's r²/I times the scalar's epsilon) and the solve
  /// diverges: a ball 14 cm across joined 1e7 m from its center went to
  /// NaN in its first step. 1 000 in float, 10⁶ in double; a long pendulum
  /// is a distance joint, whose anchors sit on the bodies.
  T max_joint_lever = std::is_same_v<T, float> ? T(1e3) : T(1e6);

  void validate() const {
    if (!is_finite(gravity)) detail::report_error(error_code::non_finite, "world_settings: gravity is not finite");
    if (!(fixed_dt > T(0) && fixed_dt <= T(1)))
      detail::report_error(error_code::invalid_parameter, "world_settings: fixed_dt must be positive and at most 1 s");
    if (max_steps_per_advance < 1)
      detail::report_error(error_code::invalid_parameter, "world_settings: max_steps_per_advance must be >= 1");
    if (!std::isfinite(sleep_linear_speed) || !std::isfinite(sleep_angular_speed) || !std::isfinite(sleep_time) ||
        sleep_linear_speed < T(0) || sleep_angular_speed < T(0) || sleep_time < T(0))
      detail::report_error(error_code::invalid_parameter,
                           "world_settings: sleep speeds and time must be finite and >= 0");
    if (!std::isfinite(contact_reuse_distance) || !std::isfinite(contact_reuse_angle) ||
        contact_reuse_distance < T(0) || contact_reuse_angle < T(0))
      detail::report_error(error_code::invalid_parameter,
                           "world_settings: contact reuse distance and angle must be finite and >= 0");
    if (!std::isfinite(ccd_motion_fraction) || !std::isfinite(ccd_gap) || ccd_motion_fraction < T(0) ||
        ccd_gap < T(0))
      detail::report_error(error_code::invalid_parameter,
                           "world_settings: ccd_motion_fraction and ccd_gap must be finite and >= 0");
    if (!std::isfinite(max_joint_lever) || !(max_joint_lever > T(0)))
      detail::report_error(error_code::invalid_parameter, "world_settings: max_joint_lever must be positive and finite");
    if (!(max_coordinate > T(0) && max_coordinate <= coordinate_ceiling))
      detail::report_error(error_code::invalid_parameter,
                           "world_settings: max_coordinate must be positive and at most 1e8 (float) or 1e15 (double)");
    if (max_contact_pairs < 1)
      detail::report_error(error_code::invalid_parameter, "world_settings: max_contact_pairs must be >= 1");
    if (!(max_linear_speed > T(0) && max_linear_speed <= speed_ceiling) ||
        !(max_angular_speed > T(0) && max_angular_speed <= speed_ceiling))
      detail::report_error(error_code::invalid_parameter,
                           "world_settings: max_linear_speed and max_angular_speed must be positive and at most 1e6");
    // Gravity that would take a body past the speed limit within a second
    // (the longest step) is an overflow waiting to happen: every body would
    // be held at every step.
    if (!(length_squared(gravity) <= max_linear_speed * max_linear_speed))
      detail::report_error(error_code::invalid_parameter,
                           "world_settings: gravity must be at most max_linear_speed per second");
  }
};

}  // namespace detail

/// The world's runtime settings (the compile-time ones are in its config):
/// those above, and its solver's (solver_settings.hpp): a world<Config>
/// holds world_settings<T, its solver's settings_type>, its settings_type,
/// so a soft_step world has soft_step's knobs and a sequential_impulse
/// world has its own. The default is sequential_impulse's, the default
/// config's solver.
template <scalar_type T, class SolverSettings>
struct world_settings : detail::world_settings_base<T> {
  using solver_settings_type = SolverSettings;
  SolverSettings solver{};

  void validate() const {
    detail::world_settings_base<T>::validate();
    solver.validate();
  }
};

}  // namespace impulse
