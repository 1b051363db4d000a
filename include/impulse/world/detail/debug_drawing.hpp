// impulse/world/detail/debug_drawing.hpp — a world drawn through a debug_drawer
// (debug_draw.hpp): bodies' boxes, contact points, normals, forces and
// velocities, as world::draw's flags ask.
#pragma once

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
/// sleeping dynamic ones.
template <scalar_type T>
[[nodiscard]] debug_color color_of(const body_record<T>& r) noexcept {
  if (r.body.type == body_type::static_body) return {0.5f, 0.5f, 0.5f};
  if (r.body.type == body_type::kinematic) return {0.5f, 0.5f, 1};
  return r.awake ? debug_color{0.3f, 1, 0.3f} : debug_color{0.2f, 0.4f, 0.2f};
}

template <class Config, class D>
void draw_world(const world_state<Config>& state, D& d, const debug_draw_flags& flags) {
  using T = typename Config::scalar;
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
