// impulse/io/shape_mesh.hpp — each shape as triangles, for drawing and for
// export (gltf.hpp): positions and normals in the shape's own frame, three
// indices per triangle, counter-clockwise seen from outside.
//
// Balls and capsules are latitude–longitude meshes of `segments` around
// (24: a ball of radius 1 m is off by at most 0.9 cm between vertices);
// boxes and hulls have flat faces with their own vertices, so that each
// face is lit flat; a plane is a square `plane_half_size` (100 m) from the
// point of the plane nearest the shape's origin; a triangle mesh is its
// own triangles, flat; a compound is its children's meshes, each at its
// pose.
#pragma once

#include <cmath>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

#include "../math/vec3.hpp"
#include "../shapes/box.hpp"
#include "../shapes/capsule.hpp"
#include "../shapes/compound.hpp"
#include "../shapes/convex_hull.hpp"
#include "../shapes/plane.hpp"
#include "../shapes/sphere.hpp"
#include "../shapes/heightfield.hpp"
#include "../shapes/triangle_mesh.hpp"

namespace impulse::io {

struct shape_mesh {
  std::vector<vec3<float>> positions;  ///< m, the shape's frame
  std::vector<vec3<float>> normals;    ///< unit, per vertex
  std::vector<std::uint32_t> indices;  ///< three per triangle

  std::uint32_t add_vertex(const vec3<float>& p, const vec3<float>& n) {
    positions.push_back(p);
    normals.push_back(n);
    return std::uint32_t(positions.size() - 1);
  }
  void add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) { indices.insert(indices.end(), {a, b, c}); }
  /// A flat polygon, its corners counter-clockwise about n, as a fan.
  void add_polygon(const std::vector<vec3<float>>& corners, const vec3<float>& n) {
    const std::uint32_t first = std::uint32_t(positions.size());
    for (const vec3<float>& p : corners) add_vertex(p, n);
    for (std::uint32_t k = 2; k < corners.size(); ++k) add_triangle(first, first + k - 1, first + k);
  }
};

namespace detail {

template <scalar_type T>
vec3<float> to_float(const vec3<T>& v) noexcept {
  return {float(v.x), float(v.y), float(v.z)};
}

/// Rings of latitude from the top pole to the bottom one, each lifted by
/// `lift` along y while above the equator and lowered by it below (a
/// capsule's caps; 0 for a ball, whose equator is then a single ring).
inline shape_mesh rounded(float radius, float lift, int segments) {
  shape_mesh m;
  const int half = std::max(2, segments / 4);  // rings from pole to equator
  const int around = 4 * half;
  std::vector<std::pair<int, float>> rings;  // quarter-turns in half steps from the top, offset along y
  for (int i = 0; i <= half; ++i) rings.emplace_back(i, lift);
  for (int i = (lift > 0 ? half : half + 1); i <= 2 * half; ++i) rings.emplace_back(i, -lift);
  for (const auto& [i, offset] : rings) {
    // The poles and the equator exactly, so that a pole's vertices meet.
    const float theta = std::numbers::pi_v<float> / 2 * float(i) / float(half);
    const float across = i == 0 || i == 2 * half ? 0 : i == half ? 1 : std::sin(theta);
    const float up = i == 0 ? 1 : i == 2 * half ? -1 : i == half ? 0 : std::cos(theta);
    for (int j = 0; j <= around; ++j) {
      const float phi = 2 * std::numbers::pi_v<float> * float(j) / float(around);
      const vec3<float> n{across * std::cos(phi), up, across * std::sin(phi)};
      m.add_vertex(n * radius + vec3<float>{0, offset, 0}, n);
    }
  }
  const std::uint32_t row = std::uint32_t(around + 1);
  for (std::uint32_t i = 0; i + 1 < rings.size(); ++i)
    for (std::uint32_t j = 0; j < std::uint32_t(around); ++j) {
      const std::uint32_t a = i * row + j, b = a + 1, c = a + row, d = c + 1;
      m.add_triangle(a, b, c);
      m.add_triangle(b, d, c);
    }
  return m;
}

}  // namespace detail

template <scalar_type T>
shape_mesh mesh_of(const sphere<T>& s, int segments = 24) {
  return detail::rounded(float(s.radius), 0, segments);
}

template <scalar_type T>
shape_mesh mesh_of(const capsule<T>& c, int segments = 24) {
  return detail::rounded(float(c.radius), float(c.half_height), segments);
}

template <scalar_type T>
shape_mesh mesh_of(const box<T>& b, int = 0) {
  shape_mesh m;
  const vec3<float> h = detail::to_float(b.half_extents);
  for (int axis = 0; axis < 3; ++axis)
    for (const float sign : {1.0f, -1.0f}) {
      vec3<float> n{}, u{}, v{};
      n[axis] = sign;
      // u × v = n: the corners below run counter-clockwise about n.
      u[(axis + 1) % 3] = 1;
      v[(axis + 2) % 3] = sign;
      const vec3<float> center = n * h[axis];
      const vec3<float> du = u * h[(axis + 1) % 3], dv = v * h[(axis + 2) % 3];
      m.add_polygon({center - du - dv, center + du - dv, center + du + dv, center - du + dv}, n);
    }
  return m;
}

template <scalar_type T>
shape_mesh mesh_of(const convex_hull<T>& hull, int = 0) {
  shape_mesh m;
  std::vector<vec3<float>> corners;
  for (std::size_t f = 0; f < hull.face_count(); ++f) {
    corners.clear();
    for (const std::uint32_t k : hull.face(f)) corners.push_back(detail::to_float(hull.vertices()[k]));
    m.add_polygon(corners, detail::to_float(hull.plane(f).normal));
  }
  return m;
}

/// How far a plane's square reaches from its center, m.
inline constexpr float plane_half_size = 100;

template <scalar_type T>
shape_mesh mesh_of(const plane<T>& p, int = 0) {
  shape_mesh m;
  const vec3<float> n = detail::to_float(p.normal);
  const vec3<float> center = n * -float(p.offset);
  // Any two directions across n with u × v = n.
  const vec3<float> helper = std::abs(n.x) < 0.57f ? vec3<float>{1, 0, 0} : vec3<float>{0, 1, 0};
  const vec3<float> u = normalize(cross(helper, n)) * plane_half_size;
  const vec3<float> v = cross(n, u);
  m.add_polygon({center - u - v, center + u - v, center + u + v, center - u + v}, n);
  return m;
}

namespace detail {
/// A mesh's or a heightfield's triangles (a heightfield's holes have none).
template <scalar_type T, class Mesh>
shape_mesh triangles_of(const Mesh& mesh) {
  shape_mesh m;
  mesh.for_each_overlapping(mesh.local_aabb(), [&](std::size_t t) {
    vec3<T> a, b, c;
    mesh.triangle(t, a, b, c);
    const vec3<T> n = cross(b - a, c - a);
    const T area = length(n);
    m.add_polygon({to_float(a), to_float(b), to_float(c)},
                  area > T(0) ? to_float(n * (T(1) / area)) : vec3<float>{0, 1, 0});
  });
  return m;
}
}  // namespace detail

template <scalar_type T>
shape_mesh mesh_of(const triangle_mesh<T>& mesh, int = 0) {
  return detail::triangles_of<T>(mesh);
}
template <scalar_type T>
shape_mesh mesh_of(const heightfield<T>& field, int = 0) {
  return detail::triangles_of<T>(field);
}

/// The children's meshes, each moved to its pose in the compound's frame,
/// as one mesh: the vertices of each child after those of the children
/// before it, and its indices shifted by as many.
template <scalar_type T>
shape_mesh mesh_of(const compound<T>& c, int segments = 24) {
  shape_mesh m;
  for (std::size_t i = 0; i < c.child_count(); ++i)
    c.visit(i, [&](const auto& child, const transform<T>& pose) {
      const shape_mesh part = mesh_of(child, segments);
      const auto first = std::uint32_t(m.positions.size());
      // Moved in T, then rounded to float once.
      const auto widen = [](const vec3<float>& v) { return vec3<T>{T(v.x), T(v.y), T(v.z)}; };
      for (std::size_t k = 0; k < part.positions.size(); ++k)
        m.add_vertex(detail::to_float(apply(pose, widen(part.positions[k]))),
                     detail::to_float(rotate(pose.rotation, widen(part.normals[k]))));
      for (const std::uint32_t k : part.indices) m.indices.push_back(first + k);
    });
  return m;
}

}  // namespace impulse::io
