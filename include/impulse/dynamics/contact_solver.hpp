// impulse/dynamics/contact_solver.hpp — what the world asks of a solver:
// the contact_solver concept, and the check that names what a solver
// lacks.
//
// A config's `solver` is a policy struct (`kind = policy_kind::solver`)
// whose `type<T>` is the solver: sequential_impulse.hpp and soft_step.hpp
// hold the two the library ships, and a user's own plugs in the same way
// (tests/world/test_user_solver.cpp builds a plain projected Gauss–Seidel).
// Each step the world (world/detail/solve.hpp) makes one solver_body per body and
// one contact_constraint per touching manifold and joint_constraint per
// joint, then calls, in order:
//
//   prepare(bodies, contacts)          the contacts' masses and anchors
//   solve(bodies, contacts, joints, settings, dt)
//                                      this step's forces (force_linear,
//                                      force_angular: velocity changes)
//                                      applied and the rows solved; the
//                                      impulses left in the constraints
//                                      are kept for the next step's warm
//                                      start
//   project_joints(bodies, joints, settings)
//                                      after the bodies have moved: their
//                                      poses put back onto their joints
//
// and reads three members of its type:
//
//   settings_type       its numbers: solver_settings<T> (those the world
//                       reads too: the speculative distance, the slop,
//                       warm starting) or a type derived from it with the
//                       solver's own (solver_settings.hpp); a world's
//                       settings hold one (world_settings<T, settings_type>)
//   moves_bodies        false: the world moves the bodies with the solved
//                       velocities plus bias_linear and bias_angular (the
//                       position pass's pseudo-velocities), turning each
//                       with its L held (free_rotation.hpp); true: the
//                       solver moves them itself and keeps each body's
//                       angular_momentum in step with its ω, and the world
//                       takes their poses and L
//   impulse_step(settings, dt)
//                       the time over which one of its impulses acts: dt,
//                       or a substep's length for a solver whose impulses
//                       are per substep (the world turns a joint's impulse
//                       into its force with it, and guesses new contacts'
//                       first impulses from the weight over it)
//
// and, where the solver has it, calls set_fourth_order_turns(bool) before
// each solve: true under a fourth-order integrator policy (RK4), for a
// solver that turns the bodies itself to turn them to fourth order
// (free_rotation.hpp, free_turn). Both shipped solvers move the bodies
// themselves, in parts or substeps of the step.
#pragma once

#include <concepts>
#include <span>

#include "../core/policy.hpp"
#include "contact_constraint.hpp"
#include "joint.hpp"
#include "solver_settings.hpp"

namespace impulse {

// One requirement per member, so that the loud check below can name the
// one that is missing.
namespace detail {
template <class S, class T>
concept solver_has_settings = requires { typename S::settings_type; } &&
                              std::derived_from<typename S::settings_type, solver_settings<T>> &&
                              std::copyable<typename S::settings_type> &&
                              std::default_initializable<typename S::settings_type> &&
                              requires(const typename S::settings_type& s) { s.validate(); };
template <class S, class T>
concept solver_prepares = requires(S& s, std::span<const solver_body<T>> bodies,
                                   std::span<contact_constraint<T>> contacts) { s.prepare(bodies, contacts); };
template <class S, class T>
concept solver_solves = requires(S& s, std::span<solver_body<T>> bodies, std::span<contact_constraint<T>> contacts,
                                 std::span<joint_constraint<T>> joints, const typename S::settings_type& settings,
                                 T dt) {
  s.solve(bodies, contacts, joints, settings, dt);
};
template <class S, class T>
concept solver_projects = requires(S& s, std::span<solver_body<T>> bodies, std::span<joint_constraint<T>> joints,
                                   const typename S::settings_type& settings) {
  s.project_joints(bodies, joints, settings);
};
template <class S>
concept solver_says_who_moves = requires {
  { S::moves_bodies } -> std::convertible_to<bool>;
};
template <class S, class T>
concept solver_has_impulse_step = requires(const typename S::settings_type& settings, T dt) {
  { S::impulse_step(settings, dt) } -> std::same_as<T>;
};
}  // namespace detail

/// Quiet form: true when S is a contact solver over scalar T.
template <class S, class T>
concept contact_solver = std::default_initializable<S> && std::copyable<S> && detail::solver_has_settings<S, T> &&
                         detail::solver_prepares<S, T> &&
                         detail::solver_solves<S, T> && detail::solver_projects<S, T> &&
                         detail::solver_says_who_moves<S> && detail::solver_has_impulse_step<S, T>;

/// Loud form: `static_assert(check_contact_solver<S, T>());` fails with one
/// message per missing member, naming it.
template <class S, class T>
consteval bool check_contact_solver() {
  static_assert(std::default_initializable<S> && std::copyable<S>,
                "impulse solver: must be default constructible and copyable (a world is a value)");
  static_assert(detail::solver_has_settings<S, T>,
                "impulse solver: missing `using settings_type = ...`: solver_settings<T>, or a type derived from it "
                "with a validate() of its own");
  if constexpr (detail::solver_has_settings<S, T>) {
    static_assert(detail::solver_prepares<S, T>,
                  "impulse solver: missing `prepare(std::span<const solver_body<T>>, std::span<contact_constraint<T>>)`");
    static_assert(detail::solver_solves<S, T>,
                  "impulse solver: missing `solve(std::span<solver_body<T>>, std::span<contact_constraint<T>>, "
                  "std::span<joint_constraint<T>>, const settings_type&, T dt)`");
    static_assert(detail::solver_projects<S, T>,
                  "impulse solver: missing `project_joints(std::span<solver_body<T>>, std::span<joint_constraint<T>>, "
                  "const settings_type&)`");
    static_assert(detail::solver_says_who_moves<S>, "impulse solver: missing `static constexpr bool moves_bodies`");
    static_assert(detail::solver_has_impulse_step<S, T>,
                  "impulse solver: missing `static T impulse_step(const settings_type&, T dt)`");
  }
  return contact_solver<S, T>;
}

}  // namespace impulse
