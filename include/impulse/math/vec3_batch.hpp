// impulse/math/vec3_batch.hpp — W three-vectors held as three batches (x, y, z).
//
// The structure-of-arrays twin of vec3: lane i of (x, y, z) is one vector.
// It is the state the particle kernels hand to the integrators, so it models
// integrators::ode_state (addition, scaling by a scalar or a batch) and has
// the few geometric functions the forces need.
#pragma once

#include "../core/batch.hpp"
#include "vec3.hpp"

namespace impulse {

template <scalar_type T, int W = native_width<T>>
  requires batch_width<T, W>
struct vec3_batch {
  using scalar = T;
  using lanes = batch<T, W>;
  static constexpr int width = W;

  lanes x, y, z;

  static vec3_batch broadcast(const vec3<T>& v) noexcept {
    return {lanes::broadcast(v.x), lanes::broadcast(v.y), lanes::broadcast(v.z)};
  }
  /// W consecutive vectors from three structure-of-arrays columns.
  static vec3_batch load(const T* xs, const T* ys, const T* zs) noexcept {
    return {lanes::load(xs), lanes::load(ys), lanes::load(zs)};
  }
  void store(T* xs, T* ys, T* zs) const noexcept {
    x.store(xs);
    y.store(ys);
    z.store(zs);
  }
  vec3<T> lane(int i) const noexcept { return {x[i], y[i], z[i]}; }
  void set_lane(int i, const vec3<T>& v) noexcept {
    x.set(i, v.x);
    y.set(i, v.y);
    z.set(i, v.z);
  }

  friend vec3_batch operator-(const vec3_batch& a) noexcept { return {-a.x, -a.y, -a.z}; }
  friend vec3_batch operator+(const vec3_batch& a, const vec3_batch& b) noexcept { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  friend vec3_batch operator-(const vec3_batch& a, const vec3_batch& b) noexcept { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend vec3_batch operator*(const vec3_batch& a, T s) noexcept { return {a.x * s, a.y * s, a.z * s}; }
  friend vec3_batch operator*(T s, const vec3_batch& a) noexcept { return {a.x * s, a.y * s, a.z * s}; }
  /// Each lane's vector scaled by that lane's scalar.
  friend vec3_batch operator*(const vec3_batch& a, lanes s) noexcept { return {a.x * s, a.y * s, a.z * s}; }
  friend vec3_batch operator*(lanes s, const vec3_batch& a) noexcept { return {a.x * s, a.y * s, a.z * s}; }
};

template <scalar_type T, int W>
batch<T, W> dot(const vec3_batch<T, W>& a, const vec3_batch<T, W>& b) noexcept {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

template <scalar_type T, int W>
vec3_batch<T, W> cross(const vec3_batch<T, W>& a, const vec3_batch<T, W>& b) noexcept {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

template <scalar_type T, int W>
batch<T, W> length_squared(const vec3_batch<T, W>& a) noexcept {
  return dot(a, a);
}

template <scalar_type T, int W>
batch<T, W> length(const vec3_batch<T, W>& a) noexcept {
  return sqrt(dot(a, a));
}

}  // namespace impulse
