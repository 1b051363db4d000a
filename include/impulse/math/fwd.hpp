// impulse/math/fwd.hpp — forward declarations and user-facing aliases of the math module.
#pragma once

#include "../core/policy.hpp"

namespace impulse {

template <scalar_type T> struct scalar_traits;
template <scalar_type T> struct vec3;
template <scalar_type T> struct quat;
template <scalar_type T> struct mat3;
template <scalar_type T> struct transform;
template <scalar_type T> struct aabb;
template <scalar_type T> struct ray;

using vec3f = vec3<float>;
using vec3d = vec3<double>;
using quatf = quat<float>;
using quatd = quat<double>;
using mat3f = mat3<float>;
using mat3d = mat3<double>;
using transformf = transform<float>;
using transformd = transform<double>;
using aabbf = aabb<float>;
using aabbd = aabb<double>;

}  // namespace impulse
