// impulse/world/detail/debug_drawing.hpp — a world drawn through a debug_drawer
// (debug_draw.hpp): shapes as wireframes, joints, bodies' boxes, contact
// points, normals, forces and velocities, as world::draw's flags ask.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>

#include "../../shapes/box.hpp"
#include "../../shapes/capsule.hpp"
#include "../../shapes/compound.hpp"
#include "../../shapes/convex_hull.hpp"
#include "../../shapes/plane.hpp"
#include "../../shapes/sphere.hpp"
#include "../../shapes/heightfield.hpp"
#include "../../shapes/triangle_mesh.hpp"
#include "../debug_draw.hpp"
#include "world_state.hpp"

namespace impulse::detail {

template <scalar_type T, class D>
void draw_box(D& d, const aabb<T>& box, const debug_color& color) {
  const vec3<T>& l = box.lower;
  const vec3<T>& u = box.upper;
  const vec3<T> c[8] = {{l.x, l.y, l.z}, {u.x, l.y, l.z}, {u.x, u.y, l.z}, {l.x, u.y, l.z},
                        {l.x, l.y, u.z}, {u.x, l.y, u.z}, {u.x, u.y, u.z}, {l.x, u.y, u.z}};
  for (int i = 0; i < 4; ++i) {
    d.line(c[i], c[(i + 1) % 4], color);
    d.line(c[i + 4], c[(i + 1) % 4 + 4], color);
    d.line(c[i], c[i + 4], color);
  }
}

/// Grey static bodies, blue kinematic ones, green awake and dark green
/// sleeping dynamic ones; sensors yellow.
template <scalar_type T>
[[nodiscard]] debug_color color_of(const body_record<T>& r) noexcept {
  if (r.sensor) return {1, 0.9f, 0.2f};
  if (r.body.type == body_type::static_body) return {0.5f, 0.5f, 0.5f};
  if (r.body.type == body_type::kinematic) return {0.5f, 0.5f, 1};
  return r.awake ? debug_color{0.3f, 1, 0.3f} : debug_color{0.2f, 0.4f, 0.2f};
}

/// Segments a circle is drawn with.
inline constexpr int circle_segments = 16;

/// An arc about `center` from `from` (a radius vector) turning about the
/// unit `axis` by `angle`, in circle_segments·angle/2π segments (at least 1).
template <scalar_type T, class D>
void draw_arc(D& d, const vec3<T>& center, const vec3<T>& axis, const vec3<T>& from, T angle,
              const debug_color& color) {
  const int n = std::max(1, int(std::ceil(std::abs(angle) / (T(2) * std::numbers::pi_v<T>) * T(circle_segments))));
  vec3<T> last = center + from;
  for (int k = 1; k <= n; ++k) {
    const vec3<T> next = center + rotate(quat<T>::from_axis_angle(axis, angle * T(k) / T(n)), from);
    d.line(last, next, color);
    last = next;
  }
}

template <scalar_type T, class D>
void draw_shape(D& d, const sphere<T>& s, const transform<T>& pose, const debug_color& color) {
  const vec3<T> c = pose.position;
  for (const vec3<T>& axis : {vec3<T>{1, 0, 0}, vec3<T>{0, 1, 0}, vec3<T>{0, 0, 1}}) {
    const vec3<T> a = rotate(pose.rotation, axis);
    const vec3<T> across = rotate(pose.rotation, vec3<T>{axis.z, axis.x, axis.y}) * s.radius;
    draw_arc(d, c, a, across, T(2) * std::numbers::pi_v<T>, color);
  }
}

template <scalar_type T, class D>
void draw_shape(D& d, const box<T>& b, const transform<T>& pose, const debug_color& color) {
  const vec3<T>& h = b.half_extents;
  vec3<T> c[8];
  for (int i = 0; i < 8; ++i)
    c[i] = apply(pose, vec3<T>{(i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z});
  for (int i = 0; i < 8; ++i)
    for (const int bit : {1, 2, 4})
      if ((i & bit) == 0) d.line(c[i], c[i | bit], color);
}

template <scalar_type T, class D>
void draw_shape(D& d, const capsule<T>& s, const transform<T>& pose, const debug_color& color) {
  const vec3<T> axis = rotate(pose.rotation, vec3<T>{0, 1, 0});
  const vec3<T> x = rotate(pose.rotation, vec3<T>{s.radius, 0, 0}), z = rotate(pose.rotation, vec3<T>{0, 0, s.radius});
  const vec3<T> top = pose.position + axis * s.half_height, bottom = pose.position - axis * s.half_height;
  const T pi = std::numbers::pi_v<T>;
  for (const vec3<T>& end : {top, bottom}) draw_arc(d, end, axis, x, T(2) * pi, color);
  for (const vec3<T>& side : {x, z, x * T(-1), z * T(-1)}) d.line(bottom + side, top + side, color);
  // Each cap's two half circles over its end, across x and across z.
  const vec3<T> ax = normalize(cross(x, axis)), az = normalize(cross(z, axis));
  draw_arc(d, top, ax, x, pi, color);
  draw_arc(d, top, az, z, pi, color);
  draw_arc(d, bottom, ax, x, -pi, color);
  draw_arc(d, bottom, az, z, -pi, color);
}

template <scalar_type T, class D>
void draw_shape(D& d, const convex_hull<T>& h, const transform<T>& pose, const debug_color& color) {
  const std::span<const vec3<T>> v = h.vertices();
  for (const hull_edge& e : h.edges()) d.line(apply(pose, v[e.a]), apply(pose, v[e.b]), color);
}

/// A mesh's triangles; a heightfield's, less its holes.
template <scalar_type T, class Mesh, class D>
  requires std::same_as<Mesh, triangle_mesh<T>> || std::same_as<Mesh, heightfield<T>>
void draw_shape(D& d, const Mesh& m, const transform<T>& pose, const debug_color& color) {
  m.for_each_overlapping(m.local_aabb(), [&](std::size_t t) {
    vec3<T> a, b, c;
    m.triangle(t, a, b, c);
    a = apply(pose, a), b = apply(pose, b), c = apply(pose, c);
    d.line(a, b, color);
    d.line(b, c, color);
    d.line(c, a, color);
  });
}

/// A plane: a square 10 m across about the point nearest the origin, and
/// its normal.
template <scalar_type T, class D>
void draw_shape(D& d, const plane<T>& p, const transform<T>& pose, const debug_color& color) {
  const vec3<T> n = rotate(pose.rotation, p.normal);
  const vec3<T> o = apply(pose, p.normal * -p.offset);
  const vec3<T> helper = std::abs(n.x) < T(0.9) ? vec3<T>{1, 0, 0} : vec3<T>{0, 1, 0};
  const vec3<T> u = normalize(cross(n, helper)) * T(5), w = cross(n, u);
  const vec3<T> c[4] = {o + u + w, o - u + w, o - u - w, o + u - w};
  for (int i = 0; i < 4; ++i) d.line(c[i], c[(i + 1) % 4], color);
  d.arrow(o, o + n, color);
}

/// Each child of a compound, where the body holds it.
template <scalar_type T, class D>
void draw_shape(D& d, const compound<T>& c, const transform<T>& pose, const debug_color& color) {
  for (std::size_t i = 0; i < c.child_count(); ++i)
    c.visit(i, [&](const auto& child, const transform<T>& local) { draw_shape(d, child, pose * local, color); });
}

/// A joint's anchors, its bodies' lever lines, its axis and its limits.
template <scalar_type T, class D>
void draw_joint(D& d, const joint_record<T>& j, const rigid_body<T>& a, const rigid_body<T>& b) {
  const debug_color lever{0.8f, 0.8f, 0.8f}, anchor{1, 0.4f, 1}, axis_color{0.3f, 0.9f, 1}, limit{1, 0.3f, 0.3f};
  const joint_constraint<T>& c = j.constraint;
  const vec3<T> pa = a.position + rotate(a.orientation, c.local_anchor_a);
  const vec3<T> pb = b.position + rotate(b.orientation, c.local_anchor_b);
  d.line(a.position, pa, lever);
  d.line(b.position, pb, lever);
  d.point(pa, anchor);
  d.point(pb, anchor);
  if (j.def.type == joint_type::distance) d.line(pa, pb, anchor);
  if (j.def.type != joint_type::hinge && j.def.type != joint_type::slider) return;
  const vec3<T> axis = rotate(a.orientation, c.local_axis_a);
  d.arrow(pa, pa + axis * T(0.3), axis_color);
  if (!j.def.enable_limit) return;
  if (j.def.type == joint_type::slider) {
    d.line(pa + axis * j.def.lower, pa + axis * j.def.upper, limit);
    return;
  }
  // A hinge's limits: the arc its angle may sweep, 0.2 m out, from the
  // direction B's anchor had from the axis at creation (or any across it).
  const vec3<T> helper = std::abs(axis.x) < T(0.9) ? vec3<T>{1, 0, 0} : vec3<T>{0, 1, 0};
  const vec3<T> across = normalize(cross(axis, helper)) * T(0.2);
  draw_arc(d, pa, axis, rotate(quat<T>::from_axis_angle(axis, j.def.lower), across), j.def.upper - j.def.lower, limit);
}

template <class Config, class D>
void draw_world(const world_state<Config>& state, D& d, const debug_draw_flags& flags) {
  using T = typename Config::scalar;
  if (flags.shapes)
    for (const body_record<T>& r : state.bodies.values()) {
      const transform<T> pose = shape_pose_of(r);
      const debug_color color = color_of(r);
      state.shape_store.visit(r.shape, [&](const auto& s) {
        if constexpr (requires { draw_shape(d, s, pose, color); }) draw_shape(d, s, pose, color);
      });
    }
  if (flags.joints)
    for (const joint_record<T>& j : state.joints.values())
      if (!j.broken) draw_joint(d, j, state.bodies[j.a].body, state.bodies[j.b].body);
  if (flags.aabbs)
    for (const body_record<T>& r : state.bodies.values()) draw_box(d, state.bounds_of(r), color_of(r));
  for (const contact_record<T>& c : state.contacts) {
    if (!c.touching) continue;
    for (int m = 0; m < c.manifold_count; ++m) {
      const contact_manifold<T>& manifold = state.slot_of(c, m).manifold;
      for (int i = 0; i < manifold.count; ++i) {
        const vec3<T>& p = manifold.points[std::size_t(i)].position;
        if (flags.contacts) d.point(p, debug_color{1, 0.2f, 0.2f});
        if (flags.normals) d.arrow(p, p + manifold.normal * T(0.2), debug_color{1, 1, 0.2f});
        if (flags.forces && state.last_dt > T(0)) {
          const T force = state.slot_of(c, m).impulse.normal[std::size_t(i)] / state.last_dt;
          d.arrow(p, p + manifold.normal * (force * T(0.01)), debug_color{1, 0.5f, 0});
        }
      }
    }
  }
  if (flags.velocities)
    for (const body_record<T>& r : state.bodies.values())
      if (r.body.type != body_type::static_body)
        d.arrow(r.body.position, r.body.position + r.body.linear_velocity() * T(0.1), debug_color{0.2f, 0.6f, 1});
}

}  // namespace impulse::detail
