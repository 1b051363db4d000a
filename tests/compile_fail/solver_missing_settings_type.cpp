// expect: impulse solver: missing `using settings_type
// A solver that does not say which settings it reads is named, at the world
// that would hold them, for what it lacks.
#include <span>

#include "impulse/world.hpp"

template <impulse::scalar_type T>
struct no_settings {
  static constexpr bool moves_bodies = false;
  static T impulse_step(const impulse::solver_settings<T>&, T dt) { return dt; }
  void prepare(std::span<const impulse::solver_body<T>>, std::span<impulse::contact_constraint<T>>) {}
  void solve(std::span<impulse::solver_body<T>>, std::span<impulse::contact_constraint<T>>,
             std::span<impulse::joint_constraint<T>>, const impulse::solver_settings<T>&, T) {}
  void project_joints(std::span<impulse::solver_body<T>>, std::span<impulse::joint_constraint<T>>,
                      const impulse::solver_settings<T>&) {}
};

struct no_settings_policy {
  static constexpr impulse::policy_kind kind = impulse::policy_kind::solver;
  template <impulse::scalar_type T>
  using type = no_settings<T>;
};

struct bad_config : impulse::default_config {
  using solver = no_settings_policy;
};

impulse::world<bad_config> w;
