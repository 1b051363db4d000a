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
#include <limits>

#include "../core/random.hpp"
#include "force.hpp"

namespace impulse::particles {

/// The smallest mass a particle may have, kg: the smallest normal number of
/// T (1.2e-38 for float, 2.2e-308 for double). A step multiplies forces by
/// the inverse mass, and below this the mass is denormal: its inverse is
/// infinite for most such masses (1 / 1e-45 overflows float), and drag, zero
/// times infinity, turns the particle NaN in one step.
template <class T>
inline constexpr T min_particle_mass = std::numeric_limits<T>::min();

template <class T>
struct emitter {
  /// The largest rate, particles/s. No particle_system holds more than
  /// max_capacity (2^26, about 6.7e7) particles, which a billion a second
  /// fills in 67 ms, so a larger rate can only be a slip of zeros or units;
  /// and it keeps rate·dt, which due() converts to a count, far inside size_t.
  static constexpr T max_rate = T(1e9);
  /// The most particles due() returns for one step. Any larger count would
  /// not fit a system either (the excess is dropped and counted); saturating
  /// here keeps the conversion from T defined for every finite dt.
  static constexpr std::size_t max_due = std::size_t(1) << 32;

  vec3<T> position{};
  /// Half extents of the box particles appear in, m (0 for a point source).
  vec3<T> half_extents{};
  vec3<T> velocity{};
  /// Per-axis half-range of the initial velocity, m/s.
  vec3<T> velocity_spread{};
  /// Particles per second, in [0, max_rate].
  T rate = T(100);
  /// Lifetime, s, > 0; each particle gets lifetime ± lifetime_spread.
  T lifetime = T(5);
  T lifetime_spread = T(0);
  /// Mass of each particle, kg, ≥ min_particle_mass<T>.
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
    require(rate <= max_rate, error_code::invalid_parameter,
            "emitter: rate is above emitter::max_rate (1e9 particles/s)", index);
    require(mass > T(0), error_code::non_positive_mass, "emitter: mass must be positive", index);
    require(mass >= min_particle_mass<T>, error_code::invalid_parameter,
            "emitter: mass is below min_particle_mass (denormal: its inverse overflows)", index);
    require(owed >= T(0) && owed < T(1), error_code::invalid_parameter, "emitter: owed must be in [0, 1)", index);
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

  /// How many particles are due after dt seconds, at most max_due; keeps
  /// the remainder.
  std::size_t due(T dt) noexcept {
    if (!enabled) return 0;
    const T total = owed + rate * dt;
    // Converting a T outside size_t's range is undefined behaviour, so the
    // two ends are settled before the conversion: nothing is due for a
    // negative or NaN total (an owed that validate() refuses), and a huge
    // one (a huge dt; rate·dt may even be infinite) saturates.
    if (!(total >= T(0))) {
      owed = T(0);
      return 0;
    }
    if (!(total < T(max_due))) {
      owed = T(0);
      return max_due;
    }
    const auto whole = static_cast<std::size_t>(total);
    owed = total - T(whole);
    return whole;
  }
};

}  // namespace impulse::particles
