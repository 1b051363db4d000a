// impulse/dynamics/free_rotation.hpp — the turn of a torque-free rigid body
// over a step, with its angular momentum held: exact for a symmetric body,
// symplectic for any other.
//
// With no torque, L (world) is constant and the body's kinetic energy is
//     T = ½·(l₁²/I₁ + l₂²/I₂ + l₃²/I₃),   l = Qᵀ·L (principal frame),
// where Q turns the principal frame into the world. Picking the middle
// moment I_r as reference splits it into three parts,
//     T = ½·|L|²/I_r + ½·(1/I_a − 1/I_r)·l_a² + ½·(1/I_b − 1/I_r)·l_b²,
// each of whose flows is a turn at a constant rate about a fixed axis: the
// first about L itself at |L|/I_r, the others about a principal axis at
// (1/I_i − 1/I_r)·l_i (McLachlan, "Explicit Lie-Poisson integration and the
// Euler equations", Phys. Rev. Lett. 71, 1993; Dullweber, Leimkuhler and
// McLachlan, J. Chem. Phys. 107, 1997). The first commutes with the others
// (|L| is the same in every frame), so a step is that turn for the whole
// step composed with the symmetric (Strang) product of the other two:
// second order, L kept exactly, and the energy error bounded for ever
// rather than growing. A body with two equal moments has one part left over
// and is turned exactly, at any speed: a top spinning 5 radians a step
// precesses at its true rate. Three symmetric products with Yoshida's
// weights give fourth order, for the RK4 policy.
//
// An explicit step, ω = I_w⁻¹·L taken at the start and held, spins a body on
// its intermediate axis up onto its minor one (energy +259 % over 10⁴ steps
// at 60 Hz) and precesses a top at 20 rad/s 8.6 times too fast; Catto's
// implicit gyroscopic step (one Newton step on the implicit Euler
// equation) is stable but damps: the same top precessed 1.46 times too fast
// at 100 rad/s.
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "../math/mat3.hpp"
#include "../math/quat.hpp"
#include "../math/scalar_traits.hpp"
#include "../math/vec3.hpp"

namespace impulse {

/// A body's inertia about its principal axes: the moments, the turn from
/// the principal frame to the body frame, and the split's rates (below),
/// worked out once by principal_inertia_of.
template <scalar_type T>
struct principal_inertia {
  vec3<T> moments{T(1), T(1), T(1)};   ///< kg·m²
  quat<T> axes = quat<T>::identity();  ///< principal frame to body frame
  /// 1/I_r, and 1/I_i − 1/I_r for each axis i (0 at the reference), 1/(kg·m²).
  T rate = T(1);
  vec3<T> rates{};
  int reference = 1;  ///< the axis of the middle moment
  /// Of the other two, the axis of the faster turn (the smaller moment):
  /// Strang's product halves that turn, which halves its error.
  int halved = 0;
  bool own_axes = true;  ///< axes is the identity: the body's axes are principal

  /// All three moments equal (a sphere, a cube): I_w is the same at every pose.
  [[nodiscard]] constexpr bool isotropic() const noexcept { return rates == vec3<T>{}; }
};

/// The principal moments and axes of a symmetric inertia tensor, by cyclic
/// Jacobi rotations. A diagonal tensor comes back as it is, with axes the
/// identity; a symmetric body's two equal moments stay equal to the bit
/// when its tensor is diagonal.
template <scalar_type T>
principal_inertia<T> principal_inertia_of(const mat3<T>& inertia) noexcept {
  mat3<T> a = inertia, axes = mat3<T>::identity();
  const T scale = std::abs(a(0, 0)) + std::abs(a(1, 1)) + std::abs(a(2, 2));
  const T small = scalar_traits<T>::epsilon * scale;
  for (int sweep = 0; sweep < 16; ++sweep) {
    if (!(std::abs(a(0, 1)) + std::abs(a(0, 2)) + std::abs(a(1, 2)) > small)) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (a(p, q) == T(0)) continue;
        // The plane turn that zeroes a(p, q): tan θ = t, the smaller root of
        // t² + 2·cot(2θ)·t − 1 = 0.
        const T theta = (a(q, q) - a(p, p)) / (T(2) * a(p, q));
        const T t = std::abs(theta) > T(1e15) ? T(0.5) / theta
                                               : std::copysign(T(1), theta) / (std::abs(theta) + std::sqrt(theta * theta + T(1)));
        const T c = T(1) / std::sqrt(t * t + T(1)), s = t * c;
        mat3<T> turn = mat3<T>::identity();
        turn(p, p) = c, turn(q, q) = c, turn(p, q) = s, turn(q, p) = -s;
        a = transpose(turn) * a * turn;
        axes = axes * turn;
      }
  }
  principal_inertia<T> p;
  p.moments = {a(0, 0), a(1, 1), a(2, 2)};
  p.axes = from_mat3(axes);
  p.own_axes = p.axes == quat<T>::identity();
  // The reference is the middle moment; the first of equal ones.
  const vec3<T>& m = p.moments;
  p.reference = (m[0] <= m[1]) == (m[1] <= m[2]) ? 1 : (m[1] <= m[0]) == (m[0] <= m[2]) ? 0 : 2;
  p.rate = T(1) / m[p.reference];
  for (int i = 0; i < 3; ++i) p.rates[i] = i == p.reference ? T(0) : T(1) / m[i] - p.rate;
  const int first = p.reference == 0 ? 1 : 0, second = p.reference == 2 ? 1 : 2;
  p.halved = std::abs(p.rates[first]) >= std::abs(p.rates[second]) ? first : second;
  return p;
}

/// The most pieces free_turn cuts a step into.
inline constexpr int max_free_turn_pieces = 32;

namespace detail {

/// Turns `turned` (principal frame to world) by `angle` about its
/// principal axis I, Q·exp(angle·e_I/2), and l, which is Qᵀ·L, the other
/// way. The axis is a constant, so the products skip their zeros.
template <int I, scalar_type T>
void turn_about(quat<T>& turned, vec3<T>& l, T angle) noexcept {
  if (angle == T(0)) return;  // the other axis of a symmetric body
  vec3<T> half{};
  half[I] = T(0.5) * angle;
  const quat<T> turn = exp_pure(half);
  turned = turned * turn;
  const T sine = turn.vector_part()[I], cosine = turn.w;
  constexpr int j = (I + 1) % 3, k = (I + 2) % 3;
  const T c = cosine * cosine - sine * sine, s = T(2) * sine * cosine;
  const T lj = l[j], lk = l[k];
  l[j] = c * lj + s * lk;
  l[k] = c * lk - s * lj;
}

/// The two turns about the principal axes A and B (the reference is the
/// third) over h: Strang's product, in pieces when they go far.
template <int A, int B, scalar_type T>
void split_turns(quat<T>& turned, const vec3<T>& rates, const vec3<T>& angular_momentum, T h, bool fourth_order) noexcept {
  vec3<T> l = inverse_rotate(turned, angular_momentum);
  // Turns this small (a body at rest, or nearly) are taken as one: Strang's
  // product of X/2, Y, X/2 is exp(X + Y) to third order in the angles, and
  // at 2e-3 rad in float (5e-6 in double) that is under rounding.
  constexpr T small = std::is_same_v<T, float> ? T(2e-3) : T(5e-6);
  const T angle_a = h * rates[A] * l[A], angle_b = h * rates[B] * l[B];
  if (std::abs(angle_a) < small && std::abs(angle_b) < small) {
    vec3<T> half{};
    half[A] = T(0.5) * angle_a;
    half[B] = T(0.5) * angle_b;
    turned = turned * exp_pure(half);
    return;
  }
  const auto strang = [&](T step) {
    turn_about<A>(turned, l, T(0.5) * step * rates[A] * l[A]);
    turn_about<B>(turned, l, step * rates[B] * l[B]);
    turn_about<A>(turned, l, T(0.5) * step * rates[A] * l[A]);
  };
  // The splitting's error grows with the square of how far its two turns
  // go in a step, so a fast spin is turned in pieces in which they go at
  // most a quarter radian (up to 32 pieces: 8 rad a step).
  const T reach = std::max(std::abs(rates[A]), std::abs(rates[B])) * length(l) * h;
  const int pieces = !(reach > T(0.25)) ? 1 : int(std::min(std::ceil(reach / T(0.25)), T(max_free_turn_pieces)));
  const T piece = h / T(pieces);
  for (int i = 0; i < pieces; ++i) {
    if (fourth_order) {
      // Yoshida's triple jump: w₁ = 1/(2 − ∛2), w₀ = 1 − 2·w₁.
      constexpr T outer = T(1.3512071919596576340476878089715), inner = T(1) - T(2) * outer;
      strang(outer * piece);
      strang(inner * piece);
      strang(outer * piece);
    } else {
      strang(piece);
    }
  }
}

}  // namespace detail

/// The orientation of a torque-free body after h seconds, from
/// `orientation` (body to world) with angular momentum L (world) held:
/// the split flow above, second order or, with `fourth_order`, fourth.
/// `also` is a world angular velocity turned with the turn about L (the
/// position pass's pseudo-velocity, rad/s).
template <scalar_type T>
quat<T> free_turn(const quat<T>& orientation, const principal_inertia<T>& inertia, const vec3<T>& angular_momentum,
                  T h, bool fourth_order = false, const vec3<T>& also = {}) noexcept {
  quat<T> turned = inertia.own_axes ? orientation : orientation * inertia.axes;  // principal frame to world
  if (!inertia.isotropic()) {
    const vec3<T>& rates = inertia.rates;
    switch (inertia.reference * 3 + inertia.halved) {
      case 1: detail::split_turns<1, 2>(turned, rates, angular_momentum, h, fourth_order); break;
      case 2: detail::split_turns<2, 1>(turned, rates, angular_momentum, h, fourth_order); break;
      case 3: detail::split_turns<0, 2>(turned, rates, angular_momentum, h, fourth_order); break;
      case 5: detail::split_turns<2, 0>(turned, rates, angular_momentum, h, fourth_order); break;
      case 6: detail::split_turns<0, 1>(turned, rates, angular_momentum, h, fourth_order); break;
      default: detail::split_turns<1, 0>(turned, rates, angular_momentum, h, fourth_order); break;
    }
  }
  turned = exp_pure((angular_momentum * inertia.rate + also) * (T(0.5) * h)) * turned;
  return normalize(inertia.own_axes ? turned : turned * conjugate(inertia.axes));
}

}  // namespace impulse
