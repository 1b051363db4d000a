// Two unit cubes side by side along x as a compound: the 2 × 1 × 1 box
// centred at 0, made of parts (tests/shapes/test_compound.cpp and
// tests/world/test_compound.cpp compare it with the box and its hull).
#pragma once

#include "impulse/shapes/compound.hpp"

namespace impulse::test {

template <class T>
compound<T> two_cubes() {
  typename compound<T>::builder b;
  const quat<T> upright = quat<T>::identity();
  b.add(box<T>{{T(0.5), T(0.5), T(0.5)}}, transform<T>{{T(-0.5), 0, 0}, upright});
  b.add(box<T>{{T(0.5), T(0.5), T(0.5)}}, transform<T>{{T(0.5), 0, 0}, upright});
  return b.build();
}

}  // namespace impulse::test
