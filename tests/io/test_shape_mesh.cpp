// Shapes as triangles (io/shape_mesh.hpp): every closed mesh encloses its
// shape's volume with its triangles facing out, which the divergence
// theorem checks at once: V = Σ a·(b × c) / 6 over the triangles is the
// volume when they are all counter-clockwise seen from outside, and
// anything missing, doubled or turned inward shows. A compound's mesh is
// its children's, each placed by its pose.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "impulse/io/shape_mesh.hpp"
#include "impulse/shapes/compound.hpp"

namespace io_shape_mesh_tests {

using namespace impulse;

namespace {

double enclosed_volume(const io::shape_mesh& m) {
  double v = 0;
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    const vec3<float>& a = m.positions[m.indices[i]];
    const vec3<float>& b = m.positions[m.indices[i + 1]];
    const vec3<float>& c = m.positions[m.indices[i + 2]];
    v += double(dot(a, cross(b, c))) / 6;
  }
  return v;
}

/// Every vertex normal is unit, and every triangle's own normal agrees
/// with its vertices' (no triangle wound against its normals).
void check_normals(const io::shape_mesh& m) {
  REQUIRE(m.normals.size() == m.positions.size());
  REQUIRE(m.indices.size() % 3 == 0);
  for (const vec3<float>& n : m.normals) CHECK(std::abs(length(n) - 1) < 1e-5f);
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    const vec3<float>& a = m.positions[m.indices[i]];
    const vec3<float> face = cross(m.positions[m.indices[i + 1]] - a, m.positions[m.indices[i + 2]] - a);
    if (length(face) < 1e-9f) continue;  // the slivers at a pole
    for (int k = 0; k < 3; ++k) CHECK(dot(face, m.normals[m.indices[i + std::size_t(k)]]) > 0);
  }
}

}  // namespace

TEST_CASE("a box's mesh encloses its volume exactly with its faces outward") {
  const io::shape_mesh m = io::mesh_of(box<float>::make({0.5f, 1, 2}));
  CHECK(m.indices.size() == 36);
  CHECK(enclosed_volume(m) == doctest::Approx(8 * 0.5 * 1 * 2).epsilon(1e-6));
  check_normals(m);
}

TEST_CASE("a ball's and a capsule's meshes enclose their volumes to the inscribed polyhedron's shortfall") {
  // 24 segments around: the inscribed polyhedron holds about 2 % less than
  // the ball (a 24-gon's area is 0.989 of its circle's, twice over).
  const double pi = std::numbers::pi;
  const io::shape_mesh ball = io::mesh_of(sphere<float>::make(0.5f));
  const double ball_volume = 4.0 / 3 * pi * 0.125;
  CHECK(enclosed_volume(ball) < ball_volume);
  CHECK(enclosed_volume(ball) > 0.97 * ball_volume);
  check_normals(ball);
  const io::shape_mesh pill = io::mesh_of(capsule<float>::make(0.25f, 0.5f));
  const double pill_volume = 4.0 / 3 * pi * 0.25 * 0.25 * 0.25 + pi * 0.25 * 0.25 * 1.0;
  CHECK(enclosed_volume(pill) < pill_volume);
  CHECK(enclosed_volume(pill) > 0.97 * pill_volume);
  check_normals(pill);
}

TEST_CASE("a hull's mesh encloses the hull's volume exactly") {
  // A unit cube with one corner cut off: 1 − 1/48 m³.
  const std::vector<vec3<float>> points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0},
                                        {1, 0, 1}, {0, 1, 1}, {1, 1, 0.5f}, {1, 0.5f, 1}, {0.5f, 1, 1}};
  const io::shape_mesh m = io::mesh_of(convex_hull<float>::from_points(points));
  CHECK(enclosed_volume(m) == doctest::Approx(1 - 1.0 / 48).epsilon(1e-5));
  check_normals(m);
}

TEST_CASE("a plane's mesh is a square on the plane facing along its normal") {
  const io::shape_mesh m = io::mesh_of(plane<float>::make(normalize(vec3<float>{0, 1, 1}), -2));
  REQUIRE(m.positions.size() == 4);
  const vec3<float> n = normalize(vec3<float>{0, 1, 1});
  for (const vec3<float>& p : m.positions) CHECK(dot(n, p) == doctest::Approx(2.0f).epsilon(1e-5));
  check_normals(m);
  CHECK(length(cross(m.positions[1] - m.positions[0], m.positions[2] - m.positions[0])) ==
        doctest::Approx(2 * io::plane_half_size * 2 * io::plane_half_size).epsilon(1e-5));
}

TEST_CASE("a triangle mesh's mesh is its own triangles") {
  const vec3<float> corners[] = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
  const std::uint32_t triangles[] = {0, 2, 1, 0, 3, 2};
  const io::shape_mesh m = io::mesh_of(triangle_mesh<float>::make(corners, triangles));
  CHECK(m.indices.size() == 6);
  for (const vec3<float>& n : m.normals) CHECK(n.y == doctest::Approx(1.0f));
  check_normals(m);
}

TEST_CASE("a compound's mesh is its children's meshes placed by their poses and fills the compound's box") {
  // A box, a ball, a turned capsule and a hull, at poses of their own: the
  // mesh holds each child's vertices and triangles once, its triangles index
  // within it, and its vertices reach the compound's box exactly (each
  // child's mesh reaches its own box: a box's and a hull's corners, a
  // ball's poles and equator, a capsule's caps turned a quarter about z).
  const std::vector<vec3<float>> points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  const box<float> brick = box<float>::make({0.5f, 0.25f, 1});
  const sphere<float> ball = sphere<float>::make(0.4f);
  const capsule<float> pill = capsule<float>::make(0.2f, 0.6f);
  const convex_hull<float> wedge = convex_hull<float>::from_points(points);
  const quat<float> quarter = quat<float>::from_axis_angle({0, 0, 1}, std::numbers::pi_v<float> / 2);
  compound<float>::builder b;
  b.add(brick, {{-1, 0, 0}, quat<float>::identity()});
  b.add(ball, {{2, 1, 0}, quat<float>::identity()}, 3);
  b.add(pill, {{0, -1.5f, 0.5f}, quarter});
  b.add(wedge, {{0.5f, 2, -2}, quarter});
  const compound<float> c = b.build();
  const io::shape_mesh m = io::mesh_of(c);
  const io::shape_mesh parts[] = {io::mesh_of(brick), io::mesh_of(ball), io::mesh_of(pill), io::mesh_of(wedge)};
  std::size_t vertices = 0, indices = 0;
  for (const io::shape_mesh& part : parts) vertices += part.positions.size(), indices += part.indices.size();
  CHECK(m.positions.size() == vertices);
  CHECK(m.indices.size() == indices);
  for (const std::uint32_t k : m.indices) CHECK(k < m.positions.size());
  // Each child's triangles, in order, are its own mesh's moved by its pose.
  std::size_t first_vertex = 0, first_index = 0;
  for (std::size_t i = 0; i < c.child_count(); ++i) {
    const transform<float>& pose = c.child_at(i).pose;
    const io::shape_mesh& part = parts[i];
    for (std::size_t k = 0; k < part.indices.size(); ++k) {
      CHECK(m.indices[first_index + k] == first_vertex + part.indices[k]);
      const vec3<float> expected = apply(pose, part.positions[part.indices[k]]);
      CHECK(length(m.positions[m.indices[first_index + k]] - expected) < 1e-5f);
    }
    first_vertex += part.positions.size();
    first_index += part.indices.size();
  }
  aabb<float> reach = aabb<float>::empty();
  for (const vec3<float>& p : m.positions) reach = merge(reach, p);
  const aabb<float> expected = c.local_aabb();
  for (int axis = 0; axis < 3; ++axis) {
    CHECK(std::abs(reach.lower[axis] - expected.lower[axis]) < 1e-5f);
    CHECK(std::abs(reach.upper[axis] - expected.upper[axis]) < 1e-5f);
  }
  // Every child is closed and outward, so the whole encloses the sum of theirs.
  double volume = 0;
  for (const io::shape_mesh& part : parts) volume += enclosed_volume(part);
  CHECK(enclosed_volume(m) == doctest::Approx(volume).epsilon(1e-5));
  check_normals(m);
}

}  // namespace io_shape_mesh_tests
