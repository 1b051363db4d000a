// The box the broad-phase tests build most: a cube by its center and half
// extent.
#pragma once

#include "impulse/math/aabb.hpp"

namespace impulse::test {

template <class T>
aabb<T> cube(T x, T y, T z, T half) {
  return aabb<T>::from_center_half_extents({x, y, z}, vec3<T>::splat(half));
}

}  // namespace impulse::test
