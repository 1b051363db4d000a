// impulse/dynamics/rigid_body_system.hpp — bodies moved by forces and springs.
//
// A set of rigid bodies under gravity, their accumulated loads, damped
// springs (body_spring.hpp) and an optional force field, advanced by the
// config's integrator policy. It is the force-driven half of the world's
// step (docs/architecture.md, "The world's step"); contacts and joints
// come with the world.
//
// Forces are evaluated at every stage of the integrator, on the stage's
// speculative state: springs see where the bodies would be mid-step, and so
// does a user's field. Loads applied with rigid_body::apply_force are held
// constant over the step and cleared after it.
//
// Two paths run the same integrator code. When no spring joins two moving
// bodies, each body is independent: it is advanced alone, with its state in
// registers (body_motion.hpp's pose and momenta as the integrator's x and
// p). When springs couple bodies, every stage needs every body's stage
// state, so the integrator is handed the whole set as one state
// (core/detail/pooled_state.hpp), as the particle system does for its
// springs.
//
// Input is checked before a step changes anything: a non-finite position,
// orientation, momentum or load, a non-unit orientation, a dynamic body
// without positive finite mass, or a spring with a missing end or a negative
// parameter is refused, naming the body or spring, and the set is left as
// it was. A body whose state becomes non-finite during a step (valid input
// can still overflow: a spring of stiffness 1e300) is left where it was at
// the start of the step, the others keep their step, and the error names
// it.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "../config.hpp"
#include "../core/detail/pooled_state.hpp"
#include "../core/error.hpp"
#include "../core/slot_map.hpp"
#include "../math/quat.hpp"
#include "../math/scalar_traits.hpp"
#include "body_motion.hpp"
#include "body_spring.hpp"
#include "fwd.hpp"
#include "rigid_body.hpp"

namespace impulse {

namespace detail {
/// The field used when a step is given none.
struct no_force_field {};
}  // namespace detail

/// A force model evaluated per body at every integrator stage:
/// field(id, kinematics) -> wrench (force through the center of mass and
/// torque about it). It must not change the system.
template <class F, class T>
concept body_force_field = std::is_same_v<std::remove_cvref_t<F>, detail::no_force_field> ||
                           std::is_invocable_r_v<wrench<T>, F&, body_id, const body_kinematics<T>&>;

template <class Config>
class rigid_body_system {
 public:
  using config = Config;
  using scalar = typename Config::scalar;
  using integrator = typename Config::integrator;
  using T = scalar;

  /// Acceleration of gravity on every dynamic body, m/s².
  vec3<T> gravity{T(0), T(-9.81), T(0)};

  // ---- bodies ----

  /// Adds a body. Its inverse mass and inverse inertia are recomputed from
  /// mass and inertia (so a hand-built body cannot carry inconsistent
  /// ones); its state must be finite with a unit orientation.
  body_id add_body(rigid_body<T> b) {
    validate_body(b, no_object);
    if (b.type == body_type::dynamic) b.set_mass_properties({b.mass, vec3<T>{}, b.inertia});
    return bodies_.insert(b);
  }
  /// Removes a body and every spring attached to it.
  void remove_body(body_id id) {
    require_body(id, "rigid_body_system::remove_body: no such body");
    for (std::size_t i = springs_.size(); i-- > 0;) {
      const body_spring<T>& s = springs_.values()[i];
      if (s.body_a == id || s.body_b == id) springs_.erase(springs_.ids()[i]);
    }
    bodies_.erase(id);
  }
  [[nodiscard]] bool contains(body_id id) const noexcept { return bodies_.contains(id); }
  [[nodiscard]] rigid_body<T>& body(body_id id) {
    require_body(id, "rigid_body_system::body: no such body");
    return bodies_[id];
  }
  [[nodiscard]] const rigid_body<T>& body(body_id id) const {
    require_body(id, "rigid_body_system::body: no such body");
    return bodies_[id];
  }
  [[nodiscard]] std::size_t body_count() const noexcept { return bodies_.size(); }
  /// The bodies in storage order; body_ids()[i] names bodies()[i].
  [[nodiscard]] const std::vector<rigid_body<T>>& bodies() const noexcept { return bodies_.values(); }
  [[nodiscard]] const std::vector<body_id>& body_ids() const noexcept { return bodies_.ids(); }

  // ---- springs ----

  spring_id add_spring(const body_spring<T>& s) {
    validate_spring(s, no_object);
    return springs_.insert(s);
  }
  void remove_spring(spring_id id) {
    require_spring(id, "rigid_body_system::remove_spring: no such spring");
    springs_.erase(id);
  }
  [[nodiscard]] bool contains(spring_id id) const noexcept { return springs_.contains(id); }
  [[nodiscard]] body_spring<T>& spring(spring_id id) {
    require_spring(id, "rigid_body_system::spring: no such spring");
    return springs_[id];
  }
  [[nodiscard]] const body_spring<T>& spring(spring_id id) const {
    require_spring(id, "rigid_body_system::spring: no such spring");
    return springs_[id];
  }
  [[nodiscard]] std::size_t spring_count() const noexcept { return springs_.size(); }
  [[nodiscard]] const std::vector<body_spring<T>>& springs() const noexcept { return springs_.values(); }

  // ---- stepping ----

  /// Advances every body by dt seconds under gravity, loads and springs.
  /// (Defined after the class, not inline: IMPULSE_DECLARE_RIGID_BODY_SYSTEM
  /// then keeps the integration out of other translation units.)
  void step(T dt);

  /// The same, with field(id, kinematics) -> wrench added on every dynamic
  /// body at every stage.
  template <class Field>
    requires body_force_field<Field, T>
  void step(T dt, Field&& field) {
    validate_step(dt);
    resolve_springs();
    failed_ = none;
    if (coupled_) {
      step_coupled(dt, field);
    } else {
      step_each(dt, field);
    }
    finish_step(dt);
  }

  /// Simulated time, s.
  [[nodiscard]] T time() const noexcept { return time_; }

  // ---- what is conserved, for tests and diagnostics ----

  /// Σ ½·m·v² + ½·ω·L over dynamic bodies, J.
  [[nodiscard]] T kinetic_energy() const noexcept {
    T e = T(0);
    for (const rigid_body<T>& b : bodies_.values()) e += b.kinetic_energy();
    return e;
  }
  /// Gravitational (−m·g·x, zero at the origin) plus spring energy, J.
  [[nodiscard]] T potential_energy() const {
    T e = T(0);
    for (const rigid_body<T>& b : bodies_.values())
      if (b.type == body_type::dynamic) e -= b.mass * dot(gravity, b.position);
    for (const body_spring<T>& s : springs_.values()) {
      const rigid_body<T>& a = bodies_[s.body_a];
      const vec3<T> pa = a.position + rotate(a.orientation, s.point_a);
      const vec3<T> pb = s.body_b.is_none() ? s.point_b
                                            : bodies_[s.body_b].position +
                                                  rotate(bodies_[s.body_b].orientation, s.point_b);
      e += spring_energy(s, pa, pb);
    }
    return e;
  }
  /// Σ P over dynamic bodies, kg·m/s.
  [[nodiscard]] vec3<T> linear_momentum() const noexcept {
    vec3<T> p{};
    for (const rigid_body<T>& b : bodies_.values())
      if (b.type == body_type::dynamic) p += b.linear_momentum;
    return p;
  }
  /// Σ (x × P + L) over dynamic bodies, about the world origin, kg·m²/s.
  [[nodiscard]] vec3<T> angular_momentum() const noexcept {
    vec3<T> l{};
    for (const rigid_body<T>& b : bodies_.values())
      if (b.type == body_type::dynamic) l += cross(b.position, b.linear_momentum) + b.angular_momentum;
    return l;
  }

 private:
  static constexpr std::uint32_t none = no_object;

  // A spring with its ends as storage positions, resolved once per step.
  struct spring_ends {
    std::uint32_t a, b;  // b == none: world anchor
  };

  // ---- validation ----

  void require_body(body_id id, const char* message) const {
    if (!bodies_.contains(id)) detail::report_error(error_code::out_of_range, message, id.index);
  }
  void require_spring(spring_id id, const char* message) const {
    if (!springs_.contains(id)) detail::report_error(error_code::out_of_range, message, id.index);
  }

  static void validate_body(const rigid_body<T>& b, std::uint32_t id) {
    if (!is_finite(b.position) || !is_finite(b.orientation) || !is_finite(b.linear_momentum) ||
        !is_finite(b.angular_momentum) || !is_finite(b.kinematic_velocity) ||
        !is_finite(b.kinematic_angular_velocity))
      detail::report_error(error_code::non_finite, "rigid_body_system: a body's state is not finite", id);
    if (!is_finite(b.force) || !is_finite(b.torque))
      detail::report_error(error_code::non_finite, "rigid_body_system: a body's load is not finite", id);
    if (!is_normalized(b.orientation))
      detail::report_error(error_code::not_normalized, "rigid_body_system: a body's orientation is not a unit quaternion",
                           id);
    if (b.type == body_type::dynamic && !(b.mass > T(0) && std::isfinite(b.mass)))
      detail::report_error(error_code::non_positive_mass,
                           "rigid_body_system: a dynamic body needs a positive, finite mass", id);
  }

  void validate_spring(const body_spring<T>& s, std::uint32_t id) const {
    if (!bodies_.contains(s.body_a) || (!s.body_b.is_none() && !bodies_.contains(s.body_b)))
      detail::report_error(error_code::out_of_range, "rigid_body_system: a spring's end names no body", id);
    if (s.body_a == s.body_b)
      detail::report_error(error_code::invalid_parameter, "rigid_body_system: a spring joins a body to itself", id);
    if (!is_finite(s.point_a) || !is_finite(s.point_b) || !std::isfinite(s.stiffness) || !std::isfinite(s.damping) ||
        !std::isfinite(s.rest_length))
      detail::report_error(error_code::non_finite, "rigid_body_system: a spring's points or parameters are not finite",
                           id);
    if (s.stiffness < T(0) || s.damping < T(0) || s.rest_length < T(0))
      detail::report_error(error_code::invalid_parameter,
                           "rigid_body_system: a spring's stiffness, damping and rest length must be >= 0", id);
  }

  // Bodies and springs are plain data the user may edit between steps, so
  // all of it is checked before the step touches anything.
  void validate_step(T dt) const {
    if (!std::isfinite(dt) || !(dt > T(0)))
      detail::report_error(error_code::invalid_parameter, "rigid_body_system::step: dt must be positive and finite");
    if (!is_finite(gravity)) detail::report_error(error_code::non_finite, "rigid_body_system: gravity is not finite");
    for (std::size_t i = 0; i < bodies_.size(); ++i) validate_body(bodies_.values()[i], bodies_.ids()[i].index);
    for (std::size_t i = 0; i < springs_.size(); ++i) validate_spring(springs_.values()[i], springs_.ids()[i].index);
  }

  // ---- forces at a stage ----

  void resolve_springs() {
    const std::size_t n = bodies_.size();
    ends_.resize(springs_.size());
    coupled_ = false;
    first_spring_.assign(n + 1, 0);
    for (std::size_t i = 0; i < springs_.size(); ++i) {
      const body_spring<T>& s = springs_.values()[i];
      spring_ends& e = ends_[i];
      e.a = static_cast<std::uint32_t>(bodies_.dense_index(s.body_a));
      e.b = s.body_b.is_none() ? none : static_cast<std::uint32_t>(bodies_.dense_index(s.body_b));
      const bool a_moves = bodies_.values()[e.a].type != body_type::static_body;
      const bool b_moves = e.b != none && bodies_.values()[e.b].type != body_type::static_body;
      coupled_ = coupled_ || (a_moves && b_moves);
      ++first_spring_[e.a + 1];
      if (e.b != none) ++first_spring_[e.b + 1];
    }
    // Springs of each body, for the independent path (counting sort).
    for (std::size_t i = 0; i < n; ++i) first_spring_[i + 1] += first_spring_[i];
    springs_of_.resize(first_spring_[n]);
    fill_.assign(first_spring_.begin(), first_spring_.end() - 1);
    for (std::uint32_t i = 0; i < ends_.size(); ++i) {
      springs_of_[fill_[ends_[i].a]++] = i;
      if (ends_[i].b != none) springs_of_[fill_[ends_[i].b]++] = i;
    }
  }

  // Gravity, the held loads and the field on body i at kinematics k.
  template <class Field>
  wrench<T> body_wrench(std::size_t i, const body_kinematics<T>& k, Field& field) const {
    const rigid_body<T>& b = bodies_.values()[i];
    if (b.type != body_type::dynamic) return {};
    wrench<T> w{b.force + gravity * b.mass, b.torque};
    if constexpr (!std::is_same_v<std::remove_cvref_t<Field>, detail::no_force_field>)
      w += field(bodies_.ids()[i], k);
    return w;
  }

  static body_momentum<T> as_rate(const wrench<T>& w) noexcept { return {w.force, w.torque}; }

  // One dynamic body alone, its springs' other ends fixed for the step
  // (static bodies or world anchors).
  template <class Field>
  struct single_body {
    const rigid_body_system& system;
    std::size_t index;
    Field& field;
    // Most methods ask for both rates at the same stage state; the
    // kinematics (a rotation matrix and the world inverse inertia) are
    // worked out once for both.
    body_pose<T> cached_x{};
    body_momentum<T> cached_p{};
    body_kinematics<T> cached_k{};
    bool cached = false;

    const body_kinematics<T>& kinematics(const body_pose<T>& x, const body_momentum<T>& p) {
      if (!cached || !(x.position == cached_x.position && x.orientation == cached_x.orientation &&
                       p.linear == cached_p.linear && p.angular == cached_p.angular)) {
        cached_k = kinematics_of(system.bodies_.values()[index], x, p);
        cached_x = x, cached_p = p, cached = true;
      }
      return cached_k;
    }

    body_pose<T> position_rate(const body_pose<T>& x, const body_momentum<T>& p) {
      return pose_rate(kinematics(x, p), x.orientation);
    }
    body_momentum<T> momentum_rate(const body_pose<T>& x, const body_momentum<T>& p) {
      const body_kinematics<T>& k = kinematics(x, p);
      wrench<T> w = system.body_wrench(index, k, field);
      for (std::uint32_t j = system.first_spring_[index]; j < system.first_spring_[index + 1]; ++j) {
        const std::uint32_t s = system.springs_of_[j];
        const spring_ends& e = system.ends_[s];
        const body_spring<T>& spring = system.springs_.values()[s];
        // This body may be either end; the other end does not move.
        if (e.a == index && e.b == none) {  // a world anchor
          const spring_load<T> load = spring_load_of<T>(spring, k, nullptr);
          add_at(w, k, load.force, load.point_a);
        } else if (e.a == index) {
          const body_kinematics<T> other = system.resting_kinematics(e.b);
          const spring_load<T> load = spring_load_of(spring, k, &other);
          add_at(w, k, load.force, load.point_a);
        } else {
          const body_kinematics<T> other = system.resting_kinematics(e.a);
          const spring_load<T> load = spring_load_of(spring, other, &k);
          add_at(w, k, -load.force, load.point_b);
        }
      }
      return as_rate(w);
    }
  };

  static void add_at(wrench<T>& w, const body_kinematics<T>& k, const vec3<T>& f, const vec3<T>& p) noexcept {
    w.force += f;
    w.torque += cross(p - k.position, f);
  }

  // A static body at the other end of a spring: it does not move in the step.
  body_kinematics<T> resting_kinematics(std::uint32_t i) const noexcept {
    const rigid_body<T>& b = bodies_.values()[i];
    return kinematics_of(b, pose_of(b), momentum_of(b));
  }

  template <class Field>
  void step_each(T dt, Field& field) {
    std::vector<rigid_body<T>>& bodies = bodies_.values();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (bodies[i].type != body_type::dynamic) continue;  // kinematic ones are placed exactly in finish_step
      body_pose<T> x = pose_of(bodies[i]);
      body_momentum<T> p = momentum_of(bodies[i]);
      integrator::advance(x, p, dt, single_body<Field>{*this, i, field});
      commit(i, x, p);
    }
  }

  // Every body at once: the whole set is the integrator's state.
  using poses = detail::pooled_state<body_pose<T>>;
  using momenta = detail::pooled_state<body_momentum<T>>;

  template <class Field>
  struct whole_set {
    rigid_body_system& system;
    Field& field;

    poses position_rate(const poses& x, const momenta& p) const {
      const std::vector<rigid_body<T>>& bodies = system.bodies_.values();
      poses rate(system.pose_pool_);
      for (std::size_t i = 0; i < bodies.size(); ++i)
        rate[i] = pose_rate(kinematics_of(bodies[i], x[i], p[i]), x[i].orientation);
      return rate;
    }
    momenta momentum_rate(const poses& x, const momenta& p) const {
      const std::vector<rigid_body<T>>& bodies = system.bodies_.values();
      std::vector<body_kinematics<T>>& k = system.stage_kinematics_;
      std::vector<wrench<T>>& w = system.stage_wrenches_;
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        k[i] = kinematics_of(bodies[i], x[i], p[i]);
        w[i] = system.body_wrench(i, k[i], field);
      }
      for (std::size_t s = 0; s < system.ends_.size(); ++s) {
        const spring_ends& e = system.ends_[s];
        const spring_load<T> load = spring_load_of(system.springs_.values()[s], k[e.a], e.b == none ? nullptr : &k[e.b]);
        if (bodies[e.a].type == body_type::dynamic) add_at(w[e.a], k[e.a], load.force, load.point_a);
        if (e.b != none && bodies[e.b].type == body_type::dynamic) add_at(w[e.b], k[e.b], -load.force, load.point_b);
      }
      momenta rate(system.momentum_pool_);
      for (std::size_t i = 0; i < bodies.size(); ++i)
        rate[i] = bodies[i].type == body_type::dynamic ? as_rate(w[i]) : body_momentum<T>{};
      return rate;
    }
  };

  template <class Field>
  void step_coupled(T dt, Field& field) {
    std::vector<rigid_body<T>>& bodies = bodies_.values();
    const std::size_t n = bodies.size();
    pose_pool_.resize(1, n, n);
    momentum_pool_.resize(1, n, n);
    stage_kinematics_.resize(n);
    stage_wrenches_.resize(n);
    poses x(pose_pool_);
    momenta p(momentum_pool_);
    for (std::size_t i = 0; i < n; ++i) x[i] = pose_of(bodies[i]), p[i] = momentum_of(bodies[i]);
    integrator::advance(x, p, dt, whole_set<Field>{*this, field});
    for (std::size_t i = 0; i < n; ++i) commit(i, x[i], p[i]);
  }

  // ---- the end of a step ----

  // Writes a dynamic body's step, or, if it came out non-finite, leaves the
  // body as it was and remembers it. Nothing else reads a body's stored
  // state after its step is computed, so no copy of the start is needed.
  void commit(std::size_t i, const body_pose<T>& x, const body_momentum<T>& p) noexcept {
    rigid_body<T>& b = bodies_.values()[i];
    if (b.type != body_type::dynamic) return;
    const bool finite = is_finite(x.position) && is_finite(x.orientation) && is_finite(p.linear) &&
                        is_finite(p.angular) &&
                        length_squared(x.orientation) > scalar_traits<T>::zero_length_squared;
    if (!finite) {
      if (failed_ == none) failed_ = bodies_.ids()[i].index;
      return;
    }
    b.position = x.position;
    b.orientation = normalize(x.orientation);
    b.linear_momentum = p.linear;
    b.angular_momentum = p.angular;
  }

  void finish_step(T dt) {
    for (rigid_body<T>& b : bodies_.values()) {
      if (b.type == body_type::kinematic) {
        // A kinematic body's motion is prescribed: place it exactly rather
        // than where an integrator's approximation of q' = ½ω⊗q would.
        b.position += b.kinematic_velocity * dt;
        b.orientation = integrate(b.orientation, b.kinematic_angular_velocity, dt);
      }
      b.clear_loads();
    }
    time_ += dt;
    if (failed_ != none)
      detail::report_error(error_code::non_finite,
                           "rigid_body_system::step: a body's state became non-finite; it was left where it was",
                           failed_);
  }

  slot_map<rigid_body<T>, body_id> bodies_;
  slot_map<body_spring<T>, spring_id> springs_;
  T time_ = T(0);

  // Per-step scratch, kept to allocate nothing once warm.
  std::uint32_t failed_ = none;
  std::vector<spring_ends> ends_;
  std::vector<std::uint32_t> first_spring_, springs_of_, fill_;
  bool coupled_ = false;
  detail::buffer_pool<body_pose<T>> pose_pool_;
  detail::buffer_pool<body_momentum<T>> momentum_pool_;
  std::vector<body_kinematics<T>> stage_kinematics_;
  std::vector<wrench<T>> stage_wrenches_;
};

template <class Config>
void rigid_body_system<Config>::step(T dt) {
  step(dt, detail::no_force_field{});
}

}  // namespace impulse

#if IMPULSE_EXTERN_TEMPLATES
IMPULSE_DECLARE_RIGID_BODY_SYSTEM(impulse::default_config);
IMPULSE_DECLARE_RIGID_BODY_SYSTEM(impulse::default_double_config);
#endif
