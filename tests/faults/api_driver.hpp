// A randomized driver of the world's whole interface, for the fault suite
// (test_api_driver.cpp) and its libFuzzer entry (tests/fuzz/world_fuzz.cpp).
//
// Each call is chosen, and its arguments made, from a stream of 32-bit
// numbers: a seeded generator in the test, the fuzzer's bytes in the
// fuzzer. Arguments are mostly sensible and sometimes hostile: NaN,
// infinities, 1e30, the largest float, denormals, zero and negative sizes,
// stale and made-up ids. After every call the driver checks the promises
// of docs/world.md:
//
//   - a call refuses only with impulse::invalid_argument;
//   - a refused call leaves the world as it was (state_hash);
//   - no body becomes non-finite, whatever finite input was accepted;
//   - a step that holds a body (non_finite) names a body it held.
//
// A broken promise is reported through the `fail` callback with the call's
// number and name, so the test can print it and the fuzzer can abort.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "../world/scenes.hpp"
#include "impulse/world.hpp"

namespace impulse::test {

/// FNV-1a over everything a call could change: each body's id, type,
/// pose, momenta, loads, awake flag and kinematic velocities; each joint's
/// id, state, motor and limits; the settings that calls set; time.
template <class World>
std::uint64_t state_hash(const World& w) {
  using T = typename World::scalar;
  std::uint64_t h = 1469598103934665603ull;
  const auto mix = [&](const auto& value) {
    unsigned char bytes[sizeof value];
    std::memcpy(bytes, &value, sizeof value);
    for (const unsigned char b : bytes) h = (h ^ b) * 1099511628211ull;
  };
  const auto mix_vec = [&](const impulse::vec3<T>& v) { mix(v.x), mix(v.y), mix(v.z); };
  mix(w.body_count());
  for (const impulse::body_id id : w.body_ids()) {
    const auto& b = w.body(id);
    mix(id.index), mix(id.generation), mix(int(b.type)), mix(w.is_awake(id));
    mix_vec(b.position), mix(b.orientation.x), mix(b.orientation.y), mix(b.orientation.z), mix(b.orientation.w);
    mix_vec(b.linear_momentum), mix_vec(b.angular_momentum), mix_vec(b.force), mix_vec(b.torque);
    mix_vec(b.kinematic_velocity), mix_vec(b.kinematic_angular_velocity);
  }
  mix(w.joint_count());
  for (const impulse::joint_id id : w.joint_ids()) {
    const impulse::joint_def<T>& d = w.joint(id);
    mix(id.index), mix(id.generation), mix(w.is_broken(id)), mix(d.enable_motor), mix(d.motor_speed);
    mix(d.max_motor_force), mix(d.enable_limit), mix(d.lower), mix(d.upper);
  }
  const auto& s = w.settings();
  mix_vec(s.gravity), mix(s.fixed_dt), mix(s.max_linear_speed), mix(s.max_angular_speed);
  mix(s.max_contact_pairs), mix(s.solver.velocity_iterations), mix(s.solver.speculative_distance);
  mix(w.time()), mix(w.step_count());
  return h;
}

/// SplitMix64: the test's stream of numbers. (A linear congruential
/// generator's low bits repeat with short periods, and the driver takes
/// its choices modulo small numbers.)
struct splitmix {
  std::uint64_t state;
  std::uint32_t operator()() noexcept {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return std::uint32_t((z ^ (z >> 31)) >> 32);
  }
};

/// The driver. Next is a callable returning std::uint32_t; Fail takes the
/// call number, the call's name and what went wrong.
template <class World>
class api_driver {
 public:
  using T = typename World::scalar;
  /// How many bodies the driver keeps at most: enough for heaps, stacks and
  /// joint chains, few enough that a step stays cheap under a sanitizer.
  static constexpr std::size_t max_bodies = 24;

  /// Calls made, refused (invalid_argument), and steps that held a body.
  struct counts {
    std::uint64_t calls = 0, refused = 0, held_steps = 0, steps = 0;
    std::uint64_t body_steps = 0;  ///< bodies summed over the steps: how full the world was
    std::array<std::uint64_t, 24> refused_by_call{};
  };

  template <class Next, class Fail>
  void run(std::uint64_t calls, Next&& next, Fail&& fail) {
    for (std::uint64_t n = 0; n < calls; ++n) {
      const std::uint32_t op = next() % 24;
      hostile_ = next() % 4 == 0;
      const std::uint64_t before = state_hash(world_);
      bool refused = false, held = false, other = false;
      impulse::error_code code = impulse::error_code::none;
      try {
        call(op, next);
      } catch (const impulse::invalid_argument& e) {
        code = e.code();
        error_ = e.what();
        // A step that held a body reports it after the step, which ran: not
        // a refusal (docs/world.md). Every other throw refuses the call.
        if (op >= op_step && op <= op_advance && code == impulse::error_code::non_finite &&
            !world_.held_bodies().empty()) {
          held = true;
          bool named = false;
          for (const impulse::body_id id : world_.held_bodies()) named = named || id.index == e.object();
          if (!named) fail(n, name(op), "the step's error names a body it did not hold");
        } else {
          refused = true;
        }
      } catch (...) {
        other = true;
      }
      ++counts_.calls;
      if (op >= op_step && op < op_advance) counts_.body_steps += world_.body_count();
      counts_.refused += refused;
      counts_.refused_by_call[op] += refused;
      counts_.held_steps += held;
      if (other) fail(n, name(op), "threw something other than impulse::invalid_argument");
      if (refused && state_hash(world_) != before)
        fail(n, name(op), ("a refused call changed the world: " + error_).c_str());
      if (!all_finite(world_)) fail(n, name(op), "a body became non-finite");
      if (std::exchange(reentry_accepted_, false))
        fail(n, name(op), "a call that changes the world's containers was accepted inside a callback");
      forget_dead();
    }
  }

  [[nodiscard]] const counts& tally() const noexcept { return counts_; }
  [[nodiscard]] const World& world() const noexcept { return world_; }

 private:
  enum op_code : std::uint32_t {
    op_create = 0,  // 0–3: the most common, so the world fills
    op_destroy = 4,
    op_joint = 5,
    op_destroy_joint = 6,
    op_velocity = 7,
    op_pose = 8,
    op_target = 9,
    op_force = 10,
    op_force_at = 11,
    op_torque = 12,
    op_impulse = 13,
    op_step = 14,  // 14–16: steps
    op_advance = 17,
    op_snapshot = 18,
    op_query = 19,
    op_motor = 20,
    op_settings = 21,
    op_callback = 22,
    op_wake = 23,
  };

  static const char* name(std::uint32_t op) {
    static constexpr std::array<const char*, 24> names{
        "create_body", "create_body", "create_body", "create_body", "destroy_body",  "create_joint",
        "destroy_joint", "set_velocity", "set_pose", "set_target_pose", "apply_force", "apply_force_at",
        "apply_torque", "apply_impulse_at", "step", "step", "step", "advance", "snapshot/restore",
        "queries", "motor/limits", "settings", "callback re-entry", "wake/set_filter"};
    return names[op % 24];
  }

  /// A scalar within ±scale; in a hostile call, a third of them are not.
  template <class Next>
  T real(Next& next, T scale) {
    const std::uint32_t r = next();
    switch (hostile_ ? r % 27 : 9) {
      case 0: return std::numeric_limits<T>::quiet_NaN();
      case 1: return std::numeric_limits<T>::infinity();
      case 2: return -std::numeric_limits<T>::infinity();
      case 3: return std::numeric_limits<T>::max();
      case 4: return T(1e30);
      case 5: return T(-1e30);
      case 6: return std::numeric_limits<T>::denorm_min();
      case 7: return T(0);
      case 8: return T(1e7);
      default: return scale * (T((r >> 5) % 20001) / T(10000) - T(1));  // to 10⁻⁴ of the scale
    }
  }
  template <class Next>
  impulse::vec3<T> vector(Next& next, T scale) {
    const T x = real(next, scale), y = real(next, scale), z = real(next, scale);
    return {x, y, z};
  }
  /// A rotation: mostly a unit quaternion, sometimes not.
  template <class Next>
  impulse::quat<T> rotation(Next& next) {
    const std::uint32_t r = next();
    if (r % 16 == 0) return {real(next, T(2)), real(next, T(2)), real(next, T(2)), real(next, T(2))};
    const impulse::vec3<T> axis{T(r % 7) + T(0.1), T((r >> 3) % 5), T((r >> 6) % 3)};
    return impulse::quat<T>::from_axis_angle(impulse::normalize(axis), T((r >> 9) % 628) / T(100));
  }
  template <class Next>
  impulse::transform<T> pose(Next& next) {
    impulse::vec3<T> at = vector(next, T(8));
    if (next() % 4 != 0) at = {std::abs(at.x) < T(1e6) ? at.x : T(0), T(1) + std::abs(at.y) * T(0.5), at.z};
    return {at, rotation(next)};
  }
  /// A live body, a destroyed one, or a made-up id.
  template <class Next>
  impulse::body_id body(Next& next) {
    const std::uint32_t r = next();
    if (r % 16 == 0) return impulse::body_id{r >> 4, r & 3};
    if (r % 16 == 1 && !dead_.empty()) return dead_[(r >> 4) % dead_.size()];
    const auto ids = world_.body_ids();
    if (ids.empty()) return impulse::body_id{};
    return ids[(r >> 4) % ids.size()];
  }
  /// A live joint, a destroyed one, or a made-up id.
  template <class Next>
  impulse::joint_id joint(Next& next) {
    const std::uint32_t r = next();
    if (r % 8 == 1 && !dead_joints_.empty()) return dead_joints_[(r >> 3) % dead_joints_.size()];
    const auto ids = world_.joint_ids();
    if (ids.empty() || r % 8 == 0) return impulse::joint_id{r >> 3, r & 1};
    return ids[(r >> 3) % ids.size()];
  }

  /// One call. Arguments are drawn into named variables first: the order
  /// in which a call's arguments are evaluated is unspecified, and the same
  /// numbers must make the same calls under every compiler.
  template <class Next>
  void call(std::uint32_t op, Next& next) {
    switch (op) {
      case 0:
      case 1:
      case 2:
      case 3: create(next); break;
      case op_destroy: {
        const impulse::body_id id = body(next);
        const bool live = world_.contains(id);
        world_.destroy_body(id);
        if (live) dead_.push_back(id);
        break;
      }
      case op_joint: create_joint(next); break;
      case op_destroy_joint: {
        const impulse::joint_id id = joint(next);
        const bool live = world_.contains(id);
        world_.destroy_joint(id);
        if (live) dead_joints_.push_back(id);
        break;
      }
      case op_velocity: {
        const impulse::body_id id = body(next);
        const impulse::vec3<T> v = vector(next, T(20)), w = vector(next, T(20));
        world_.set_velocity(id, v, w);
        break;
      }
      case op_pose: {
        const impulse::body_id id = body(next);
        world_.set_pose(id, pose(next));
        break;
      }
      case op_target: {
        const impulse::body_id id = body(next);
        const impulse::transform<T> p = pose(next);
        world_.set_target_pose(id, p, next() % 8 == 0 ? real(next, T(1)) : T(1) / T(60));
        break;
      }
      case op_force: {
        const impulse::body_id id = body(next);
        world_.apply_force(id, vector(next, T(500)));
        break;
      }
      case op_force_at: {
        const impulse::body_id id = body(next);
        const impulse::vec3<T> f = vector(next, T(500)), p = vector(next, T(5));
        world_.apply_force_at(id, f, p);
        break;
      }
      case op_torque: {
        const impulse::body_id id = body(next);
        world_.apply_torque(id, vector(next, T(200)));
        break;
      }
      case op_impulse: {
        const impulse::body_id id = body(next);
        const impulse::vec3<T> j = vector(next, T(20)), p = vector(next, T(5));
        world_.apply_impulse_at(id, j, p);
        break;
      }
      case op_step:
      case op_step + 1:
      case op_step + 2: {
        ++counts_.steps;
        world_.step(next() % 16 == 0 ? real(next, T(0.1)) : T(1) / T(60));
        break;
      }
      case op_advance: (void)world_.advance(next() % 4 == 0 ? real(next, T(0.1)) : T(1) / T(30)); break;
      case op_snapshot:
        if (next() % 2 == 0 || !saved_) {
          saved_ = world_.snapshot();
        } else {
          world_.restore(*saved_);
        }
        break;
      case op_query: query(next); break;
      case op_motor: {
        const impulse::joint_id id = joint(next);
        const T a = real(next, T(3)), b = real(next, T(3)), c = real(next, T(100));
        if (next() % 2 == 0) {
          world_.set_joint_motor(id, next() % 2 == 0, a, std::abs(c));
        } else {
          world_.set_joint_limits(id, next() % 2 == 0, std::min(a, b), std::max(a, b));
        }
        break;
      }
      case op_settings: settings(next); break;
      case op_callback: reenter(next); break;
      case op_wake: {
        const impulse::body_id id = body(next);
        if (next() % 2 == 0) {
          world_.wake(id);
        } else {
          const impulse::collision_filter f = filter(next);
          world_.set_filter(id, f);
        }
        break;
      }
      default: break;
    }
  }

  template <class Next>
  void create(Next& next) {
    if (world_.body_count() >= max_bodies) {
      const impulse::body_id id = world_.body_ids()[next() % world_.body_count()];
      world_.destroy_body(id);
      dead_.push_back(id);
      return;
    }
    impulse::body_def<T> d;
    const std::uint32_t r = next();
    d.type = r % 8 == 0 ? impulse::body_type::static_body
                        : (r % 8 == 1 ? impulse::body_type::kinematic : impulse::body_type::dynamic);
    d.pose = pose(next);
    if (next() % 4 == 0) d.mass = real(next, T(10));
    if (next() % 4 == 0) d.material.density = real(next, T(2000));
    if (next() % 8 == 0) d.material.friction = real(next, T(1));
    if (next() % 8 == 0) d.material.restitution = real(next, T(1));
    if (next() % 4 == 0) d.linear_velocity = vector(next, T(10));
    if (next() % 4 == 0) d.angular_velocity = vector(next, T(10));
    d.bullet = next() % 16 == 0;
    d.sensor = next() % 16 == 0;
    if (next() % 8 == 0) d.filter = filter(next);
    const T size = next() % 16 == 0 ? real(next, T(1)) : T(0.1) + T(next() % 100) / T(100);
    switch (next() % 6) {
      case 0: world_.create_body(d, impulse::sphere<T>{size}); break;
      case 1: world_.create_body(d, impulse::box<T>{{size, size * T(0.5), size}}); break;
      case 2: world_.create_body(d, impulse::capsule<T>{size * T(0.5), size}); break;
      case 3: {
        const std::array<impulse::vec3<T>, 5> points{
            impulse::vec3<T>{0, 0, 0}, {size, 0, 0}, {0, size, 0}, {0, 0, size}, {size, size, size}};
        world_.create_body(d, impulse::convex_hull<T>::from_points(points));
        break;
      }
      case 4: {
        // A box and a ball beside it, the ball's place from the input.
        typename impulse::compound<T>::builder parts;
        parts.add(impulse::box<T>{{size, size * T(0.5), size}});
        parts.add(impulse::sphere<T>{size * T(0.7)}, {vector(next, T(2)), impulse::quat<T>::identity()});
        world_.create_body(d, parts.build());
        break;
      }
      default: {
        d.type = impulse::body_type::static_body;
        world_.create_body(d, impulse::plane<T>{impulse::normalize(impulse::vec3<T>{0, 1, T(0.1)}), T(0)});
        break;
      }
    }
  }

  template <class Next>
  void create_joint(Next& next) {
    const impulse::body_id a = body(next), b = body(next);
    const impulse::vec3<T> anchor = vector(next, T(6)), axis = vector(next, T(1));
    impulse::joint_def<T> d;
    switch (next() % 5) {
      case 0: d = impulse::joint_def<T>::ball(a, b, anchor); break;
      case 1: d = impulse::joint_def<T>::hinge(a, b, anchor, axis); break;
      case 2: d = impulse::joint_def<T>::slider(a, b, anchor, axis); break;
      case 3: d = impulse::joint_def<T>::fixed(a, b, anchor); break;
      default: d = impulse::joint_def<T>::distance(a, b, anchor, anchor + axis); break;
    }
    if (next() % 8 == 0) d.break_force = real(next, T(1000));
    if (next() % 8 == 0) d.spring_hertz = real(next, T(10));
    (void)world_.create_joint(d);
  }

  /// A filter of random bits and a group from −2 to 2.
  template <class Next>
  impulse::collision_filter filter(Next& next) {
    const std::uint32_t category = next(), mask = next();
    const auto group = std::int32_t(next() % 5) - 2;
    return {category, mask, group};
  }

  template <class Next>
  void query(Next& next) {
    switch (next() % 8) {
      case 5: {
        const impulse::transform<T> at = pose(next);
        const impulse::vec3<T> by = vector(next, T(20));
        (void)world_.shape_cast(impulse::sphere<T>{T(0.3)}, at, by, impulse::query_filter{next(), 0, next() % 2 == 0});
        return;
      }
      case 6: {
        const impulse::transform<T> at = pose(next);
        world_.shape_overlap(impulse::box<T>{{T(0.5), T(0.5), T(0.5)}}, at, [](impulse::body_id) {});
        return;
      }
      case 7: {
        const impulse::ray<T> r{vector(next, T(10)), vector(next, T(20))};
        const T stop = real(next, T(1));
        world_.ray_cast_all(r, [&](const impulse::world_ray_hit<T>&) { return stop; });
        return;
      }
      default: break;
    }
    switch (next() % 5) {
      case 0: {
        const impulse::ray<T> r{vector(next, T(10)), vector(next, T(20))};  // a braced list is evaluated in order
        const T reach = real(next, T(1));
        (void)world_.ray_cast(r, reach);
        break;
      }
      case 1: {
        const impulse::vec3<T> a = vector(next, T(10)), b = vector(next, T(10));
        world_.overlap(impulse::aabb<T>{a, b}, [](impulse::body_id) {});
        break;
      }
      case 2: {
        const impulse::body_id id = body(next);
        (void)world_.interpolated_pose(id, real(next, T(1)));
        break;
      }
      case 3: (void)world_.joint_position(joint(next)); break;
      default: (void)world_.kinetic_energy(); break;
    }
  }

  template <class Next>
  void settings(Next& next) {
    auto s = world_.settings();
    switch (next() % 7) {
      case 0: world_.set_gravity(vector(next, T(20))); return;
      case 1: s.max_linear_speed = hostile_ ? real(next, T(100)) : T(30) + std::abs(real(next, T(1e4))); break;
      case 6: s = {}; break;  // back to the defaults
      case 2: s.solver.velocity_iterations = int(next() % 40) - 2; break;
      case 3: s.solver.speculative_distance = real(next, T(0.1)); break;
      case 4: s.max_contact_pairs = next() % 400; break;
      default: s.fixed_dt = real(next, T(0.05)); break;
    }
    world_.set_settings(s);
  }

  /// A call from inside a callback: refused if it would change what the
  /// callback walks (reentry_accepted_ records one that was not).
  template <class Next>
  void reenter(Next& next) {
    const std::uint32_t what = next();
    const auto inner = [&] {
      switch (what % 4) {
        case 0: world_.step(T(1) / T(60)); break;
        case 1: world_.destroy_body(body(next)); break;
        case 2: create(next); break;
        default: {
          const impulse::body_id id = body(next);
          world_.apply_force(id, vector(next, T(10)));
          break;
        }
      }
    };
    // Stepping, destroying and creating change the containers a callback
    // walks: each must be refused; a force may be applied.
    const bool structural = what % 4 != 3;
    const auto guarded = [&] {
      try {
        inner();
        if (structural) reentry_accepted_ = true;
      } catch (const impulse::invalid_argument&) {
      }
    };
    if ((what >> 2) % 2 == 0) {
      world_.for_each_contact([&](impulse::body_id, impulse::body_id, auto) { guarded(); });
    } else {
      world_.overlap(impulse::aabb<T>{{-50, -50, -50}, {50, 50, 50}}, [&](impulse::body_id) { guarded(); });
    }
  }

  /// Keeps the lists of destroyed ids short.
  void forget_dead() {
    if (dead_.size() > 1024) dead_.erase(dead_.begin(), dead_.begin() + 512);
    if (dead_joints_.size() > 1024) dead_joints_.erase(dead_joints_.begin(), dead_joints_.begin() + 512);
  }

  World world_;
  std::vector<impulse::body_id> dead_;
  std::vector<impulse::joint_id> dead_joints_;
  std::optional<impulse::world_snapshot<typename World::config>> saved_;
  counts counts_;
  bool hostile_ = false;  ///< whether this call's arguments may be hostile
  bool reentry_accepted_ = false;
  std::string error_;  ///< the last refusal's message
};

}  // namespace impulse::test
