// impulse/world/world_bodies.hpp — world<Config>'s members that make,
// destroy and move bodies, defined outside the class (world.hpp says why
// they are not inline).
#pragma once

#include <algorithm>
#include <type_traits>
#include <vector>

#include "world.hpp"

namespace impulse {

template <class Config>
template <class Shape>
body_id world<Config>::create_body(const body_def<T>& def, const Shape& shape) {
  static_assert(detail::shape_store<shapes, T>::template index_of<Shape>() < shapes::size,
                "impulse world: this shape is not in the config's shape_list");
  refuse_in_callback("world::create_body: called from inside a world callback (for_each_contact, overlap, "
                     "visit_shape, draw); make the change after it returns");
  // Every shape is checked here; a hull or mesh only for being empty
  // (moved from), since their factories checked the rest.
  if constexpr (requires { shape.validate(); }) shape.validate();
  if constexpr (std::is_same_v<Shape, compound<T>>)
    if (!detail::world_state<Config>::dispatcher::holds_children_of(shape))
      detail::report_error(error_code::invalid_parameter, "world::create_body: the compound has a child whose shape "
                                                          "is not in the config's shape_list");
  def.material.validate();
  const rigid_body<T> body = detail::make_body(def, shape);  // checks the pose, the mass and the type
  const vec3<T> center = def.type == body_type::dynamic ? detail::center_of_mass(def, shape) : vec3<T>{};
  body_record record = prepare_body(def, body, center);  // checks the velocities
  if constexpr (!std::is_same_v<Shape, plane<T>>) {  // a plane is unbounded by nature
    const aabb<T> box = shape.world_aabb(def.pose);
    if (!state_.within_bounds(box.lower) || !state_.within_bounds(box.upper))
      detail::report_error(error_code::invalid_parameter,
                           "world::create_body: the shape reaches farther than max_coordinate from the origin");
  }
  // Nothing below can fail on the input.
  record.shape = state_.shape_store.add(shape);
  record.thinnest = detail::thinnest_half_extent<T>(shape);
  return insert_body(record);
}

template <class Config>
auto world<Config>::prepare_body(const body_def<T>& def, rigid_body<T> body, const vec3<T>& center) const
    -> body_record {
  if (def.type == body_type::dynamic) body.position = apply(def.pose, center);
  if (!is_finite(def.linear_velocity) || !is_finite(def.angular_velocity))
    detail::report_error(error_code::non_finite, "world::create_body: velocity is not finite");
  state_.require_speeds(def.linear_velocity, def.angular_velocity,
                 "world::create_body: faster than max_linear_speed or max_angular_speed");
  state_.require_within_bounds(body.position, "world::create_body: the body is farther than max_coordinate from the origin");
  if (def.type == body_type::static_body && (def.linear_velocity != vec3<T>{} || def.angular_velocity != vec3<T>{}))
    detail::report_error(error_code::invalid_parameter, "world::create_body: a static body cannot move");
  if (def.type != body_type::static_body) body.set_velocity(def.linear_velocity, def.angular_velocity);
  body_record record{};
  record.body = body;
  record.material = def.material;
  record.center = center;
  record.awake = def.awake || def.type != body_type::dynamic;
  record.user_data = def.user_data;
  record.filter = def.filter;
  if (def.sensor && !collision)
    detail::report_error(error_code::invalid_parameter, "world::create_body: a world without collision has no sensors");
  record.sensor = def.sensor;
  record.bullet = def.bullet;
  record.previous = body.pose();
  return record;
}

template <class Config>
body_id world<Config>::insert_body(const body_record& record) {
  const body_id id = state_.bodies.insert(record);
  body_record& r = state_.bodies[id];
  if constexpr (collision) r.proxy = state_.broad.create(state_.proxy_box(r), detail::pack(id));
  if (r.sensor) state_.sensors.push_back({id, {}});
  state_.awake_stale = true;
  if (r.body.type == body_type::dynamic && !r.awake) state_.ungrouped_sleepers = true;
  return id;
}

template <class Config>
void world<Config>::destroy_body(body_id id) {
  refuse_in_callback("world::destroy_body: called from inside a world callback (for_each_contact, overlap, "
                     "visit_shape, draw); make the change after it returns");
  require(id, "world::destroy_body: no such body (destroyed already?)");
  scratch_.doomed_joints.clear();
  for (std::size_t k = 0; k < state_.joints.size(); ++k) {
    const joint_record& j = state_.joints.values()[k];
    if (j.a == id || j.b == id) scratch_.doomed_joints.push_back(state_.joints.ids()[k]);
  }
  for (const joint_id j : scratch_.doomed_joints) destroy_joint(j);
  scratch_.doomed_springs.clear();
  for (std::size_t k = 0; k < state_.springs.size(); ++k) {
    const body_spring<T>& d = state_.springs.values()[k].def;
    if (d.body_a == id || d.body_b == id) scratch_.doomed_springs.push_back(state_.springs.ids()[k]);
  }
  for (const spring_id s : scratch_.doomed_springs) destroy_spring(s);
  std::erase_if(state_.contacts, [&](const contact_record& c) {
    if (c.a != id && c.b != id) return false;
    state_.end_contact(c);
    const body_id other = c.a == id ? c.b : c.a;
    state_.wake(state_.bodies[other]);
    return true;
  });
  end_sensor_overlaps(id);
  body_record& r = state_.bodies[id];
  if constexpr (collision) state_.broad.destroy(r.proxy);
  state_.shape_store.remove(r.shape);
  state_.bodies.erase(id);
  state_.awake_stale = true;  // the last body took its dense place
}

template <class Config>
void world<Config>::set_pose(body_id id, const transform<T>& pose) {
  refuse_in_callback("world::set_pose: called from inside a world callback (for_each_contact, overlap, "
                     "visit_shape, draw); make the change after it returns");
  require(id, "world::set_pose: no such body");
  body_record& r = state_.bodies[id];
  body_record moved = r;
  moved.body.set_pose({apply(pose, r.center), pose.rotation});  // refuses a bad pose
  moved.previous = moved.body.pose();
  const aabb<T> box = state_.proxy_box(moved);
  const bool plane_shape = r.shape.type == detail::shape_store<shapes, T>::template index_of<plane<T>>();
  if (!state_.within_bounds(moved.body.position) || (!plane_shape && (!state_.within_bounds(box.lower) || !state_.within_bounds(box.upper))))
    detail::report_error(error_code::invalid_parameter,
                         "world::set_pose: the body would reach farther than max_coordinate from the origin", id.index);
  r = moved;
  if constexpr (collision) state_.broad.move(r.proxy, box);
  state_.wake(r);
}

template <class Config>
void world<Config>::end_sensor_overlaps(body_id id) {
  std::erase_if(state_.sensors, [&](detail::sensor_record& s) {
    if (s.sensor == id) {
      for (const body_id inside : s.inside) state_.sensor_ended.push_back({id, inside});
      return true;
    }
    const auto at = std::ranges::find(s.inside, id);
    if (at != s.inside.end()) {
      s.inside.erase(at);
      state_.sensor_ended.push_back({s.sensor, id});
    }
    return false;
  });
}

template <class Config>
void world<Config>::set_filter(body_id id, const collision_filter& filter) {
  refuse_in_callback("world::set_filter: called from inside a world callback (for_each_contact, overlap, "
                     "visit_shape, draw); make the change after it returns");
  require(id, "world::set_filter: no such body");
  body_record& r = state_.bodies[id];
  r.filter = filter;
  state_.wake(r);
  end_filtered_contacts(id);
}

template <class Config>
void world<Config>::refilter(body_id id) {
  set_filter(id, filter(id));
}

template <class Config>
void world<Config>::set_pair_filter(const pair_filter& rule) {
  refuse_in_callback("world::set_pair_filter: called from inside a world callback (for_each_contact, overlap, "
                     "visit_shape, draw); make the change after it returns");
  scratch_.pair_rule = rule;
  end_filtered_contacts(body_id{});
}

template <class Config>
void world<Config>::end_filtered_contacts(body_id only) {
  if constexpr (collision) {
    std::erase_if(state_.contacts, [&](const contact_record& c) {
      if (!only.is_none() && c.a != only && c.b != only) return false;
      if (state_.may_collide(c.a, c.b, scratch_.pair_rule)) return false;
      state_.end_contact(c);
      state_.wake(state_.bodies[c.a]);
      state_.wake(state_.bodies[c.b]);
      return true;
    });
    state_.pairs_stale = true;
    state_.awake_stale = true;
  }
}

template <class Config>
void world<Config>::set_target_pose(body_id id, const transform<T>& target, T dt) {
  require(id, "world::set_target_pose: no such body");
  body_record& r = state_.bodies[id];
  if (r.body.type != body_type::kinematic)
    detail::report_error(error_code::invalid_parameter, "world::set_target_pose: the body is not kinematic",
                         id.index);
  if (!std::isfinite(dt) || !(dt > T(0)))
    detail::report_error(error_code::invalid_parameter, "world::set_target_pose: dt must be positive and finite");
  if (!is_finite(target.position) || !is_finite(target.rotation))
    detail::report_error(error_code::non_finite, "world::set_target_pose: the pose is not finite");
  if (!is_normalized(target.rotation))
    detail::report_error(error_code::not_normalized, "world::set_target_pose: the rotation is not a unit quaternion");
  state_.require_within_bounds(target.position, "world::set_target_pose: farther than max_coordinate from the origin", id);
  const vec3<T> rotation = rotation_between(r.body.orientation, target.rotation);
  const vec3<T> linear = (target.position - detail::shape_pose_of(r).position) * (T(1) / dt), angular = rotation * (T(1) / dt);
  if (!is_finite(linear) || !is_finite(angular) || !state_.within_speed_limits(linear, angular))
    detail::report_error(error_code::invalid_parameter,
                         "world::set_target_pose: reaching the target in dt is faster than max_linear_speed or "
                         "max_angular_speed",
                         id.index);
  r.body.set_velocity(linear, angular);
  if (r.target == detail::target_state::none) state_.targeted.push_back(id);
  r.target = detail::target_state::armed;
}

template <class Config>
void world<Config>::expire_targets() {
  std::erase_if(state_.targeted, [&](body_id id) {
    if (!state_.bodies.contains(id)) return true;
    body_record& r = state_.bodies[id];
    if (r.target != detail::target_state::arrived) return false;
    r.body.set_velocity({}, {});
    r.target = detail::target_state::none;
    return true;
  });
}

}  // namespace impulse
