// impulse/particles/particle_system.hpp — particles in SIMD batches, stepped by
// one fused pass.
//
//   struct snow_config : impulse::default_config {};
//   impulse::particle_system<snow_config, gravity, wind> snow{10'000};
//   snow.add_plane(plane_collider<float>::half_space({0, 1, 0}, 0, 0, 1));
//   snow.add_emitter({.position = {0, 20, 0}, .half_extents = {10, 0, 10}, .rate = 500});
//   snow.step(1.0f / 60);
//
// Storage is structure-of-arrays: one 64-byte-aligned column per component
// (x, y, z, vx, vy, vz, inverse mass, and the per-particle wind variation,
// age and lifetime when the configuration uses them), each padded to whole
// batches of W lanes. A step loads a batch into registers, runs the
// configured integrator over it with the force list evaluated at every stage,
// resolves the planes, ages it and stores it: every byte is read and written
// once per step whatever the integrator, so RK4 moves the bytes Euler moves.
//
// Springs couple particles across batches, so a force list that contains them
// is stepped in stages instead: each integrator stage computes every spring's
// force, then sweeps all batches, adding each particle's springs to its
// batch's forces and running the integrator on to the next stage. The same
// integrator code runs both paths.
//
// With a task system (set_task_system, core/task_system.hpp) the batches
// are split across workers, and the particles come out bit-identical for any
// worker count: each range writes only its own batches, and what crosses
// batches (deaths, emission, the springs' sums) is done in a fixed order.
//
// Indices are positions in the columns. Killing a particle, or its death by
// age, moves the last particle into its slot, so the columns stay dense and
// the kernel never spends lanes on the dead; a spring follows the particle
// it is attached to.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "../core/aligned_array.hpp"
#include "../core/detail/assert.hpp"
#include "../core/floating_point.hpp"
#include "../core/policy.hpp"
#include "../core/random.hpp"
#include "../core/task_system.hpp"
#include "../integrators/ode_state.hpp"
#include "emitter.hpp"
#include "force.hpp"
#include "plane_collider.hpp"

namespace impulse::particles {

/// Batch width of a configuration's particle systems: Config::particle_width
/// when it sets one, else the widest the target compiles for.
template <class Config>
inline constexpr int particle_width_of = [] {
  if constexpr (requires { Config::particle_width; }) return int(Config::particle_width);
  else return native_width<typename Config::scalar>;
}();

/// Whether particles age and die: Config::particle_lifetime, default true.
/// Without it the age and lifetime columns do not exist and a step moves
/// 12 fewer bytes per float particle.
template <class Config>
inline constexpr bool particle_lifetime_of = [] {
  if constexpr (requires { Config::particle_lifetime; }) return bool(Config::particle_lifetime);
  else return true;
}();

/// Whether each particle has its own mass: Config::particle_masses, default
/// true. Without it every particle has unit mass, forces are accelerations,
/// and the inverse-mass column does not exist: a step of the standard
/// `particles` scene then reads 24 bytes a float particle, not 28 (at
/// 4·10⁶ particles, past the caches, the column cost 7 % of the step).
template <class Config>
inline constexpr bool particle_masses_of = [] {
  if constexpr (requires { Config::particle_masses; }) return bool(Config::particle_masses);
  else return true;
}();

/// Read-only view of three columns as vectors.
template <class T>
struct vec3_columns {
  std::span<const T> x, y, z;
  [[nodiscard]] std::size_t size() const noexcept { return x.size(); }
  vec3<T> operator[](std::size_t i) const noexcept { return {x[i], y[i], z[i]}; }
};

template <class Config, template <class> class... Forces>
class particle_system {
 public:
  using config = Config;
  using scalar = typename Config::scalar;
  using integrator = typename Config::integrator;
  static constexpr int width = particle_width_of<Config>;
  static constexpr bool has_lifetime = particle_lifetime_of<Config>;
  static constexpr bool has_masses = particle_masses_of<Config>;
  /// Config `cross_platform_determinism` (off by default): the same bits from
  /// every build (core/floating_point.hpp), forces in their portable form
  /// (point_forces: never the hardware's 1/√ estimate, which differs by vendor).
  static constexpr bool cross_platform_determinism = impulse::detail::cross_platform_determinism<Config>();
  /// The most particles a system may be created for: 2^26, about 6.7e7.
  /// Each takes up to 10 columns of scalar (40 bytes with float, 80 with
  /// double; springs add 3 to 18 for the stages), allocated and zeroed when
  /// the system is made, so this many is 2.7 GB of float columns; a step moves 52 bytes a particle, about 90 ms
  /// at the 38–57 GB/s memory roof of docs/particles_benchmark.md, far past
  /// real time. A larger capacity is a slip of zeros (1e9 would be 40 GB),
  /// refused before anything is allocated. It also keeps every index well
  /// below no_object in the std::uint32_t the API hands out.
  static constexpr std::size_t max_capacity = std::size_t(1) << 26;

  static_assert(scalar_type<scalar>, "impulse particle_system: Config::scalar must be float or double");
  static_assert(batch_width<scalar, width>,
                "impulse particle_system: Config::particle_width must be 1, 2, 4, 8 or 16 and at most 64 bytes");
  static_assert(integrator_policy<integrator>,
                "impulse particle_system: Config::integrator must be an integrator policy");
  static_assert((particle_force<Forces<scalar>, scalar, width> && ...),
                "impulse particle_system: every force must state its effect, validate() and evaluate(x, v, p)");
  static_assert(((Forces<scalar>::effect == force_effect::pairwise ? 1 : 0) + ... + 0) <= 1,
                "impulse particle_system: at most one pairwise force (springs) in the list");
  static_assert(impulse::detail::check_determinism_build<Config>());

 private:
  using T = scalar;
  using lanes = batch<T, width>;
  using state = vec3_batch<T, width>;
  template <class F>
  static constexpr bool is_pairwise = F::effect == force_effect::pairwise;
  static constexpr bool has_pairwise = (is_pairwise<Forces<T>> || ...);
  static constexpr bool needs_inverse_mass =
      has_masses && ((Forces<T>::effect != force_effect::acceleration) || ...);
  static constexpr bool needs_variation = (uses_variation<Forces<T>>() || ...);

 public:
  /// A system that holds up to `capacity` particles, with each force's
  /// default parameters.
  explicit particle_system(std::size_t capacity)
    requires(sizeof...(Forces) > 0)
      : particle_system(capacity, Forces<T>{}...) {}
  /// A system that holds up to `capacity` particles, with the forces' parameters.
  /// A capacity of 0 or above max_capacity is refused before any column is allocated.
  explicit particle_system(std::size_t capacity, Forces<T>... forces)
      : forces_(std::move(forces)...),
        capacity_(checked_capacity(capacity)),
        stride_((capacity + width - 1) / width * width),
        x_(stride_), y_(stride_), z_(stride_), vx_(stride_), vy_(stride_), vz_(stride_),
        inverse_mass_(has_masses ? stride_ : 0),
        variation_(needs_variation ? stride_ : 0),
        age_(has_lifetime ? stride_ : 0),
        lifetime_(has_lifetime ? stride_ : 0),
        died_(has_lifetime ? stride_ / width : 0),
        staged_(has_pairwise ? staged_columns * stride_ : 0) {}

  // ---- particles --------------------------------------------------------------

  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  [[nodiscard]] std::size_t capacity() const noexcept { return capacity_; }
  [[nodiscard]] bool empty() const noexcept { return size_ == 0; }

  /// Adds a particle and returns its index. Lifetime in s (has_lifetime only);
  /// an infinite lifetime never dies. Without has_masses the mass must be 1.
  std::uint32_t add(const vec3<T>& position, const vec3<T>& velocity = {}, T mass = T(1),
                    T lifetime = std::numeric_limits<T>::infinity()) {
    check_particle(position, velocity, mass, no_object);
    detail::require(lifetime > T(0), error_code::invalid_parameter,
                    "particle_system: lifetime must be positive (infinity for none)");
    detail::require(size_ < capacity_, error_code::capacity_exceeded,
                    "particle_system: add() on a full system (capacity reached)");
    const std::size_t i = size_++;
    write(i, position, velocity, T(1) / mass, lifetime);
    return std::uint32_t(i);
  }

  /// Adds `count` particles drawn from the emitter's distribution now, as far
  /// as they fit; returns how many were added.
  std::size_t emit(emitter<T>& source, std::size_t count) {
    check_emitter(source, no_object);
    return emit_unchecked(source, count);
  }

  /// Removes particle i; the last particle takes its index.
  void kill(std::uint32_t i) {
    check_index(i);
    begin_removals();
    remove(i);
    end_removals();
  }

  /// Removes every particle (forces, planes and emitters stay).
  void clear() noexcept {
    size_ = 0;
    if constexpr (has_pairwise) std::get<pairwise_index()>(forces_).clear();
  }

  [[nodiscard]] vec3<T> position(std::uint32_t i) const { check_index(i); return {x_[i], y_[i], z_[i]}; }
  [[nodiscard]] vec3<T> velocity(std::uint32_t i) const { check_index(i); return {vx_[i], vy_[i], vz_[i]}; }
  [[nodiscard]] T mass(std::uint32_t i) const {
    check_index(i);
    if constexpr (has_masses) return T(1) / inverse_mass_[i];
    else return T(1);
  }
  [[nodiscard]] T age(std::uint32_t i) const requires has_lifetime { check_index(i); return age_[i]; }
  [[nodiscard]] T lifetime(std::uint32_t i) const requires has_lifetime { check_index(i); return lifetime_[i]; }

  void set_position(std::uint32_t i, const vec3<T>& p) {
    check_index(i);
    detail::require_finite(p, "particle_system: position is not finite", i);
    x_[i] = p.x, y_[i] = p.y, z_[i] = p.z;
  }
  void set_velocity(std::uint32_t i, const vec3<T>& v) {
    check_index(i);
    detail::require_finite(v, "particle_system: velocity is not finite", i);
    vx_[i] = v.x, vy_[i] = v.y, vz_[i] = v.z;
  }
  void set_mass(std::uint32_t i, T m) requires has_masses {
    check_index(i);
    check_mass(m, i);
    inverse_mass_[i] = T(1) / m;
  }

  [[nodiscard]] vec3_columns<T> positions() const noexcept { return {column(x_), column(y_), column(z_)}; }
  [[nodiscard]] vec3_columns<T> velocities() const noexcept { return {column(vx_), column(vy_), column(vz_)}; }
  [[nodiscard]] std::span<const T> inverse_masses() const noexcept requires has_masses {
    return column(inverse_mass_);
  }
  [[nodiscard]] std::span<const T> ages() const noexcept requires has_lifetime { return column(age_); }
  [[nodiscard]] std::span<const T> lifetimes() const noexcept requires has_lifetime { return column(lifetime_); }

  // ---- forces, planes, emitters ---------------------------------------------------

  /// The parameters of force F (one of the system's force list).
  template <template <class> class F>
  F<T>& force() noexcept { return std::get<F<T>>(forces_); }
  template <template <class> class F>
  const F<T>& force() const noexcept { return std::get<F<T>>(forces_); }

  /// Adds a plane; it must be valid now, and is checked again at every step.
  std::uint32_t add_plane(const plane_collider<T>& plane) {
    plane.validate(std::uint32_t(planes_.size()));
    planes_.push_back(plane);
    return std::uint32_t(planes_.size() - 1);
  }
  /// Removes every plane.
  void clear_planes() noexcept { planes_.clear(); }
  std::span<plane_collider<T>> planes() noexcept { return planes_; }
  std::span<const plane_collider<T>> planes() const noexcept { return planes_; }

  std::uint32_t add_emitter(const emitter<T>& source) {
    check_emitter(source, std::uint32_t(emitters_.size()));
    emitters_.push_back(source);
    return std::uint32_t(emitters_.size() - 1);
  }
  std::span<emitter<T>> emitters() noexcept { return emitters_; }
  std::span<const emitter<T>> emitters() const noexcept { return emitters_; }

  /// Simulated time, s: the sum of the steps taken.
  [[nodiscard]] double time() const noexcept { return time_; }

  // ---- threads ----------------------------------------------------------------------

  /// Steps the batches (and the springs) across the hook's workers
  /// (core/task_system.hpp); the default runs on the calling thread. The
  /// particles come out bit-identical for any worker count.
  void set_task_system(const task_system& tasks) {
    detail::require(tasks.workers >= 1, error_code::invalid_parameter,
                    "particle_system: a task system needs at least one worker");
    detail::require((tasks.enqueue == nullptr) == (tasks.finish == nullptr), error_code::invalid_parameter,
                    "particle_system: a task system needs both enqueue and finish, or neither");
    tasks_ = tasks;
  }
  [[nodiscard]] const task_system& tasks() const noexcept { return tasks_; }

  // ---- stepping ---------------------------------------------------------------------

  /// Advances every particle by dt seconds: forces and integration, planes,
  /// ageing and death, then emission. Every parameter is checked first; on a
  /// bad one nothing moves.
  /// (Defined after the class, not inline: IMPULSE_DECLARE_PARTICLE_SYSTEM
  /// then keeps the kernel out of other translation units.)
  void step(T dt);

 private:
  // ---- the kernel -----------------------------------------------------------------

  /// The columns' starts, null for those this configuration lacks (known
  /// at compile time). A loop over batches takes them once, as a local,
  /// and indexes them by the batch's first particle: stores to the columns
  /// may alias anything (they are copies of bytes), so GCC reloaded the
  /// pointers from the system at every batch, and a per-batch struct of
  /// ten pointers was built through the stack.
  struct columns_start {
    T *x, *y, *z, *vx, *vy, *vz, *inverse_mass, *variation, *age, *lifetime;
  };
  columns_start start_of_columns() noexcept {
    columns_start s{x_.data(), y_.data(), z_.data(), vx_.data(), vy_.data(), vz_.data(),
                    nullptr, nullptr, nullptr, nullptr};
    if constexpr (has_masses) s.inverse_mass = inverse_mass_.data();
    if constexpr (needs_variation) s.variation = variation_.data();
    if constexpr (has_lifetime) s.age = age_.data(), s.lifetime = lifetime_.data();
    return s;
  }

  /// Whether one of the forces from index `from` on has this effect.
  static constexpr bool any_effect(force_effect effect, std::size_t from = 0) noexcept {
    constexpr std::array<force_effect, sizeof...(Forces)> effects{Forces<T>::effect...};
    for (std::size_t i = from; i < effects.size(); ++i)
      if (effects[i] == effect) return true;
    return false;
  }

  /// A force's term (evaluate_portable under cross_platform_determinism, where the force has it); add_term adds
  /// the I-th to the accelerations or forces, from the last force to the first, the first assigned: no zero added.
  template <class F>
  [[gnu::always_inline]] static state term_of(const F& f, const state& x, const state& v,
                                              const particle_lanes<T, width>& p) noexcept {
    if constexpr (cross_platform_determinism && requires { f.evaluate_portable(x, v, p); })
      return f.evaluate_portable(x, v, p);
    return f.evaluate(x, v, p);
  }

  template <std::size_t I>
  [[gnu::always_inline]] static void add_term(const std::tuple<Forces<T>...>& forces, const state& x,
                                              const state& v, const particle_lanes<T, width>& p, state& accel,
                                              state& force) noexcept {
    using F = std::tuple_element_t<I, std::tuple<Forces<T>...>>;
    if constexpr (F::effect == force_effect::acceleration) {
      const state term = term_of(std::get<I>(forces), x, v, p);
      if constexpr (any_effect(force_effect::acceleration, I + 1)) accel = accel + term;
      else accel = term;
    } else if constexpr (F::effect == force_effect::force) {
      const state term = term_of(std::get<I>(forces), x, v, p);
      if constexpr (any_effect(force_effect::force, I + 1)) force = force + term;
      else force = term;
    }
  }

  /// Acceleration of a batch: the accelerations as they are plus the forces
  /// over the mass. Only the listed forces are compiled in. Always inlined:
  /// called four times a step by RK4, GCC 12 outlined it, and each call
  /// passed six batches and returned three through memory (35 % of RK4's
  /// time in float). No lambda: one capturing x and v by reference made
  /// GCC keep the kernel's whole state in memory, stored and reloaded
  /// around the planes in every batch. Last to first: the standard scene
  /// lists point_forces, a loop over runtime attractors, last, so that
  /// drag's product then fuses into the sum after the loop (GCC fuses a
  /// multiply and an add only within one basic block): 1-4 %.
  template <std::size_t... I>
  [[gnu::always_inline]] static state acceleration(std::index_sequence<I...>,
                                                  const std::tuple<Forces<T>...>& forces, const state& x,
                                                  const state& v, const lanes& inverse_mass,
                                                  const particle_lanes<T, width>& p) noexcept {
    constexpr bool have_accel = any_effect(force_effect::acceleration);
    constexpr bool have_force = any_effect(force_effect::force);
    state accel{}, force{};
    constexpr std::size_t last = sizeof...(Forces) - 1;
    (add_term<last - I>(forces, x, v, p, accel, force), ...);
    if constexpr (!have_force) return have_accel ? accel : state::broadcast({});
    else if constexpr (!have_accel) return force * inverse_mass;
    else return accel + force * inverse_mass;
  }
  [[gnu::always_inline]] static state acceleration(const std::tuple<Forces<T>...>& forces, const state& x,
                                                  const state& v, const lanes& inverse_mass,
                                                  const particle_lanes<T, width>& p) noexcept {
    return acceleration(std::index_sequence_for<Forces<T>...>{}, forces, x, v, inverse_mass, p);
  }

  lanes load_inverse_mass(const columns_start& c, std::size_t first) const noexcept {
    if constexpr (needs_inverse_mass) return lanes::load(c.inverse_mass + first);
    else return lanes::broadcast(T(1));
  }
  particle_lanes<T, width> load_lanes(const columns_start& c, std::size_t first) const noexcept {
    if constexpr (needs_variation) return {lanes::load(c.variation + first)};
    else return {lanes::broadcast(T(0))};
  }

  /// Planes, then age: the part of a step after integration. The batch's
  /// columns still hold where it started the step until x and v are stored
  /// here. Flags the batch when a particle in it died (a flag per batch, so
  /// that workers never write the same place).
  [[gnu::always_inline]] void finish_batch(const columns_start& c, std::size_t first, state& x, state& v,
                                           T dt) {
    if (!planes_.empty()) collide(first, x, v);
    x.store(c.x + first, c.y + first, c.z + first);
    v.store(c.vx + first, c.vy + first, c.vz + first);
    if constexpr (has_lifetime) {
      const lanes age = lanes::load(c.age + first) + dt;
      age.store(c.age + first);
      died_[first / width] = any(age >= lanes::load(c.lifetime + first));
    }
  }

  /// A batch's x and v stored for the rare paths below, which are not
  /// inlined and read the start of the step from the columns. Passed a
  /// state by reference instead, even a copy, GCC 12 kept it in memory for
  /// the whole kernel: six stores and six loads a batch more, on the common
  /// path too. Keeping the start of the step in registers for them spilled
  /// with AVX2's 16.
  /// Always inlined, and stored lane column by lane column: GCC 12 kept
  /// both the constructor and vec3_batch::store out of line, and x and v,
  /// their addresses passed to them, then lived on the stack through the
  /// planes' loop (the AVX2 kernel, 16 registers).
  struct parked {
    alignas(64) T rows[6][width];
    [[gnu::always_inline]] parked(const state& x, const state& v) noexcept { put(x, v); }
    [[gnu::always_inline]] void put(const state& x, const state& v) noexcept {
      x.x.store(rows[0]), x.y.store(rows[1]), x.z.store(rows[2]);
      v.x.store(rows[3]), v.y.store(rows[4]), v.z.store(rows[5]);
    }
    [[gnu::always_inline]] state position() const noexcept { return state::load(rows[0], rows[1], rows[2]); }
    [[gnu::always_inline]] state velocity() const noexcept { return state::load(rows[3], rows[4], rows[5]); }
  };

  /// Where the batch at `first` started the step: its columns, before
  /// finish_batch stores into them.
  state start_of_step(std::size_t first) const noexcept {
    return state::load(x_.data() + first, y_.data() + first, z_.data() + first);
  }

  /// The planes: rectangles, then half-spaces, then the creases between
  /// them when a projection may have left a lane behind another plane.
  [[gnu::always_inline]] void collide(std::size_t first, state& x, state& v) const noexcept {
    if (any_rectangle_) {
      parked p(x, v);
      collide_rectangles(first, p);
      x = p.position(), v = p.velocity();
    }
    // Moving a lane out of plane k along n_k lowers its distance to plane j
    // only if n_j·n_k < 0; only then can it leave the lane behind a plane j
    // checked before k (risky_[k]). The floor and its walls meet at right
    // angles, so most contacts skip the check below.
    bool check = false;
    for (const detail::half_space_rule<T>& h : half_spaces_)
      if (detail::collide_half_space(h, x, v)) check |= h.risky;
    if (!check) return;
    parked p(x, v);
    settle_creases(first, p);
    x = p.position(), v = p.velocity();
  }

  [[gnu::noinline]] void collide_rectangles(std::size_t first, parked& p) const noexcept {
    const state x0 = start_of_step(first);
    state x = p.position(), v = p.velocity();
    for (const plane_collider<T>& plane : planes_)
      if (plane.finite) detail::collide_rectangle(plane, x0, x, v);
    p.put(x, v);
  }

  [[gnu::noinline]] void settle_creases(std::size_t first, parked& p) const noexcept {
    const state x0 = start_of_step(first);
    state x = p.position(), v = p.velocity();
    detail::settle_creases(std::span<const plane_collider<T>>(planes_), crease_.data(), x0, x, v);
    p.put(x, v);
  }

  /// Batches per range of a parallel loop: 64 batches of the standard
  /// scene take about 2 µs in float Euler, as long as handing a range to a
  /// worker can take.
  static constexpr std::uint32_t min_batches = 64;

  /// Runs body(first, end) over the used batches' particle indices, split
  /// across the task system's workers.
  template <class Body>
  void for_batches(const Body& body) {
    auto ranges = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      body(std::size_t(begin) * width, std::size_t(end) * width);
    };
    impulse::detail::parallel_for(tasks_, std::uint32_t(padded(size_) / width), min_batches, ranges);
  }

  void step_fused(T dt) {
    for_batches([this, dt](std::size_t begin, std::size_t end) { step_batches(begin, end, dt); });
  }

  /// The fused kernel over particles [begin, end), whole batches.
  void step_batches(std::size_t begin, std::size_t end, T dt) {
    // The forces' parameters, copied: the columns hold T too, so a store
    // to a column could otherwise be taken to change them.
    const std::tuple<Forces<T>...> forces = forces_;
    const columns_start c = start_of_columns();
    for (std::size_t first = begin; first < end; first += width) {
      state x = state::load(c.x + first, c.y + first, c.z + first);
      state v = state::load(c.vx + first, c.vy + first, c.vz + first);
      const lanes inverse_mass = load_inverse_mass(c, first);
      const particle_lanes<T, width> p = load_lanes(c, first);
      integrator::step(x, v, dt, [&](const state& xs, const state& vs) __attribute__((always_inline)) {
        return acceleration(forces, xs, vs, inverse_mass, p);
      });
      finish_batch(c, first, x, v, dt);
    }
  }

  // ---- the staged step, for springs ------------------------------------------------

  /// A spring pulls with both its ends at the same stage of the step, so
  /// each of the integrator's stages is two loops over the system with a
  /// barrier between: the springs' forces, from every particle's state at
  /// that stage, then, batch by batch, its acceleration at that stage and
  /// the integrator run on to the next stage's state (or to the end of the
  /// step, at the last). Each batch runs the integrator from the start of
  /// the step and is handed back the accelerations of the stages before,
  /// as stored, so any integrator works unchanged (it must call the
  /// acceleration exactly `stages` times, as its policy states) and a step
  /// is 2 × stages loops: Euler's 2, RK4's 8.
  static constexpr int stages = integrator::stages;
  /// staged_: the next stage's positions and velocities (6 columns, when
  /// there is a next stage), then each stage's accelerations (3 each).
  static constexpr std::size_t staged_columns = (stages > 1 ? 6 : 0) + 3 * std::size_t(stages);

  // Not `requires has_pairwise`: clang 14 compiles a constrained member in
  // an explicit instantiation (IMPULSE_INSTANTIATE_PARTICLE_SYSTEM) even
  // when the constraint is false; the discarded branch it does not.
  void step_staged(T dt) {
    if constexpr (has_pairwise)
      [&]<int... S>(std::integer_sequence<int, S...>) {
        (stage<S>(dt), ...);
      }(std::make_integer_sequence<int, stages>{});
  }

  template <int S>
  void stage(T dt) {
    auto& pairwise = std::get<pairwise_index()>(forces_);
    const columns_start c = start_of_columns();
    const T* next = staged_.data();
    using columns3 = std::array<const T*, 3>;
    const columns3 x = S == 0 ? columns3{c.x, c.y, c.z} : columns3{next, next + stride_, next + 2 * stride_};
    const columns3 v = S == 0 ? columns3{c.vx, c.vy, c.vz}
                              : columns3{next + 3 * stride_, next + 4 * stride_, next + 5 * stride_};
    auto spring_forces = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      pairwise.compute_forces(begin, end, x, v);
    };
    impulse::detail::parallel_for(tasks_, std::uint32_t(pairwise.groups()), min_batches, spring_forces);
    constexpr std::size_t block = std::tuple_element_t<pairwise_index(), decltype(forces_)>::block;
    for_batches([&](std::size_t begin, std::size_t end) {
      for (std::size_t low = begin, high; low < end; low = high) {
        high = std::min(end, (low / block + 1) * block);
        pairwise.set_accelerations(low, high, has_masses ? c.inverse_mass : nullptr, stride_, accelerations(S));
        for (std::size_t first = low; first < high; first += width) run_stage<S>(c, x, v, first, dt);
      }
    });
  }

  T* accelerations(int stage) noexcept {
    return staged_.data() + ((stages > 1 ? 6 : 0) + 3 * std::size_t(stage)) * stride_;
  }

  /// A batch's integrator from the start of the step up to stage S: the
  /// stages before are handed their stored accelerations; stage S's is
  /// worked out here from its state (x, v) and the springs' part of it
  /// already in its columns; the next stage's state is stored for the
  /// springs, or, at the last stage, the step finished.
  template <int S>
  [[gnu::always_inline]] void run_stage(const columns_start& c, const std::array<const T*, 3>& x,
                                        const std::array<const T*, 3>& v, std::size_t first, T dt) {
    state xb = state::load(c.x + first, c.y + first, c.z + first);
    state vb = state::load(c.vx + first, c.vy + first, c.vz + first);
    int call = 0;
    integrator::step(xb, vb, dt, [&](const state& xs, const state& vs) __attribute__((always_inline)) {
      const int j = call++;
      if (j < S) return load_from(accelerations(j), first);
      if (j == S) {
        const state at = state::load(x[0] + first, x[1] + first, x[2] + first);
        const state moving = state::load(v[0] + first, v[1] + first, v[2] + first);
        const state a = acceleration(forces_, at, moving, load_inverse_mass(c, first), load_lanes(c, first)) +
                        load_from(accelerations(S), first);
        if constexpr (S + 1 < stages) a.store(accelerations(S) + first, accelerations(S) + stride_ + first,
                                              accelerations(S) + 2 * stride_ + first);
        return a;
      }
      if (j == S + 1) {
        T* next = staged_.data();
        xs.store(next + first, next + stride_ + first, next + 2 * stride_ + first);
        vs.store(next + 3 * stride_ + first, next + 4 * stride_ + first, next + 5 * stride_ + first);
      }
      return state::broadcast({});
    });
    IMPULSE_ASSERT(S + 1 < stages || call == stages);  // the policy's `stages` is its evaluations
    if constexpr (S + 1 == stages) finish_batch(c, first, xb, vb, dt);
  }

  state load_from(const T* columns, std::size_t first) const noexcept {
    return state::load(columns + first, columns + stride_ + first, columns + 2 * stride_ + first);
  }

  static constexpr std::size_t pairwise_index() {
    std::size_t index = 0, i = 0;
    ((is_pairwise<Forces<T>> ? (index = i, ++i) : ++i), ...);
    return index;
  }

  /// Which pairs of half-spaces can form a crease (not parallel, where
  /// 1 − c² would vanish and one projection settles both anyway), and which
  /// planes can push a lane behind an earlier one. Planes can be edited
  /// between steps, so this is redone (k² dot products) each step.
  void prepare_planes() {
    const std::size_t k = planes_.size();
    crease_.assign(k * k, 0);
    risky_.assign(k, 0);
    any_rectangle_ = false;
    for (const plane_collider<T>& plane : planes_) any_rectangle_ |= plane.finite;
    half_spaces_.clear();
    for (std::size_t a = 0; a < k; ++a)
      for (std::size_t b = 0; b < k; ++b) {
        if (a == b || planes_[a].finite || planes_[b].finite) continue;
        const T c = dot(planes_[a].normal, planes_[b].normal);
        crease_[a * k + b] = std::abs(c) < T(1) - T(1e-3);
        if (b < a && c < T(0)) risky_[a] = 1;
      }
    for (std::size_t a = 0; a < k; ++a)
      if (!planes_[a].finite) half_spaces_.push_back(detail::half_space_rule<T>::of(planes_[a], risky_[a] != 0));
  }

  // ---- storage upkeep -----------------------------------------------------------

  std::size_t padded(std::size_t n) const noexcept { return (n + width - 1) / width * width; }

  /// The lanes past the last particle in its batch are computed with it and
  /// thrown away. They hold copies of the last particle, so they stay finite
  /// and cost nothing special; they never die (infinite lifetime).
  void fill_padding() noexcept {
    const std::size_t last = size_ - 1, end = padded(size_);
    for (aligned_array<T>* column : columns())
      for (std::size_t i = size_; i < end; ++i) (*column)[i] = (*column)[last];
    if constexpr (has_lifetime)
      for (std::size_t i = size_; i < end; ++i) lifetime_[i] = std::numeric_limits<T>::infinity();
  }

  std::array<aligned_array<T>*, 10> all_columns() noexcept {
    return {&x_, &y_, &z_, &vx_, &vy_, &vz_, &inverse_mass_, &variation_, &age_, &lifetime_};
  }
  /// The columns this configuration stores.
  std::span<aligned_array<T>*> columns() noexcept {
    columns_ = all_columns();
    std::size_t n = 0;
    for (aligned_array<T>* c : columns_)
      if (c->size() != 0) columns_[n++] = c;
    return {columns_.data(), n};
  }

  void write(std::size_t i, const vec3<T>& p, const vec3<T>& v, T inverse_mass, T lifetime) noexcept {
    x_[i] = p.x, y_[i] = p.y, z_[i] = p.z;
    vx_[i] = v.x, vy_[i] = v.y, vz_[i] = v.z;
    if constexpr (has_masses) inverse_mass_[i] = inverse_mass;
    if constexpr (needs_variation) variation_[i] = hash_signed_unit<T>(serial_);
    ++serial_;
    if constexpr (has_lifetime) age_[i] = T(0), lifetime_[i] = lifetime;
  }

  std::size_t emit_unchecked(emitter<T>& source, std::size_t count) {
    const std::size_t room = capacity_ - size_, fit = count < room ? count : room;
    for (std::size_t k = 0; k < fit; ++k) {
      const auto d = source.next();
      write(size_++, d.position, d.velocity, T(1) / source.mass, d.lifetime);
    }
    source.dropped += count - fit;
    return fit;
  }

  // Removal keeps the columns dense: the last particle moves into the hole.
  // With springs, origin_ records which original particle each slot holds
  // so that the springs can be re-pointed once, after all the moves.
  void begin_removals() {
    if constexpr (has_pairwise) {
      origin_.resize(size_);
      for (std::size_t i = 0; i < size_; ++i) origin_[i] = std::uint32_t(i);
      removed_from_ = size_;
    }
  }
  void remove(std::size_t i) noexcept {
    const std::size_t last = --size_;
    if (i != last)
      for (aligned_array<T>* column : columns()) (*column)[i] = (*column)[last];
    if constexpr (has_pairwise) origin_[i] = origin_[last];
  }
  void end_removals() {
    if constexpr (has_pairwise) {
      remap_.assign(removed_from_, no_object);
      for (std::size_t i = 0; i < size_; ++i) remap_[origin_[i]] = std::uint32_t(i);
      std::get<pairwise_index()>(forces_).remap(remap_.data());
    }
  }

  /// Particles whose age reached their lifetime this step. Batches are
  /// visited from the end so that the particle moved into a hole is always
  /// one already known to be alive.
  void remove_dead() requires has_lifetime {
    const std::size_t batches = padded(size_) / width;
    std::size_t b = batches;
    while (b > 0 && !died_[b - 1]) --b;
    if (b == 0) return;
    begin_removals();
    for (; b > 0; --b) {
      if (!died_[b - 1]) continue;
      for (int lane = width - 1; lane >= 0; --lane) {
        const std::size_t i = (b - 1) * width + std::size_t(lane);
        if (i < size_ && age_[i] >= lifetime_[i]) remove(i);
      }
    }
    end_removals();
  }

  // ---- checks ---------------------------------------------------------------------

  void check_index(std::uint32_t i) const {
    detail::require(i < size_, error_code::out_of_range, "particle_system: no particle has this index", i);
  }
  /// The capacity, once it is known to be allowed: called from the member
  /// initialisers ahead of the columns, so that a refused capacity allocates
  /// nothing (members are initialised in declaration order).
  static std::size_t checked_capacity(std::size_t capacity) {
    detail::require(capacity != 0 && capacity <= max_capacity, error_code::invalid_parameter,
                    "particle_system: capacity must be between 1 and max_capacity (2^26)");
    if constexpr (cross_platform_determinism)
      detail::require(!impulse::detail::contraction_in_effect(), error_code::invalid_parameter,
                      impulse::detail::contraction_message);
    return capacity;
  }
  static void check_mass(T mass, std::uint32_t i) {
    detail::require_finite(mass, "particle_system: mass is not finite", i);
    detail::require(mass > T(0), error_code::non_positive_mass, "particle_system: mass must be positive", i);
    detail::require(mass >= min_particle_mass<T>, error_code::invalid_parameter,
                    "particle_system: mass is below min_particle_mass (denormal: its inverse overflows)", i);
    if constexpr (!has_masses)
      detail::require(mass == T(1), error_code::invalid_parameter,
                      "particle_system: this configuration stores no masses (Config::particle_masses is "
                      "false), so every particle's mass is 1",
                      i);
  }
  static void check_emitter(const emitter<T>& source, std::uint32_t index) {
    source.validate(index);
    check_mass(source.mass, index);
  }
  static void check_particle(const vec3<T>& p, const vec3<T>& v, T mass, std::uint32_t i) {
    detail::require_finite(p, "particle_system: position is not finite", i);
    detail::require_finite(v, "particle_system: velocity is not finite", i);
    check_mass(mass, i);
  }

  void validate(T dt) const {
    detail::require(std::isfinite(dt) && dt > T(0), error_code::invalid_parameter,
                    "particle_system: step() needs a finite, positive dt");
    // The springs' ends are checked by their prepare() in step().
    auto check = [&](const auto& f) {
      if constexpr (!is_pairwise<std::remove_cvref_t<decltype(f)>>) f.validate();
    };
    std::apply([&](const auto&... f) { (check(f), ...); }, forces_);
    for (std::size_t i = 0; i < planes_.size(); ++i) planes_[i].validate(std::uint32_t(i));
    for (std::size_t i = 0; i < emitters_.size(); ++i) check_emitter(emitters_[i], std::uint32_t(i));
  }

  std::span<const T> column(const aligned_array<T>& c) const noexcept { return {c.data(), size_}; }

  std::tuple<Forces<T>...> forces_;
  std::size_t capacity_, stride_, size_ = 0;
  aligned_array<T> x_, y_, z_, vx_, vy_, vz_, inverse_mass_, variation_, age_, lifetime_;
  std::vector<plane_collider<T>> planes_;
  std::vector<unsigned char> crease_, risky_;
  bool any_rectangle_ = false;  // whether a plane is a rectangle (prepare_planes)
  /// The half-spaces in the kernel's terms, made once a step
  /// (prepare_planes): the loop over them reads 24 bytes a plane and no
  /// flag, where it read each plane_collider's 60 and tested `finite`.
  std::vector<detail::half_space_rule<T>> half_spaces_;
  std::vector<emitter<T>> emitters_;
  /// Per batch, whether a particle in it died this step (has_lifetime only).
  std::vector<unsigned char> died_;
  task_system tasks_{};
  std::array<aligned_array<T>*, 10> columns_{};
  std::vector<std::uint32_t> origin_, remap_;
  std::size_t removed_from_ = 0;
  aligned_array<T> staged_;
  std::uint32_t serial_ = 0;
  double time_ = 0;
};

template <class Config, template <class> class... Forces>
void particle_system<Config, Forces...>::step(T dt) {
  validate(dt);
  if constexpr (has_pairwise) std::get<pairwise_index()>(forces_).prepare(size_, tasks_);
  prepare_planes();
  if (size_ != 0) {
    fill_padding();
    if constexpr (has_pairwise) step_staged(dt);
    else step_fused(dt);
    if constexpr (has_lifetime) remove_dead();
  }
  for (emitter<T>& source : emitters_) emit_unchecked(source, source.due(dt));
  time_ += double(dt);
}

}  // namespace impulse::particles

namespace impulse {
using particles::particle_system;
}  // namespace impulse
