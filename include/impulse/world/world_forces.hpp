// impulse/world/world_forces.hpp — world<Config>'s springs and force
// fields, defined outside the class (world.hpp says why they are not
// inline).
//
// A spring (dynamics/body_spring.hpp) is solved with the contacts and
// joints, as a distance row of its own stiffness and damping
// (softness.hpp, soften_absolute): the implicit Euler step of the spring,
// stable at any stiffness and step, and coupled to every contact and joint
// of its bodies in the same iterations. A force field is a load: evaluated
// once at the start of a step, on every awake dynamic body, and held over
// the step like every other force.
//
// In a world without collision (detail/force_motion.hpp) both are forces
// evaluated at every stage of the integrator instead.
#pragma once

#include <cmath>

#include "world.hpp"

namespace impulse {

template <class Config>
spring_id world<Config>::create_spring(const body_spring<T>& def) {
  refuse_in_callback("world::create_spring: called from inside a world callback (for_each_contact, overlap, "
                     "visit_shape, draw); make the change after it returns");
  require(def.body_a, "world::create_spring: no such body at end a");
  const bool anchored = def.body_b.is_none();
  if (!anchored) require(def.body_b, "world::create_spring: no such body at end b");
  if (def.body_a == def.body_b)
    detail::report_error(error_code::invalid_parameter, "world::create_spring: both ends on one body", def.body_a.index);
  if (state_.bodies[def.body_a].body.type != body_type::dynamic &&
      (anchored || state_.bodies[def.body_b].body.type != body_type::dynamic))
    detail::report_error(error_code::invalid_parameter, "world::create_spring: neither end is on a dynamic body",
                         def.body_a.index);
  if (!is_finite(def.point_a) || !is_finite(def.point_b) || !std::isfinite(def.stiffness) ||
      !std::isfinite(def.damping) || !std::isfinite(def.rest_length))
    detail::report_error(error_code::non_finite, "world::create_spring: a point or a number is not finite");
  if (def.stiffness < T(0) || def.damping < T(0) || def.rest_length < T(0))
    detail::report_error(error_code::invalid_parameter,
                         "world::create_spring: stiffness, damping and rest length must be >= 0");
  if (anchored) state_.require_within_bounds(def.point_b, "world::create_spring: the anchor is farther than max_coordinate");
  detail::spring_record<T> record{};
  record.def = def;
  const spring_id id = state_.springs.insert(record);
  state_.wake(state_.bodies[def.body_a]);
  if (!anchored) state_.wake(state_.bodies[def.body_b]);
  state_.awake_stale = true;
  return id;
}

template <class Config>
void world<Config>::destroy_spring(spring_id id) {
  refuse_in_callback("world::destroy_spring: called from inside a world callback (for_each_contact, overlap, "
                     "visit_shape, draw); make the change after it returns");
  require(id, "world::destroy_spring: no such spring (destroyed already?)");
  const body_spring<T>& def = state_.springs[id].def;
  state_.wake(state_.bodies[def.body_a]);
  if (!def.body_b.is_none()) state_.wake(state_.bodies[def.body_b]);
  state_.springs.erase(id);
  state_.awake_stale = true;
}

template <class Config>
template <class Field>
  requires body_force_field<Field, typename Config::scalar>
void world<Config>::step(T dt, Field&& field) {
  if constexpr (!collision) {
    begin_step(dt);
    {
      // The field may read the world, and not change it (world::for_each_contact's rules).
      const in_callback scope(*this);
      detail::force_motion<Config>{state_, scratch_}.run(dt, field);
    }
    finish_step(dt);
  } else {
    refuse_in_callback("world::step: called from inside a world callback (for_each_contact, overlap, "
                       "visit_shape, draw); make the change after it returns");
    // Every load first, checked: a field that gives one body a force that is
    // not finite (or overflows what it bears already) is refused before any
    // body has been given anything.
    state_.refresh_awake();
    scratch_.field_loads.clear();
    {
      // The field may read the world, and not change what this walks (world::for_each_contact's rules).
      const in_callback scope(*this);
      for (const std::uint32_t i : state_.awake_bodies) {
        const rigid_body<T>& b = state_.bodies.values()[i].body;
        if (b.type != body_type::dynamic) continue;
        const body_id id = state_.bodies.ids()[i];
        const wrench<T> w = field(id, kinematics_of(b, body_pose<T>{b.position, b.orientation},
                                                    body_momentum<T>{b.linear_momentum, b.angular_momentum}));
        if (!is_finite(b.force + w.force) || !is_finite(b.torque + w.torque))
          detail::report_error(error_code::non_finite, "world::step: the force field's load on a body is not finite",
                               id.index);
        scratch_.field_loads.push_back({i, w});
      }
    }
    for (const auto& [i, w] : scratch_.field_loads) {
      rigid_body<T>& b = state_.bodies.values()[i].body;
      b.apply_force(w.force);
      b.apply_torque(w.torque);
    }
    step(dt);
  }
}

}  // namespace impulse
