// tests/peers/ccd_shapes.hpp — the shapes of convex_pairs.hpp as libccd
// sees them: an object with a support function and a center, in double
// (Debian's libccd 2.1 is built with CCD_DOUBLE).
//
// The support functions are written here from the shape's definition and
// rotated with libccd's own quaternions, so nothing of impulse's support
// code enters libccd's answers: a hull's support is the farthest of the
// points it was built from, not of impulse's quickhull vertices.
//
// libccd 2.1 has no distance query (ccdGJKDist exists only in FCL's fork):
// its GJK answers "do they intersect?", its EPA and MPR "how deep?". For
// separated shapes, `ccd_distance` gets the distance from EPA all the same:
// grow B by a ball of radius g greater than their distance d and B overlaps
// A by exactly g − d (the origin lies d outside A − B, so d inside the
// boundary of (A − B) ⊕ ball(g), whose points are all exactly g from A − B).
// The grown shape is curved, so libccd's EPA ends within its epa_tolerance
// of it, not exactly.
#pragma once

#include <ccd/ccd.h>
#include <ccd/quat.h>

#include <cmath>
#include <vector>

#include "convex_pairs.hpp"

namespace peers {

struct ccd_shape {
  shape_kind kind = shape_kind::sphere;
  double radius = 0, half_height = 0;
  ccd_vec3_t half_extents{};
  std::vector<ccd_vec3_t> points;
  ccd_vec3_t position{};
  ccd_quat_t rotation{}, inverse{};
  double grow = 0;  ///< m: a ball added to the shape (see ccd_distance)

  explicit ccd_shape(const shape_spec& s) : kind(s.kind), radius(s.radius), half_height(s.half_height) {
    ccdVec3Set(&half_extents, s.half_extents.x, s.half_extents.y, s.half_extents.z);
    for (const v3& p : s.points) {
      ccd_vec3_t q;
      ccdVec3Set(&q, p.x, p.y, p.z);
      points.push_back(q);
    }
    ccdVec3Set(&position, s.pose.position.x, s.pose.position.y, s.pose.position.z);
    ccdQuatSet(&rotation, s.pose.rotation.x, s.pose.rotation.y, s.pose.rotation.z, s.pose.rotation.w);
    ccdQuatInvert2(&inverse, &rotation);
  }
};

/// d scaled to length r (along x if d is zero).
inline void ccd_scaled_unit(const ccd_vec3_t& d, double r, ccd_vec3_t* out) {
  const double length = std::sqrt(ccdVec3Len2(&d));
  if (length > 0)
    ccdVec3Set(out, d.v[0] * r / length, d.v[1] * r / length, d.v[2] * r / length);
  else
    ccdVec3Set(out, r, 0, 0);
}

extern "C" inline void ccd_support(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
  const ccd_shape& s = *static_cast<const ccd_shape*>(object);
  ccd_vec3_t d = *direction, p{};
  ccdQuatRotVec(&d, &s.inverse);  // into the body frame
  switch (s.kind) {
    case shape_kind::sphere: ccd_scaled_unit(d, s.radius, &p); break;
    case shape_kind::capsule: {
      ccd_scaled_unit(d, s.radius, &p);
      p.v[1] += d.v[1] < 0 ? -s.half_height : s.half_height;
      break;
    }
    case shape_kind::box:
      for (int k = 0; k < 3; ++k) p.v[k] = d.v[k] < 0 ? -s.half_extents.v[k] : s.half_extents.v[k];
      break;
    case shape_kind::hull: {
      p = s.points[0];
      for (const ccd_vec3_t& q : s.points)
        if (ccdVec3Dot(&q, &d) > ccdVec3Dot(&p, &d)) p = q;
      break;
    }
  }
  ccdQuatRotVec(&p, &s.rotation);
  ccdVec3Add(&p, &s.position);
  if (s.grow > 0) {
    ccd_vec3_t g;
    ccd_scaled_unit(*direction, s.grow, &g);
    ccdVec3Add(&p, &g);
  }
  *out = p;
}

extern "C" inline void ccd_center(const void* object, ccd_vec3_t* center) {
  *center = static_cast<const ccd_shape*>(object)->position;
}

/// libccd set up for our shapes. Its defaults stop EPA 1e-4 m short
/// (epa_tolerance, absolute) and MPR likewise: far coarser than 1e-4
/// relative on 0.1 m shapes, so the agreement test tightens them to
/// `tolerance` (m).
inline ccd_t ccd_setup(double tolerance = 1e-4) {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = ccd_support;
  ccd.support2 = ccd_support;
  ccd.center1 = ccd_center;
  ccd.center2 = ccd_center;
  ccd.max_iterations = 1000;  // GJK's cap; CCD_INIT leaves it unbounded
  ccd.epa_tolerance = tolerance;
  ccd.mpr_tolerance = tolerance;
  ccd.dist_tolerance = tolerance;
  return ccd;
}

/// libccd's penetration depth of b into a by GJK + EPA, or −1 when its GJK
/// finds them apart.
inline double ccd_depth(const ccd_t& ccd, const ccd_shape& a, const ccd_shape& b) {
  ccd_real_t depth = 0;
  ccd_vec3_t direction, position;
  if (ccdGJKPenetration(&a, &b, &ccd, &depth, &direction, &position) != 0) return -1;
  return depth;
}

/// libccd's distance between separated a and b, from EPA on b grown by a
/// ball of radius `grow` (m), which must exceed the distance; −1 if libccd
/// finds even the grown b apart from a.
inline double ccd_distance(const ccd_t& ccd, const ccd_shape& a, ccd_shape b, double grow) {
  b.grow = grow;
  const double depth = ccd_depth(ccd, a, b);
  return depth < 0 ? -1 : grow - depth;
}

}  // namespace peers
