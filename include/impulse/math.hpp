// impulse/math.hpp — the math module: vectors, quaternions, matrices,
// transforms and bounding boxes for float and double, and vec3_batch, the
// structure-of-arrays form of vec3 the particle kernels integrate.
#pragma once

#include "math/aabb.hpp"
#include "math/fwd.hpp"
#include "math/mat3.hpp"
#include "math/quat.hpp"
#include "math/ray.hpp"
#include "math/scalar_traits.hpp"
#include "math/transform.hpp"
#include "math/vec3.hpp"
#include "math/vec3_batch.hpp"
