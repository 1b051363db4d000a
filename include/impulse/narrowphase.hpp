// impulse/narrowphase.hpp — the narrow phase module: contact manifolds
// between pairs of shapes. So far the closed-form tests between spheres,
// capsules, boxes and planes (narrowphase/analytic.hpp), box against box
// by separating axes and clipping (narrowphase/box_box.hpp), the closest
// point on a triangle by Voronoi regions (narrowphase/triangle.hpp), and the
// distance between any two convex shapes by GJK (narrowphase/gjk.hpp).
#pragma once

#include "narrowphase/analytic.hpp"
#include "narrowphase/box_box.hpp"
#include "narrowphase/gjk.hpp"
#include "narrowphase/manifold.hpp"
#include "narrowphase/triangle.hpp"
