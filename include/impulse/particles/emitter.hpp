// impulse/particles/emitter.hpp — a source that keeps a stream of particles coming.
//
// An emitter adds `rate` particles per second, each placed uniformly in a box
// around `position`, with a velocity drawn uniformly in `velocity` ±
// `velocity_spread` (per axis) and a lifetime drawn uniformly in
// `lifetime` ± `lifetime_spread`. Emission carries its fraction over between
// steps, so 30 particles/s at dt = 1/120 gives one particle every fourth step,
// not none. Its generator is seeded, so a run is the same every time.
//
// Particles whose age reaches their lifetime die at the end of a step and
// their slots are reused by the next emissions: a snowfall of rate r and
// lifetime L holds about r·L particles, and runs for ever in the capacity the
// system was created with. Emissions that do not fit are dropped and counted.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "../core/random.hpp"
#include "force.hpp"

namespace impulse::particles {

template <class T>
struct emitter {
  vec3<T> position{};
  /// Half extents of the box particles appear in, m (0 for a point source).
  vec3<T> half_extents{};
  vec3<T> velocity{};
  /// Per-axis half-range of the initial velocity, m/s.
  vec3<T> velocity_spread{};
  /// Particles per second, ≥ 0.
  T rate = T(100);
  /// Lifetime, s, > 0; each particle gets lifetime ± lifetime_spread.
  T lifetime = T(5);
  T lifetime_spread = T(0);
  /// Mass of each particle, kg, > 0.
  T mass = T(1);
  bool enabled = true;
  /// Generator state; set it to choose a different but repeatable stream.
  lcg32 random{12345};

  /// Fraction of a particle owed from the previous steps, in [0, 1).
  T owed = T(0);
  /// Particles that were due but found the system full.
  std::uint64_t dropped = 0;

  void validate(std::uint32_t index = no_object) const {
    using detail::require;
    const bool finite = is_finite(position) && is_finite(half_extents) && is_finite(velocity) &&
                        is_finite(velocity_spread) && std::isfinite(rate) && std::isfinite(lifetime) &&
                        std::isfinite(lifetime_spread) && std::isfinite(mass) && std::isfinite(owed);
    require(finite, error_code::non_finite, "emitter: a parameter is not finite", index);
    require(min_component(half_extents) >= T(0) && min_component(velocity_spread) >= T(0),
            error_code::invalid_parameter, "emitter: half extents and velocity spread must be non-negative",
            index);
    require(rate >= T(0), error_code::invalid_parameter, "emitter: rate is negative", index);
    require(mass > T(0), error_code::non_positive_mass, "emitter: mass must be positive", index);
    require(lifetime > T(0) && lifetime_spread >= T(0) && lifetime_spread < lifetime,
            error_code::invalid_parameter,
            "emitter: lifetime must be positive and larger than its spread", index);
  }

  /// Position, velocity and lifetime of the next particle.
  struct draw {
    vec3<T> position, velocity;
    T lifetime;
  };
  draw next() noexcept {
    auto signed_unit = [this] { return random.template uniform<T>(T(-1), T(1)); };
    draw d;
    d.position = position + mul(half_extents, vec3<T>{signed_unit(), signed_unit(), signed_unit()});
    d.velocity = velocity + mul(velocity_spread, vec3<T>{signed_unit(), signed_unit(), signed_unit()});
    d.lifetime = lifetime + lifetime_spread * signed_unit();
    return d;
  }

  /// How many particles are due after dt seconds; keeps the remainder.
  std::size_t due(T dt) noexcept {
    if (!enabled) return 0;
    const T total = owed + rate * dt;
    const auto whole = static_cast<std::size_t>(total);
    owed = total - T(whole);
    return whole;
  }
};

}  // namespace impulse::particles
