// impulse/particles/force.hpp — what a particle force policy is.
//
// A particle system is compiled for a list of force policies
// (particle_system<Config, gravity, drag, point_forces>); only the listed ones
// exist in its kernel. Each policy is a class template over the scalar with
// runtime parameters as public data members, so a program changes them
// between steps like any struct; the system checks them with validate() at
// the start of every step and refuses to step on a bad value.
//
// A force states how it enters the motion:
//  - acceleration: the same for every mass (gravity), added as is;
//  - force: newtons, multiplied by each particle's inverse mass;
//  - pairwise: between pairs of particles (springs), evaluated by passes of
//    their own over the whole system at every integrator stage.
// The first two are evaluated lane-parallel on a batch by evaluate(x, v, p).
#pragma once

#include <concepts>

#include <cmath>
#include <cstdint>

#include "../core/batch.hpp"
#include "../core/error.hpp"
#include "../math/vec3.hpp"
#include "../math/vec3_batch.hpp"

namespace impulse::particles {

enum class force_effect { acceleration, force, pairwise };

/// Per-particle inputs a force may read besides position and velocity.
template <scalar_type T, int W>
struct particle_lanes {
  /// A fixed number in [-1, 1) per particle, hashed from its serial number
  /// when it was added (wind uses it for a deterministic per-particle gust).
  batch<T, W> variation;
};

/// True when the force reads particle_lanes::variation, so the system stores
/// and loads that column only for force lists that need it.
template <class F>
constexpr bool uses_variation() {
  if constexpr (requires { F::uses_variation; }) return F::uses_variation;
  else return false;
}

/// A particle force policy instantiated for scalar T, evaluated W lanes at a time.
template <class F, class T, int W>
concept particle_force =
    requires(const F& f) {
      { F::effect } -> std::convertible_to<force_effect>;
      f.validate();
    } &&
    (F::effect == force_effect::pairwise ||
     requires(const F& f, const vec3_batch<T, W>& x, const particle_lanes<T, W>& p) {
       { f.evaluate(x, x, p) } -> std::same_as<vec3_batch<T, W>>;
     });

namespace detail {

/// The checks the validate() functions share: each reports with a message
/// naming the parameter, before anything has been changed.
inline void require(bool ok, error_code code, const char* message,
                    std::uint32_t object = no_object) {
  if (!ok) impulse::detail::report_error(code, message, object);
}
template <scalar_type T>
void require_finite(T value, const char* message, std::uint32_t object = no_object) {
  require(std::isfinite(value), error_code::non_finite, message, object);
}
template <scalar_type T>
void require_finite(const vec3<T>& value, const char* message, std::uint32_t object = no_object) {
  require(is_finite(value), error_code::non_finite, message, object);
}

}  // namespace detail
}  // namespace impulse::particles
