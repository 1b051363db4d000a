// tests/peers/convex_pairs.hpp — seeded random pairs of convex shapes, and
// the exact distance or penetration depth of each by brute force: the
// ground truth that our GJK/EPA and the peers' (libccd, Bullet) are judged
// against. Used by tests/peers/ccd_agreement.cpp and bench/narrowphase.
//
// Every shape is a core grown by a radius: a sphere is a point grown by its
// radius, a capsule a segment, a box or a hull a polytope grown by nothing.
// Let K = core(A) − core(B) (a polytope, flat for two points or segments)
// and R the sum of the radii. Then, by brute force over features and axes:
// - if K misses the origin, at distance d, the cores are d apart and the
//   shapes d − R apart (overlapping by R − d when d < R). d is the least
//   distance between boundary features (vertex–triangle both ways,
//   edge–edge), exact for disjoint convex polytopes;
// - if K holds the origin, the shapes overlap by R + δ, δ the least
//   overlap of the cores' projections over every face normal of either
//   core and every cross product of an edge of one with an edge of the
//   other: those include every face normal of K, and no direction overlaps
//   less than the nearest face of K, so the least is exactly the depth
//   (the separating axis theorem, Ericson §4.4 and §5.2.1). Disjoint cores
//   show a gap on one of those axes: that decides which case applies.
// Faces and edges of a hull come from impulse::convex_hull (quickhull,
// tested in tests/shapes); everything else here is independent of the
// narrow phase under test. It is slow (every edge pair) and meant to be.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "impulse/core/random.hpp"
#include "impulse/math/transform.hpp"
#include "impulse/shapes/box.hpp"
#include "impulse/shapes/capsule.hpp"
#include "impulse/shapes/convex_hull.hpp"
#include "impulse/shapes/sphere.hpp"

namespace peers {

using impulse::vec3;
using v3 = vec3<double>;

enum class shape_kind { sphere, box, capsule, hull };

inline const char* name_of(shape_kind k) {
  switch (k) {
    case shape_kind::sphere: return "sphere";
    case shape_kind::box: return "box";
    case shape_kind::capsule: return "capsule";
    case shape_kind::hull: return "hull";
  }
  return "?";
}

/// One shape and its pose, in double; `make<Shape, T>` builds our shape
/// from it in either precision, the peers' adapters theirs.
struct shape_spec {
  shape_kind kind = shape_kind::sphere;
  double radius = 0;              ///< m: sphere, capsule
  double half_height = 0;         ///< m: capsule, along its local y
  v3 half_extents{};              ///< m: box
  std::vector<v3> points;         ///< body frame: the cloud a hull is the hull of (a box's 8 corners)
  impulse::transform<double> pose = impulse::transform<double>::identity();

  /// Radius of a ball about pose.position holding the shape (m).
  [[nodiscard]] double bound() const {
    switch (kind) {
      case shape_kind::sphere: return radius;
      case shape_kind::capsule: return radius + half_height;
      default: {
        double r = 0;
        for (const v3& p : points) r = std::max(r, length(p));
        return r;
      }
    }
  }
};

struct pair_spec {
  shape_spec a, b;
};

/// A shape of kind k, 0.1 m to 1 m across its largest dimension or more,
/// with elongations up to 10:1, at the origin.
inline shape_spec random_shape(shape_kind k, impulse::lcg32& random) {
  shape_spec s;
  s.kind = k;
  const auto u = [&](double lo, double hi) { return random.uniform<double>(lo, hi); };
  switch (k) {
    case shape_kind::sphere: s.radius = u(0.1, 1.0); break;
    case shape_kind::capsule:
      s.radius = u(0.05, 0.5);
      s.half_height = u(0.05, 1.0);
      break;
    case shape_kind::box:
      s.half_extents = {u(0.1, 1.0), u(0.1, 1.0), u(0.1, 1.0)};
      for (int c = 0; c < 8; ++c)
        s.points.push_back({c & 1 ? s.half_extents.x : -s.half_extents.x, c & 2 ? s.half_extents.y : -s.half_extents.y,
                            c & 4 ? s.half_extents.z : -s.half_extents.z});
      break;
    case shape_kind::hull: {
      // 6 to 24 points in an ellipsoid: irregular hulls with triangles,
      // slivers and points inside.
      const v3 axes{u(0.1, 1.0), u(0.1, 1.0), u(0.1, 1.0)};
      const int n = 6 + int(random.next() % 19);
      for (int i = 0; i < n; ++i) {
        v3 p;
        do p = {u(-1, 1), u(-1, 1), u(-1, 1)};
        while (length_squared(p) > 1.0);
        s.points.push_back(mul(p, axes));
      }
      break;
    }
  }
  return s;
}

/// A rotation about a random axis by a random angle.
inline impulse::quat<double> random_rotation(impulse::lcg32& random) {
  v3 axis;
  do axis = {random.uniform(-1.0, 1.0), random.uniform(-1.0, 1.0), random.uniform(-1.0, 1.0)};
  while (!(length_squared(axis) > 1e-4 && length_squared(axis) <= 1.0));
  return impulse::quat<double>::from_axis_angle(normalize(axis), random.uniform(-3.14159, 3.14159));
}

// ---- the exact answer -------------------------------------------------------------

/// A shape's core in world space, with the features the brute force visits.
struct world_core {
  std::vector<v3> vertices;
  std::vector<std::pair<int, int>> edges;     ///< a point core has none, a segment one
  std::vector<std::array<int, 3>> triangles;  ///< the faces, fanned; none for a point or a segment
  std::vector<v3> face_normals;               ///< unit, outward
  double radius = 0;
};

inline world_core core_of(const shape_spec& s) {
  world_core c;
  const auto& pose = s.pose;
  switch (s.kind) {
    case shape_kind::sphere:
      c.vertices = {pose.position};
      c.radius = s.radius;
      break;
    case shape_kind::capsule:
      c.vertices = {apply(pose, v3{0, -s.half_height, 0}), apply(pose, v3{0, s.half_height, 0})};
      c.edges = {{0, 1}};
      c.radius = s.radius;
      break;
    default: {
      const auto hull = impulse::convex_hull<double>::from_points(s.points);
      for (const v3& p : hull.vertices()) c.vertices.push_back(apply(pose, p));
      for (const auto& e : hull.edges()) c.edges.push_back({int(e.a), int(e.b)});
      for (std::size_t f = 0; f < hull.face_count(); ++f) {
        const auto polygon = hull.face(f);
        for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
          c.triangles.push_back({int(polygon[0]), int(polygon[k]), int(polygon[k + 1])});
        c.face_normals.push_back(rotate(pose.rotation, hull.plane(f).normal));
      }
    }
  }
  return c;
}

/// Squared distance between segments p0p1 and q0q1 (either may be a point):
/// Ericson §5.1.9, clamping each parameter in turn.
inline double segment_segment_distance2(const v3& p0, const v3& p1, const v3& q0, const v3& q1) {
  const v3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  double s = 0, t = 0;
  if (a <= 0 && e <= 0) return length_squared(r);
  if (a <= 0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = dot(d1, r);
    if (e <= 0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = dot(d1, d2), denominator = a * e - b * b;
      s = denominator > 0 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) t = 0, s = std::clamp(-c / a, 0.0, 1.0);
      else if (t > 1) t = 1, s = std::clamp((b - c) / a, 0.0, 1.0);
    }
  }
  return length_squared((p0 + d1 * s) - (q0 + d2 * t));
}

/// Squared distance from p to triangle abc: to its plane if p projects
/// inside it, else to its nearest edge (a projection by signed areas, not
/// the Voronoi-region walk of impulse's triangle.hpp, on purpose).
inline double point_triangle_distance2(const v3& p, const v3& a, const v3& b, const v3& c) {
  const v3 n = cross(b - a, c - a);
  const double n2 = length_squared(n);
  if (n2 > 0) {
    const double h = dot(p - a, n);
    const v3 q = p - n * (h / n2);  // p projected on the plane
    if (dot(cross(b - a, q - a), n) >= 0 && dot(cross(c - b, q - b), n) >= 0 && dot(cross(a - c, q - c), n) >= 0)
      return h * h / n2;
  }
  return std::min({segment_segment_distance2(p, p, a, b), segment_segment_distance2(p, p, b, c),
                   segment_segment_distance2(p, p, c, a)});
}

/// The least of max(A)−min(B), max(B)−min(A) along n: > 0 an overlap,
/// < 0 a gap (in units of |n|).
inline double overlap_along(const world_core& a, const world_core& b, const v3& n) {
  double lo_a = std::numeric_limits<double>::infinity(), hi_a = -lo_a, lo_b = lo_a, hi_b = hi_a;
  for (const v3& v : a.vertices) lo_a = std::min(lo_a, dot(v, n)), hi_a = std::max(hi_a, dot(v, n));
  for (const v3& v : b.vertices) lo_b = std::min(lo_b, dot(v, n)), hi_b = std::max(hi_b, dot(v, n));
  return std::min(hi_a - lo_b, hi_b - lo_a);
}

struct exact_answer {
  bool overlapping = false;
  double distance = 0;  ///< m, when apart
  double depth = 0;     ///< m, when overlapping
};

inline exact_answer exact(const pair_spec& pair) {
  const world_core a = core_of(pair.a), b = core_of(pair.b);
  const double radii = a.radius + b.radius;
  // Do the cores overlap, and by how much? Only a core with faces can hold
  // the origin in K with depth: two points or segments make a flat K.
  bool cores_overlap = !a.face_normals.empty() || !b.face_normals.empty();
  double core_depth = std::numeric_limits<double>::infinity();
  const auto axis = [&](const v3& n) {
    const double o = overlap_along(a, b, n);
    core_depth = std::min(core_depth, o);
    if (o < 0) cores_overlap = false;
  };
  if (cores_overlap) {
    for (const v3& n : a.face_normals) axis(n);
    for (const v3& n : b.face_normals) axis(n);
    for (const auto& [i, j] : a.edges)
      for (const auto& [k, l] : b.edges) {
        const v3 n = cross(a.vertices[j] - a.vertices[i], b.vertices[l] - b.vertices[k]);
        // Parallel edges add no face to K that the face normals miss.
        if (length_squared(n) > 1e-18 * length_squared(a.vertices[j] - a.vertices[i]) *
                                    length_squared(b.vertices[l] - b.vertices[k]))
          axis(normalize(n));
      }
  }
  exact_answer answer;
  if (cores_overlap) {
    answer.overlapping = true;
    answer.depth = radii + std::max(core_depth, 0.0);
    return answer;
  }
  // Apart: the least distance between boundary features.
  double d2 = std::numeric_limits<double>::infinity();
  const auto segments = [](const world_core& c) {
    std::vector<std::pair<int, int>> s = c.edges;
    if (s.empty()) s.push_back({0, 0});  // a point core
    return s;
  };
  for (const auto& [i, j] : segments(a))
    for (const auto& [k, l] : segments(b))
      d2 = std::min(d2, segment_segment_distance2(a.vertices[i], a.vertices[j], b.vertices[k], b.vertices[l]));
  for (const v3& p : a.vertices)
    for (const auto& t : b.triangles)
      d2 = std::min(d2, point_triangle_distance2(p, b.vertices[t[0]], b.vertices[t[1]], b.vertices[t[2]]));
  for (const v3& p : b.vertices)
    for (const auto& t : a.triangles)
      d2 = std::min(d2, point_triangle_distance2(p, a.vertices[t[0]], a.vertices[t[1]], a.vertices[t[2]]));
  const double d = std::sqrt(d2);
  answer.overlapping = d < radii;
  if (answer.overlapping)
    answer.depth = radii - d;
  else
    answer.distance = d - radii;
  return answer;
}

/// n pairs of kinds ka and kb: B placed at a random offset from A (A's
/// center somewhere in a 10 m cube about the origin, `far` m out along x),
/// random rotations; half of them overlapping by the exact answer, half
/// apart, each pair with its exact answer. Pairs within 1e-6 m of touching
/// are drawn again: there the question "overlapping?" is rounding.
struct generated_pairs {
  std::vector<pair_spec> pairs;
  std::vector<exact_answer> answers;
};

inline generated_pairs random_pairs(shape_kind ka, shape_kind kb, int n, std::uint32_t seed, double far = 0) {
  impulse::lcg32 random{seed};
  generated_pairs out;
  int overlapping = 0, apart = 0;
  while (overlapping + apart < n) {
    pair_spec p{random_shape(ka, random), random_shape(kb, random)};
    p.a.pose = {v3{far + random.uniform(-5.0, 5.0), random.uniform(-5.0, 5.0), random.uniform(-5.0, 5.0)},
                random_rotation(random)};
    v3 direction;
    do direction = {random.uniform(-1.0, 1.0), random.uniform(-1.0, 1.0), random.uniform(-1.0, 1.0)};
    while (!(length_squared(direction) > 1e-4 && length_squared(direction) <= 1.0));
    const double reach = p.a.bound() + p.b.bound();
    p.b.pose = {p.a.pose.position + normalize(direction) * (reach * random.uniform(0.0, 1.1)),
                random_rotation(random)};
    const exact_answer e = exact(p);
    if ((e.overlapping ? e.depth : e.distance) < 1e-6) continue;
    int& count = e.overlapping ? overlapping : apart;
    if (2 * count >= n) continue;  // keep the halves even
    ++count;
    out.pairs.push_back(std::move(p));
    out.answers.push_back(e);
  }
  return out;
}

// ---- our shapes from a spec -------------------------------------------------------

template <class Shape>
struct maker;
template <impulse::scalar_type T>
struct maker<impulse::sphere<T>> {
  static impulse::sphere<T> make(const shape_spec& s) { return impulse::sphere<T>::make(T(s.radius)); }
};
template <impulse::scalar_type T>
struct maker<impulse::box<T>> {
  static impulse::box<T> make(const shape_spec& s) {
    return impulse::box<T>::make({T(s.half_extents.x), T(s.half_extents.y), T(s.half_extents.z)});
  }
};
template <impulse::scalar_type T>
struct maker<impulse::capsule<T>> {
  static impulse::capsule<T> make(const shape_spec& s) {
    return impulse::capsule<T>::make(T(s.radius), T(s.half_height));
  }
};
template <impulse::scalar_type T>
struct maker<impulse::convex_hull<T>> {
  static impulse::convex_hull<T> make(const shape_spec& s) {
    std::vector<vec3<T>> points;
    for (const v3& p : s.points) points.push_back({T(p.x), T(p.y), T(p.z)});
    return impulse::convex_hull<T>::from_points(points);
  }
};

/// Our shape of type Shape (its scalar T) from the spec.
template <class Shape>
Shape make(const shape_spec& s) {
  return maker<Shape>::make(s);
}

template <impulse::scalar_type T>
impulse::transform<T> pose_of(const shape_spec& s) {
  const auto& p = s.pose;
  return {{T(p.position.x), T(p.position.y), T(p.position.z)},
          {T(p.rotation.x), T(p.rotation.y), T(p.rotation.z), T(p.rotation.w)}};
}

}  // namespace peers
