// impulse/world/body_def.hpp — what a world is told: how to make a body,
// and the settings of the world itself; and what it reports back.
#pragma once

#include <cmath>
#include <cstdint>

#include "../core/error.hpp"
#include "../dynamics/fwd.hpp"
#include "../dynamics/material.hpp"
#include "../dynamics/rigid_body.hpp"
#include "../dynamics/solver_settings.hpp"
#include "../math/transform.hpp"

namespace impulse {

/// A body to create. Everything is checked by world::create_body before
/// the world changes.
template <scalar_type T>
struct body_def {
  body_type type = body_type::dynamic;
  /// Where the shape's origin is and how it is turned. (A hull whose centre
  /// of mass is off its origin keeps the origin here; the body's position
  /// is its centre of mass.)
  transform<T> pose = transform<T>::identity();
  vec3<T> linear_velocity{};   ///< m/s (dynamic and kinematic bodies)
  vec3<T> angular_velocity{};  ///< rad/s, world (dynamic and kinematic bodies)
  impulse::material<T> material{};
  /// kg. 0: the shape's volume times material.density. A dynamic body's
  /// inertia is the shape's, scaled to this mass.
  T mass = T(0);
  /// Created asleep: a settled scene loaded from a file need not settle again.
  bool awake = true;
  /// With ccd on in the world's config: swept every step against every
  /// body it could meet, dynamic ones too (a projectile). Other bodies are
  /// swept only when fast, and only against static and kinematic ones.
  bool bullet = false;
  std::uint64_t user_data = 0;
};

/// The world's runtime settings (the compile-time ones are in its config).
template <scalar_type T>
struct world_settings {
  vec3<T> gravity{T(0), T(-9.81), T(0)};  ///< m/s²
  solver_settings<T> solver{};
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
  /// centre, so the angle here is 0.5° (4.4 mm): a box tipping over an
  /// edge is tested again before it has turned far.
  T contact_reuse_distance = T(0.001);  ///< m
  T contact_reuse_angle = T(0.0087);    ///< rad
  /// With ccd on in the config, a body whose centre moves farther in a step
  /// than this fraction of its thinnest half-extent (a ball's radius) is
  /// swept against static and kinematic bodies. Below it the speculative
  /// contacts (solver.speculative_distance) already catch what it meets.
  T ccd_motion_fraction = T(0.5);
  /// How far short of the impact a swept body is stopped, m: the next
  /// step's speculative contact then meets it apart, not overlapping by
  /// rounding. Box2D's linear slop.
  T ccd_gap = T(0.005);

  void validate() const {
    if (!is_finite(gravity)) detail::report_error(error_code::non_finite, "world_settings: gravity is not finite");
    solver.validate();
    if (!std::isfinite(fixed_dt) || !(fixed_dt > T(0)))
      detail::report_error(error_code::invalid_parameter, "world_settings: fixed_dt must be positive and finite");
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
  }
};

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

/// The nearest body a ray meets.
template <scalar_type T>
struct world_ray_hit {
  body_id body;
  T fraction = T(0);  ///< of the ray's translation
  vec3<T> point{};    ///< world, m
  vec3<T> normal{};   ///< world, unit, out of the body
};

}  // namespace impulse
