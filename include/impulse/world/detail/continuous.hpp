// impulse/world/detail/continuous.hpp — the step's continuous collision (with
// `ccd` in the config; off, none of it is compiled): after the bodies
// have moved, each bullet, and each body that crossed more than
// ccd_motion_fraction of its thinnest half-extent, is swept from where it
// started the step to where it ended, and stopped ccd_gap short of the
// first body it would have met (Box2D v3's continuous stage: the rest of
// its step is lost, and the next step's speculative contact resolves the
// impact; its velocity is kept for that). The sweeps run across the
// workers (run).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "../../narrowphase/epa.hpp"
#include "../../narrowphase/ray_cast.hpp"
#include "../../narrowphase/time_of_impact.hpp"
#include "../../shapes/compound.hpp"
#include "../../shapes/detail/thinnest_half_extent.hpp"
#include "world_state.hpp"

namespace impulse::detail {

template <class Config>
struct continuous_collision {
  using T = typename Config::scalar;

  world_state<Config>& state;
  step_scratch<Config>& scratch;

  /// The fewest bodies a worker checks at a time: a check is a subtraction,
  /// a length and a comparison.
  static constexpr std::uint32_t min_bodies = 256;
  /// What a worker saw among its bodies (scratch.sweep_seen, one per worker
  /// so that no two write the same).
  enum seen : std::uint8_t { bullet = 1, mover = 2 };

  /// Sweeps the bodies that need it (above), across the workers, in two
  /// passes as Box2D v3 does: first the fast bodies, which meet only static
  /// and kinematic bodies, which no sweep moves; then the bullets, which
  /// meet moving bodies too, where the first pass left them, but never
  /// another bullet. Within a pass no sweep reads what another writes (a
  /// body's own pose), so the poses are the same whichever worker sweeps
  /// which body, and in whatever order.
  void run() {
    const std::vector<std::uint32_t>& awake = state.awake_bodies;
    const std::vector<body_record<T>>& bodies = state.bodies.values();
    const auto swept = [&](std::uint32_t i) {
      return is_solved(bodies[i]) && !scratch.is_held(scratch.solver_place[i]);
    };
    scratch.sweep_movers.clear();
    find_movers([&](const body_record<T>& r, std::uint8_t& saw) {
      if (r.bullet && is_solved(r)) saw |= bullet;
      return r.body.type == body_type::kinematic && is_moving(r);
    });
    auto fast = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      for (std::uint32_t k = begin; k < end; ++k) {
        const std::uint32_t i = awake[k];
        const body_record<T>& r = bodies[i];
        if (!r.bullet && swept(i) &&
            length(r.body.position - r.previous.position) > state.settings.ccd_motion_fraction * r.thinnest)
          sweep_back(i);
      }
    };
    parallel_for(scratch.tasks, std::uint32_t(awake.size()), min_bodies, fast);
    if (!saw_any(bullet)) return;
    find_movers([](const body_record<T>& r, std::uint8_t&) { return is_solved(r) && !r.bullet; });
    auto bullets = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      for (std::uint32_t k = begin; k < end; ++k)
        if (bodies[awake[k]].bullet && swept(awake[k])) sweep_back(awake[k]);
    };
    parallel_for(scratch.tasks, std::uint32_t(awake.size()), min_bodies, bullets);
  }

 private:
  /// Adds to scratch.sweep_movers, in awake order, the awake bodies that
  /// `pick(record, saw)` picks and that left their broad-phase boxes in the
  /// step. The broad phase holds a body's box swept over its reach, which
  /// is capped (solver.max_speculative_distance): a query for a sweep
  /// cannot find a body that went further, so every sweep tests these too.
  template <class Pick>
  void find_movers(Pick pick) {
    const std::vector<std::uint32_t>& awake = state.awake_bodies;
    const std::vector<body_record<T>>& bodies = state.bodies.values();
    std::vector<std::uint8_t>& left = scratch.sweep_left;
    left.resize(awake.size());
    scratch.sweep_seen.assign(scratch.tasks.workers, 0);
    auto mark = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t worker) {
      std::uint8_t saw = 0;
      for (std::uint32_t k = begin; k < end; ++k) {
        const body_record<T>& r = bodies[awake[k]];
        left[k] = pick(r, saw) && !contains(state.broad.box(r.proxy), state.bounds_of(r));
        if (left[k]) saw |= mover;
      }
      scratch.sweep_seen[worker] |= saw;
    };
    parallel_for(scratch.tasks, std::uint32_t(awake.size()), min_bodies, mark);
    if (!saw_any(mover)) return;
    for (std::size_t k = 0; k < awake.size(); ++k)
      if (left[k]) scratch.sweep_movers.push_back(awake[k]);
  }
  [[nodiscard]] bool saw_any(std::uint8_t what) const noexcept {
    return std::any_of(scratch.sweep_seen.begin(), scratch.sweep_seen.end(),
                       [&](std::uint8_t saw) { return (saw & what) != 0; });
  }

  /// The body at dense place i stopped ccd_gap short of the first body its
  /// motion over the step meets, if any.
  void sweep_back(std::uint32_t i) {
    body_record<T>& r = state.bodies.values()[i];
    if (r.sensor) return;  // meets nothing
    const body_id id = state.bodies.ids()[i];
    const narrowphase::sweep<T> path = path_of(r);
    const aabb<T> swept = swept_box(r, path);
    T first = T(1);
    const auto meet = [&](body_id other) {
      if (other == id || !state.may_collide(id, other, scratch.pair_rule)) return;
      const body_record<T>& o = state.bodies[other];
      if (o.sensor) return;
      // Fast bodies meet the world; bullets meet moving bodies too, but
      // not each other (each is already swept).
      if (o.body.type == body_type::dynamic && (!r.bullet || o.bullet)) return;
      first = std::min(first, impact_time(r, path, o, path_of(o)));
    };
    state.broad.query(swept, [&](proxy_id proxy) { meet(state.unpack(state.broad.user_data(proxy))); });
    // Those the query cannot find where they went (one it found as well
    // gives the same impact again).
    for (const std::uint32_t m : scratch.sweep_movers) {
      const body_record<T>& o = state.bodies.values()[m];
      if (overlaps(swept, swept_box(o, path_of(o)))) meet(state.bodies.ids()[m]);
    }
    if (!(first < T(1))) return;
    const transform<T> at = narrowphase::sweep_motion<T>(path).at(first);
    r.body.position = apply(at, r.center);
    r.body.orientation = at.rotation;
  }

  /// A body's shape's motion over the step, from where it started to where
  /// it is.
  [[nodiscard]] static narrowphase::sweep<T> path_of(const body_record<T>& r) {
    return {{r.previous.position - rotate(r.previous.rotation, r.center), r.previous.rotation}, shape_pose_of(r),
            r.center};
  }
  /// The box around its shape at both ends of the path.
  [[nodiscard]] aabb<T> swept_box(const body_record<T>& r, const narrowphase::sweep<T>& path) const {
    return state.shape_store.visit(r.shape, [&](const auto& s) {
      return merge(s.world_aabb(path.start), s.world_aabb(path.end));
    });
  }

  /// When r, moving along path, first comes within ccd_gap of o moving along
  /// its own; 1 if not within the step.
  T impact_time(const body_record<T>& r, const narrowphase::sweep<T>& path, const body_record<T>& o,
                const narrowphase::sweep<T>& other_path) const {
    return state.shape_store.visit(r.shape, [&](const auto& mover) {
      return state.shape_store.visit(o.shape, [&](const auto& target) {
        return impact_between(mover, path, target, other_path);
      });
    });
  }

  /// Convex pairs by convex_impact_time; a mesh triangle by triangle
  /// (mesh_impact_time); a compound child by child, each swept with its
  /// body (the earliest of its children; of the target's, those near the
  /// mover's sweep). Planes are half-spaces, which nothing can cross unseen.
  template <class M, class O>
  T impact_between(const M& mover, const narrowphase::sweep<T>& path, const O& target,
                   const narrowphase::sweep<T>& other_path) const {
    constexpr bool convex_mover = requires(const M& m, vec3<T> d) { m.support(d); };
    constexpr bool convex_target = requires(const O& t, vec3<T> d) { t.support(d); };
    if constexpr (std::is_same_v<M, compound<T>>) {
      T first = T(1);
      for (std::size_t i = 0; i < mover.child_count(); ++i)
        mover.visit(i, [&](const auto& child, const transform<T>& local) {
          first = std::min(first, impact_between(child, child_sweep(path, local), target, other_path));
        });
      return first;
    } else if constexpr (convex_mover && std::is_same_v<O, compound<T>>) {
      T first = T(1);
      target.for_each_overlapping(near_box(mover, path, other_path), [&](std::size_t i) {
        target.visit(i, [&](const auto& child, const transform<T>& local) {
          first = std::min(first, impact_between(mover, path, child, child_sweep(other_path, local)));
        });
      });
      return first;
    } else if constexpr (convex_mover && (std::is_same_v<O, triangle_mesh<T>> || std::is_same_v<O, heightfield<T>>)) {
      return mesh_impact_time(mover, path, target, other_path);
    } else if constexpr (convex_mover && convex_target) {
      return convex_impact_time(mover, path, target, other_path);
    } else {
      return T(1);
    }
  }

  /// A compound's child's motion: its body's, from the child's place in it.
  static narrowphase::sweep<T> child_sweep(const narrowphase::sweep<T>& path, const transform<T>& local) noexcept {
    return {path.start * local, path.end * local, inverse_apply(local, path.local_center)};
  }
  /// The box, in the frame of a body moving along other_path, around the
  /// mover's sweep at both of its ends, grown by ccd_gap: where the parts
  /// (triangles, children) it may meet are.
  template <class M>
  aabb<T> near_box(const M& mover, const narrowphase::sweep<T>& path, const narrowphase::sweep<T>& other_path) const {
    const aabb<T> swept = merge(mover.world_aabb(path.start), mover.world_aabb(path.end));
    aabb<T> near = transform_aabb(swept, inverse(other_path.start));
    if (!(other_path.start == other_path.end)) near = merge(near, transform_aabb(swept, inverse(other_path.end)));
    return expand(near, state.settings.ccd_gap);
  }

  /// A convex pair. A ball against a body that does not turn is a sphere
  /// cast, exact; other pairs are conservative advancement
  /// (narrowphase/time_of_impact.hpp).
  template <class M, class O>
  T convex_impact_time(const M& mover, const narrowphase::sweep<T>& path, const O& target,
                       const narrowphase::sweep<T>& other_path) const {
    const T gap = state.settings.ccd_gap;
    if constexpr (std::is_same_v<M, sphere<T>>) {
      if (other_path.start == other_path.end) {
        // The ball's center against the body grown by its radius.
        const vec3<T> from = path.start.position, to = path.end.position;
        const T distance = length(to - from);
        const narrowphase::ray_hit<T> hit =
            narrowphase::sphere_cast(ray<T>{from, to - from}, mover.radius, target, other_path.start);
        // Starting within the grown body: the discrete contact has it (a
        // ball rolling fast on the ground is not stopped by it).
        if (!hit.hit || !(hit.fraction > T(0))) return T(1);
        const T t = hit.fraction - gap / distance;
        if (t > T(0)) return t;
        return passed(mover, path, target, other_path, -hit.normal) ? T(0) : T(1);
      }
    }
    narrowphase::toi_options<T> options;
    options.target = gap;
    options.tolerance = gap * T(0.25);
    const narrowphase::toi_result<T> hit = narrowphase::time_of_impact(mover, path, target, other_path, options);
    if (hit.state == narrowphase::toi_state::overlapping) return T(1);  // the discrete contacts have it
    if (hit.state == narrowphase::toi_state::separated) return T(1);
    if (hit.t > T(0)) return hit.t;
    return passed(mover, path, target, other_path, hit.normal) ? T(0) : T(1);
  }

  /// The earliest impact on any triangle of the mesh near the mover's
  /// sweep, each triangle a convex shape of its own.
  template <class M, class Mesh>
  T mesh_impact_time(const M& mover, const narrowphase::sweep<T>& path, const Mesh& mesh,
                     const narrowphase::sweep<T>& other_path) const {
    T first = T(1);
    mesh.for_each_overlapping(near_box(mover, path, other_path), [&](std::size_t t) {
      narrowphase::detail::convex_triangle<T> triangle;
      mesh.triangle(t, triangle.v[0], triangle.v[1], triangle.v[2]);
      first = std::min(first, convex_impact_time(mover, path, triangle, other_path));
    });
    return first;
  }

  /// For a pair that starts the step within ccd_gap (normal: from the
  /// mover towards the other), whether the step ended with the mover
  /// through the other or deeper in it than ccd_gap. Such a pair is the
  /// discrete contacts' to handle, and they nearly always hold it; a body
  /// that turns fast under the contact's impulse can still swing through
  /// (a 2 cm plate hitting a wall at 150 m/s, spinning at 10 rad/s), and is
  /// then put back where it started the step.
  template <class M, class O>
  bool passed(const M& mover, const narrowphase::sweep<T>& path, const O& target,
              const narrowphase::sweep<T>& other_path, const vec3<T>& normal) const {
    const narrowphase::gjk_result<T> end = narrowphase::gjk_distance(mover, path.end, target, other_path.end);
    if (!end.overlapping) return dot(end.on_b - end.on_a, normal) < T(0);
    return narrowphase::epa_penetration(mover, path.end, target, other_path.end).depth > state.settings.ccd_gap;
  }
};

}  // namespace impulse::detail
