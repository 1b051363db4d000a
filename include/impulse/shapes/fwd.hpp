// impulse/shapes/fwd.hpp — the shape module's names.
#pragma once

#include "../core/policy.hpp"

namespace impulse {

template <scalar_type T> struct sphere;
template <scalar_type T> struct box;
template <scalar_type T> struct capsule;
template <scalar_type T> struct plane;
template <scalar_type T> class triangle_mesh;
template <scalar_type T> class convex_hull;
struct hull_edge;
template <scalar_type T> struct mass_properties;

}  // namespace impulse
