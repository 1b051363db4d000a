// impulse/narrowphase.hpp — the narrow phase module: contact manifolds
// between pairs of shapes. So far the closed-form tests between spheres,
// capsules, boxes and planes (narrowphase/analytic.hpp), box against box
// by separating axes and clipping (narrowphase/box_box.hpp), the closest
// point on a triangle by Voronoi regions (narrowphase/triangle.hpp), the
// distance between any two convex shapes by GJK (narrowphase/gjk.hpp),
// their penetration when they overlap by EPA (narrowphase/epa.hpp),
// convex hulls against planes and spheres (narrowphase/hull.hpp), and
// hulls against hulls and boxes by separating axes and clipping
// (narrowphase/hull_hull.hpp), capsules against boxes and hulls
// (narrowphase/capsule_polyhedron.hpp), ray casts against every shape
// (narrowphase/ray_cast.hpp), and the time of impact of two moving convex
// shapes by conservative advancement (narrowphase/time_of_impact.hpp);
// static triangle meshes against spheres, capsules, boxes and hulls, and
// rays against them (narrowphase/mesh.hpp);
// the table of pair tests built from a config's shape_list
// (narrowphase/dispatch.hpp); and the tolerances they all decide by
// (narrowphase/tolerances.hpp).
#pragma once

#include "narrowphase/analytic.hpp"
#include "narrowphase/box_box.hpp"
#include "narrowphase/capsule_polyhedron.hpp"
#include "narrowphase/compound.hpp"
#include "narrowphase/dispatch.hpp"
#include "narrowphase/epa.hpp"
#include "narrowphase/gjk.hpp"
#include "narrowphase/hull.hpp"
#include "narrowphase/hull_hull.hpp"
#include "narrowphase/manifold.hpp"
#include "narrowphase/mesh.hpp"
#include "narrowphase/ray_cast.hpp"
#include "narrowphase/time_of_impact.hpp"
#include "narrowphase/tolerances.hpp"
#include "narrowphase/triangle.hpp"
