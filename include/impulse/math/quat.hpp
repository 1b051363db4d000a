// impulse/math/quat.hpp — unit quaternions for orientation (Hamilton convention).
//
// q = w + xi + yj + zk, stored x, y, z, w. A unit quaternion rotates v by
// q v q*; composition a * b applies b first, then a. Orientation is advanced
// by the exact exponential map (Baraff 2001, "Physically Based Modeling:
// Rigid Body Simulation", with the closed form of exp for a pure quaternion),
// never by adding ½ω q dt, which leaves the unit sphere at first order.
#pragma once

#include <cmath>

#include "mat3.hpp"
#include "trigonometry.hpp"
#include "vec3.hpp"

namespace impulse {

template <scalar_type T>
struct quat {
  using scalar = T;

  T x{};
  T y{};
  T z{};
  T w{1};

  static constexpr quat identity() noexcept { return {T(0), T(0), T(0), T(1)}; }

  /// Rotation by `angle` radians about `axis`. The axis must be unit length.
  static quat from_axis_angle(const vec3<T>& axis, T angle) noexcept {
    IMPULSE_ASSERT(is_normalized(axis));
    const sine_cosine<T> half = portable_sin_cos(angle * T(0.5));
    return {axis.x * half.sin, axis.y * half.sin, axis.z * half.sin, half.cos};
  }

  constexpr vec3<T> vector_part() const noexcept { return {x, y, z}; }

  friend constexpr bool operator==(const quat&, const quat&) = default;
};

/// Hamilton product: (a * b) rotates by b, then by a.
template <scalar_type T>
constexpr quat<T> operator*(const quat<T>& a, const quat<T>& b) noexcept {
  return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
          a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
          a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w,
          a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}

namespace detail {

/// Whether this build fuses the multiplies and adds of the product above:
/// GCC 12's SLP vectoriser forms fused multiply-subtract-adds from its
/// alternating signs even with -ffp-contract=off (core/floating_point.hpp).
/// The product of two quaternions loaded from volatiles and stored whole
/// (the stores are what the vectoriser groups), against the same sums with
/// every term stored to a volatile first, which nothing can fuse.
[[gnu::noinline]] inline void multiply_into(const quat<float>& a, const quat<float>& b, quat<float>& out) noexcept {
  out = a * b;
}
inline bool quat_product_fused() noexcept {
  volatile float in[8] = {0.1f, 0.7f, -0.3f, 0.9f, -0.6f, 0.2f, 0.8f, 0.35f};
  const quat<float> a{in[0], in[1], in[2], in[3]}, b{in[4], in[5], in[6], in[7]};
  quat<float> product;
  multiply_into(a, b, product);
  volatile float t[16] = {a.w * b.x, a.x * b.w, a.y * b.z, a.z * b.y, a.w * b.y, a.x * b.z, a.y * b.w, a.z * b.x,
                          a.w * b.z, a.x * b.y, a.y * b.x, a.z * b.w, a.w * b.w, a.x * b.x, a.y * b.y, a.z * b.z};
  const quat<float> rounded{t[0] + t[1] + t[2] - t[3], t[4] - t[5] + t[6] + t[7], t[8] + t[9] - t[10] + t[11],
                            t[12] - t[13] - t[14] - t[15]};
  return !(product == rounded);
}

}  // namespace detail

template <scalar_type T>
constexpr quat<T> operator*(const quat<T>& q, T s) noexcept {
  return {q.x * s, q.y * s, q.z * s, q.w * s};
}
template <scalar_type T>
constexpr quat<T> operator+(const quat<T>& a, const quat<T>& b) noexcept {
  return {a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w};
}

template <scalar_type T>
constexpr quat<T> conjugate(const quat<T>& q) noexcept {
  return {-q.x, -q.y, -q.z, q.w};
}

template <scalar_type T>
constexpr T dot(const quat<T>& a, const quat<T>& b) noexcept {
  return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w;
}

template <scalar_type T> constexpr T length_squared(const quat<T>& q) noexcept { return dot(q, q); }
template <scalar_type T> T length(const quat<T>& q) noexcept { return std::sqrt(dot(q, q)); }

/// q / |q|. Precondition: q is not (nearly) zero. A NaN or infinite q
/// gives NaN rather than failing the assertion: a solve that diverged on
/// hostile input is the world's to find and hold (world::step), in a
/// debug build as in a release one.
template <scalar_type T>
quat<T> normalize(const quat<T>& q) noexcept {
  const T l2 = length_squared(q);
  IMPULSE_ASSERT(!(l2 <= scalar_traits<T>::zero_length_squared));
  return q * (T(1) / std::sqrt(l2));
}

template <scalar_type T>
bool is_normalized(const quat<T>& q) noexcept {
  return std::abs(length_squared(q) - T(1)) <= T(2) * scalar_traits<T>::unit_tolerance;
}

template <scalar_type T>
bool is_finite(const quat<T>& q) noexcept {
  return std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w);
}

/// Inverse of any non-zero quaternion; for a unit quaternion use conjugate.
template <scalar_type T>
quat<T> inverse(const quat<T>& q) noexcept {
  const T l2 = length_squared(q);
  IMPULSE_ASSERT(l2 > scalar_traits<T>::zero_length_squared);
  return conjugate(q) * (T(1) / l2);
}

/// Rotates v by the unit quaternion q: q v q*, expanded to
/// v + 2w(u × v) + 2u × (u × v) with u the vector part (15 multiplies
/// instead of the 28 of two Hamilton products).
template <scalar_type T>
constexpr vec3<T> rotate(const quat<T>& q, const vec3<T>& v) noexcept {
  const vec3<T> u = q.vector_part();
  const vec3<T> t = cross(u, v) * T(2);
  return v + t * q.w + cross(u, t);
}

/// Rotates v by the inverse of the unit quaternion q (world to body).
template <scalar_type T>
constexpr vec3<T> inverse_rotate(const quat<T>& q, const vec3<T>& v) noexcept {
  return rotate(conjugate(q), v);
}

/// Rotation matrix of the unit quaternion q (columns are the rotated axes).
template <scalar_type T>
constexpr mat3<T> to_mat3(const quat<T>& q) noexcept {
  const T xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
  const T xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
  const T wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
  return mat3<T>::from_columns({T(1) - T(2) * (yy + zz), T(2) * (xy + wz), T(2) * (xz - wy)},
                               {T(2) * (xy - wz), T(1) - T(2) * (xx + zz), T(2) * (yz + wx)},
                               {T(2) * (xz + wy), T(2) * (yz - wx), T(1) - T(2) * (xx + yy)});
}

/// Unit quaternion of a rotation matrix (Shepperd's method: take the square
/// root of the largest of w², x², y², z² so the division is never by a small
/// number). The result has w >= 0.
template <scalar_type T>
quat<T> from_mat3(const mat3<T>& m) noexcept {
  const T m00 = m(0, 0), m11 = m(1, 1), m22 = m(2, 2);
  const T tr = m00 + m11 + m22;
  quat<T> q;
  if (tr >= m00 && tr >= m11 && tr >= m22) {
    const T s = std::sqrt(T(1) + tr) * T(2);  // 4w
    q = {(m(2, 1) - m(1, 2)) / s, (m(0, 2) - m(2, 0)) / s, (m(1, 0) - m(0, 1)) / s, s * T(0.25)};
  } else if (m00 >= m11 && m00 >= m22) {
    const T s = std::sqrt(T(1) + m00 - m11 - m22) * T(2);  // 4x
    q = {s * T(0.25), (m(0, 1) + m(1, 0)) / s, (m(0, 2) + m(2, 0)) / s, (m(2, 1) - m(1, 2)) / s};
  } else if (m11 >= m22) {
    const T s = std::sqrt(T(1) + m11 - m00 - m22) * T(2);  // 4y
    q = {(m(0, 1) + m(1, 0)) / s, s * T(0.25), (m(1, 2) + m(2, 1)) / s, (m(0, 2) - m(2, 0)) / s};
  } else {
    const T s = std::sqrt(T(1) + m22 - m00 - m11) * T(2);  // 4z
    q = {(m(0, 2) + m(2, 0)) / s, (m(1, 2) + m(2, 1)) / s, s * T(0.25), (m(1, 0) - m(0, 1)) / s};
  }
  if (q.w < T(0)) q = q * T(-1);
  return normalize(q);
}

/// exp of the pure quaternion (0, v): (v/|v| · sin|v|, cos|v|). A unit
/// quaternion for every v; the series branch keeps it exact and finite as
/// |v| -> 0 (see scalar_traits::series_threshold).
template <scalar_type T>
quat<T> exp_pure(const vec3<T>& v) noexcept {
  const T h2 = length_squared(v);
  constexpr T threshold = scalar_traits<T>::series_threshold;
  if (h2 < threshold * threshold) {
    // Horner's form of the two series; a body at rest or turning slowly
    // (most of a scene) costs no square root and no sin or cos.
    const T sin_h_over_h = T(1) - h2 / T(6) * (T(1) - h2 / T(20) * (T(1) - h2 / T(42)));
    const T cos_h = T(1) - h2 / T(2) * (T(1) - h2 / T(12) * (T(1) - h2 / T(30) * (T(1) - h2 / T(56))));
    return {v.x * sin_h_over_h, v.y * sin_h_over_h, v.z * sin_h_over_h, cos_h};
  }
  const T h = std::sqrt(h2);
  const sine_cosine<T> turn = portable_sin_cos(h);
  const T sin_h_over_h = turn.sin / h;
  return {v.x * sin_h_over_h, v.y * sin_h_over_h, v.z * sin_h_over_h, turn.cos};
}

/// Orientation after turning at constant world-space angular velocity
/// `omega` (rad/s) for `dt` seconds: exp(ω dt / 2) * q. Exact for constant ω,
/// so a body spinning about a fixed axis accumulates only rounding error.
/// The exponential is unit in exact arithmetic; the final normalisation
/// removes the rounding that would otherwise random-walk |q| away from 1
/// (about √N · epsilon after N steps: 1e-4 in float after 10^6 steps).
template <scalar_type T>
quat<T> integrate(const quat<T>& q, const vec3<T>& omega, T dt) noexcept {
  return normalize(exp_pure(omega * (dt * T(0.5))) * q);
}

/// Angle (radians, in [0, π]) of the rotation taking unit a to unit b.
/// Uses atan2 of the relative rotation's vector and scalar parts rather than
/// acos(|a·b|): acos is flat at 1 and cannot resolve angles below
/// √(2·epsilon) (2e-8 rad in double), exactly the errors a test wants to see.
template <scalar_type T>
T angle_between(const quat<T>& a, const quat<T>& b) noexcept {
  const quat<T> d = conjugate(a) * b;
  return T(2) * portable_atan2(length(d.vector_part()), std::abs(d.w));  // q and -q: same rotation
}

/// The rotation vector (world axis times angle, radians) of the shortest
/// turn taking orientation `from` to `to`: the inverse of integrate, so
/// integrate(from, rotation_between(from, to), 1) is `to` up to rounding.
template <scalar_type T>
vec3<T> rotation_between(const quat<T>& from, const quat<T>& to) noexcept {
  quat<T> q = to * conjugate(from);
  if (q.w < T(0)) q = q * T(-1);  // the short way round
  const vec3<T> axis = q.vector_part();
  const T sine = length(axis);
  return sine > T(0) ? axis * (T(2) * portable_atan2(sine, q.w) / sine) : vec3<T>{};
}

}  // namespace impulse
