// impulse/world/world_queries.hpp — world<Config>'s queries, defined outside
// the class (world.hpp says why they are not inline): ray casts, box
// overlaps, interpolated poses, and the energies and momenta tests and
// diagnostics check conservation with.
//
// A world without collision keeps no broad phase: its ray casts and
// overlaps test every body, in storage order.
#pragma once

#include <optional>

#include "world.hpp"

namespace impulse {

template <class Config>
auto world<Config>::interpolated_pose(body_id id, T alpha) const -> transform<T> {
  require(id, "world::interpolated_pose: no such body");
  if (!(alpha >= T(0) && alpha <= T(1)))
    detail::report_error(error_code::invalid_parameter, "world::interpolated_pose: alpha must be within [0, 1]",
                         id.index);
  const body_record& r = state_.bodies[id];
  const transform<T> now = r.body.pose();
  quat<T> q1 = now.rotation;
  if (dot(r.previous.rotation, q1) < T(0)) q1 = q1 * T(-1);  // the short way round
  const transform<T> center{lerp(r.previous.position, now.position, alpha),
                            normalize(r.previous.rotation * (T(1) - alpha) + q1 * alpha)};
  return {center.position - rotate(center.rotation, r.center), center.rotation};
}

template <class Config>
auto world<Config>::ray_cast(const ray<T>& r, T max_fraction, const query_filter& filter) const
    -> std::optional<world_ray_hit<T>> {
  std::optional<world_ray_hit<T>> best;
  T reach = max_fraction;
  const auto test = [&](body_id id) {
    const std::optional<world_ray_hit<T>> hit = ray_hit_of(id, r, reach, filter);
    if (hit) reach = hit->fraction, best = hit;
    return reach;
  };
  if constexpr (collision) {
    state_.broad.ray_cast(r, max_fraction,
                          [&](proxy_id proxy, T) { return test(state_.unpack(state_.broad.user_data(proxy))); });
  } else {
    for (const body_id id : state_.bodies.ids()) test(id);
  }
  return best;
}

template <class Config>
template <class F>
void world<Config>::overlap(const aabb<T>& box, F&& f, const query_filter& filter) const {
  if (!is_finite(box.lower) || !is_finite(box.upper) || !is_valid(box))
    detail::report_error(error_code::invalid_parameter, "world::overlap: the box is not finite and ordered");
  const in_callback scope(*this);
  if constexpr (collision) {
    state_.broad.query(box, [&](proxy_id proxy) {
      const body_id id = state_.unpack(state_.broad.user_data(proxy));
      const body_record& rec = state_.bodies[id];
      if (filter.sees(rec.filter, rec.sensor) && overlaps(state_.bounds_of(rec), box)) f(id);
    });
  } else {
    for (const body_id id : state_.bodies.ids()) {
      const body_record& rec = state_.bodies[id];
      if (filter.sees(rec.filter, rec.sensor) && overlaps(state_.bounds_of(rec), box)) f(id);
    }
  }
}

template <class Config>
auto world<Config>::ray_hit_of(body_id id, const ray<T>& r, T reach, const query_filter& filter) const
    -> std::optional<world_ray_hit<T>> {
  const body_record& rec = state_.bodies[id];
  if (!filter.sees(rec.filter, rec.sensor)) return std::nullopt;
  const transform<T> pose = detail::shape_pose_of(rec);
  const narrowphase::ray_hit<T> hit =
      state_.shape_store.visit(rec.shape, [&](const auto& s) { return narrowphase::ray_cast(r, s, pose, reach); });
  if (!hit.hit || hit.fraction > reach) return std::nullopt;
  return world_ray_hit<T>{id, hit.fraction, hit.point, hit.normal};
}

template <class Config>
template <class F>
void world<Config>::ray_cast_all(const ray<T>& r, F&& f, const query_filter& filter) const {
  if (!is_finite(r.origin) || !is_finite(r.translation))
    detail::report_error(error_code::non_finite, "world::ray_cast_all: the ray is not finite");
  const in_callback scope(*this);
  T reach = T(1);
  const auto test = [&](body_id id) {
    const std::optional<world_ray_hit<T>> hit = ray_hit_of(id, r, reach, filter);
    if (hit) {
      const T wanted = T(f(*hit));
      reach = wanted > T(0) ? std::min(wanted, reach) : T(0);  // NaN stops, as 0 does
    }
    return reach;
  };
  if constexpr (collision) {
    state_.broad.ray_cast(r, T(1),
                          [&](proxy_id proxy, T) { return test(state_.unpack(state_.broad.user_data(proxy))); });
  } else {
    for (const body_id id : state_.bodies.ids())
      if (test(id) <= T(0)) break;
  }
}

template <class Config>
template <class Shape>
auto world<Config>::shape_cast(const Shape& shape, const transform<T>& pose, const vec3<T>& translation,
                               const query_filter& filter) const -> std::optional<world_ray_hit<T>> {
  static_assert(detail::convex_shape<Shape, T>,
                "world::shape_cast: the cast shape must be convex (a sphere, capsule, box or hull)");
  if constexpr (requires { shape.validate(); }) shape.validate();
  if (!is_finite(pose.position) || !is_finite(pose.rotation) || !is_finite(translation))
    detail::report_error(error_code::non_finite, "world::shape_cast: the pose or translation is not finite");
  if (!is_normalized(pose.rotation))
    detail::report_error(error_code::not_normalized, "world::shape_cast: the rotation is not a unit quaternion");
  std::optional<world_ray_hit<T>> best;
  T reach = T(1);
  const auto test = [&](body_id id) {
    const body_record& rec = state_.bodies[id];
    if (!filter.sees(rec.filter, rec.sensor)) return;
    const transform<T> at = detail::shape_pose_of(rec);
    const std::optional<detail::cast_contact<T>> hit = state_.shape_store.visit(rec.shape, [&](const auto& target) {
      return detail::cast_shape(shape, pose, translation, target, at, reach);
    });
    if (hit && (!best || hit->fraction < reach)) {
      reach = hit->fraction;
      best = world_ray_hit<T>{id, hit->fraction, hit->point, hit->normal};
    }
  };
  const aabb<T> swept = merge(shape.world_aabb(pose), shape.world_aabb({pose.position + translation, pose.rotation}));
  if constexpr (collision) {
    state_.broad.query(swept, [&](proxy_id proxy) { test(state_.unpack(state_.broad.user_data(proxy))); });
  } else {
    for (const body_id id : state_.bodies.ids())
      if (overlaps(state_.bounds_of(state_.bodies[id]), swept)) test(id);
  }
  return best;
}

template <class Config>
template <class Shape, class F>
void world<Config>::shape_overlap(const Shape& shape, const transform<T>& pose, F&& f,
                                  const query_filter& filter) const {
  using dispatcher = typename state_type::dispatcher;
  if constexpr (requires { shape.validate(); }) shape.validate();
  if (!is_finite(pose.position) || !is_finite(pose.rotation))
    detail::report_error(error_code::non_finite, "world::shape_overlap: the pose is not finite");
  if (!is_normalized(pose.rotation))
    detail::report_error(error_code::not_normalized, "world::shape_overlap: the rotation is not a unit quaternion");
  const in_callback scope(*this);
  const typename dispatcher::shape_ref probe = dispatcher::ref(shape);
  const auto test = [&](body_id id) {
    const body_record& rec = state_.bodies[id];
    if (filter.sees(rec.filter, rec.sensor) &&
        detail::shapes_overlap<dispatcher>(probe, pose, state_.shape_ref_of(rec), detail::shape_pose_of(rec)))
      f(id);
  };
  const aabb<T> box = shape.world_aabb(pose);
  if constexpr (collision) {
    state_.broad.query(box, [&](proxy_id proxy) { test(state_.unpack(state_.broad.user_data(proxy))); });
  } else {
    for (const body_id id : state_.bodies.ids())
      if (overlaps(state_.bounds_of(state_.bodies[id]), box)) test(id);
  }
}

template <class Config>
auto world<Config>::potential_energy() const -> T {
  T e = T(0);
  for (const body_record& r : state_.bodies.values())
    if (r.body.type == body_type::dynamic) e -= r.body.mass * dot(state_.settings.gravity, r.body.position);
  for (const detail::spring_record<T>& record : state_.springs.values()) {
    const body_spring<T>& s = record.def;
    const rigid_body<T>& a = state_.bodies[s.body_a].body;
    const vec3<T> pa = a.position + rotate(a.orientation, s.point_a);
    vec3<T> pb = s.point_b;
    if (!s.body_b.is_none()) {
      const rigid_body<T>& b = state_.bodies[s.body_b].body;
      pb = b.position + rotate(b.orientation, s.point_b);
    }
    e += spring_energy(s, pa, pb);
  }
  return e;
}

template <class Config>
auto world<Config>::linear_momentum() const noexcept -> vec3<T> {
  vec3<T> p{};
  for (const body_record& r : state_.bodies.values())
    if (r.body.type == body_type::dynamic) p += r.body.linear_momentum;
  return p;
}

template <class Config>
auto world<Config>::angular_momentum() const noexcept -> vec3<T> {
  vec3<T> l{};
  for (const body_record& r : state_.bodies.values())
    if (r.body.type == body_type::dynamic) l += cross(r.body.position, r.body.linear_momentum) + r.body.angular_momentum;
  return l;
}

}  // namespace impulse
