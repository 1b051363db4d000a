// impulse/integrators/ode_state.hpp — what an integrator needs of a state.
//
// Every integrator in this folder advances the second-order system
//     x' = v,   v' = a(x, v)
// of mechanics, for a position x and velocity v of one type S: a scalar, a
// vec3, a vec3_batch of particles, and (with its own drift) a rigid body. S
// needs to be a vector space over the step's scalar: S + S and S * h. The one
// operation that is not vector arithmetic, moving a position along a
// velocity, goes through drift(x, v, h), so a state whose positions live on a
// curved space (an orientation quaternion) supplies its own overload and the
// integrators stay unchanged.
#pragma once

#include <concepts>
#include <type_traits>

#include "../core/policy.hpp"

namespace impulse::integrators {

/// S is a vector space over H: closed under addition and scaling by a step.
template <class S, class H>
concept ode_state = requires(const S& a, const S& b, H h) {
  { a + b } -> std::convertible_to<S>;
  { a * h } -> std::convertible_to<S>;
};

/// An acceleration field for state S: a(x, v) -> S.
template <class F, class S>
concept acceleration_field = std::is_invocable_r_v<S, F&, const S&, const S&>;

/// Position after moving at velocity v for time h. The default is x + v·h;
/// overload it (found by argument-dependent lookup) for a state whose
/// positions are not a vector space.
template <class S, class H>
  requires ode_state<S, H>
constexpr S drift(const S& x, const S& v, H h) {
  return x + v * h;
}

}  // namespace impulse::integrators
