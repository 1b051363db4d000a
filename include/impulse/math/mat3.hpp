// impulse/math/mat3.hpp — 3×3 matrix of float or double (rotations, inertia tensors).
//
// Stored as three columns, so m * v = v.x·c0 + v.y·c1 + v.z·c2 and the columns
// of a rotation matrix are the rotated basis vectors. m(r, c) reads row r of
// column c.
#pragma once

#include <cmath>
#include <optional>

#include "vec3.hpp"

namespace impulse {

template <scalar_type T>
struct mat3 {
  using scalar = T;

  vec3<T> col[3]{};

  static constexpr mat3 zero() noexcept { return {}; }
  static constexpr mat3 identity() noexcept { return diagonal({T(1), T(1), T(1)}); }
  static constexpr mat3 diagonal(const vec3<T>& d) noexcept {
    return from_columns({d.x, T(0), T(0)}, {T(0), d.y, T(0)}, {T(0), T(0), d.z});
  }
  static constexpr mat3 from_columns(const vec3<T>& c0, const vec3<T>& c1, const vec3<T>& c2) noexcept {
    mat3 m;
    m.col[0] = c0;
    m.col[1] = c1;
    m.col[2] = c2;
    return m;
  }
  static constexpr mat3 from_rows(const vec3<T>& r0, const vec3<T>& r1, const vec3<T>& r2) noexcept {
    return from_columns({r0.x, r1.x, r2.x}, {r0.y, r1.y, r2.y}, {r0.z, r1.z, r2.z});
  }

  constexpr T& operator()(int row, int column) noexcept { return col[column][row]; }
  constexpr const T& operator()(int row, int column) const noexcept { return col[column][row]; }
  constexpr vec3<T> row(int r) const noexcept { return {col[0][r], col[1][r], col[2][r]}; }

  constexpr mat3& operator+=(const mat3& b) noexcept { for (int c = 0; c < 3; ++c) col[c] += b.col[c]; return *this; }
  constexpr mat3& operator-=(const mat3& b) noexcept { for (int c = 0; c < 3; ++c) col[c] -= b.col[c]; return *this; }
  constexpr mat3& operator*=(T s) noexcept { for (int c = 0; c < 3; ++c) col[c] *= s; return *this; }

  friend constexpr bool operator==(const mat3& a, const mat3& b) noexcept {
    return a.col[0] == b.col[0] && a.col[1] == b.col[1] && a.col[2] == b.col[2];
  }
};

template <scalar_type T> constexpr mat3<T> operator+(mat3<T> a, const mat3<T>& b) noexcept { return a += b; }
template <scalar_type T> constexpr mat3<T> operator-(mat3<T> a, const mat3<T>& b) noexcept { return a -= b; }
template <scalar_type T> constexpr mat3<T> operator*(mat3<T> a, T s) noexcept { return a *= s; }
template <scalar_type T> constexpr mat3<T> operator*(T s, mat3<T> a) noexcept { return a *= s; }
template <scalar_type T> constexpr mat3<T> operator-(const mat3<T>& a) noexcept { return a * T(-1); }

template <scalar_type T>
constexpr vec3<T> operator*(const mat3<T>& m, const vec3<T>& v) noexcept {
  return m.col[0] * v.x + m.col[1] * v.y + m.col[2] * v.z;
}

template <scalar_type T>
constexpr mat3<T> operator*(const mat3<T>& a, const mat3<T>& b) noexcept {
  return mat3<T>::from_columns(a * b.col[0], a * b.col[1], a * b.col[2]);
}

template <scalar_type T>
constexpr mat3<T> transpose(const mat3<T>& m) noexcept {
  return mat3<T>::from_rows(m.col[0], m.col[1], m.col[2]);
}

/// mᵀ·v without forming the transpose (world-to-body for a rotation matrix).
template <scalar_type T>
constexpr vec3<T> transpose_mul(const mat3<T>& m, const vec3<T>& v) noexcept {
  return {dot(m.col[0], v), dot(m.col[1], v), dot(m.col[2], v)};
}

template <scalar_type T>
constexpr T trace(const mat3<T>& m) noexcept {
  return m.col[0].x + m.col[1].y + m.col[2].z;
}

template <scalar_type T>
constexpr T determinant(const mat3<T>& m) noexcept {
  return dot(m.col[0], cross(m.col[1], m.col[2]));
}

/// The cross-product matrix: skew(a) * b == cross(a, b).
template <scalar_type T>
constexpr mat3<T> skew(const vec3<T>& a) noexcept {
  return mat3<T>::from_columns({T(0), a.z, -a.y}, {-a.z, T(0), a.x}, {a.y, -a.x, T(0)});
}

/// The outer product a·bᵀ.
template <scalar_type T>
constexpr mat3<T> outer(const vec3<T>& a, const vec3<T>& b) noexcept {
  return mat3<T>::from_columns(a * b.x, a * b.y, a * b.z);
}

/// Inverse by the adjugate, or nothing when |det| is below
/// scalar_traits<T>::singular_tolerance times the product of the column
/// lengths (a scale-free test: a tiny but well-conditioned inertia tensor
/// still inverts, a rank-deficient one of any size does not).
template <scalar_type T>
std::optional<mat3<T>> try_inverse(const mat3<T>& m) noexcept {
  // The rows of the inverse are the cross products of pairs of columns over det.
  const vec3<T> r0 = cross(m.col[1], m.col[2]);
  const vec3<T> r1 = cross(m.col[2], m.col[0]);
  const vec3<T> r2 = cross(m.col[0], m.col[1]);
  const T det = dot(m.col[0], r0);
  const T scale = length(m.col[0]) * length(m.col[1]) * length(m.col[2]);
  if (!(std::abs(det) > scalar_traits<T>::singular_tolerance * scale)) return std::nullopt;
  return mat3<T>::from_rows(r0, r1, r2) * (T(1) / det);
}

/// Inverse of a matrix known to be invertible. Precondition checked by IMPULSE_ASSERT.
template <scalar_type T>
mat3<T> inverse(const mat3<T>& m) noexcept {
  const std::optional<mat3<T>> inv = try_inverse(m);
  IMPULSE_ASSERT(inv.has_value());
  return inv ? *inv : mat3<T>::zero();
}

template <scalar_type T>
bool is_finite(const mat3<T>& m) noexcept {
  return is_finite(m.col[0]) && is_finite(m.col[1]) && is_finite(m.col[2]);
}

}  // namespace impulse
