// impulse/integrators/ode_state.hpp — what an integrator needs of a state.
//
// Every integrator in this folder advances a mechanical system in
// partitioned form,
//     x' = g(x, p)   (position rate: velocity, or ½ ω⊗q for a quaternion)
//     p' = f(x, p)   (momentum rate: force, torque, or an acceleration)
// for a position x and a momentum p. A particle is the special case p = v,
// g(x, v) = v, f = a(x, v): the second-order form x'' = a(x, v), which every
// integrator also accepts directly as step(x, v, h, accel). A rigid body is
// x = (position, orientation), p = (P, L), g = (P/m, ½ ω⊗q) with
// ω = I_w(q)⁻¹·L, f = (F, τ) (Baraff 2001). Each method is written once,
// over the partitioned form; the second-order form is an adapter.
//
// x and p need to be vector spaces over the step's scalar: S + S and S * h.
// Moving a position along a rate goes through drift(x, dx, h), x + dx·h by
// default, so a state whose positions are not a vector space can supply its
// own overload and the integrators stay unchanged.
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

/// Position after moving at rate dx for time h. The default is x + dx·h;
/// overload it (found by argument-dependent lookup) for a state whose
/// positions are not a vector space.
template <class S, class D, class H>
  requires ode_state<D, H> && requires(const S& x, const D& d) {
    { x + d } -> std::convertible_to<S>;
  }
constexpr S drift(const S& x, const D& dx, H h) {
  return x + dx * h;
}

/// A mechanical system in partitioned form over positions X and momenta P:
/// `position_rate(x, p)` is x' (any type drift accepts; it may return a
/// reference to p, as the second-order adapter does) and `momentum_rate(x,
/// p)` is p'. Both must be callable on any stage state, not only on the
/// stored one: midpoint and RK4 evaluate them at speculative states.
template <class System, class X, class P>
concept mechanical_system = requires(System& s, const X& x, const P& p) {
  s.position_rate(x, p);
  { s.momentum_rate(x, p) } -> std::convertible_to<P>;
};

/// The second-order form x'' = a(x, v) as a mechanical system: p = v.
/// Always inlined, as the integrators' steps are: the particle kernel
/// calls them once a batch, and RK4's stages, left as calls by GCC 12,
/// passed their states through memory.
template <class Accel>
struct second_order_system {
  Accel& accel;
  template <class S>
  [[gnu::always_inline]] constexpr const S& position_rate(const S&, const S& v) const noexcept {
    return v;
  }
  template <class S>
  [[gnu::always_inline]] constexpr S momentum_rate(const S& x, const S& v) const {
    return accel(x, v);
  }
};

}  // namespace impulse::integrators
