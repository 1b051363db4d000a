// bench/scenes/metrics.hpp — the figures each standard scene is judged by,
// computed from the body states an engine reports (engine.hpp), so that
// every engine is measured by the same code; and the step-time median.
//
// A metric_recorder is told which steps it wants to see (most scenes only
// the last; bounce, heavy_on_light, landing and stack_1000to1 every step; incline steps 60 and 120)
// and turns them into named values. Displacements are measured from the
// scene's initial positions (scene_spec), which every engine starts from.
//
// Names and units of the values, per metric_set:
//   pile            lowest_box_center_y (m), boxes_below_y_0.45 (count),
//                   highest_box_top_y (m: max center y + 0.5),
//                   mean_column_top_y (m: mean over the 100 columns of the
//                   highest box top in the column; a box belongs to the
//                   column of the nearest grid (i, k)), bodies_awake,
//                   max_speed (m/s)
//   pyramid         max_abs_dx, max_abs_dy, max_abs_dz, max_displacement
//                   (m, over all boxes), top_box_y (m), bodies_awake,
//                   max_speed (m/s)
//   spheres         escaped (count: center outside |x|, |z| < 7.5 or below
//                   y = 0), mean_height (m, of the centers), bodies_awake,
//                   max_speed (m/s)
//   bounce          first_rebound_peak (m, center y)
//   incline_sliding acceleration (m/s²: down-slope speed at step 120 minus
//                   at step 60, 1 s apart at dt = 1/60), speed_at_2s (m/s)
//   incline_static  drift (m the center moved by the last step, 5 s),
//                   final_speed (m/s)
//   tower           top_horizontal_drift (m), top_height_lost (m: initial
//                   top center y − final)
//   heavy_on_light  sinking_end, sinking_max (m: initial heavy center y −
//                   its y, at the end and the largest over the run)
//   cradle          last_ball_speed_ratio, first_ball_speed_ratio (final
//                   speed over the first ball's initial speed),
//                   kinetic_energy_ratio (final over initial)
//   landing         depth_max, depth_end (m: how far below its resting
//                   height 0.5 a body's center is, the largest over the
//                   bodies and the run, and over the bodies at the end)
//   stack           sink_max, sink_end (m: how far below its initial
//                   height a box's center is, the largest over the boxes
//                   and the run, and at the end), and the top box's as in tower
//
// Column height: a settled column of ten unit boxes has its top face at
// y = 10 and its top box's center at 9.5 (the `pile` scene's "nominal 9.5"); the
// two pile heights here are top faces, so their nominal value is 10.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "engine.hpp"
#include "scene_spec.hpp"

namespace bench::scenes {

struct metric_value {
  std::string name;
  double value = 0;
};

/// Steps whose times enter the median: the last 300, or the last half of
/// a shorter run (the first steps of a scene are its transient).
inline std::size_t timing_window(int steps) { return static_cast<std::size_t>(std::min(300, steps / 2)); }

/// Median of the last `window` samples (all of them if fewer).
inline double median_of_last(std::span<const double> samples, std::size_t window) {
  window = std::min(window, samples.size());
  if (window == 0) return 0;
  std::vector<double> tail(samples.end() - static_cast<std::ptrdiff_t>(window), samples.end());
  const auto mid = tail.begin() + static_cast<std::ptrdiff_t>(window / 2);
  std::nth_element(tail.begin(), mid, tail.end());
  if (window % 2 == 1) return *mid;
  return (*mid + *std::max_element(tail.begin(), mid)) / 2;
}

namespace detail {

inline double length(const vec3& v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }
inline vec3 minus(const vec3& a, const vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline double dot(const vec3& a, const vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

}  // namespace detail

class metric_recorder {
 public:
  explicit metric_recorder(const scene_spec& spec) : spec_(&spec) {
    for (std::size_t i = 0; i < spec.bodies.size(); ++i)
      if (!spec.bodies[i].is_static) dynamic_.push_back(i);
  }

  /// Whether observe() must see the states after step `step` (1-based).
  [[nodiscard]] bool wants(int step) const {
    switch (spec_->metrics) {
      case metric_set::bounce:
      case metric_set::heavy_on_light:
      case metric_set::landing:
      case metric_set::stack:
        return true;
      case metric_set::incline_sliding:
        return step == steps_per_second() || step == 2 * steps_per_second();
      default:
        return step == spec_->steps;
    }
  }

  void observe(int step, std::span<const body_state> states) {
    switch (spec_->metrics) {
      case metric_set::pile: if (step == spec_->steps) end_pile(states); break;
      case metric_set::pyramid: if (step == spec_->steps) end_pyramid(states); break;
      case metric_set::spheres: if (step == spec_->steps) end_spheres(states); break;
      case metric_set::bounce: track_bounce(step, states); break;
      case metric_set::incline_sliding: track_incline(step, states); break;
      case metric_set::incline_static: if (step == spec_->steps) end_incline_static(states); break;
      case metric_set::tower: if (step == spec_->steps) end_tower(states); break;
      case metric_set::heavy_on_light: track_heavy(step, states); break;
      case metric_set::cradle: if (step == spec_->steps) end_cradle(states); break;
      case metric_set::landing: track_landing(step, states); break;
      case metric_set::stack: track_stack(step, states); break;
    }
  }

  [[nodiscard]] const std::vector<metric_value>& results() const { return values_; }

 private:
  [[nodiscard]] int steps_per_second() const { return static_cast<int>(std::lround(1.0 / spec_->dt)); }
  [[nodiscard]] const body_spec& initial(std::size_t i) const { return spec_->bodies[i]; }
  void put(const char* name, double value) { values_.push_back({name, value}); }

  // Figures every scene of many bodies reports.
  void put_awake_and_speed(std::span<const body_state> states) {
    int awake = 0;
    double max_speed = 0;
    for (std::size_t i : dynamic_) {
      awake += states[i].awake ? 1 : 0;
      max_speed = std::max(max_speed, detail::length(states[i].linear_velocity));
    }
    put("bodies_awake", awake);
    put("max_speed", max_speed);
  }

  void end_pile(std::span<const body_state> states) {
    using L = pile_layout;
    double lowest = infinity, highest_top = -infinity;
    int below = 0;
    // A column with no box left in it counts as height 0 (the ground).
    std::array<double, L::side * L::side> column_top{};
    auto column = [](double coordinate) {
      const long c = std::lround(coordinate / L::spacing + L::center_offset);
      return static_cast<std::size_t>(std::clamp<long>(c, 0, L::side - 1));
    };
    for (std::size_t i : dynamic_) {
      const vec3& p = states[i].position;
      lowest = std::min(lowest, p.y);
      below += p.y < 0.45 ? 1 : 0;  // a box resting on the ground has its center at 0.5
      const double top = p.y + L::half_extent;
      highest_top = std::max(highest_top, top);
      double& col = column_top[column(p.x) * L::side + column(p.z)];
      col = std::max(col, top);
    }
    double sum = 0;
    for (double top : column_top) sum += top;
    put("lowest_box_center_y", lowest);
    put("boxes_below_y_0.45", below);
    put("highest_box_top_y", highest_top);
    put("mean_column_top_y", sum / double(column_top.size()));
    put_awake_and_speed(states);
  }

  void end_pyramid(std::span<const body_state> states) {
    double dx = 0, dy = 0, dz = 0, d = 0;
    for (std::size_t i : dynamic_) {
      const vec3 delta = detail::minus(states[i].position, initial(i).position);
      dx = std::max(dx, std::abs(delta.x));
      dy = std::max(dy, std::abs(delta.y));
      dz = std::max(dz, std::abs(delta.z));
      d = std::max(d, detail::length(delta));
    }
    put("max_abs_dx", dx);
    put("max_abs_dy", dy);
    put("max_abs_dz", dz);
    put("max_displacement", d);
    put("top_box_y", states[dynamic_.back()].position.y);
    put_awake_and_speed(states);
  }

  void end_spheres(std::span<const body_state> states) {
    int escaped = 0;
    double sum_y = 0;
    for (std::size_t i : dynamic_) {
      const vec3& p = states[i].position;
      escaped += (std::abs(p.x) >= 7.5 || std::abs(p.z) >= 7.5 || p.y < 0) ? 1 : 0;
      sum_y += p.y;
    }
    put("escaped", escaped);
    put("mean_height", sum_y / double(dynamic_.size()));
    put_awake_and_speed(states);
  }

  // The first rebound's peak: the highest center after the ball first
  // touches (center below radius + 2 cm, or already moving up) and before
  // it comes back down to that height. Phases: falling, rebounding, done.
  // The ball has left the ground once it is above the touch height and
  // rising: at dt = 1/60 it arrives at 13.6 m/s, so the step that reverses
  // it may still leave it below the touch height, moving up.
  void track_bounce(int step, std::span<const body_state> states) {
    const std::size_t ball = dynamic_.front();
    const double touch_y = initial(ball).radius + 0.02;
    const double y = states[ball].position.y, vy = states[ball].linear_velocity.y;
    if (bounce_phase_ == 0 && (y < touch_y || vy > 0)) bounce_phase_ = 1;
    if (bounce_phase_ == 1) {
      bounce_peak_ = std::max(bounce_peak_, y);
      if (y > touch_y && vy > 0) bounce_left_ground_ = true;
      if (bounce_left_ground_ && y < touch_y) bounce_phase_ = 2;
    }
    if (step == spec_->steps) put("first_rebound_peak", bounce_peak_);
  }

  // Down-slope speed: the velocity along the slab's −x axis (the slab is
  // the scene's static body, its turn gives the slope).
  [[nodiscard]] double down_slope_speed(std::span<const body_state> states) const {
    const vec3 down = rotate(initial(0).orientation, {-1, 0, 0});
    return detail::dot(states[dynamic_.front()].linear_velocity, down);
  }

  void track_incline(int step, std::span<const body_state> states) {
    if (step == steps_per_second()) incline_speed_1s_ = down_slope_speed(states);
    if (step == 2 * steps_per_second()) {
      const double speed_2s = down_slope_speed(states);
      put("acceleration", speed_2s - incline_speed_1s_);  // over exactly 1 s
      put("speed_at_2s", speed_2s);
    }
  }

  void end_incline_static(std::span<const body_state> states) {
    const std::size_t box = dynamic_.front();
    put("drift", detail::length(detail::minus(states[box].position, initial(box).position)));
    put("final_speed", detail::length(states[box].linear_velocity));
  }

  void end_tower(std::span<const body_state> states) {
    const std::size_t top = dynamic_.back();
    const vec3 delta = detail::minus(states[top].position, initial(top).position);
    put("top_horizontal_drift", std::sqrt(delta.x * delta.x + delta.z * delta.z));
    put("top_height_lost", -delta.y);
  }

  void track_heavy(int step, std::span<const body_state> states) {
    const std::size_t heavy = dynamic_.back();
    const double sinking = initial(heavy).position.y - states[heavy].position.y;
    sinking_max_ = std::max(sinking_max_, sinking);
    if (step == spec_->steps) {
      put("sinking_end", sinking);
      put("sinking_max", sinking_max_);
    }
  }

  void track_landing(int step, std::span<const body_state> states) {
    double deepest = -infinity;
    for (std::size_t i : dynamic_) deepest = std::max(deepest, 0.5 - states[i].position.y);
    landing_max_ = std::max(landing_max_, deepest);
    if (step == spec_->steps) {
      put("depth_max", landing_max_);
      put("depth_end", deepest);
    }
  }

  void track_stack(int step, std::span<const body_state> states) {
    double sink = -infinity;
    for (std::size_t i : dynamic_) sink = std::max(sink, initial(i).position.y - states[i].position.y);
    sink_max_ = std::max(sink_max_, sink);
    if (step == spec_->steps) {
      put("sink_max", sink_max_);
      put("sink_end", sink);
      end_tower(states);
    }
  }

  void end_cradle(std::span<const body_state> states) {
    const std::size_t first = dynamic_.front(), last = dynamic_.back();
    const double v0 = detail::length(initial(first).linear_velocity);
    double energy_0 = 0, energy = 0;
    for (std::size_t i : dynamic_) {
      const double v_init = detail::length(initial(i).linear_velocity);
      const double v = detail::length(states[i].linear_velocity);
      energy_0 += initial(i).mass * v_init * v_init / 2;
      energy += initial(i).mass * v * v / 2;
    }
    put("last_ball_speed_ratio", detail::length(states[last].linear_velocity) / v0);
    put("first_ball_speed_ratio", detail::length(states[first].linear_velocity) / v0);
    put("kinetic_energy_ratio", energy / energy_0);
  }

  static constexpr double infinity = std::numeric_limits<double>::infinity();

  const scene_spec* spec_;
  std::vector<std::size_t> dynamic_;  // indices of the dynamic bodies, in spec order
  std::vector<metric_value> values_;
  int bounce_phase_ = 0;
  bool bounce_left_ground_ = false;
  double bounce_peak_ = -infinity;
  double incline_speed_1s_ = 0;
  double sinking_max_ = -infinity;
  double landing_max_ = -infinity;
  double sink_max_ = -infinity;
};

}  // namespace bench::scenes
