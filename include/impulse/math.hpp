// impulse/math.hpp — the math module: vectors, quaternions, matrices,
// transforms and bounding boxes for float and double.
#pragma once

#include "math/aabb.hpp"
#include "math/fwd.hpp"
#include "math/mat3.hpp"
#include "math/quat.hpp"
#include "math/scalar_traits.hpp"
#include "math/transform.hpp"
#include "math/vec3.hpp"
