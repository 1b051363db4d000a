// expect: impulse solver: missing `project_joints
// A solver with no joint projection is named, at the world that would call
// it, for what it lacks.
#include <span>

#include "impulse/world.hpp"

template <impulse::scalar_type T>
struct no_projection {
  using settings_type = impulse::solver_settings<T>;
  static constexpr bool moves_bodies = false;
  static T impulse_step(const impulse::solver_settings<T>&, T dt) { return dt; }
  void prepare(std::span<const impulse::solver_body<T>>, std::span<impulse::contact_constraint<T>>) {}
  void solve(std::span<impulse::solver_body<T>>, std::span<impulse::contact_constraint<T>>,
             std::span<impulse::joint_constraint<T>>, const impulse::solver_settings<T>&, T) {}
};

struct no_projection_policy {
  static constexpr impulse::policy_kind kind = impulse::policy_kind::solver;
  template <impulse::scalar_type T>
  using type = no_projection<T>;
};

struct bad_config : impulse::default_config {
  using solver = no_projection_policy;
};

impulse::world<bad_config> w;
