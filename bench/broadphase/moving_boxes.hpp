// bench/broadphase/moving_boxes.hpp — the three scenes of boxes that the
// broad-phase benchmark moves, specified so that another engine can replay
// them draw for draw.
//
// Every scene draws from impulse::lcg32 seeded 2026, in the order written
// below, in float; a step is dt = 1/60 s. Each box is drawn as its center
// (x, y, z) then its half extents (x, y, z), then what the scene says.
//
// uniform     N boxes in the cube [0, L]³, L = 1.5·∛N m; half extents
//             uniform in [0.1, 0.6] m (about one overlap per box). Then a
//             draw u: if u < 0.25 the box stands still, else its velocity
//             is uniform in [−2, 2]³ m/s, reflected at the cube's faces
//             (a component is negated when the center is outside [0, L]
//             and moving further out).
// clustered   Eight cluster centers uniform in [0, 3L]³ drawn first; each box
//             picks a cluster (next() % 8) and lies at its center plus
//             (a + b + c)·0.1·L per axis, a, b, c uniform in [−1, 1];
//             sizes and motion as uniform, reflected at [0, 3L]³.
// falling     A static ground box [−S/2 − 1, S/2 + 1] × [−1, 0] ×
//  pile       [−S/2 − 1, S/2 + 1] (proxy 0), S = 0.7·√N m; then N − 1
//             boxes with centers x, z uniform in [−S/2, S/2], half extents
//             uniform in [0.2, 0.5] m, bottom at rest uniform in [1, 11] m
//             and a landing height for the bottom uniform in [0, 1] m.
//             Each falls from rest under 9.81 m/s² (symplectic Euler,
//             velocity first) until its bottom reaches the landing height,
//             where it stops: after 90 steps (1.5 s) most have landed in a
//             1 m layer, overlapping the ground and several neighbours.
//
// Only the boxes that moved in a step are handed to the broad phase.
#pragma once

#include <cmath>
#include <cstdint>
#include <string_view>
#include <vector>

#include "impulse/core/random.hpp"
#include "impulse/math/aabb.hpp"

namespace bench {

using box = impulse::aabb<float>;
using vec = impulse::vec3<float>;

enum class distribution { uniform, clustered, falling_pile };

inline std::string_view name_of(distribution d) {
  switch (d) {
    case distribution::uniform: return "uniform";
    case distribution::clustered: return "clustered";
    case distribution::falling_pile: return "falling_pile";
  }
  return "?";
}

class moving_boxes {
 public:
  static constexpr float dt = 1.0f / 60.0f;

  moving_boxes(distribution d, int n) : kind_(d), random_{2026} {
    const float L = 1.5f * std::cbrt(float(n));
    if (d == distribution::falling_pile) {
      const float S = 0.7f * std::sqrt(float(n));
      boxes_.push_back({{-S / 2 - 1, -1, -S / 2 - 1}, {S / 2 + 1, 0, S / 2 + 1}});
      bodies_.push_back({});
      for (int i = 1; i < n; ++i) {
        const float x = uniform(-S / 2, S / 2), z = uniform(-S / 2, S / 2);
        const vec half{uniform(0.2f, 0.5f), uniform(0.2f, 0.5f), uniform(0.2f, 0.5f)};
        const float bottom = uniform(1.0f, 11.0f), landing = uniform(0.0f, 1.0f);
        boxes_.push_back({{x - half.x, bottom, z - half.z}, {x + half.x, bottom + 2 * half.y, z + half.z}});
        bodies_.push_back({{}, landing, true});
      }
      bounds_ = {{-S / 2 - 2, -2, -S / 2 - 2}, {S / 2 + 2, 13, S / 2 + 2}};
      return;
    }
    const float reach = d == distribution::clustered ? 3 * L : L;
    vec clusters[8]{};
    if (d == distribution::clustered)
      for (vec& c : clusters) c = random_vec(0, reach);
    for (int i = 0; i < n; ++i) {
      vec center;
      if (d == distribution::clustered) {
        const vec& c = clusters[random_.next() % 8];
        const vec a = random_vec(-1, 1), b = random_vec(-1, 1), e = random_vec(-1, 1);
        center = c + (a + b + e) * (0.1f * L);
      } else {
        center = random_vec(0, L);
      }
      const vec half = random_vec(0.1f, 0.6f);
      boxes_.push_back({center - half, center + half});
      const bool still = uniform(0, 1) < 0.25f;
      bodies_.push_back({still ? vec{} : random_vec(-2, 2), 0, !still});
    }
    reach_ = reach;
    bounds_ = {vec::splat(-0.3f * L - 2), vec::splat(reach + 0.3f * L + 2)};
  }

  /// Advances one step and lists the boxes that moved.
  void step() {
    moved_.clear();
    for (std::uint32_t i = 0; i < boxes_.size(); ++i) {
      body& b = bodies_[i];
      if (!b.moving) continue;
      box& x = boxes_[i];
      if (kind_ == distribution::falling_pile) {
        b.velocity.y -= 9.81f * dt;
        float drop = b.velocity.y * dt;
        if (x.lower.y + drop <= b.landing) drop = b.landing - x.lower.y, b.moving = false;
        x.lower.y += drop;
        x.upper.y += drop;
      } else {
        const vec d = b.velocity * dt;
        x.lower += d;
        x.upper += d;
        const vec c = impulse::center(x);
        for (int axis = 0; axis < 3; ++axis)
          if ((c[axis] < 0 && b.velocity[axis] < 0) || (c[axis] > reach_ && b.velocity[axis] > 0))
            b.velocity[axis] = -b.velocity[axis];
      }
      moved_.push_back(i);
    }
  }

  [[nodiscard]] const std::vector<box>& boxes() const noexcept { return boxes_; }
  [[nodiscard]] const std::vector<std::uint32_t>& moved() const noexcept { return moved_; }
  /// A box that holds the scene for its whole run (Bullet's axis sweep
  /// quantises within it).
  [[nodiscard]] const box& bounds() const noexcept { return bounds_; }

 private:
  struct body {
    vec velocity{};
    float landing = 0;
    bool moving = false;
  };
  float uniform(float lo, float hi) { return random_.uniform(lo, hi); }
  vec random_vec(float lo, float hi) {
    const float x = uniform(lo, hi), y = uniform(lo, hi), z = uniform(lo, hi);
    return {x, y, z};
  }

  distribution kind_;
  impulse::lcg32 random_;
  std::vector<box> boxes_;
  std::vector<body> bodies_;
  std::vector<std::uint32_t> moved_;
  box bounds_{};
  float reach_ = 0;
};

}  // namespace bench
