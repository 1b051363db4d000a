// Tests of impulse/shapes/convex_hull.hpp. Every hull built here goes through
// check_hull, which tests what the narrow phase will rely on: a closed mesh
// (Euler's formula, each edge once between the two faces that share it),
// vertices that are input points, unit normals, convex polygons wound
// counter-clockwise from outside, planes that support the hull, and every
// input point within the tolerance of the hull. The clouds are drawn from a
// fixed generator, so a failure reproduces exactly.
#include <impulse/shapes/convex_hull.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <impulse/core/error.hpp>
#include <impulse/core/policy.hpp>
#include <impulse/math/aabb.hpp>
#include <impulse/math/quat.hpp>
#include <impulse/math/transform.hpp>

#include "../math/tolerances.hpp"

namespace shapes_convex_hull_tests {

using namespace impulse;
using namespace impulse::test;

static_assert(shape_type<convex_hull<float>>);
static_assert(shape_type<convex_hull<double>>);

namespace {

template <class T>
vec3<T> v3(double x, double y, double z) {
  return {static_cast<T>(x), static_cast<T>(y), static_cast<T>(z)};
}

vec3<double> to_double(const vec3<float>& v) { return {v.x, v.y, v.z}; }
vec3<double> to_double(const vec3<double>& v) { return v; }

/// The tolerance from_points derives for these points: Gregorius'
/// 3·(max|x| + max|y| + max|z|)·ε, coordinates from the bounding box center.
template <class T>
double expected_tolerance(const std::vector<vec3<T>>& points) {
  vec3<double> lo = to_double(points[0]), hi = lo;
  for (const vec3<T>& p : points) {
    lo = min(lo, to_double(p));
    hi = max(hi, to_double(p));
  }
  const vec3<double> half = (hi - lo) * 0.5;
  return 3 * (half.x + half.y + half.z) * double(epsilon<T>);
}

/// Largest |x| + |y| + |z| of the points: the scale of the rounding of a
/// plane evaluated at them.
template <class T>
double reach(const std::vector<vec3<T>>& points) {
  double r = 0;
  for (const vec3<T>& p : points) r = std::fmax(r, max_component(abs(to_double(p))) * 3);
  return r;
}

/// How far the tests let what the construction guarantees stray, in units
/// of hull.tolerance(), each measured over every hull built while writing
/// these tests (the maximum seen in brackets):
/// - an input point outside a face's plane: points within one tolerance of
///   the hull are dropped, merged faces are refit, and planes then move out
///   to the supporting vertex [1.5];
constexpr double outside_slack = 3;
/// - a face's own vertex below its plane: within one tolerance of the fitted
///   plane, which then moves out to the supporting vertex by up to one more
///   [2.1];
constexpr double below_slack = 3;
/// - a vertex of a face outside the line of one of its edges [1e-9].
constexpr double reflex_slack = 1;

/// Rounding of n·x + offset evaluated in double from values stored in T:
/// the normal's and the offset's own rounding, each ε of T relative, at
/// points as far out as `reach`.
template <class T>
double rounding(double reach) {
  return 4 * double(epsilon<T>) * reach;
}

/// Checks everything a hull promises (see the top of this file) against the
/// points it was built from.
template <class T>
void check_hull(const convex_hull<T>& hull, const std::vector<vec3<T>>& points) {
  const std::span<const vec3<T>> vertices = hull.vertices();
  const std::size_t v_count = vertices.size(), f_count = hull.face_count();
  const std::span<const hull_edge> edges = hull.edges();
  const double tol = hull.tolerance();
  const double round = rounding<T>(reach(points));
  INFO("hull of " << points.size() << " points: " << v_count << " vertices, " << f_count << " faces, "
                  << edges.size() << " edges, tolerance " << tol);

  REQUIRE(v_count >= 4);
  REQUIRE(f_count >= 4);
  CHECK(hull.vertex_count() == v_count);
  // Euler's formula for a closed polyhedron of genus 0.
  CHECK(static_cast<long>(v_count) - static_cast<long>(edges.size()) + static_cast<long>(f_count) == 2);
  CHECK(std::abs(tol - expected_tolerance(points)) <= 1e-6 * tol);

  // Faces: at least three distinct vertices each, and each directed edge of
  // a face once in the whole mesh; its reverse belongs to another face.
  // The face on which each directed edge runs, in a dense table: the hulls
  // here have at most a few thousand vertices.
  const bool dense = v_count <= 2048;
  std::vector<std::uint32_t> next_of(dense ? v_count * v_count : 0, 0xffffffffu);
  std::size_t corners = 0, bad_faces = 0, repeated = 0;
  for (std::size_t f = 0; f < f_count; ++f) {
    const std::span<const std::uint32_t> face = hull.face(f);
    corners += face.size();
    if (face.size() < 3) ++bad_faces;
    for (std::size_t i = 0; i < face.size(); ++i) {
      if (face[i] >= v_count) ++bad_faces;
      for (std::size_t j = i + 1; j < face.size(); ++j) bad_faces += face[i] == face[j] ? 1 : 0;
      if (dense && face[i] < v_count) {
        const std::uint32_t to = face[(i + 1) % face.size()];
        std::uint32_t& slot = next_of[face[i] * v_count + (to < v_count ? to : 0)];
        if (slot != 0xffffffffu) ++repeated;
        slot = static_cast<std::uint32_t>(f);
      }
    }
  }
  CHECK(bad_faces == 0);
  CHECK(repeated == 0);
  CHECK(corners == 2 * edges.size());

  // Edges: each once, between the two faces that run along it.
  std::size_t bad_edges = 0;
  for (const hull_edge& e : edges) {
    if (e.a >= v_count || e.b >= v_count || e.a == e.b || e.face_ab >= f_count || e.face_ba >= f_count ||
        e.face_ab == e.face_ba) {
      ++bad_edges;
      continue;
    }
    if (dense && (next_of[e.a * v_count + e.b] != e.face_ab || next_of[e.b * v_count + e.a] != e.face_ba))
      ++bad_edges;
  }
  CHECK(bad_edges == 0);

  // Vertices: distinct input points.
  std::size_t strangers = 0, twins = 0;
  for (std::size_t i = 0; i < v_count; ++i) {
    bool found = false;
    for (const vec3<T>& p : points) found = found || p == vertices[i];
    strangers += found ? 0 : 1;
    for (std::size_t j = i + 1; j < v_count; ++j) twins += vertices[i] == vertices[j] ? 1 : 0;
  }
  CHECK(strangers == 0);
  CHECK(twins == 0);

  // Planes and polygons.
  double worst_normal = 0, worst_winding = 1, worst_below = 0, worst_above = 0, worst_outside = 0,
         worst_reflex = 0;
  for (std::size_t f = 0; f < f_count; ++f) {
    const std::span<const std::uint32_t> face = hull.face(f);
    const auto& plane = hull.plane(f);
    CHECK(&plane == &hull.planes()[f]);
    const vec3<double> n = to_double(plane.normal);
    const auto distance = [&](const vec3<T>& x) { return dot(n, to_double(x)) + double(plane.offset); };
    worst_normal = std::fmax(worst_normal, std::abs(length(n) - 1));
    // Newell's normal of the polygon as wound: it must agree with the plane.
    const vec3<double> first = to_double(vertices[face[0]]);
    vec3<double> newell{};
    for (std::size_t i = 0; i < face.size(); ++i)
      newell += cross(to_double(vertices[face[i]]) - first, to_double(vertices[face[(i + 1) % face.size()]]) - first);
    worst_winding = std::fmin(worst_winding, dot(normalize(newell), n));
    for (const std::uint32_t i : face) worst_below = std::fmax(worst_below, -distance(vertices[i]));
    for (const vec3<T>& v : vertices) worst_above = std::fmax(worst_above, distance(v));
    for (const vec3<T>& p : points) worst_outside = std::fmax(worst_outside, distance(p));
    // Convex: every vertex on the inner side of the line of every edge.
    for (std::size_t i = 0; i < face.size(); ++i) {
      const vec3<double> a = to_double(vertices[face[i]]), b = to_double(vertices[face[(i + 1) % face.size()]]);
      const vec3<double> inward = normalize(cross(n, b - a));
      for (const std::uint32_t j : face) worst_reflex = std::fmax(worst_reflex, -dot(inward, to_double(vertices[j]) - a));
    }
  }
  // A normal rounded to T: a few ε of T off unit length.
  CHECK(worst_normal <= 4 * double(epsilon<T>));
  CHECK(worst_winding > 0.99);
  CHECK(worst_above <= round);
  CHECK(worst_outside <= outside_slack * tol + round);
  CHECK(worst_below <= below_slack * tol + round);
  CHECK(worst_reflex <= reflex_slack * tol + round);
}

template <class T>
std::vector<vec3<T>> box_corners(const vec3<double>& center, const vec3<double>& half) {
  std::vector<vec3<T>> corners;
  for (int i = 0; i < 8; ++i)
    corners.push_back(v3<T>(center.x + ((i & 1) ? half.x : -half.x), center.y + ((i & 2) ? half.y : -half.y),
                            center.z + ((i & 4) ? half.z : -half.z)));
  return corners;
}

/// A box's hull: eight vertices (the corners), six quads with axis normals.
template <class T>
void check_box_hull(const convex_hull<T>& hull, const std::vector<vec3<T>>& points,
                    const std::vector<vec3<T>>& corners) {
  check_hull(hull, points);
  CHECK(hull.vertex_count() == 8);
  CHECK(hull.face_count() == 6);
  CHECK(hull.edges().size() == 12);
  for (const vec3<T>& c : corners) {
    bool found = false;
    for (const vec3<T>& v : hull.vertices()) found = found || v == c;
    CHECK(found);
  }
  int axis_count[3] = {0, 0, 0};
  for (std::size_t f = 0; f < hull.face_count(); ++f) {
    CHECK(hull.face(f).size() == 4);
    const vec3<double> n = to_double(hull.plane(f).normal);
    const vec3<double> a = abs(n);
    const int axis = a.x > 0.5 ? 0 : (a.y > 0.5 ? 1 : 2);
    ++axis_count[axis];
    // An axis normal, up to the rounding of the fit of a jittered face.
    CHECK(a[axis] >= 1 - 1e-3);
  }
  CHECK(axis_count[0] == 2);
  CHECK(axis_count[1] == 2);
  CHECK(axis_count[2] == 2);
}

template <class T>
convex_hull<T> build(const std::vector<vec3<T>>& points) {
  return convex_hull<T>::from_points(points);
}

/// Calls from_points and returns the error code it reports (none if it
/// builds a hull).
template <class T>
error_code error_of(const std::vector<vec3<T>>& points, std::uint32_t* object = nullptr) {
  try {
    (void)convex_hull<T>::from_points(points);
  } catch (const impulse::invalid_argument& e) {
    if (object) *object = e.object();
    return e.code();
  }
  return error_code::none;
}

/// Fisher-Yates with the test generator: the same order on every run.
template <class T>
void shuffle(std::vector<vec3<T>>& points, lcg& random) {
  for (std::size_t i = points.size(); i > 1; --i) {
    const auto j = static_cast<std::size_t>(random.uniform() * double(i));
    const vec3<T> swap = points[i - 1];
    points[i - 1] = points[j < i ? j : i - 1];
    points[j < i ? j : i - 1] = swap;
  }
}

}  // namespace

TEST_CASE_TEMPLATE("the eight corners of a box give six quads", T, float, double) {
  const vec3<double> center{0.5, -1, 2}, half{1, 2, 3};
  const std::vector<vec3<T>> corners = box_corners<T>(center, half);
  const convex_hull<T> hull = build(corners);
  check_box_hull(hull, corners, corners);
  // Each plane passes through its face: offset = -(n·center + half extent).
  for (std::size_t f = 0; f < hull.face_count(); ++f) {
    const vec3<double> n = to_double(hull.plane(f).normal);
    const double expected = -(dot(n, center) + dot(abs(n), half));
    CHECK(std::abs(double(hull.plane(f).offset) - expected) <= rounding<T>(reach(corners)));
  }
}

TEST_CASE_TEMPLATE("a box with points on its faces and edges and inside and repeated corners gives six quads", T,
                   float, double) {
  const vec3<double> center{-3, 0.25, 1}, half{2, 0.5, 1.5};
  const std::vector<vec3<T>> corners = box_corners<T>(center, half);
  std::vector<vec3<T>> points;
  lcg random;
  for (int k = 0; k < 3; ++k) points.insert(points.end(), corners.begin(), corners.end());
  for (int axis = 0; axis < 3; ++axis) {
    for (const double side : {-1.0, 1.0}) {
      // A 5 x 5 grid on each face, corners and edges included.
      for (int i = 0; i <= 4; ++i) {
        for (int j = 0; j <= 4; ++j) {
          vec3<double> p;
          p[axis] = side;
          p[(axis + 1) % 3] = -1 + 0.5 * i;
          p[(axis + 2) % 3] = -1 + 0.5 * j;
          points.push_back(v3<T>(center.x + half.x * p.x, center.y + half.y * p.y, center.z + half.z * p.z));
        }
      }
    }
  }
  for (int k = 0; k < 200; ++k) {
    const vec3<double> u = random.vector<double>(-1, 1);
    points.push_back(v3<T>(center.x + half.x * u.x, center.y + half.y * u.y, center.z + half.z * u.z));
  }
  check_box_hull(build(points), points, corners);
  // The order of the input changes nothing.
  shuffle(points, random);
  check_box_hull(build(points), points, corners);
}

TEST_CASE_TEMPLATE("a box with corners and face points jittered below the tolerance still gives six quads", T, float,
                   double) {
  const vec3<double> center{0, 0, 0}, half{1, 2, 3};
  lcg random;
  // Noise from a thousandth of the tolerance, the rounding of the corners
  // of a box computed in T, to a third of it (a quad's four corners then
  // stay within the tolerance of one plane).
  for (const double fraction : {1e-3, 0.1, 0.3}) {
    CAPTURE(fraction);
    std::vector<vec3<T>> points = box_corners<T>(center, half);
    const double amplitude = fraction * expected_tolerance(points);
    std::vector<vec3<T>> corners;
    for (vec3<T>& p : points) {
      p = v3<T>(p.x + amplitude * random.in<double>(-1, 1), p.y + amplitude * random.in<double>(-1, 1),
                p.z + amplitude * random.in<double>(-1, 1));
      corners.push_back(p);
    }
    for (int k = 0; k < 300; ++k) {
      vec3<double> u = random.vector<double>(-1, 1);
      const int axis = k % 3;
      u[axis] = k % 2 ? 1 : -1;
      points.push_back(v3<T>(half.x * u.x + amplitude * random.in<double>(-1, 1),
                             half.y * u.y + amplitude * random.in<double>(-1, 1),
                             half.z * u.z + amplitude * random.in<double>(-1, 1)));
    }
    check_box_hull(build(points), points, corners);
  }
}

TEST_CASE_TEMPLATE("a tetrahedron has four triangles and six edges", T, float, double) {
  const std::vector<vec3<T>> points{v3<T>(0, 0, 0), v3<T>(1, 0, 0), v3<T>(0, 1, 0), v3<T>(0, 0, 1)};
  const convex_hull<T> hull = build(points);
  check_hull(hull, points);
  CHECK(hull.vertex_count() == 4);
  CHECK(hull.face_count() == 4);
  CHECK(hull.edges().size() == 6);
  for (std::size_t f = 0; f < 4; ++f) CHECK(hull.face(f).size() == 3);
}

TEST_CASE_TEMPLATE("random points in a cube give a valid hull that rebuilds from its vertices", T, float, double) {
  lcg random;
  for (const int n : {10, 50, 200, 2000}) {
    CAPTURE(n);
    std::vector<vec3<T>> points;
    for (int i = 0; i < n; ++i) points.push_back(random.vector<T>(-1, 1));
    const convex_hull<T> hull = build(points);
    check_hull(hull, points);
    const std::vector<vec3<T>> vertices(hull.vertices().begin(), hull.vertices().end());
    const convex_hull<T> again = build(vertices);
    check_hull(again, vertices);
    CHECK(again.vertex_count() == hull.vertex_count());
    CHECK(again.face_count() == hull.face_count());
  }
}

TEST_CASE_TEMPLATE("random points in a spherical shell give a valid hull with many vertices", T, float, double) {
  lcg random;
  for (const int n : {10, 100, 2000}) {
    CAPTURE(n);
    std::vector<vec3<T>> points;
    for (int i = 0; i < n; ++i) {
      const vec3<T> u = random.unit_vector<T>();
      points.push_back(u * random.in<T>(0.99, 1));
    }
    const convex_hull<T> hull = build(points);
    check_hull(hull, points);
    // In a shell 1% thick most points are on the hull.
    CHECK(hull.vertex_count() >= points.size() / 3);
  }
}

TEST_CASE_TEMPLATE("points on a sphere are all vertices of their hull", T, float, double) {
  lcg random;
  std::vector<vec3<T>> points;
  for (int i = 0; i < 2000; ++i) points.push_back(random.unit_vector<T>());
  const convex_hull<T> hull = build(points);
  check_hull(hull, points);
  CHECK(hull.vertex_count() == points.size());
}

TEST_CASE_TEMPLATE("clustered points give a valid hull", T, float, double) {
  lcg random;
  std::vector<vec3<T>> points;
  // Eight clusters a thousandth of the cloud across, and eight narrower
  // than the tolerance, which weld into one point each.
  for (int c = 0; c < 16; ++c) {
    const vec3<double> center = random.vector<double>(-1, 1);
    const double radius = c < 8 ? 1e-3 : 0.2 * 3 * 3 * double(epsilon<T>);
    for (int k = 0; k < 120; ++k) {
      const vec3<double> p = center + random.vector<double>(-radius, radius);
      points.push_back(v3<T>(p.x, p.y, p.z));
    }
  }
  check_hull(build(points), points);
}

TEST_CASE_TEMPLATE("points on latitude rings give quads between the rings and triangles at the poles", T, float,
                   double) {
  const double pi = 3.14159265358979323846;
  for (const int rings : {6, 16}) {
    const int around = 2 * rings;
    CAPTURE(rings);
    std::vector<vec3<T>> points{v3<T>(0, 0, 1), v3<T>(0, 0, -1)};
    for (int i = 1; i < rings; ++i) {
      for (int j = 0; j < around; ++j) {
        const double theta = pi * i / rings, phi = 2 * pi * j / around;
        points.push_back(v3<T>(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
      }
    }
    const convex_hull<T> hull = build(points);
    check_hull(hull, points);
    CHECK(hull.vertex_count() == points.size());
    // Two isosceles trapezoids' worth of corners per band: planar, so quads.
    std::size_t quads = 0, triangles = 0;
    for (std::size_t f = 0; f < hull.face_count(); ++f) {
      quads += hull.face(f).size() == 4 ? 1 : 0;
      triangles += hull.face(f).size() == 3 ? 1 : 0;
    }
    CHECK(quads == static_cast<std::size_t>(around * (rings - 2)));
    CHECK(triangles == static_cast<std::size_t>(2 * around));
    CHECK(hull.face_count() == quads + triangles);
  }
}

TEST_CASE_TEMPLATE("a subdivided icosahedron on the sphere gives one triangle per face", T, float, double) {
  // Icosahedron: the cyclic permutations of (0, ±1, ±φ).
  const double phi = (1 + std::sqrt(5.0)) / 2;
  std::vector<vec3<double>> corners;
  for (const double a : {-1.0, 1.0}) {
    for (const double b : {-phi, phi}) {
      corners.push_back({0, a, b});
      corners.push_back({a, b, 0});
      corners.push_back({b, 0, a});
    }
  }
  // Its 20 faces: the triples of corners at mutual distance 2.
  std::vector<std::uint32_t> triangles;
  for (std::uint32_t i = 0; i < 12; ++i)
    for (std::uint32_t j = i + 1; j < 12; ++j)
      for (std::uint32_t k = j + 1; k < 12; ++k)
        if (std::abs(distance(corners[i], corners[j]) - 2) < 1e-9 && std::abs(distance(corners[j], corners[k]) - 2) < 1e-9 &&
            std::abs(distance(corners[i], corners[k]) - 2) < 1e-9)
          triangles.insert(triangles.end(), {i, j, k});
  REQUIRE(triangles.size() == 60);
  // Three times: split each triangle in four at its edge midpoints, found
  // again by position so that neighbours share them.
  for (int level = 0; level < 3; ++level) {
    std::vector<std::uint32_t> finer;
    const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const vec3<double> m = (corners[a] + corners[b]) * 0.5;
      for (std::uint32_t i = 0; i < corners.size(); ++i)
        if (corners[i] == m) return i;
      corners.push_back(m);
      return static_cast<std::uint32_t>(corners.size() - 1);
    };
    for (std::size_t t = 0; t < triangles.size(); t += 3) {
      const std::uint32_t a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
      const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      finer.insert(finer.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
    }
    triangles = finer;
  }
  std::vector<vec3<T>> points;
  for (const vec3<double>& c : corners) {
    const vec3<double> u = normalize(c);
    points.push_back(v3<T>(u.x, u.y, u.z));
  }
  REQUIRE(points.size() == 642);
  const convex_hull<T> hull = build(points);
  check_hull(hull, points);
  CHECK(hull.vertex_count() == 642);
  CHECK(hull.face_count() == 1280);
  CHECK(hull.edges().size() == 1920);
}

TEST_CASE_TEMPLATE("a cloud far from the origin has the hull of the same cloud at the origin", T, float, double) {
  // The same points (the offset subtracts exactly: both are within a factor
  // two of each other) give the same hull moved by the offset: the hull is
  // built relative to the center of the points, not the origin.
  const double offset = 1e4;
  lcg random;
  std::vector<vec3<T>> far, near;
  for (int i = 0; i < 500; ++i) {
    const vec3<T> p = v3<T>(offset + random.uniform(), offset + random.uniform(), offset + random.uniform());
    far.push_back(p);
    near.push_back(p - vec3<T>::splat(static_cast<T>(offset)));
  }
  const convex_hull<T> far_hull = build(far), near_hull = build(near);
  check_hull(far_hull, far);
  check_hull(near_hull, near);
  REQUIRE(far_hull.vertex_count() == near_hull.vertex_count());
  REQUIRE(far_hull.face_count() == near_hull.face_count());
  CHECK(double(far_hull.tolerance()) == doctest::Approx(double(near_hull.tolerance())));
  for (std::size_t i = 0; i < far_hull.vertex_count(); ++i)
    CHECK(far_hull.vertices()[i] - vec3<T>::splat(static_cast<T>(offset)) == near_hull.vertices()[i]);
  for (std::size_t f = 0; f < far_hull.face_count(); ++f) {
    const std::span<const std::uint32_t> a = far_hull.face(f), b = near_hull.face(f);
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) CHECK(a[i] == b[i]);
    CHECK(far_hull.plane(f).normal == near_hull.plane(f).normal);
  }
}

TEST_CASE_TEMPLATE("points that do not enclose a volume are a degenerate shape", T, float, double) {
  lcg random;
  std::vector<vec3<T>> points;
  CHECK(error_of(points) == error_code::degenerate_shape);
  points.push_back(v3<T>(1, 2, 3));
  CHECK(error_of(points) == error_code::degenerate_shape);
  points.push_back(v3<T>(2, 2, 3));
  points.push_back(v3<T>(1, 5, 3));
  CHECK(error_of(points) == error_code::degenerate_shape);  // three points, a triangle
  points.push_back(v3<T>(7, -1, 3));
  CHECK(error_of(points) == error_code::degenerate_shape);  // four points in the plane z = 3

  const std::vector<vec3<T>> same(1000, v3<T>(0.1, -0.2, 0.3));
  CHECK(error_of(same) == error_code::degenerate_shape);

  std::vector<vec3<T>> line;
  const vec3<double> origin{1, 2, -1}, direction{0.3, -0.4, 0.5};
  for (int i = 0; i < 100; ++i) {
    const vec3<double> p = origin + direction * random.in<double>(-10, 10);
    line.push_back(v3<T>(p.x, p.y, p.z));
  }
  CHECK(error_of(line) == error_code::degenerate_shape);

  // A square grid in a tilted plane: coplanar up to the rounding of T.
  std::vector<vec3<T>> grid;
  const vec3<double> u{0.3, 0.2, 0.7}, v{0.1, -0.5, 0.2};
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) {
      const vec3<double> p = origin + u * double(i) + v * double(j);
      grid.push_back(v3<T>(p.x, p.y, p.z));
    }
  CHECK(error_of(grid) == error_code::degenerate_shape);

  // One point off the plane by more than the tolerance makes it a solid.
  grid.push_back(v3<T>(origin.x, origin.y, origin.z) + v3<T>(0, 0, 0.01) + v3<T>(u.x, u.y, u.z) * T(2));
  CHECK(error_of(grid) == error_code::none);
}

TEST_CASE_TEMPLATE("a point with a NaN or infinite coordinate is reported with its index", T, float, double) {
  std::vector<vec3<T>> points{v3<T>(0, 0, 0), v3<T>(1, 0, 0), v3<T>(0, 1, 0), v3<T>(0, 0, 1), v3<T>(1, 1, 1)};
  std::uint32_t object = 0;
  points[3].y = std::numeric_limits<T>::quiet_NaN();
  CHECK(error_of(points, &object) == error_code::non_finite);
  CHECK(object == 3);
  points[3].y = 0;
  points[4].z = -std::numeric_limits<T>::infinity();
  CHECK(error_of(points, &object) == error_code::non_finite);
  CHECK(object == 4);
  // Reported before the count: two points, one of them NaN.
  const std::vector<vec3<T>> two{v3<T>(0, 0, 0), v3<T>(std::numeric_limits<T>::quiet_NaN(), 0, 0)};
  CHECK(error_of(two) == error_code::non_finite);
}

TEST_CASE_TEMPLATE("support returns the vertex farthest along any direction", T, float, double) {
  lcg random;
  std::vector<vec3<T>> points;
  for (int i = 0; i < 500; ++i) points.push_back(random.vector<T>(-2, 3));
  const convex_hull<T> hull = build(points);
  const std::span<const vec3<T>> vertices = hull.vertices();
  for (int k = 0; k < 200; ++k) {
    const vec3<T> d = random.unit_vector<T>() * random.in<T>(0.1, 10);
    T best = dot(vertices[0], d);
    for (const vec3<T>& v : vertices) best = dot(v, d) > best ? dot(v, d) : best;
    const vec3<T> s = hull.support(d);
    CHECK(dot(s, d) == best);
    CHECK(s == vertices[hull.support_index(d)]);
    // No input point is farther out than the support, beyond the tolerance.
    T farthest = best;
    for (const vec3<T>& p : points) farthest = dot(p, d) > farthest ? dot(p, d) : farthest;
    CHECK(double(farthest - best) <= double(hull.tolerance()) * double(length(d)) * outside_slack);
  }
  // A box's support is the corner on the side of every component.
  const std::vector<vec3<T>> corners = box_corners<T>({0, 0, 0}, {1, 2, 3});
  const convex_hull<T> box = build(corners);
  CHECK(box.support(v3<T>(1, -1, 1)) == v3<T>(1, -2, 3));
  CHECK(box.support(v3<T>(-0.1, 0.2, -5)) == v3<T>(-1, 2, -3));
}

TEST_CASE_TEMPLATE("the bounding boxes hold the hull in shape space and in the world", T, float, double) {
  lcg random;
  std::vector<vec3<T>> points;
  for (int i = 0; i < 300; ++i) points.push_back(random.vector<T>(-1, 2));
  const convex_hull<T> hull = build(points);
  aabb<T> tight{hull.vertices()[0], hull.vertices()[0]};
  for (const vec3<T>& v : hull.vertices()) tight = merge(tight, v);
  CHECK(hull.local_aabb() == tight);
  // The extreme points along the axes are vertices: the box is the cloud's.
  aabb<T> cloud{points[0], points[0]};
  for (const vec3<T>& p : points) cloud = merge(cloud, p);
  CHECK(hull.local_aabb() == cloud);
  for (int k = 0; k < 50; ++k) {
    const transform<T> pose{random.vector<T>(-10, 10), random.rotation<T>()};
    const aabb<T> world = hull.world_aabb(pose);
    // A rotated point lands within rotation rounding of the exact box.
    const aabb<T> loose = expand(world, T(16) * epsilon<T> * T(20));
    for (const vec3<T>& v : hull.vertices()) CHECK(contains(loose, apply(pose, v)));
  }
}

}  // namespace shapes_convex_hull_tests
