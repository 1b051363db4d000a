// impulse/world/world_joints.hpp — world<Config>'s members that make and
// destroy joints, defined outside the class (world.hpp says why they are
// not inline).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "world.hpp"

namespace impulse {

template <class Config>
joint_id world<Config>::create_joint(const joint_def<T>& def)
  requires(detail::world_collides<Config>())
{
  refuse_in_callback("world::create_joint: called from inside a world callback (for_each_contact, overlap, "
                     "visit_shape, draw); make the change after it returns");
  require(def.body_a, "world::create_joint: body_a does not exist (destroyed?)");
  require(def.body_b, "world::create_joint: body_b does not exist (destroyed?)");
  if (def.body_a == def.body_b)
    detail::report_error(error_code::invalid_parameter, "world::create_joint: a joint needs two different bodies",
                         def.body_a.index);
  def.validate();
  state_.require_within_bounds(def.anchor_a, "world::create_joint: anchor_a is farther than max_coordinate from the origin");
  state_.require_within_bounds(def.anchor_b, "world::create_joint: anchor_b is farther than max_coordinate from the origin");
  body_record& ra = state_.bodies[def.body_a];
  body_record& rb = state_.bodies[def.body_b];
  if (ra.body.type != body_type::dynamic && rb.body.type != body_type::dynamic)
    detail::report_error(error_code::invalid_parameter, "world::create_joint: at least one body must be dynamic",
                         def.body_a.index);

  const bool two_ends = def.type == joint_type::distance;
  state_.require_lever(ra.body, def.anchor_a, def.body_a);
  state_.require_lever(rb.body, two_ends ? def.anchor_b : def.anchor_a, def.body_b);

  // Nothing below can fail on the input.
  const rigid_body<T>& a = ra.body;
  const rigid_body<T>& b = rb.body;
  joint_constraint<T> c;
  c.type = def.type;
  c.local_anchor_a = inverse_rotate(a.orientation, def.anchor_a - a.position);
  c.local_anchor_b = inverse_rotate(b.orientation, (two_ends ? def.anchor_b : def.anchor_a) - b.position);
  vec3<T> axis = def.axis;
  if (two_ends) axis = def.anchor_b - def.anchor_a;
  c.local_axis_a = length_squared(axis) > T(0) ? inverse_rotate(a.orientation, normalize(axis)) : vec3<T>{1, 0, 0};
  c.reference = conjugate(a.orientation) * b.orientation;
  c.enable_limit = def.enable_limit, c.lower = def.lower, c.upper = def.upper;
  c.enable_motor = def.enable_motor, c.motor_speed = def.motor_speed, c.max_motor_force = def.max_motor_force;
  c.length = def.length, c.spring_hertz = def.spring_hertz, c.spring_damping_ratio = def.spring_damping_ratio;
  joint_record record{};
  record.constraint = c;
  record.def = def;
  record.a = def.body_a, record.b = def.body_b;
  if (!def.collide_connected) {
    const std::uint64_t key = detail::pair_key(def.body_a, def.body_b);
    state_.joined.insert(std::upper_bound(state_.joined.begin(), state_.joined.end(), key), key);
    end_contacts_between(def.body_a, def.body_b);
  }
  state_.wake(ra);
  state_.wake(rb);
  state_.awake_stale = true;
  return state_.joints.insert(record);
}

template <class Config>
void world<Config>::destroy_joint(joint_id id) {
  refuse_in_callback("world::destroy_joint: called from inside a world callback (for_each_contact, overlap, "
                     "visit_shape, draw); make the change after it returns");
  require(id, "world::destroy_joint: no such joint (destroyed already?)");
  const joint_record& r = state_.joints[id];
  if (!r.broken) state_.unjoin(r);
  state_.wake(state_.bodies[r.a]);
  state_.wake(state_.bodies[r.b]);
  state_.joints.erase(id);
  state_.awake_stale = true;
}

template <class Config>
void world<Config>::end_contacts_between(body_id a, body_id b) {
  std::erase_if(state_.contacts, [&](const contact_record& c) {
    if (!((c.a == a && c.b == b) || (c.a == b && c.b == a))) return false;
    state_.end_contact(c);
    return true;
  });
}

template <class Config>
void world<Config>::set_joint_motor(joint_id id, bool enable, T speed, T max_force) {
  require(id, "world::set_joint_motor: no such joint");
  joint_record& r = state_.joints[id];
  joint_def<T> def = r.def;
  def.enable_motor = enable, def.motor_speed = speed, def.max_motor_force = max_force;
  def.validate();
  r.def = def;
  r.constraint.enable_motor = enable, r.constraint.motor_speed = speed, r.constraint.max_motor_force = max_force;
  if (!enable) r.constraint.motor_impulse = T(0);
  state_.wake_joint(r);
}

template <class Config>
void world<Config>::set_joint_limits(joint_id id, bool enable, T lower, T upper) {
  require(id, "world::set_joint_limits: no such joint");
  joint_record& r = state_.joints[id];
  joint_def<T> def = r.def;
  def.enable_limit = enable, def.lower = lower, def.upper = upper;
  def.validate();
  r.def = def;
  r.constraint.enable_limit = enable, r.constraint.lower = lower, r.constraint.upper = upper;
  if (!enable) r.constraint.lower_impulse = r.constraint.upper_impulse = T(0);
  state_.wake_joint(r);
}

}  // namespace impulse
