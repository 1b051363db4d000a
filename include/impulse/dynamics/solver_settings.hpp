// impulse/dynamics/solver_settings.hpp — the contact solvers' numbers, each
// with its unit and the reason for its value: solver_settings, the ones the
// world and every solver read, and each shipped solver's own type, which
// adds what only that solver reads (sequential_impulse_settings,
// soft_step_settings). A solver names its type as `settings_type`
// (contact_solver.hpp), and a world's settings hold that type
// (world_settings.hpp), so a world has exactly the knobs its solver turns.
//
// These are runtime values (docs/architecture.md: iteration counts,
// restitution and tolerances stay runtime knobs); a world holds its
// solver's settings and hands them to the solver every step. The defaults
// are what the hard-case tests (tests/world/) are run with.
#pragma once

#include <cmath>

#include "../core/error.hpp"
#include "../core/policy.hpp"

namespace impulse {

template <scalar_type T>
struct solver_settings {
  /// Projected Gauss–Seidel sweeps over every contact's velocity rows per
  /// part of a step (sequential_impulse, whose own default is 8 in each of
  /// its 4 parts: sequential_impulse_settings) and the most sweeps of the
  /// restitution pass (both solvers). In one part, a 10-box tower holds for
  /// 80 s at 6 or more (rest_depth says why it did not); the 20-row
  /// pyramid moves about half a millimetre in 20 s at 10 or 20; the
  /// 100-row pyramid of 100 kg boxes moves 5.5 cm in 200 steps at 10 and
  /// 5.5 mm at 20. ODE's quickstep also takes 20, Bullet 10.
  /// docs/world.md has the measurements.
  int velocity_iterations = 20;
  /// Sweeps of the split-impulse position pass (sequential_impulse, in
  /// the last part of its step): only the normal rows, on pseudo-velocities
  /// that move the bodies this part and are then forgotten. Also the
  /// passes that move the bodies back onto their joints after each step
  /// (both solvers; joint_correction), after which joint trees not yet settled take
  /// further Newton steps, up to 8 per pass in all (joint_tree.hpp,
  /// project_joints).
  int position_iterations = 4;
  /// Passes over the normal rows of one manifold each time it is visited.
  /// They are coupled through the bodies' rotation (a corner's impulse
  /// lifts the opposite corner) far more than manifolds are to each other.
  /// The 10-box tower over 80 s at 20 iterations: its top drifts 0.24 mm
  /// with one pass, 0.044 mm with two, 0.016 mm with four; at 10
  /// iterations one pass falls. soft_step's tower drifts 1.7 cm in 20 s
  /// with one. sequential_impulse runs the passes on the rows' speeds
  /// (contact_batch.hpp), at little cost.
  int manifold_sweeps = 4;

  /// Penetration left uncorrected, m. Contacts rest this deep, so that a
  /// touching pair keeps its manifold (and its warm-started impulses)
  /// rather than flickering between touching and apart. Box2D takes 5 mm
  /// and Jolt 2 cm; a 10-box tower then stands 5 cm (or 19 cm in Jolt)
  /// lower than its height. 0.5 mm keeps a 20-high stack within a centimetre.
  T linear_slop = T(0.0005);
  /// Largest correction speed of the position pass (soft_step: of the soft
  /// rows' push), m/s: bodies created
  /// deep inside each other separate over several steps instead of
  /// jumping apart in one.
  T max_correction_speed = T(3);
  /// Contacts are reported this far before the shapes touch, m, and the
  /// solver lets the gap close but not overshoot (speculative contacts,
  /// Catto, GDC 2014): a body meets the ground on the step it arrives,
  /// with no penetration to correct and no bounce from correcting it.
  T speculative_distance = T(0.02);
  /// How far ahead a fast pair's contacts reach, at most, m. A pair whose
  /// surfaces can close more than speculative_distance in the step (their
  /// centers' relative path, with gravity, and the turn of their farthest
  /// points) is tested that much ahead, so a box landing at 20 m/s (33 cm
  /// a step at 60 Hz) is met on the step it arrives, not 5 cm deep after
  /// it. A contact found farther than speculative_distance is kept only if
  /// the pair's sweep over the step (time_of_impact.hpp) meets: a ball
  /// flying past a box's edge is not caught by it (a ghost collision).
  /// 1 m is 60 m/s at 60 Hz; faster bodies are what the config's ccd is for.
  T max_speculative_distance = T(1);
  /// Approach speed below which a contact is treated as resting and does
  /// not bounce, m/s. Resting contacts approach at about g·dt/2 = 0.08 m/s
  /// under gravity at 60 Hz; bouncing them would make stacks with
  /// restitution jitter. Box2D and Jolt take 1 m/s; 0.5 m/s lets slower
  /// impacts (a Newton's cradle at 0.6 m/s) keep their bounce.
  T restitution_threshold = T(0.5);
  /// Tangential slip below which a contact counts as at rest for the
  /// choice of its friction directions, m/s: below it the tangents are a
  /// fixed function of the normal, so that resting friction carries over
  /// from step to step; above it the first tangent follows the slip.
  T rest_slip_speed = T(0.01);
  /// Fraction of a joint's error (its anchors apart, its axes or
  /// orientation off, a limit passed) removed by each of the
  /// position_iterations Gauss–Seidel passes that move the bodies back
  /// onto their joints after they have moved (joint.hpp, project_joint;
  /// joint trees take a whole Newton step instead, joint_tree.hpp). Each
  /// joint corrects its own error as if alone, so coupled joints overshoot
  /// at 1: bench/joints' grid of 19 800 ball joints tore 12 m open in 300
  /// steps at 1, 4.4 m at 0.8, 2.0 m at 0.65, 0.56 m at 0.5 and 1.1 m at
  /// 0.2. Solved joint by joint, a 1 m pendulum let go from horizontal
  /// keeps its pivot within 0.17 mm at 0.5 (1.8 mm at 0.2), and a hanging
  /// chain of 10 and 1 kg links opens 13 mm at 0.5, 18.6 mm at 1.
  T joint_correction = T(0.5);
  /// Whether joints that form trees have their rows that hold solved
  /// exactly, all at once, in each iteration and each position pass
  /// (joint_tree.hpp, Baraff 1996), rather than one joint at a time by
  /// Gauss–Seidel. Groups with loops, limits and motors stay with
  /// Gauss–Seidel. The hanging 10:1 chain opens 0.01 mm with it, 13 mm
  /// without; the cost is a factorisation per step (per substep for
  /// soft_step) and about one per projection after the step (more while
  /// a long chain whips: 2.2 on average at 100 links), linear in the
  /// joints.
  bool exact_joint_trees = true;
  /// Whether each step starts from the last step's impulses.
  bool warm_starting = true;

  void validate() const {
    if (velocity_iterations < 1 || position_iterations < 0 || manifold_sweeps < 1)
      detail::report_error(error_code::invalid_parameter,
                           "solver_settings: velocity_iterations and manifold_sweeps must be >= 1, "
                           "position_iterations >= 0");
    const T values[] = {linear_slop,     max_correction_speed, speculative_distance, max_speculative_distance,
                        restitution_threshold, rest_slip_speed, joint_correction};
    for (const T v : values)
      if (!std::isfinite(v) || v < T(0))
        detail::report_error(error_code::invalid_parameter,
                             "solver_settings: slop, correction, speeds and distances must be finite and >= 0");
    if (joint_correction > T(1))
      detail::report_error(error_code::invalid_parameter, "solver_settings: joint_correction must lie in [0, 1]");
  }
};

/// sequential_impulse's settings: the shared numbers, and those of its
/// split-impulse position pass and its resting depth.
template <scalar_type T>
struct sequential_impulse_settings : solver_settings<T> {
  /// Fraction of the penetration beyond the slop removed per step by the
  /// split-impulse pass (1/s after division by dt). It moves positions
  /// without adding velocity, so it adds no energy: larger only corrects
  /// faster. 0.2 corrects 90 % of an error in 10 steps without the
  /// overshoot a larger fraction shows in deep piles.
  T position_correction = T(0.2);
  /// Depth a resting contact is let sink to, m (sequential_impulse): the
  /// velocity rows let a point approach until it lies this deep (a gap
  /// closes to it, not to zero). At depth zero a face is on the edge
  /// between pressing and not, and float rounding of the positions
  /// (0.5 µm at 5 m) chose each step which of its points bore the load: a
  /// 10-box tower swayed on that noise, and over 80 s fell at 12, 16 or 26
  /// iterations and drifted 15 mm at 20, depending on the build. Pressed
  /// 3 µm in, its top stays within 0.05 mm at 6 to 30 iterations in every
  /// build (0.016 mm at 10 to 30), and within 0.07 mm standing on a floor
  /// 60 m up (rounding 3.8 µm there). Deeper costs a tall heavy stack: the
  /// 100-row pyramid of 100 kg boxes sags 5.5 mm in 200 steps at 3 µm,
  /// 6.1 mm at zero, 10.7 mm at 10 µm.
  T rest_depth = T(0.000003);
  /// The step taken in this many equal parts, each with
  /// velocity_iterations sweeps, the bodies moved after each (collision
  /// and the rows' preparation once a step; sequential_impulse.hpp). A
  /// part's length, not the number of sweeps, sets how tall a tower stands
  /// (docs/stacks.md): 4 parts of 8 sweeps hold towers of 20 and 30 boxes,
  /// a 1:1000 stack and a top spinning at 300 rad/s, where 1 part of 20
  /// sweeps lets all three fall; they cost 1.4 times as much on `pile`
  /// (docs/world.md, "A step in parts").
  int substeps = 4;
  /// Whether each part ends with the support sweep (support_sweep.hpp):
  /// the normal rows once more from the ground up, each manifold solved
  /// as if its lower body could not move. It stops a stack in one pass
  /// whatever its masses: without it a 10 000 kg box squeezed a 1 kg box
  /// out from under it (it sank 0.17 m and slid 0.42 m in 10 s); with it,
  /// 6 µm and 85 µm.
  bool support_sweep = true;

  /// Its sweeps are per part: 8, 32 a step. 6 in 4 parts let a tower of
  /// 30 boxes fall; 4 in 6 parts let the 1:1000 stack collapse.
  sequential_impulse_settings() noexcept { this->velocity_iterations = 8; }

  void validate() const {
    solver_settings<T>::validate();
    if (!std::isfinite(position_correction) || !std::isfinite(rest_depth) || position_correction < T(0) ||
        position_correction > T(1) || rest_depth < T(0))
      detail::report_error(error_code::invalid_parameter,
                           "sequential_impulse_settings: position_correction must lie in [0, 1], rest_depth be "
                           "finite and >= 0");
    if (substeps < 1 || substeps > 64)
      detail::report_error(error_code::invalid_parameter, "sequential_impulse_settings: substeps must lie in [1, 64]");
  }
};

/// soft_step's settings: the shared numbers, and its substeps and the
/// softness of its rows. velocity_iterations counts the sweeps of its
/// restitution pass only: the substeps, not the iterations, carry its
/// convergence (substep_iterations counts its sweeps per substep).
template <scalar_type T>
struct soft_step_settings : solver_settings<T> {
  /// Substeps of soft_step (Box2D v3 takes 4).
  int substeps = 4;
  /// soft_step: sweeps of the soft rows, and then of the rigid ones (the
  /// relax pass), per substep. Box2D v3 takes one of each: the substeps,
  /// not the sweeps, carry the convergence.
  int substep_iterations = 1;
  int relax_iterations = 1;
  /// soft_step: stiffness of the soft contact rows, Hz, capped at a quarter
  /// of the substep rate (a spring stiffer than that is not resolved by the
  /// substeps); static contacts take twice it. Box2D v3's 30 Hz.
  T contact_hertz = T(30);
  /// soft_step: damping ratio of the soft contact rows. 10 (Box2D v3's)
  /// is far past critical: a pushed-in contact creeps out without
  /// overshoot instead of springing out.
  T contact_damping_ratio = T(10);
  /// soft_step: stiffness of the joints' rows, Hz, capped at a quarter of
  /// the substep rate like contact_hertz, and their damping ratio (Box2D
  /// v3's joint softness: 60 Hz and 2, i.e. twice its contact stiffness).
  T joint_hertz = T(60);
  T joint_damping_ratio = T(2);

  void validate() const {
    solver_settings<T>::validate();
    if (substeps < 1 || substep_iterations < 1 || relax_iterations < 0)
      detail::report_error(error_code::invalid_parameter,
                           "soft_step_settings: substeps and substep_iterations must be >= 1, relax_iterations >= 0");
    const T values[] = {contact_hertz, contact_damping_ratio, joint_hertz, joint_damping_ratio};
    for (const T v : values)
      if (!std::isfinite(v) || v < T(0))
        detail::report_error(error_code::invalid_parameter,
                             "soft_step_settings: stiffnesses and damping ratios must be finite and >= 0");
  }
};

}  // namespace impulse
