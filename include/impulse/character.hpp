// impulse/character.hpp — a character controller: an upright capsule that
// walks where it is told, slides along what it meets, climbs steps and
// walkable slopes, stops at steep ones and walls, falls under gravity, is
// carried by what it stands on (moving and turning platforms), pushes
// dynamic bodies with at most a set force, and crouches. Optional: nothing
// else in impulse includes it.
//
//   impulse::character<config> hero(world, {}, {0, 0, 0});
//   hero.move({2, 0, 0}, dt);   // after world.step(dt): 2 m/s along x
//   if (hero.on_ground() && jump_pressed) hero.jump(5);
//
// The character is not a body of the world: it moves by the world's shape
// casts (world::shape_cast) and only ever stops short of what it meets,
// which a solver never pushes back. Bodies do not collide with it, and
// sensors do not see it; it pushes the dynamic bodies it walks into with a
// force of at most push_force over the world's next step (Jolt's
// CharacterVirtual and Box2D v3's mover work the same way).
//
// A move, after Bullet's kinematic character and Jolt's virtual one:
// 1. Carried: the ground it stood on moved (translated and turned) since
//    the last move; the feet go with it, exactly, by the ground's change
//    of pose, so a turning platform carries it round a circle, not out
//    along a spiral.
// 2. Along the ground: the walk and the carry, as collide-and-slide: cast
//    the capsule grown by `skin` (so that it stops a skin short of what it
//    meets, and slides along what it stands a skin from), take off the part
//    of what is left that runs into the hit's normal, and go on with the
//    rest (at most 4 times). A surface steeper than max_slope counts as a wall:
//    its normal is taken level, so the walk slides along it and never up.
//    A walk stopped short on the ground tries again from step_height up,
//    and keeps that if it went farther and came down on walkable ground.
// 3. Up or down: the vertical speed (gravity, a jump) the same way; what
//    it meets stops it.
// 4. The ground: a cast down by the skin, or by step_height when it stood
//    on the ground and is not rising (so it keeps to stairs and slopes
//    going down); walkable ground within it becomes the ground, and the
//    feet settle `skin` above it. On an edge the cast's normal is the slant
//    from the edge to the cap; a short ray down past the edge finds the
//    face it stands on.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "world.hpp"

namespace impulse {

template <scalar_type T>
struct character_def {
  T radius = T(0.3);             ///< m
  T height = T(1.8);             ///< m, feet to the top of the head, standing: > 2·radius
  T crouch_height = T(1.0);      ///< m, crouching: in [2·radius, height]
  T max_slope = T(0.7853982);    ///< rad: the steepest ground it stands and walks on (45°)
  T step_height = T(0.3);        ///< m: the highest step it walks up
  T skin = T(0.01);              ///< m: the gap it keeps from what it touches
  T push_force = T(200);         ///< N: the most it pushes a dynamic body with
  query_filter filter{};         ///< the bodies it collides with

  void validate() const {
    const bool finite = std::isfinite(radius) && std::isfinite(height) && std::isfinite(crouch_height) &&
                        std::isfinite(max_slope) && std::isfinite(step_height) && std::isfinite(skin) &&
                        std::isfinite(push_force);
    if (!finite) detail::report_error(error_code::non_finite, "character_def: a value is not finite");
    if (!(radius > T(0) && height > T(2) * radius && crouch_height >= T(2) * radius && crouch_height <= height &&
          max_slope >= T(0) && max_slope < T(1.5707963) && step_height >= T(0) && skin > T(0) && push_force >= T(0)))
      detail::report_error(error_code::invalid_parameter,
                           "character_def: needs radius > 0, height > 2·radius, crouch_height in [2·radius, height], "
                           "max_slope in [0, π/2), step_height ≥ 0, skin > 0, push_force ≥ 0");
  }
};

/// What a character stands on.
template <scalar_type T>
struct character_ground {
  body_id body;
  vec3<T> point{};     ///< world, m: where it touches, under the feet
  vec3<T> normal{};    ///< world, unit: the ground's, out of it
  vec3<T> velocity{};  ///< m/s: the ground's own at that point, v + ω × r
};

template <class Config>
class character {
 public:
  using T = typename Config::scalar;

  /// A character standing with its feet at `feet`, upright against the
  /// world's gravity (straight up along y in a world without gravity).
  character(world<Config>& w, const character_def<T>& def, const vec3<T>& feet)
      : world_(&w), def_(def), feet_(feet), height_(def.height) {
    def.validate();
    if (!is_finite(feet)) detail::report_error(error_code::non_finite, "character: the feet are not finite");
    const vec3<T> g = w.settings().gravity;
    up_ = length_squared(g) > T(0) ? normalize(-g) : vec3<T>{T(0), T(1), T(0)};
    const vec3<T> y{T(0), T(1), T(0)};
    const vec3<T> axis = cross(y, up_);
    const T turn = portable_acos(std::clamp(dot(y, up_), T(-1), T(1)));
    upright_ = length(axis) > T(1e-6) ? quat<T>::from_axis_angle(normalize(axis), turn)
               : dot(y, up_) > T(0)   ? quat<T>::identity()
                                      : quat<T>::from_axis_angle({T(1), T(0), T(0)}, T(3.14159265358979));
  }

  /// Walks at `velocity` (its part across up; the vertical is gravity's
  /// and jump's) for dt seconds, as the top of this file says. Call it once
  /// a step, after world::step. Refused: a velocity that is not finite, dt
  /// not positive.
  void move(const vec3<T>& velocity, T dt) {
    if (!is_finite(velocity)) detail::report_error(error_code::non_finite, "character::move: velocity is not finite");
    if (!(dt > T(0) && dt <= T(1)))
      detail::report_error(error_code::invalid_parameter, "character::move: dt must be in (0, 1]");
    const vec3<T> start = feet_;
    const bool was_grounded = ground_.has_value();
    vec3<T> along = across(velocity) * dt + carried();
    // Gravity while in the air; on the ground the vertical speed rests at 0.
    if (!was_grounded || vertical_speed_ > T(0))
      vertical_speed_ += dot(world_->settings().gravity, up_) * dt;
    const T vertical = was_grounded && vertical_speed_ <= T(0) ? T(0) : vertical_speed_ * dt;
    walk(across(along), was_grounded);
    const T up_part = dot(along, up_);  // a platform's rise or fall
    if (vertical + up_part != T(0)) {
      const T moved = slide(up_ * (vertical + up_part));
      apply_pushes();
      // A ceiling stops a rise.
      if (moved < std::abs(vertical + up_part) - T(1e-6) && vertical_speed_ > T(0)) vertical_speed_ = T(0);
    }
    find_ground(was_grounded && vertical_speed_ <= T(0));
    if (ground_) vertical_speed_ = T(0);
    velocity_ = (feet_ - start) * (T(1) / dt);
  }

  /// Leaves the ground at `speed` up (m/s) at the next move.
  void jump(T speed) {
    if (!std::isfinite(speed) || speed < T(0))
      detail::report_error(error_code::invalid_parameter, "character::jump: speed must be finite and >= 0");
    vertical_speed_ = speed;
    ground_.reset();
  }

  /// Crouches: the capsule shrinks to crouch_height, feet where they are.
  void crouch() noexcept { height_ = def_.crouch_height; }
  /// Stands up if the standing capsule has room; returns whether it did.
  bool stand() {
    if (height_ == def_.height) return true;
    bool blocked = false;
    world_->shape_overlap(shape_at(def_.height), pose_at(feet_, def_.height), [&](body_id) { blocked = true; },
                          def_.filter);
    if (!blocked) height_ = def_.height;
    return !blocked;
  }

  [[nodiscard]] vec3<T> feet() const noexcept { return feet_; }
  [[nodiscard]] vec3<T> up() const noexcept { return up_; }
  [[nodiscard]] T height() const noexcept { return height_; }
  [[nodiscard]] bool crouching() const noexcept { return height_ < def_.height; }
  [[nodiscard]] bool on_ground() const noexcept { return ground_.has_value(); }
  [[nodiscard]] const std::optional<character_ground<T>>& ground() const noexcept { return ground_; }
  /// m/s: how it moved in the last move, all told.
  [[nodiscard]] vec3<T> velocity() const noexcept { return velocity_; }
  [[nodiscard]] T vertical_speed() const noexcept { return vertical_speed_; }
  /// Its capsule and where it is, for drawing.
  [[nodiscard]] capsule<T> shape() const { return shape_at(height_); }
  [[nodiscard]] transform<T> pose() const noexcept { return pose_at(feet_, height_); }
  /// Puts the feet at `feet` at once, in the air until the next move finds ground.
  void teleport(const vec3<T>& feet) {
    if (!is_finite(feet)) detail::report_error(error_code::non_finite, "character::teleport: the feet are not finite");
    feet_ = feet;
    ground_.reset();
    vertical_speed_ = T(0);
  }

 private:
  static constexpr int max_slides = 4;

  [[nodiscard]] capsule<T> shape_at(T height) const {
    return capsule<T>::make(def_.radius, height / T(2) - def_.radius);
  }
  /// What the casts sweep: the capsule grown by the skin all round.
  [[nodiscard]] capsule<T> probe() const {
    return capsule<T>::make(def_.radius + def_.skin, height_ / T(2) - def_.radius);
  }
  [[nodiscard]] transform<T> pose_at(const vec3<T>& feet, T height) const noexcept {
    return {feet + up_ * (height / T(2)), upright_};
  }
  [[nodiscard]] vec3<T> across(const vec3<T>& v) const noexcept { return v - up_ * dot(v, up_); }
  [[nodiscard]] bool walkable(const vec3<T>& normal) const noexcept {
    return dot(normal, up_) >= portable_cos(def_.max_slope) - T(1e-6);
  }

  /// How far the ground carried the feet since the last move: its change
  /// of pose applied to them.
  vec3<T> carried() {
    if (!ground_ || !world_->contains(ground_->body)) return {};
    const transform<T> now = world_->shape_pose(ground_->body);
    const vec3<T> moved = apply(now, inverse_apply(ground_pose_, feet_)) - feet_;
    ground_pose_ = now;
    return moved;
  }

  /// Collide-and-slide by d from the feet; returns how far it went.
  T slide(vec3<T> d) {
    T moved = T(0);
    const capsule<T> body = probe();
    for (int k = 0; k < max_slides; ++k) {
      const T distance = length(d);
      if (!(distance > T(1e-7))) break;
      const std::optional<world_ray_hit<T>> hit = world_->shape_cast(body, pose(), d, def_.filter);
      if (!hit) {
        feet_ += d;
        moved += distance;
        break;
      }
      const vec3<T> direction = d * (T(1) / distance);
      vec3<T> n = hit->normal;
      const T travel = hit->fraction * distance;
      feet_ += direction * travel;
      moved += travel;
      push(*hit, direction);
      if (!walkable(n)) {
        const vec3<T> level = across(n);
        if (length_squared(level) > T(1e-12)) n = normalize(level);
      }
      d = d - direction * travel;
      const T against = dot(d, n);
      if (against < T(0)) d = d - n * against;
    }
    return moved;
  }

  /// The walk across up, with one try from a step up when it is stopped
  /// short on the ground.
  void walk(const vec3<T>& d, bool grounded) {
    const T wanted = length(d);
    if (!(wanted > T(0))) return;
    const vec3<T> from = feet_;
    pushes_.clear();
    slide(d);
    const T got = length(across(feet_ - from));
    if (!grounded || def_.step_height <= T(0) || got >= wanted * T(0.99)) return apply_pushes();
    const vec3<T> plain = feet_;
    const std::size_t plain_pushes = pushes_.size();
    feet_ = from;
    const T lifted = slide(up_ * def_.step_height);
    slide(d);
    const T further = length(across(feet_ - from));
    // Down again onto walkable ground within the lift (and its skin); on a
    // step's edge, the rounded cap meets the edge at a slant, so the ground
    // is looked for a radius further on as well.
    const T reach = lifted + def_.skin;
    const std::optional<world_ray_hit<T>> below = world_->shape_cast(probe(), pose(), up_ * -reach, def_.filter);
    bool lands = below && walkable(surface_normal(*below));
    if (below && !lands) {
      const vec3<T> ahead = normalize(across(d)) * def_.radius;
      if (!world_->shape_cast(probe(), pose(), ahead, def_.filter)) {
        const transform<T> there{pose().position + ahead, upright_};
        const std::optional<world_ray_hit<T>> beyond = world_->shape_cast(probe(), there, up_ * -reach, def_.filter);
        lands = beyond && walkable(surface_normal(*beyond));
      }
    }
    // The rounded cap rides up an edge: what it lands on must be no higher
    // than a step above where the feet were.
    lands = lands && dot(below->point - from, up_) <= def_.step_height + def_.skin;
    if (further > got + T(1e-4) && lands) {
      feet_ -= up_ * (below->fraction * reach);
      pushes_.erase(pushes_.begin(), pushes_.begin() + std::ptrdiff_t(plain_pushes));
    } else {
      feet_ = plain;
      pushes_.resize(plain_pushes);
    }
    apply_pushes();
  }

  /// The normal of the surface under a cast's hit. On an edge or a corner
  /// the cast's normal is the slant from the edge to the cap's center, not
  /// the face the cap stands on: a short ray down just past the edge, away
  /// from the character, finds that face.
  [[nodiscard]] vec3<T> surface_normal(const world_ray_hit<T>& hit) const {
    if (walkable(hit.normal)) return hit.normal;
    const vec3<T> level = across(hit.normal);
    if (!(length_squared(level) > T(1e-12))) return hit.normal;
    const vec3<T> from = hit.point - normalize(level) * def_.skin + up_ * def_.skin;
    const std::optional<world_ray_hit<T>> face =
        world_->ray_cast(ray<T>{from, up_ * -(T(2) * def_.skin)}, T(1), def_.filter);
    return face && face->body == hit.body ? face->normal : hit.normal;
  }

  /// Looks down for ground within reach; settles the feet on it.
  void find_ground(bool snap) {
    const T reach = def_.skin + (snap ? def_.step_height : T(0));
    ground_.reset();
    if (vertical_speed_ > T(0)) return;
    const std::optional<world_ray_hit<T>> hit = world_->shape_cast(probe(), pose(), up_ * -reach, def_.filter);
    if (!hit) return;
    const vec3<T> normal = surface_normal(*hit);
    if (!walkable(normal)) return;
    feet_ -= up_ * (hit->fraction * reach);
    const rigid_body<T>& b = world_->body(hit->body);
    ground_ = character_ground<T>{hit->body, hit->point, normal, b.velocity_at(hit->point)};
    ground_pose_ = world_->shape_pose(hit->body);
  }

  /// A force of at most push_force on a dynamic body walked into, for the
  /// world's next step: a force, not an impulse, so that the solver weighs
  /// it against friction and the rest over the step (an impulse is a blow:
  /// one of push_force·dt a step made a box that friction holds against
  /// push_force creep 3 cm in 2 s). Kept until the walk knows which way it
  /// went (apply_pushes).
  void push(const world_ray_hit<T>& hit, const vec3<T>& direction) {
    if (world_->body(hit.body).type != body_type::dynamic || def_.push_force <= T(0)) return;
    const T into = -dot(direction, hit.normal);
    if (!(into > T(0))) return;
    pushes_.push_back({hit.body, hit.normal * -(def_.push_force * into), hit.point});
  }
  /// The walk's pushes, one a body (the strongest): at most push_force
  /// each in a move.
  void apply_pushes() {
    for (std::size_t k = 0; k < pushes_.size(); ++k) {
      bool strongest = true;
      for (std::size_t j = 0; j < pushes_.size() && strongest; ++j)
        if (j != k && pushes_[j].body == pushes_[k].body) {
          const T a = length_squared(pushes_[j].force), b = length_squared(pushes_[k].force);
          strongest = b > a || (b == a && k < j);
        }
      if (strongest) world_->apply_force_at(pushes_[k].body, pushes_[k].force, pushes_[k].point);
    }
    pushes_.clear();
  }

  world<Config>* world_;
  character_def<T> def_;
  vec3<T> up_{T(0), T(1), T(0)};
  quat<T> upright_ = quat<T>::identity();
  vec3<T> feet_;
  T height_;
  T vertical_speed_ = T(0);
  vec3<T> velocity_{};
  std::optional<character_ground<T>> ground_;
  transform<T> ground_pose_ = transform<T>::identity();
  struct pending_push {
    body_id body;
    vec3<T> force, point;
  };
  std::vector<pending_push> pushes_;
};

}  // namespace impulse
