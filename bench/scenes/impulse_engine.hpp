// bench/scenes/impulse_engine.hpp — impulse's own rigid-body world
// (impulse::world<Config>, include/impulse/world.hpp) behind the scenes
// benchmark's engine interface (engine.hpp), set up as a user gets it out of
// the box:
//
// - the policies of the Config the adapter is instantiated with (broad
//   phase, solver, scalar; main.cpp registers one adapter per set it
//   compares), every other member defaulted; world_settings defaults apart
//   from the scene's gravity: 20 velocity iterations, 4 position
//   iterations, warm starting, 0.5 mm slop, 2 cm speculative distance,
//   restitution ignored below 0.5 m/s of approach speed.
// - boxes as impulse::box, spheres as impulse::sphere, each body its own
//   shape (the world keeps a copy per body whatever it is given); static
//   bodies are body_type::static_body. A dynamic body is given the spec's
//   mass and takes the shape's inertia scaled to it.
// - no damping: the world has none.
// - sleeping: the world's, with its defaults (an island sleeps after 0.5 s
//   below 5 cm/s and 2°/s), when the scene has it, off when it does not.
//   Sleeping is a compile-time member of the config (`sleeping`), so the
//   adapter derives two configs from Config, one with it on and one with
//   it off, and build() makes the world of whichever the scene asks for.
// - one step is world::step(dt): exactly one step, no accumulator.
// - on the calling thread alone, unless main.cpp lends the worlds workers
//   (--threads: impulse_workers below, world::set_task_system).
//
// Materials need no translation: impulse combines friction as sqrt(f0·f1)
// and restitution as max(e0, e1), the standard scenes' rules, so each body
// is given the spec's values as they are.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "impulse/broadphase/brute_force.hpp"
#include "impulse/broadphase/dynamic_bvh.hpp"
#include "impulse/broadphase/octree.hpp"
#include "impulse/broadphase/spatial_hash.hpp"
#include "impulse/broadphase/sweep_and_prune.hpp"
#include "impulse/world.hpp"

#include "engine.hpp"
#include "scene_spec.hpp"

namespace bench::scenes {

/// The workers the worlds built next step across (main.cpp, --threads);
/// null: the calling thread alone.
inline const impulse::task_system* impulse_workers = nullptr;

namespace detail {

/// The name of the broad phase a world runs, for the CSV's config column.
/// Asked of the world rather than of the config, so that a config that
/// leaves the broad phase to its default is named too.
template <class World>
constexpr std::string_view broad_phase_name() {
  using B = typename World::broad_phase_type;
  using T = typename World::scalar;
  namespace bp = impulse::broadphase;
  if constexpr (std::is_same_v<B, bp::dynamic_bvh::type<T>>) return "dynamic_bvh";
  else if constexpr (std::is_same_v<B, bp::sweep_and_prune::type<T>>) return "sweep_and_prune";
  else if constexpr (std::is_same_v<B, bp::spatial_hash::type<T>>) return "spatial_hash";
  else if constexpr (std::is_same_v<B, bp::octree::type<T>>) return "octree";
  else if constexpr (std::is_same_v<B, bp::brute_force::type<T>>) return "brute_force";
  else return "custom_broadphase";
}

/// The name of the contact solver a world runs.
template <class World>
constexpr std::string_view solver_name() {
  if constexpr (std::is_same_v<typename World::solver_policy, impulse::solver::sequential_impulse>)
    return "sequential_impulse";
  else if constexpr (std::is_same_v<typename World::solver_policy, impulse::solver::soft_step>)
    return "soft_step";
  else
    return "custom_solver";
}

}  // namespace detail

template <class Config>
class impulse_engine {
 public:
  static constexpr std::string_view name = "impulse";

  [[nodiscard]] std::string config() const {
    // soft_step's work is its substeps (one soft and one relax sweep
    // each); sequential_impulse's its velocity iterations, in its parts.
    constexpr bool substepping = std::is_same_v<typename sleeping_world::solver_policy, impulse::solver::soft_step>;
    const auto [count, parts] = std::visit(
        [](const auto& w) {
          const auto& solver = settings_of(w).solver;
          return substepping ? std::pair{solver.substeps, 1} : std::pair{solver.velocity_iterations, solver.substeps};
        },
        world_);
    return std::string(detail::solver_name<sleeping_world>()) + (substepping ? " substeps=" : " iterations=") +
           std::to_string(count) + (parts > 1 ? " substeps=" + std::to_string(parts) : std::string()) + ' ' +
           std::string(detail::broad_phase_name<sleeping_world>()) +
           (std::is_same_v<T, double> ? " double" : " float") +
           (sleeping_world::cross_platform_determinism ? " lockstep" : "") +
           (workers_ > 1 ? " workers=" + std::to_string(workers_) : std::string());
  }

  void build(const scene_spec& spec) {
    dt_ = static_cast<T>(spec.dt);
    settings_type settings;
    settings.gravity = to_impulse(spec.gravity);
    if (spec.sleeping)
      build_into(world_.template emplace<sleeping_world>(settings), spec);
    else
      build_into(world_.template emplace<awake_world>(settings), spec);
    states_.resize(spec.bodies.size());
  }

  void step() {
    if (auto* w = std::get_if<sleeping_world>(&world_))
      w->step(dt_);
    else if (auto* a = std::get_if<awake_world>(&world_))
      a->step(dt_);
  }

  [[nodiscard]] stage_times profile() const {
    return std::visit(
        [](const auto& w) {
          if constexpr (std::is_same_v<std::decay_t<decltype(w)>, std::monostate>) {
            return stage_times{};
          } else {
            const impulse::step_profile& p = w.last_step_profile();
            return stage_times{{p.broad, p.narrow, p.prepare, p.solve, p.integrate, p.continuous, p.sleep}};
          }
        },
        world_);
  }

  std::span<const body_state> states() {
    if (const auto* w = std::get_if<sleeping_world>(&world_))
      read_states(*w);
    else if (const auto* a = std::get_if<awake_world>(&world_))
      read_states(*a);
    return states_;
  }

 private:
  using T = typename Config::scalar;
  struct sleeping_config : Config {
    static constexpr bool sleeping = true;
  };
  struct awake_config : Config {
    static constexpr bool sleeping = false;
  };
  using sleeping_world = impulse::world<sleeping_config>;
  using awake_world = impulse::world<awake_config>;
  using settings_type = typename sleeping_world::settings_type;  // the awake world's too: the same solver

  static impulse::vec3<T> to_impulse(const vec3& v) { return {T(v.x), T(v.y), T(v.z)}; }
  static vec3 from_impulse(const impulse::vec3<T>& v) { return {v.x, v.y, v.z}; }

  // Before build() there is no world; config() then reports the defaults
  // a world would be made with.
  static const settings_type& settings_of(const std::monostate&) {
    static const settings_type defaults{};
    return defaults;
  }
  template <class World>
  static const settings_type& settings_of(const World& w) {
    return w.settings();
  }

  template <class World>
  void build_into(World& w, const scene_spec& spec) {
    if (impulse_workers != nullptr) w.set_task_system(*impulse_workers);
    workers_ = w.tasks().parallel() ? w.tasks().workers : 1;
    ids_.clear();
    ids_.reserve(spec.bodies.size());
    for (const body_spec& b : spec.bodies) {
      impulse::body_def<T> def;
      def.type = b.is_static ? impulse::body_type::static_body : impulse::body_type::dynamic;
      def.pose.position = to_impulse(b.position);
      def.pose.rotation = {T(b.orientation.x), T(b.orientation.y), T(b.orientation.z), T(b.orientation.w)};
      if (!b.is_static) {
        def.mass = T(b.mass);
        def.linear_velocity = to_impulse(b.linear_velocity);
      }
      def.material.friction = T(b.surface.friction);
      def.material.restitution = T(b.surface.restitution);
      if (b.shape == shape_kind::box)
        ids_.push_back(w.create_body(def, impulse::box<T>::make(to_impulse(b.half_extents))));
      else
        ids_.push_back(w.create_body(def, impulse::sphere<T>::make(T(b.radius))));
    }
  }

  template <class World>
  void read_states(const World& w) {
    for (std::size_t i = 0; i < ids_.size(); ++i) {
      const impulse::rigid_body<T>& b = w.body(ids_[i]);
      const impulse::quat<T>& q = b.orientation;
      states_[i] = {from_impulse(b.position),
                    {q.w, q.x, q.y, q.z},
                    from_impulse(b.linear_velocity()),
                    from_impulse(b.angular_velocity()),
                    b.type == impulse::body_type::dynamic && w.is_awake(ids_[i])};
    }
  }

  // One of the two worlds, whichever the scene's sleeping asks for; none
  // before build().
  std::variant<std::monostate, sleeping_world, awake_world> world_;
  std::vector<impulse::body_id> ids_;  // in spec order
  std::vector<body_state> states_;
  T dt_ = T(1) / T(60);
  std::uint32_t workers_ = 1;
};

static_assert(scene_engine<impulse_engine<impulse::default_config>>);

}  // namespace bench::scenes
