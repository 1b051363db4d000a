// impulse/shapes.hpp — the shape module: sphere, box, capsule, convex_hull, plane,
// triangle_mesh, heightfield, compound, with support functions, bounds and
// exact mass properties.
#pragma once

#include "shapes/box.hpp"
#include "shapes/capsule.hpp"
#include "shapes/compound.hpp"
#include "shapes/convex_hull.hpp"
#include "shapes/fwd.hpp"
#include "shapes/mass_properties.hpp"
#include "shapes/plane.hpp"
#include "shapes/sphere.hpp"
#include "shapes/heightfield.hpp"
#include "shapes/triangle_mesh.hpp"
