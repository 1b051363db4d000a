// bench/joints/ragdoll_pile.hpp — a pile of ragdolls dropped on the ground,
// on impulse's two solvers and on Bullet.
//
// The scene, exactly (so that another engine can be run on it). One
// ragdoll, standing, in its own frame (y up, facing +z, so +x is its
// left), 11 bodies:
//
//   body          shape, m                                   center, m          mass, kg
//   pelvis        box, half-extents (0.15, 0.10, 0.10)       (0, 0, 0)          10
//   torso         box, half-extents (0.18, 0.25, 0.11)       (0, 0.35, 0)       20
//   head          sphere, radius 0.11                        (0, 0.71, 0)       5
//   upper arms    capsule along y, radius 0.05, segment ±0.13   (±0.25, 0.38, 0)   2
//   forearms      capsule along y, radius 0.045, segment ±0.13  (±0.25, 0.025, 0)  1.5
//   thighs        capsule along y, radius 0.07, segment ±0.16   (±0.09, −0.33, 0)  7
//   shins         capsule along y, radius 0.06, segment ±0.17   (±0.09, −0.79, 0)  4
//
// and 10 joints, parent first; each hinge's axis is the frame's x, its
// angle that of the child about it, right-handed, 0 as built:
//
//   spine     pelvis–torso          hinge at (0, 0.10, 0), limits [−0.5, 0.5]
//   neck      torso–head            ball at (0, 0.60, 0)
//   shoulders torso–upper arm       ball at (±0.25, 0.56, 0)
//   elbows    upper arm–forearm     hinge at (±0.25, 0.20, 0), limits [−2.4, 0] (bends forward)
//   hips      pelvis–thigh          ball at (±0.09, −0.10, 0)
//   knees     thigh–shin            hinge at (±0.09, −0.56, 0), limits [0, 2.4] (bends back)
//
// Joined bodies do not collide; all others do. The pile: 4 × 4 columns of 5
// ragdolls each (80 ragdolls, 880 bodies, 800 joints). The ragdoll of
// column (i, k), layer l (0..4) lies on its back: its frame is turned by
// R = R_y(90°·(l mod 2))·R_x(−90°) and its pelvis placed at
// (3·(i − 1.5), 0.5 + 0.5·l, 3·(k − 1.5)), so each layer crosses the one
// below. The ground is a static box of half-extents (20, 0.5, 20) centered
// at (0, −0.5, 0). Friction 0.6, restitution 0 everywhere; gravity
// (0, −9.81, 0), dt = 1/60, no sleeping, no damping; 600 steps.
// Measured: ms/step (median of the last 300 steps, the pile settled), the
// largest gap between a joint's anchors at the end, the lowest body's
// center and the bodies still moving faster than 0.1 m/s.
//
// Bullet: as bench/joints/main.cpp says; balls as btPoint2PointConstraint,
// hinges as btHingeConstraint with setLimit at its defaults (softness 0.9,
// bias 0.3, relaxation 1). Bullet's hinge angle is the parent's about the
// axis relative to the child (a child turned +0.3 rad reads −0.3), so its
// limits are given as [−upper, −lower]. Its inertias come from its shapes
// (calculateLocalInertia: a capsule's is its bounding box's).
#pragma once

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "measure.hpp"

namespace joints_bench {

struct ragdoll_part {
  enum class shape_kind { box, sphere, capsule };
  shape_kind shape;
  double size[3];  ///< box: half-extents; sphere: radius; capsule: radius, half the segment
  double center[3];
  double mass;
};

struct ragdoll_joint {
  int parent, child;
  bool hinge;
  double anchor[3];
  double lower = 0, upper = 0;  ///< hinge limits, rad
};

struct ragdoll_pile_spec {
  using kind = ragdoll_part::shape_kind;
  static constexpr std::array<ragdoll_part, 11> parts{{
      {kind::box, {0.15, 0.10, 0.10}, {0, 0, 0}, 10},             // 0 pelvis
      {kind::box, {0.18, 0.25, 0.11}, {0, 0.35, 0}, 20},          // 1 torso
      {kind::sphere, {0.11, 0, 0}, {0, 0.71, 0}, 5},              // 2 head
      {kind::capsule, {0.05, 0.13, 0}, {0.25, 0.38, 0}, 2},       // 3 upper arm
      {kind::capsule, {0.05, 0.13, 0}, {-0.25, 0.38, 0}, 2},      // 4
      {kind::capsule, {0.045, 0.13, 0}, {0.25, 0.025, 0}, 1.5},   // 5 forearm
      {kind::capsule, {0.045, 0.13, 0}, {-0.25, 0.025, 0}, 1.5},  // 6
      {kind::capsule, {0.07, 0.16, 0}, {0.09, -0.33, 0}, 7},      // 7 thigh
      {kind::capsule, {0.07, 0.16, 0}, {-0.09, -0.33, 0}, 7},     // 8
      {kind::capsule, {0.06, 0.17, 0}, {0.09, -0.79, 0}, 4},      // 9 shin
      {kind::capsule, {0.06, 0.17, 0}, {-0.09, -0.79, 0}, 4},     // 10
  }};
  static constexpr std::array<ragdoll_joint, 10> joints{{
      {0, 1, true, {0, 0.10, 0}, -0.5, 0.5},      // spine
      {1, 2, false, {0, 0.60, 0}},                // neck
      {1, 3, false, {0.25, 0.56, 0}},             // shoulders
      {1, 4, false, {-0.25, 0.56, 0}},            //
      {3, 5, true, {0.25, 0.20, 0}, -2.4, 0},     // elbows
      {4, 6, true, {-0.25, 0.20, 0}, -2.4, 0},    //
      {0, 7, false, {0.09, -0.10, 0}},            // hips
      {0, 8, false, {-0.09, -0.10, 0}},           //
      {7, 9, true, {0.09, -0.56, 0}, 0, 2.4},     // knees
      {8, 10, true, {-0.09, -0.56, 0}, 0, 2.4},   //
  }};
  int columns = 4, layers = 5, steps = 600;
  static constexpr double dt = 1.0 / 60, friction = 0.6;

  /// The ragdoll of column (i, k), layer l: its frame's turn, about y then
  /// x as (angle about y, angle about x), and its pelvis.
  struct placement {
    double yaw, pitch;
    double origin[3];
  };
  [[nodiscard]] placement place(int i, int k, int l) const noexcept {
    const double half = (columns - 1) / 2.0;
    return {std::numbers::pi / 2 * (l % 2), -std::numbers::pi / 2, {3 * (i - half), 0.5 + 0.5 * l, 3 * (k - half)}};
  }
};

/// `exact`: solve the ragdolls' joint trees exactly (the default), or
/// joint by joint (solver_settings::exact_joint_trees false).
template <class Solver>
result run_ragdolls_impulse(const ragdoll_pile_spec& spec, bool exact = true) {
  using T = float;
  using config = awake_config<Solver>;
  using vec = impulse::vec3<T>;
  impulse::world<config> w;
  auto settings = w.settings();
  settings.solver.exact_joint_trees = exact;
  w.set_settings(settings);
  {
    impulse::body_def<T> ground;
    ground.type = impulse::body_type::static_body;
    ground.pose.position = {0, T(-0.5), 0};
    ground.material.friction = T(ragdoll_pile_spec::friction);
    w.create_body(ground, impulse::box<T>::make({20, T(0.5), 20}));
  }
  std::vector<impulse::body_id> bodies;
  std::vector<impulse::joint_id> joints;
  const auto v = [](const double (&a)[3]) { return vec{T(a[0]), T(a[1]), T(a[2])}; };
  for (int i = 0; i < spec.columns; ++i)
    for (int k = 0; k < spec.columns; ++k)
      for (int l = 0; l < spec.layers; ++l) {
        const ragdoll_pile_spec::placement p = spec.place(i, k, l);
        const impulse::quat<T> turn = impulse::quat<T>::from_axis_angle({0, 1, 0}, T(p.yaw)) *
                                      impulse::quat<T>::from_axis_angle({1, 0, 0}, T(p.pitch));
        const vec origin = v(p.origin);
        const auto to_world = [&](const double (&a)[3]) { return origin + impulse::rotate(turn, v(a)); };
        const std::size_t first = bodies.size();
        for (const ragdoll_part& part : ragdoll_pile_spec::parts) {
          impulse::body_def<T> d;
          d.pose.position = to_world(part.center);
          d.pose.rotation = turn;
          d.mass = T(part.mass);
          d.material.friction = T(ragdoll_pile_spec::friction);
          const T a = T(part.size[0]), b = T(part.size[1]), c = T(part.size[2]);
          switch (part.shape) {
            case ragdoll_part::shape_kind::box:
              bodies.push_back(w.create_body(d, impulse::box<T>::make({a, b, c})));
              break;
            case ragdoll_part::shape_kind::sphere:
              bodies.push_back(w.create_body(d, impulse::sphere<T>::make(a)));
              break;
            case ragdoll_part::shape_kind::capsule:
              bodies.push_back(w.create_body(d, impulse::capsule<T>::make(a, b)));
              break;
          }
        }
        for (const ragdoll_joint& j : ragdoll_pile_spec::joints) {
          const impulse::body_id parent = bodies[first + std::size_t(j.parent)];
          const impulse::body_id child = bodies[first + std::size_t(j.child)];
          impulse::joint_def<T> d =
              j.hinge ? impulse::joint_def<T>::hinge(parent, child, to_world(j.anchor), impulse::rotate(turn, vec{1, 0, 0}))
                      : impulse::joint_def<T>::ball(parent, child, to_world(j.anchor));
          if (j.hinge) {
            d.enable_limit = true;
            d.lower = T(j.lower);
            d.upper = T(j.upper);
          }
          joints.push_back(w.create_joint(d));
        }
      }
  return run_impulse_world(w, bodies, joints, spec.steps, ragdoll_pile_spec::dt);
}

}  // namespace joints_bench
