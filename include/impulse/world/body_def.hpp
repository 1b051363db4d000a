// impulse/world/body_def.hpp — how to make a body: its type, pose,
// velocities, material and mass, as world::create_body takes them.
#pragma once

#include <cstdint>

#include "../dynamics/fwd.hpp"
#include "../dynamics/material.hpp"
#include "../dynamics/rigid_body.hpp"
#include "../math/mat3.hpp"
#include "../math/transform.hpp"
#include "collision_filter.hpp"

namespace impulse {

/// A body to create. Everything is checked by world::create_body before
/// the world changes.
template <scalar_type T>
struct body_def {
  body_type type = body_type::dynamic;
  /// Where the shape's origin is and how it is turned. (A hull whose center
  /// of mass is off its origin keeps the origin here; the body's position
  /// is its center of mass.)
  transform<T> pose = transform<T>::identity();
  vec3<T> linear_velocity{};   ///< m/s (dynamic and kinematic bodies)
  vec3<T> angular_velocity{};  ///< rad/s, world (dynamic and kinematic bodies)
  impulse::material<T> material{};
  /// kg. 0: the shape's volume times material.density. A dynamic body's
  /// inertia is the shape's, scaled to this mass.
  T mass = T(0);
  /// kg·m² about the center of mass, in the shape's frame (a tensor from a
  /// CAD tool, or a test's principal moments). Zero: the shape's, scaled
  /// to the mass. Refused unless symmetric and positive definite, with
  /// principal moments that a solid can have (I_a + I_b ≥ I_c).
  mat3<T> inertia = mat3<T>::zero();
  /// Created asleep: a settled scene loaded from a file need not settle again.
  bool awake = true;
  /// With ccd on in the world's config: swept every step against every
  /// body it could meet, dynamic ones too (a projectile). Other bodies are
  /// swept only when fast, and only against static and kinematic ones.
  bool bullet = false;
  /// Which bodies it may touch (collision_filter.hpp): by default, all.
  collision_filter filter{};
  /// A sensor makes no contacts: it reports the bodies its shape overlaps
  /// (world::sensor_overlaps, sensor events), those its filter lets
  /// through, of every type, asleep or not, but no other sensor. Queries
  /// see it only when their filter asks for sensors.
  bool sensor = false;
  std::uint64_t user_data = 0;
};

}  // namespace impulse
