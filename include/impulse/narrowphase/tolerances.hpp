// impulse/narrowphase/tolerances.hpp — the narrow phase's tolerances, in one
// place, each with its unit and the reason for its value.
//
// These are compile-time constants, not runtime knobs: each one decides
// geometry (which axis, which feature, which points), so that the same
// poses give the same contacts in every world. Most are relative (a
// fraction of a length, the sine or cosine of an angle) and so the same in
// float and double; the few that follow the rounding of the scalar type
// differ. GJK, EPA and GJK ray casting run their arithmetic in double
// whatever T is (gjk.hpp), so their tolerances are doubles, chosen by the
// shapes' scalar type T.
//
// Loop bounds and capacities stay next to their code (gjk.hpp's and
// ray_cast.hpp's 64 iterations, epa.hpp's polytope, mesh.hpp's 16
// manifolds), and the time of impact's tolerances are runtime options
// (toi_options, time_of_impact.hpp).
#pragma once

#include <limits>
#include <type_traits>

#include "../core/policy.hpp"
#include "../math/scalar_traits.hpp"

namespace impulse::narrowphase {

template <scalar_type T>
struct tolerances {
  // ---- separating axes -----------------------------------------------------

  /// Squared sine of the angle between two edges (|a × b|² / (|a|²·|b|²))
  /// below which their cross product is no axis: edges within about 0.06°
  /// of parallel. Their axis is then a face axis already tested, and the
  /// cross product's direction is rounding noise that would report a
  /// separation along no real axis. box_box.hpp (whose axes are unit),
  /// hull_hull.hpp, capsule_polyhedron.hpp and mesh.hpp.
  static constexpr T parallel_edge_sine_squared = T(1e-6);

  /// Faces are preferred: an edge axis wins over the best face axis, and
  /// the second shape's face over the first's (box_box.hpp, hull_hull.hpp;
  /// for a mesh the polyhedron's face over the triangle's), only if its
  /// separation is larger by this fraction of the face's |separation|
  /// (relative)…
  static constexpr T face_preference_of_depth = T(0.05);
  /// …plus this fraction of a size (relative; m once multiplied): the
  /// least half extent of the smaller shape (box_box.hpp, hull_hull.hpp),
  /// of the capsule's radius and the polyhedron's least half extent
  /// (capsule_polyhedron.hpp), of the polyhedron facing a triangle
  /// (mesh.hpp). Without the bias, two faces resting on each other hop
  /// between near-equal axes from step to step, and their contact points
  /// and ids hop with them (Catto, GDC 2013, biases the choice the same
  /// way).
  static constexpr T face_preference_of_size = T(0.01);

  /// Rounding allowed in mesh.hpp's tests that an edge pair's axis N is
  /// supported by both edges (the polyhedron's edge lies between its faces'
  /// normals, a triangle's edge faces out along N): a dot product of unit
  /// vectors (sines, a cosine) may fall this far below zero, so that an
  /// axis on the border of where an edge supports its shape (along one of
  /// its faces' normals, or in a triangle's plane) is not refused on the
  /// rounding of a sign. capsule_polyhedron.hpp tests the same support of
  /// a polyhedron's edge with no slack (`< 0`); the two are kept as they
  /// are.
  static constexpr T edge_support_slack = T(1e-6);

  // ---- normals -------------------------------------------------------------

  /// Cosine above which two unit normals count as one: about 2.6°. mesh.hpp
  /// merges the manifolds of triangles whose normals agree this well, so
  /// that a box on a flat mesh of many triangles gets one manifold of four
  /// points; capsule_polyhedron.hpp takes a face's contact when GJK's
  /// normal is this close to the face's, so that a capsule lying on a box
  /// stands on two points, not one.
  static constexpr T same_normal_cosine = T(0.999);
  /// Sine of the angle between a capsule's core and a face's plane
  /// (|axis · normal|) below which the capsule lies along the face (about
  /// 2.9°) and is clipped to it, so that it rests on both ends
  /// (capsule_polyhedron.hpp).
  static constexpr T segment_along_face_sine = T(0.05);
  /// Squared sine of the angle between two capsules' cores
  /// (|da × db|² / (|da|²·|db|²)) below which they are nearly parallel (about
  /// 0.57°) and touch along a line: two points, at the ends of their
  /// overlap, so that one can rest on the other (analytic.hpp). Not the
  /// same test as parallel_edge_sine_squared: this one chooses a line
  /// contact, that one drops an axis that is noise.
  static constexpr T parallel_capsule_sine_squared = T(1e-4);

  // ---- contact points ------------------------------------------------------

  /// Distance from a line, as a fraction of the line's length (relative),
  /// within which contact points count as lying on it: reduce_to_four
  /// (manifold.hpp) keeps a line's two ends, and not a third point that
  /// only rounding put off the line (a capsule lying across a face).
  static constexpr T collinear_fraction = T(1e-3);
  /// The same 1e-3, squared, for mesh.hpp's merger, which compares squared
  /// distances: written out, since 1e-3 squared in float is not the float
  /// nearest 1e-6.
  static constexpr T collinear_fraction_squared = T(1e-6);
  /// Half-width of the band across a clipped patch's center, as a fraction
  /// of the patch's spread (its points' largest offset from the center
  /// along the face's axes; relative), inside which a point counts as on
  /// the negative side when its quarter is chosen (detail/clipping.hpp), so
  /// that the two ends of a line of contact do not toss between quarters,
  /// and change feature ids, across it.
  static constexpr T quarter_dead_band = T(0.01);
  /// Contact points of neighbouring triangles closer than this fraction of
  /// the shape's size (a sphere's or capsule's radius, a polyhedron's least
  /// half extent; relative) are one point, the deeper kept (mesh.hpp): a
  /// shape resting on a shared edge or corner otherwise gets the same
  /// point twice and fills its four with duplicates.
  static constexpr T weld_fraction = T(1e-4);
  /// A triangle's corners within this fraction of its longest edge
  /// (relative) of each other along a direction support it together, as an
  /// edge or the face (mesh.hpp, supporting_feature): a box face resting on
  /// a triangle is supported by the triangle's face, not by the corner that
  /// rounding puts an ulp higher, which would be an internal feature.
  static constexpr T feature_fraction = T(1e-4);
  /// A sphere's center or a capsule's core closer than this fraction of
  /// the radius (relative) to a triangle lies on it: the direction between
  /// them is rounding, and the triangle's face normal is taken instead
  /// (mesh.hpp).
  static constexpr T core_offset_fraction = T(1e-3);
  /// A capsule's core is clipped to a triangle's prism with the prism's
  /// side planes pushed out by this fraction of the radius (relative), so
  /// that a core standing exactly on an edge or a corner is not clipped
  /// away by rounding on both sides of it (mesh.hpp).
  static constexpr T prism_slack_fraction = T(1e-4);

  // ---- closest points, GJK, EPA, ray casts -----------------------------------

  /// Squared sine of a triangle's angle at a (|ab × ac|² / (|ab|²·|ac|²),
  /// relative) below which it has no face, only edges: 64 ulps of T, above
  /// the rounding of the cross product, whose barycentric weights would
  /// otherwise divide by it (triangle.hpp).
  static constexpr T degenerate_triangle = T(64) * scalar_traits<T>::epsilon;
  /// GJK's tetrahedron is a sliver when its volume is below this fraction
  /// of its longest edge cubed (relative): the origin's side of its faces
  /// is then rounding, every face is tried, and the origin is never taken
  /// to be inside it (gjk.hpp). Compared in the simplex's scalar (double).
  static constexpr T sliver_volume = T(1e-6);
  /// GJK ends once the support plane along −v is within this fraction of
  /// |v| of v (relative, van den Bergen's ε): about float's rounding of
  /// the support points for float shapes, and well above double's for
  /// double ones (gjk.hpp).
  static constexpr double gjk_tolerance = std::is_same_v<T, float> ? 1e-6 : 1e-12;
  /// GJK takes the shapes to overlap when v is shorter than this fraction
  /// of the simplex's size (relative): 4 ulps of T, the rounding of the
  /// support points that make v (gjk.hpp).
  static constexpr double gjk_overlap_rounding = 4.0 * double(scalar_traits<T>::epsilon);
  /// EPA ends when the support point along the nearest face's normal is
  /// within this fraction of the face's distance plus 1 m (relative); the
  /// depth then agrees with the exact one to 1.1e-6 m in float and 1.3e-15 m
  /// in double over about 1 880 random box pairs (epa.hpp).
  static constexpr double epa_tolerance = std::is_same_v<T, float> ? 1e-6 : 1e-10;
  /// While EPA blows GJK's simplex up to a tetrahedron, a support point
  /// spans a new direction only if it lies this fraction of the simplex's
  /// size (relative) off what the simplex spans, so that no face is built
  /// on rounding (epa.hpp)…
  static constexpr double epa_new_direction = 1e-9;
  /// …and the size is taken as at least this, m, so that a simplex shrunk
  /// to the origin still has a tolerance above zero.
  static constexpr double epa_least_size = 1e-30;
  /// GJK ray casting stands on a polytope once the simplex's nearest point
  /// is within this fraction of the simplex's size (relative): close to
  /// float's rounding for float shapes, and far above double's for double
  /// ones (ray_cast.hpp).
  static constexpr double ray_gjk_tolerance = std::is_same_v<T, float> ? 1e-7 : 1e-12;
  /// …and on a rounded shape (a sphere, a capsule) once its distance from
  /// the core is the radius to this fraction (8 double ulps, relative):
  /// there |v| is about the radius, and its rounding, not ray_gjk_tolerance,
  /// limits how closely the point can be put on the surface.
  static constexpr double ray_rounded_tolerance = 8.0 * std::numeric_limits<double>::epsilon();
  /// The plane through the last three support points is taken as the
  /// polytope's face when no support point lies beyond it by more than
  /// this fraction of the simplex's size (1000 ulps of T, relative): the
  /// face's plane is exact to rounding, where GJK's own point stalls about
  /// that far in front of the face (ray_cast.hpp).
  static constexpr double ray_face_tolerance = 1e3 * double(scalar_traits<T>::epsilon);
};

}  // namespace impulse::narrowphase
