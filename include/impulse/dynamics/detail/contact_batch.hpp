// impulse/dynamics/detail/contact_batch.hpp — W contacts that share no moving body,
// solved together as the W lanes of SIMD batches.
//
// The rows are those of contact_rows.hpp (a normal row per point, friction
// at the patch: a 2×2 tangent block in the Coulomb disc and a twist row),
// with every Jacobian and mass worked out before the iterations and held
// structure-of-arrays, lane i for the batch's i-th contact. An iteration
// gathers the W pairs of bodies' velocities into lanes, solves, and
// scatters them back (Box2D v3's contact_solver.c works the same way).
// One contact's rows form a chain, each reading what the last wrote: a
// lone contact is bound by the latency of that chain, W of them in lanes
// run it once for all W.
//
// A lane with fewer points than the batch's widest contact, or a lane no
// contact fills, has rows of zero mass: their impulse stays zero and they
// change nothing.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "../../core/batch.hpp"
#include "../../math/vec3_batch.hpp"
#include "../contact_constraint.hpp"
#include "../softness.hpp"

namespace impulse::detail {

/// Contacts per batch: the target's widest registers, at most 8 (wider
/// batches leave more lanes empty in the small colors).
template <scalar_type T>
inline constexpr int contact_lanes = native_width<T> < 8 ? native_width<T> : 8;

template <scalar_type T, int W>
struct contact_batch {
  using lanes = batch<T, W>;
  using vectors = vec3_batch<T, W>;
  /// One point's normal row in every lane.
  struct row {
    vectors arm_a, arm_b;    ///< r × n
    vectors turn_a, turn_b;  ///< I⁻¹ (r × n)
    lanes mass;              ///< kg
    lanes depth;             ///< m: at the start of the step (contact_constraint_point::depth)
    lanes gap_speed;         ///< m/s: the approach the row allows (contact_constraint_point::gap_speed)
    /// m/s: the speed a pushing pass asks the point to separate at:
    /// sequential_impulse's position pass, or soft_step's soft sweep
    /// (soft_targets_batch)
    lanes push_speed;
    lanes position_mass;     ///< kg: `mass` where the point is deeper than the slop, else 0
    lanes impulse;           ///< N·s
    lanes bias_impulse;      ///< N·s, of the position pass
    /// How an impulse on this row changes each row's normal speed: this
    /// row's column of the patch's J M⁻¹ Jᵀ, 1/kg (zero past the lane's
    /// points).
    lanes coupling[contact_manifold<T>::capacity];
  };

  std::uint32_t body_a[W] = {}, body_b[W] = {};
  /// Bit l: lane l's body A (B) moves under impulses (its inverse mass is
  /// not zero). scatter writes back only those: the batches of one color
  /// may share a static or kinematic body, and run on different workers.
  std::uint32_t moving_a = 0, moving_b = 0;
  std::uint32_t contact[W] = {};  ///< each lane's place in the contact array
  int size = 0;                   ///< lanes in use
  /// The batch's rows, one per point of its widest contact, are these in
  /// the solver's row array: a batch of spheres carries one row, not four.
  std::uint32_t first_row = 0;
  int rows_used = 0;
  vectors normal{}, tangent1{}, tangent2{};
  lanes inverse_mass_a{}, inverse_mass_b{};
  // Friction at the patch's middle: r × t and I⁻¹ (r × t) for each tangent
  // and body, the 2×2 block's inverse, and I⁻¹ n for the twist.
  vectors arm_a1{}, arm_a2{}, arm_b1{}, arm_b2{};
  vectors turn_a1{}, turn_a2{}, turn_b1{}, turn_b2{};
  lanes tangent_mass11{}, tangent_mass12{}, tangent_mass22{};
  lanes friction{};
  lanes slip_target1{}, slip_target2{};
  // The patch's middle from each center, and the slip targets the step
  // began with: a part after the first turns the levers (retarget_batch).
  vectors anchor_a{}, anchor_b{};
  lanes slip_base1{}, slip_base2{};
  lanes tangent_impulse1{}, tangent_impulse2{};
  vectors twist_a{}, twist_b{};
  lanes twist_mass{}, twist_radius{}, twist_impulse{};
  /// soft_step's softness of each lane's pushing rows: its rate, mass
  /// scale and leak (softness.hpp; soften_batch).
  lanes soft_rate{}, soft_mass_scale{}, soft_leak{};
  /// 1 in a lane whose contact has more than one point, else 0: a lane's
  /// single rigid row is solved by the first pass alone, whatever the
  /// points of its neighbours (solve_batch_normals).
  lanes chained{};
};

/// The velocities of a batch's bodies, in lanes.
template <scalar_type T, int W>
struct batch_velocities {
  vec3_batch<T, W> va{}, wa{}, vb{}, wb{};
  /// What follows each body's six numbers, carried from gather to scatter
  /// unchanged (the eight-lane path moves eight numbers a body).
  batch<T, W> after_a[2]{}, after_b[2]{};
};

template <scalar_type T, int W>
using batch_row = typename contact_batch<T, W>::row;

/// The rows a batch of the contacts `members` takes: one per point of its
/// widest contact.
template <scalar_type T>
[[nodiscard]] int rows_needed(std::span<const contact_constraint<T>> contacts,
                              std::span<const std::uint32_t> members) noexcept {
  int rows = 0;
  for (const std::uint32_t m : members) rows = std::max(rows, contacts[m].count);
  return rows;
}

/// Fills `out` with the contacts `members` (prepared by prepare_contacts,
/// with their row targets), its rows being rows[first_row, first_row +
/// rows_needed): those it zeroes and fills, and touches nothing else, so
/// that batches load side by side.
template <scalar_type T, int W>
void load_batch(std::span<const solver_body<T>> bodies, std::span<const contact_constraint<T>> contacts,
                std::span<const std::uint32_t> members, contact_batch<T, W>& out,
                std::span<batch_row<T, W>> rows, std::uint32_t first_row) {
  out = contact_batch<T, W>{};
  out.size = int(members.size());
  out.rows_used = rows_needed(contacts, members);
  out.first_row = first_row;
  const std::span<batch_row<T, W>> own = rows.subspan(first_row, std::size_t(out.rows_used));
  for (batch_row<T, W>& r : own) r = batch_row<T, W>{};
  for (int l = 0; l < out.size; ++l) {
    const contact_constraint<T>& c = contacts[members[std::size_t(l)]];
    const solver_body<T>& a = bodies[c.body_a];
    const solver_body<T>& b = bodies[c.body_b];
    out.contact[l] = members[std::size_t(l)];
    out.body_a[l] = c.body_a, out.body_b[l] = c.body_b;
    out.normal.set_lane(l, c.normal);
    out.tangent1.set_lane(l, c.tangent1);
    out.tangent2.set_lane(l, c.tangent2);
    out.inverse_mass_a.set(l, a.inverse_mass);
    out.inverse_mass_b.set(l, b.inverse_mass);
    out.chained.set(l, c.count > 1 ? T(1) : T(0));
    if (a.inverse_mass > T(0)) out.moving_a |= 1u << l;
    if (b.inverse_mass > T(0)) out.moving_b |= 1u << l;
    for (int i = 0; i < c.count; ++i) {
      const contact_constraint_point<T>& p = c.points[i];
      batch_row<T, W>& r = own[std::size_t(i)];
      r.arm_a.set_lane(l, p.arm_a);
      r.arm_b.set_lane(l, p.arm_b);
      r.turn_a.set_lane(l, p.turn_a);
      r.turn_b.set_lane(l, p.turn_b);
      r.mass.set(l, p.normal_mass);
      r.depth.set(l, p.depth);
      r.gap_speed.set(l, p.gap_speed);
      const bool pushed = p.push_speed >= T(0);
      r.push_speed.set(l, pushed ? p.push_speed : T(0));
      r.position_mass.set(l, pushed ? p.normal_mass : T(0));
      r.impulse.set(l, p.normal_impulse);
      r.bias_impulse.set(l, T(0));
      for (int k = 0; k < c.count; ++k) {
        const contact_constraint_point<T>& q = c.points[k];
        r.coupling[k].set(l, a.inverse_mass + b.inverse_mass + dot(q.arm_a, p.turn_a) + dot(q.arm_b, p.turn_b));
      }
    }
    const vec3<T> arm_a1 = cross(c.anchor_a, c.tangent1), arm_a2 = cross(c.anchor_a, c.tangent2);
    const vec3<T> arm_b1 = cross(c.anchor_b, c.tangent1), arm_b2 = cross(c.anchor_b, c.tangent2);
    out.arm_a1.set_lane(l, arm_a1);
    out.arm_a2.set_lane(l, arm_a2);
    out.arm_b1.set_lane(l, arm_b1);
    out.arm_b2.set_lane(l, arm_b2);
    out.turn_a1.set_lane(l, a.inverse_inertia * arm_a1);
    out.turn_a2.set_lane(l, a.inverse_inertia * arm_a2);
    out.turn_b1.set_lane(l, b.inverse_inertia * arm_b1);
    out.turn_b2.set_lane(l, b.inverse_inertia * arm_b2);
    out.tangent_mass11.set(l, c.tangent_mass11);
    out.tangent_mass12.set(l, c.tangent_mass12);
    out.tangent_mass22.set(l, c.tangent_mass22);
    out.friction.set(l, c.friction);
    out.slip_target1.set(l, c.slip_target1);
    out.slip_target2.set(l, c.slip_target2);
    out.anchor_a.set_lane(l, c.anchor_a);
    out.anchor_b.set_lane(l, c.anchor_b);
    out.slip_base1.set(l, c.slip_target1);
    out.slip_base2.set(l, c.slip_target2);
    out.tangent_impulse1.set(l, c.tangent_impulse1);
    out.tangent_impulse2.set(l, c.tangent_impulse2);
    out.twist_a.set_lane(l, a.inverse_inertia * c.normal);
    out.twist_b.set_lane(l, b.inverse_inertia * c.normal);
    out.twist_mass.set(l, c.twist_mass);
    out.twist_radius.set(l, c.twist_radius);
    out.twist_impulse.set(l, c.twist_impulse);
  }
}

/// The same, its rows appended to `rows`.
template <scalar_type T, int W>
void load_batch(std::span<const solver_body<T>> bodies, std::span<const contact_constraint<T>> contacts,
                std::span<const std::uint32_t> members, contact_batch<T, W>& out,
                std::vector<batch_row<T, W>>& rows) {
  const std::uint32_t first_row = std::uint32_t(rows.size());
  rows.resize(rows.size() + std::size_t(rows_needed(contacts, members)));
  load_batch(bodies, contacts, members, out, std::span<batch_row<T, W>>(rows), first_row);
}

/// Writes a batch's accumulated impulses back to its contacts.
template <scalar_type T, int W>
void store_batch(const contact_batch<T, W>& in, std::span<const batch_row<T, W>> rows,
                 std::span<contact_constraint<T>> contacts) noexcept {
  for (int l = 0; l < in.size; ++l) {
    contact_constraint<T>& c = contacts[in.contact[l]];
    for (int i = 0; i < c.count; ++i) {
      c.points[i].normal_impulse = rows[std::size_t(i)].impulse[l];
      c.points[i].bias_impulse = rows[std::size_t(i)].bias_impulse[l];
    }
    c.tangent_impulse1 = in.tangent_impulse1[l];
    c.tangent_impulse2 = in.tangent_impulse2[l];
    c.twist_impulse = in.twist_impulse[l];
  }
}

/// How far a body has moved since the start of the step: its center, and
/// the sum of its turns as angle vectors, m and rad; and its ω at the start
/// of the step, rad/s.
template <scalar_type T>
struct body_displacement {
  vec3<T> linear{};
  vec3<T> angular{};
  vec3<T> spin{};
};

/// What the rows ask at a substep, from the points' depths then
/// (sequential_impulse.hpp, row_targets, says what each is).
template <scalar_type T>
struct row_target_rule {
  T rest_depth, linear_slop, position_correction, max_correction_speed;
  /// 1/s: a gap closes, or a point sinks to the rest depth, within the
  /// part; the position pass, which runs in the last part, pushes the
  /// step's fraction of a penetration out within it.
  T inverse_substep;
};

/// How far a batch's bodies have moved since the start of the step, in
/// lanes (body_displacement).
template <scalar_type T, int W>
struct batch_displacement {
  vec3_batch<T, W> linear_a{}, angular_a{}, spin_a{}, linear_b{}, angular_b{}, spin_b{};
};

template <scalar_type T, int W>
[[nodiscard]] batch_displacement<T, W> gather_displacement(const contact_batch<T, W>& in,
                                                           std::span<const body_displacement<T>> moved) noexcept {
  batch_displacement<T, W> d;
  for (int l = 0; l < in.size; ++l) {
    const body_displacement<T>& a = moved[in.body_a[l]];
    const body_displacement<T>& b = moved[in.body_b[l]];
    d.linear_a.set_lane(l, a.linear), d.angular_a.set_lane(l, a.angular), d.spin_a.set_lane(l, a.spin);
    d.linear_b.set_lane(l, b.linear), d.angular_b.set_lane(l, b.angular), d.spin_b.set_lane(l, b.spin);
  }
  return d;
}

/// The friction rows keep the step's levers r, while the material points
/// that met at the patch have turned with their bodies: two such points
/// moving together are seen by the rows to slip at ω_B×(θ_B×r_B) −
/// ω_A×(θ_A×r_A), which the slip targets take out. Without it, a box
/// carried on a platform turning at 1 rad/s took the whole step's turn of
/// its velocity in the first of 4 parts, where its friction bound is a
/// quarter of the step's, and crept outward 2 mm/s.
template <scalar_type T, int W>
void turn_slip_targets(contact_batch<T, W>& in, const batch_displacement<T, W>& d) noexcept {
  const vec3_batch<T, W> turned =
      cross(d.spin_b, cross(d.angular_b, in.anchor_b)) - cross(d.spin_a, cross(d.angular_a, in.anchor_a));
  in.slip_target1 = in.slip_base1 - dot(in.tangent1, turned);
  in.slip_target2 = in.slip_base2 - dot(in.tangent2, turned);
}

/// Each of a batch's points' depth once the bodies have moved by `d`: the
/// depth found less how far its bodies have moved apart along the normal
/// since, n·(Δx_B − Δx_A) + θ_B·(r_B × n) − θ_A·(r_A × n) (to first order
/// in their turns, which a part keeps small). `depths` holds one per row.
template <scalar_type T, int W>
void depths_now(const contact_batch<T, W>& in, std::span<const batch_row<T, W>> rows,
                const batch_displacement<T, W>& d, batch<T, W>* depths) noexcept {
  const batch<T, W> apart_centers = dot(in.normal, d.linear_b - d.linear_a);
  for (std::size_t i = 0; i < rows.size(); ++i)
    depths[i] = rows[i].depth - (apart_centers + dot(d.angular_b, rows[i].arm_b) - dot(d.angular_a, rows[i].arm_a));
}

/// A manifold solved alone (one the coloring left over): its slip targets
/// once the bodies have moved by `moved`, from those the step began with
/// (`base`), as turn_slip_targets.
template <scalar_type T>
void turn_slip_targets(contact_constraint<T>& c, std::span<const body_displacement<T>> moved,
                       const std::pair<T, T>& base) noexcept {
  const body_displacement<T>& a = moved[c.body_a];
  const body_displacement<T>& b = moved[c.body_b];
  const vec3<T> turned = cross(b.spin, cross(b.angular, c.anchor_b)) - cross(a.spin, cross(a.angular, c.anchor_a));
  c.slip_target1 = base.first - dot(c.tangent1, turned);
  c.slip_target2 = base.second - dot(c.tangent2, turned);
}

/// A manifold's point's depth once the bodies have moved by `moved`, as
/// depths_now.
template <scalar_type T>
[[nodiscard]] T depth_now(const contact_constraint<T>& c, const contact_constraint_point<T>& p,
                          std::span<const body_displacement<T>> moved) noexcept {
  const body_displacement<T>& a = moved[c.body_a];
  const body_displacement<T>& b = moved[c.body_b];
  return p.depth - (dot(c.normal, b.linear - a.linear) + dot(b.angular, p.arm_b) - dot(a.angular, p.arm_a));
}

/// The rows' targets once the bodies have moved by `moved` (depths_now,
/// turn_slip_targets). The position pass's impulses start again from
/// zero: its pseudo-velocities are a part's.
template <scalar_type T, int W>
void retarget_batch(contact_batch<T, W>& in, std::span<batch_row<T, W>> rows,
                    std::span<const body_displacement<T>> moved, const row_target_rule<T>& rule) noexcept {
  using lanes = batch<T, W>;
  const batch_displacement<T, W> d = gather_displacement(in, moved);
  turn_slip_targets(in, d);
  lanes depths[contact_manifold<T>::capacity];
  depths_now(in, std::span<const batch_row<T, W>>(rows), d, depths);
  const lanes zero = lanes::broadcast(T(0));
  const lanes rest = lanes::broadcast(rule.rest_depth), slop = lanes::broadcast(rule.linear_slop);
  const lanes push_rate = lanes::broadcast(rule.position_correction * rule.inverse_substep);
  const lanes fastest = lanes::broadcast(rule.max_correction_speed);
  const lanes close_rate = lanes::broadcast(rule.inverse_substep);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    batch_row<T, W>& r = rows[i];
    const lanes depth = depths[i];
    r.gap_speed = max(rest - depth, zero) * close_rate;
    const auto pushed = depth > slop;
    r.push_speed = select(pushed, min(push_rate * (depth - slop), fastest), zero);
    r.position_mass = select(pushed, r.mass, zero);
    r.bias_impulse = zero;
  }
}

/// soft_step's softness in each lane of a batch: `fixed` where a body
/// cannot move, `moving` elsewhere.
template <scalar_type T, int W>
void soften_batch(contact_batch<T, W>& in, const softness<T>& moving, const softness<T>& fixed) noexcept {
  for (int l = 0; l < in.size; ++l) {
    const softness<T>& s = in.inverse_mass_a[l] == T(0) || in.inverse_mass_b[l] == T(0) ? fixed : moving;
    in.soft_rate.set(l, s.bias_rate);
    in.soft_mass_scale.set(l, s.mass_scale);
    in.soft_leak.set(l, s.impulse_scale);
  }
}

/// What soft_step's rows ask, from each point's depth now (depths_now):
/// a point apart closes its gap within the substep and no more (gap
/// speed); one that is not, in the soft sweep, is pushed out at the lane's
/// soft rate times its depth beyond the slop, at most `fastest` (push
/// speed; soft_step.hpp). The relax sweep asks the gap speed alone. The
/// bodies do not move between a relax sweep and the next substep's soft
/// sweep, so one call serves both.
template <scalar_type T, int W>
void soft_targets_batch(contact_batch<T, W>& in, std::span<batch_row<T, W>> rows,
                        std::span<const body_displacement<T>> moved, T slop, T fastest, T inverse_substep) noexcept {
  using lanes = batch<T, W>;
  const batch_displacement<T, W> d = gather_displacement(in, moved);
  turn_slip_targets(in, d);
  lanes depths[contact_manifold<T>::capacity];
  depths_now(in, std::span<const batch_row<T, W>>(rows), d, depths);
  const lanes zero = lanes::broadcast(T(0)), close_rate = lanes::broadcast(inverse_substep);
  const lanes slop_lanes = lanes::broadcast(slop), fastest_lanes = lanes::broadcast(fastest);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    rows[i].gap_speed = max(-depths[i], zero) * close_rate;
    rows[i].push_speed = min(in.soft_rate * max(depths[i] - slop_lanes, zero), fastest_lanes);
  }
}

/// Applies a batch's accumulated impulses to its bodies' velocities again:
/// the warm start of each substep.
template <scalar_type T, int W>
void warm_start_batch(batch_velocities<T, W>& v, const contact_batch<T, W>& in,
                      std::span<const batch_row<T, W>> rows) noexcept {
  using lanes = batch<T, W>;
  lanes pushed = lanes::broadcast(T(0));
  vec3_batch<T, W> turn_a{}, turn_b{};
  for (const batch_row<T, W>& r : rows) {
    pushed = pushed + r.impulse;
    turn_a = turn_a + r.turn_a * r.impulse;
    turn_b = turn_b + r.turn_b * r.impulse;
  }
  const lanes j1 = in.tangent_impulse1, j2 = in.tangent_impulse2;
  const vec3_batch<T, W> j = in.normal * pushed + in.tangent1 * j1 + in.tangent2 * j2;
  v.va = v.va - j * in.inverse_mass_a;
  v.wa = v.wa - (turn_a + in.turn_a1 * j1 + in.turn_a2 * j2 + in.twist_a * in.twist_impulse);
  v.vb = v.vb + j * in.inverse_mass_b;
  v.wb = v.wb + (turn_b + in.turn_b1 * j1 + in.turn_b2 * j2 + in.twist_b * in.twist_impulse);
}

#if defined(__GNUC__)
/// Transposes eight rows of eight lanes in place: row i lane j becomes row
/// j lane i (unpack pairs, then pairs of pairs, then halves: 24 shuffles).
template <class V>
[[gnu::always_inline]] inline void transpose8(V (&r)[8]) noexcept {
  V t[8], u[8];
  for (int i = 0; i < 8; i += 2) {
    t[i] = __builtin_shufflevector(r[i], r[i + 1], 0, 8, 1, 9, 4, 12, 5, 13);
    t[i + 1] = __builtin_shufflevector(r[i], r[i + 1], 2, 10, 3, 11, 6, 14, 7, 15);
  }
  for (int i = 0; i < 8; i += 4)
    for (int k = 0; k < 2; ++k) {
      u[i + k] = __builtin_shufflevector(t[i + k], t[i + k + 2], 0, 1, 8, 9, 4, 5, 12, 13);
      u[i + k + 2] = __builtin_shufflevector(t[i + k], t[i + k + 2], 2, 3, 10, 11, 6, 7, 14, 15);
    }
  // u[0..3] hold columns 0, 2, 1, 3 of rows 0–3 in their low halves and
  // columns 4, 6, 5, 7 in their high halves; u[4..7] the same of rows 4–7.
  constexpr int order[4] = {0, 2, 1, 3};
  for (int k = 0; k < 4; ++k) {
    r[k] = __builtin_shufflevector(u[order[k]], u[order[k] + 4], 0, 1, 2, 3, 8, 9, 10, 11);
    r[k + 4] = __builtin_shufflevector(u[order[k]], u[order[k] + 4], 4, 5, 6, 7, 12, 13, 14, 15);
  }
}
#endif

/// A body's velocities, or the position pass's pseudo-velocities.
enum class velocity_kind { real, pseudo };

/// Where a body's linear and angular velocities of that kind (which follow
/// one another in solver_body) start, in bytes. The eight-lane path reads
/// and writes eight numbers from there: the six and the two after them.
template <scalar_type T>
constexpr std::size_t velocities_offset(velocity_kind kind) noexcept {
  using body = solver_body<T>;
  static_assert(std::is_standard_layout_v<body>);
  static_assert(offsetof(body, angular_velocity) == offsetof(body, linear_velocity) + 3 * sizeof(T));
  static_assert(offsetof(body, bias_angular) == offsetof(body, bias_linear) + 3 * sizeof(T));
  static_assert(offsetof(body, bias_linear) + 8 * sizeof(T) <= sizeof(body));
  return kind == velocity_kind::real ? offsetof(body, linear_velocity) : offsetof(body, bias_linear);
}

template <class Body>
[[nodiscard]] auto& linear_of(Body& b, velocity_kind kind) noexcept {
  return kind == velocity_kind::real ? b.linear_velocity : b.bias_linear;
}
template <class Body>
[[nodiscard]] auto& angular_of(Body& b, velocity_kind kind) noexcept {
  return kind == velocity_kind::real ? b.angular_velocity : b.bias_angular;
}

/// The velocities of the batch's bodies, in lanes. With eight lanes each body's six
/// numbers (and two after them) are one load, and eight such rows are
/// transposed into lanes in registers; otherwise lane by lane into
/// columns and a column at a time into lanes (writing single lanes of a
/// vector register goes through memory once per lane).
template <scalar_type T, int W>
[[nodiscard, gnu::always_inline]] inline batch_velocities<T, W> gather(std::span<const solver_body<T>> bodies, const contact_batch<T, W>& in,
                                            velocity_kind kind) noexcept {
  batch_velocities<T, W> v;
#if defined(__GNUC__)
  if constexpr (W == 8) {
    using row = detail::lanes<T, 8>;
    const std::size_t start = velocities_offset<T>(kind);
    row ra[8], rb[8];
    for (int l = 0; l < W; ++l) {
      // Lanes past the batch's contacts read the first lane's bodies: any
      // finite numbers do, their rows have no mass.
      const int from = l < in.size ? l : 0;
      __builtin_memcpy(&ra[l], reinterpret_cast<const char*>(&bodies[in.body_a[from]]) + start, sizeof(row));
      __builtin_memcpy(&rb[l], reinterpret_cast<const char*>(&bodies[in.body_b[from]]) + start, sizeof(row));
    }
    transpose8(ra);
    transpose8(rb);
    v.va = {{ra[0]}, {ra[1]}, {ra[2]}};
    v.wa = {{ra[3]}, {ra[4]}, {ra[5]}};
    v.vb = {{rb[0]}, {rb[1]}, {rb[2]}};
    v.wb = {{rb[3]}, {rb[4]}, {rb[5]}};
    v.after_a[0] = {ra[6]}, v.after_a[1] = {ra[7]};
    v.after_b[0] = {rb[6]}, v.after_b[1] = {rb[7]};
    return v;
  }
#endif
  alignas(64) T columns[12][W] = {};
  for (int l = 0; l < in.size; ++l) {
    const solver_body<T>& a = bodies[in.body_a[l]];
    const solver_body<T>& b = bodies[in.body_b[l]];
    const vec3<T>* parts[4] = {&linear_of(a, kind), &angular_of(a, kind), &linear_of(b, kind), &angular_of(b, kind)};
    for (int k = 0; k < 4; ++k) {
      columns[3 * k][l] = parts[k]->x;
      columns[3 * k + 1][l] = parts[k]->y;
      columns[3 * k + 2][l] = parts[k]->z;
    }
  }
  const auto column = [&](int k) {
    return vec3_batch<T, W>::load(columns[3 * k], columns[3 * k + 1], columns[3 * k + 2]);
  };
  v.va = column(0), v.wa = column(1), v.vb = column(2), v.wb = column(3);
  return v;
}

/// Which lanes scatter writes back. A lane whose body does not move (a
/// static or kinematic body, inverse mass and inertia zero) holds the
/// velocity it read, bit for bit: v + 0·p is v, and a solver body that
/// does not move never has a −0 component (solve.hpp). On one thread
/// every lane writes back, which costs less than a test per lane; the
/// batches of one color may share such a body, so across workers only
/// the moving lanes write.
enum class lanes_written { every, moving };

/// Writes the lanes back.
template <scalar_type T, int W>
[[gnu::always_inline]] inline void scatter(std::span<solver_body<T>> bodies, const contact_batch<T, W>& in, const batch_velocities<T, W>& v,
             velocity_kind kind, lanes_written which = lanes_written::every) noexcept {
#if defined(__GNUC__)
  if constexpr (W == 8) {
    using row = detail::lanes<T, 8>;
    const std::size_t start = velocities_offset<T>(kind);
    row ra[8] = {v.va.x.v, v.va.y.v, v.va.z.v, v.wa.x.v, v.wa.y.v, v.wa.z.v, v.after_a[0].v, v.after_a[1].v};
    row rb[8] = {v.vb.x.v, v.vb.y.v, v.vb.z.v, v.wb.x.v, v.wb.y.v, v.wb.z.v, v.after_b[0].v, v.after_b[1].v};
    transpose8(ra);
    transpose8(rb);
    const auto write = [&](std::uint32_t body, const row& r) {
      __builtin_memcpy(reinterpret_cast<char*>(&bodies[body]) + start, &r, sizeof(row));
    };
    if (which == lanes_written::every) {
      for (int l = 0; l < in.size; ++l) write(in.body_a[l], ra[l]), write(in.body_b[l], rb[l]);
      return;
    }
    for (int l = 0; l < in.size; ++l) {
      if (in.moving_a >> l & 1u) write(in.body_a[l], ra[l]);
      if (in.moving_b >> l & 1u) write(in.body_b[l], rb[l]);
    }
    return;
  }
#endif
  alignas(64) T columns[12][W];
  const vec3_batch<T, W>* parts[4] = {&v.va, &v.wa, &v.vb, &v.wb};
  for (int k = 0; k < 4; ++k) parts[k]->store(columns[3 * k], columns[3 * k + 1], columns[3 * k + 2]);
  for (int l = 0; l < in.size; ++l) {
    solver_body<T>& a = bodies[in.body_a[l]];
    solver_body<T>& b = bodies[in.body_b[l]];
    vec3<T>* targets[4] = {&linear_of(a, kind), &angular_of(a, kind), &linear_of(b, kind), &angular_of(b, kind)};
    const bool every = which == lanes_written::every;
    const bool moving[2] = {every || (in.moving_a >> l & 1u) != 0, every || (in.moving_b >> l & 1u) != 0};
    for (int k = 0; k < 4; ++k)
      if (moving[k / 2]) *targets[k] = {columns[3 * k][l], columns[3 * k + 1][l], columns[3 * k + 2][l]};
  }
}

/// The passes solve_batch_normals makes: sequential_impulse's velocity
/// rows and its position pass, and soft_step's soft and relax sweeps.
enum class normal_pass { velocity, position, soft, relax };

/// `sweeps` passes over the normal rows (sequential_impulse.hpp says why
/// more than one). On the velocities (`velocity`, `relax`), each row
/// closing at most its gap; on the pseudo-velocities (`position`), pushing
/// points deeper than the slop apart; in soft_step's soft sweep (`soft`),
/// a row that is not apart (gap speed 0, soft_targets_batch) is a soft row
/// (softness.hpp), pushed out at its push speed, its mass scaled and part
/// of its impulse leaked at each update.
///
/// Within the passes the rows see the bodies only through each other: an
/// impulse d on row i changes row k's normal speed by K_ki·d, K the
/// patch's J M⁻¹ Jᵀ. So the passes run on the rows' speeds (four
/// numbers) rather than on the bodies' velocities (twelve), and the
/// impulses reach the bodies once, summed, at the end. The result is the
/// same; each row's step waits on three operations instead of a dozen.
template <normal_pass Pass, scalar_type T, int W>
void solve_batch_normals(batch_velocities<T, W>& v, const contact_batch<T, W>& in, std::span<batch_row<T, W>> rows,
                         int sweeps) noexcept {
  using lanes = batch<T, W>;
  constexpr int capacity = contact_manifold<T>::capacity;
  constexpr bool position = Pass == normal_pass::position, soft = Pass == normal_pass::soft;
  const lanes zero = lanes::broadcast(T(0));
  const int n = int(rows.size());
  // A single rigid row is solved exactly by its first pass; later passes
  // would only round it again. So a lane with one point keeps its first
  // pass's impulse: it computes the same beside lanes of any point count,
  // and a contact comes out the same in whichever batch it falls (the
  // batches of a group of islands are not the whole step's;
  // contact_groups.hpp).
  if (n == 1 && !soft) sweeps = 1;
  const auto chained = in.chained > zero;
  const vec3_batch<T, W> dv = v.vb - v.va;
  lanes speed[capacity], first[capacity], mass[capacity], target[capacity], leak[capacity];
  for (int i = 0; i < n; ++i) {
    const batch_row<T, W>& r = rows[std::size_t(i)];
    speed[i] = dot(in.normal, dv) + dot(v.wb, r.arm_b) - dot(v.wa, r.arm_a);
    first[i] = position ? r.bias_impulse : r.impulse;
    target[i] = position ? -r.push_speed : soft ? r.gap_speed - r.push_speed : r.gap_speed;
    mass[i] = position ? r.position_mass : r.mass;
    if constexpr (soft) {
      const auto pushing = r.gap_speed <= zero;
      mass[i] = select(pushing, r.mass * in.soft_mass_scale, r.mass);
      leak[i] = select(pushing, in.soft_leak, zero);
    }
  }
  for (int sweep = 0; sweep < sweeps; ++sweep)
    for (int i = 0; i < n; ++i) {
      batch_row<T, W>& r = rows[std::size_t(i)];
      lanes& total = position ? r.bias_impulse : r.impulse;
      lanes next = total - mass[i] * (speed[i] + target[i]);
      if constexpr (soft) next = next - leak[i] * total;
      next = max(next, zero);
      if constexpr (!soft)
        if (sweep > 0) next = select(chained, next, total);
      const lanes delta = next - total;
      total = next;
      for (int k = 0; k < n; ++k) speed[k] = speed[k] + r.coupling[k] * delta;
    }
  lanes pushed = zero;
  vec3_batch<T, W> turn_a{}, turn_b{};
  for (int i = 0; i < n; ++i) {
    const batch_row<T, W>& r = rows[std::size_t(i)];
    const lanes delta = (position ? r.bias_impulse : r.impulse) - first[i];
    pushed = pushed + delta;
    turn_a = turn_a + r.turn_a * delta;
    turn_b = turn_b + r.turn_b * delta;
  }
  v.va = v.va - in.normal * (pushed * in.inverse_mass_a);
  v.wa = v.wa - turn_a;
  v.vb = v.vb + in.normal * (pushed * in.inverse_mass_b);
  v.wb = v.wb + turn_b;
}

/// Friction at the patch, as solve_friction in contact_rows.hpp.
template <scalar_type T, int W>
[[gnu::always_inline]] inline void solve_batch_friction(batch_velocities<T, W>& v, contact_batch<T, W>& in,
                          std::span<const batch_row<T, W>> rows) noexcept {
  using lanes = batch<T, W>;
  lanes pressed = lanes::broadcast(T(0));
  for (const batch_row<T, W>& r : rows) pressed = pressed + r.impulse;
  const lanes limit = in.friction * pressed;
  const vec3_batch<T, W> dv = v.vb - v.va;
  const lanes v1 = dot(in.tangent1, dv) + dot(v.wb, in.arm_b1) - dot(v.wa, in.arm_a1) - in.slip_target1;
  const lanes v2 = dot(in.tangent2, dv) + dot(v.wb, in.arm_b2) - dot(v.wa, in.arm_a2) - in.slip_target2;
  lanes j1 = in.tangent_impulse1 - (in.tangent_mass11 * v1 + in.tangent_mass12 * v2);
  lanes j2 = in.tangent_impulse2 - (in.tangent_mass12 * v1 + in.tangent_mass22 * v2);
  // Back onto the Coulomb disc; the floor keeps the lanes that need no
  // scaling from dividing by zero.
  const lanes squared = j1 * j1 + j2 * j2;
  const lanes floor = lanes::broadcast(std::numeric_limits<T>::min());
  const lanes scale = select(squared > limit * limit, limit / sqrt(max(squared, floor)), lanes::broadcast(T(1)));
  j1 = j1 * scale, j2 = j2 * scale;
  const lanes d1 = j1 - in.tangent_impulse1, d2 = j2 - in.tangent_impulse2;
  in.tangent_impulse1 = j1, in.tangent_impulse2 = j2;
  const vec3_batch<T, W> j = in.tangent1 * d1 + in.tangent2 * d2;
  v.va = v.va - j * in.inverse_mass_a;
  v.wa = v.wa - (in.turn_a1 * d1 + in.turn_a2 * d2);
  v.vb = v.vb + j * in.inverse_mass_b;
  v.wb = v.wb + (in.turn_b1 * d1 + in.turn_b2 * d2);

  const lanes spin = dot(in.normal, v.wb - v.wa);
  const lanes bound = limit * in.twist_radius;
  const lanes total = min(max(in.twist_impulse - in.twist_mass * spin, -bound), bound);
  const lanes d = total - in.twist_impulse;
  in.twist_impulse = total;
  v.wa = v.wa - in.twist_a * d;
  v.wb = v.wb + in.twist_b * d;
}

}  // namespace impulse::detail
