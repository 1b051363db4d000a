// bench/scenes/scene_spec.hpp — the standard rigid-body scenes of
// docs/standard_scenes.md as plain data that any engine can build:
// a list of boxes and spheres with their pose, mass and material, the time
// step, gravity, step count, whether sleeping is on, and which metrics the
// scene is judged by (metrics.hpp).
//
// Everything an engine needs is here and nothing else is: an adapter reads
// the bodies in order, creates one body per entry and reports the states
// back in the same order. Static bodies come first in every scene, so the
// metrics find "the top box" or "the last ball" as the last dynamic entry.
//
// Materials are per body, and every body of a scene has the scene's value:
// docs/standard_scenes.md defines the *effective* pair values (friction
// combined as sqrt(a·b), restitution as max(a, b)), which with equal values
// are the values themselves. An engine that combines differently must set its
// per-body values so that its own combine gives these (bullet_engine.hpp).
//
// What the table of docs/standard_scenes.md leaves open is settled here, and
// listed on that page: the `incline` geometry, the `bounce` ground and
// material, and the hard cases `tower10`, `heavy_on_light` and `cradle`.
// Choices this file makes on its own are marked "choice:". One of them: the
// single-purpose scenes (bounce, incline, incline_static, tower10,
// heavy_on_light, cradle) run with sleeping off, so that a figure measures the solver and not a
// sleep timer (a box that fell asleep on the incline would "hold" at any
// friction; a sleeping tower cannot drift).
#pragma once

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "impulse/core/random.hpp"

namespace bench::scenes {

struct vec3 {
  double x = 0, y = 0, z = 0;
};

/// Unit quaternion w + xi + yj + zk.
struct quat {
  double w = 1, x = 0, y = 0, z = 0;
};

/// The rotation by `radians` about +z.
inline quat rotation_about_z(double radians) {
  return {std::cos(radians / 2), 0, 0, std::sin(radians / 2)};
}

/// q v q*, written out (v + 2w(u×v) + 2u×(u×v), u the vector part).
inline vec3 rotate(const quat& q, const vec3& v) {
  const vec3 t{2 * (q.y * v.z - q.z * v.y), 2 * (q.z * v.x - q.x * v.z), 2 * (q.x * v.y - q.y * v.x)};
  return {v.x + q.w * t.x + (q.y * t.z - q.z * t.y), v.y + q.w * t.y + (q.z * t.x - q.x * t.z),
          v.z + q.w * t.z + (q.x * t.y - q.y * t.x)};
}

enum class shape_kind { box, sphere };

struct material {
  double friction = 0;     ///< Coulomb coefficient, the effective pair value
  double restitution = 0;  ///< normal velocity ratio, the effective pair value
};

struct body_spec {
  shape_kind shape = shape_kind::box;
  vec3 half_extents;         ///< m, boxes only
  double radius = 0;         ///< m, spheres only
  bool is_static = false;    ///< static bodies never move and have no mass
  vec3 position;             ///< m, center of mass (= the shape's center)
  quat orientation;          ///< body to world
  vec3 linear_velocity;      ///< m/s at step 0
  double mass = 0;           ///< kg, dynamic bodies only; uniform density
  material surface;
};

/// Which figures a scene is judged by (metrics.hpp computes them).
enum class metric_set { pile, pyramid, spheres, bounce, incline_sliding, incline_static, tower, heavy_on_light, cradle, landing, stack };

struct scene_spec {
  std::string name;
  std::vector<body_spec> bodies;
  double dt = 1.0 / 60.0;         ///< s, one fixed step per engine step
  vec3 gravity{0, -9.81, 0};      ///< m/s²
  int steps = 0;
  bool sleeping = true;           ///< false: no body may ever deactivate
  metric_set metrics = metric_set::pile;
  /// > 0 (the _asleep scenes): first run untimed until every body sleeps,
  /// at most this many steps; then `steps` more, timed.
  int settle_limit = 0;
};

/// The `pile` grid: box (i, j, k) is centered at ((i − 4.5)·1.2, 1.0 + 1.2·j,
/// (k − 4.5)·1.2), i, j, k in 0..9. metrics.hpp uses the same numbers to
/// tell which of the 100 columns a box ended in.
struct pile_layout {
  static constexpr int side = 10;
  static constexpr double spacing = 1.2;  // m: 0.2 m gaps, so no initial overlap
  static constexpr double center_offset = 4.5;
  static constexpr double first_y = 1.0;
  static constexpr double half_extent = 0.5;
};

namespace detail {

inline body_spec make_box(vec3 half_extents, vec3 position, double mass, material m, bool is_static = false) {
  body_spec b;
  b.shape = shape_kind::box;
  b.half_extents = half_extents;
  b.is_static = is_static;
  b.position = position;
  b.mass = is_static ? 0 : mass;
  b.surface = m;
  return b;
}

inline body_spec make_static_box(vec3 half_extents, vec3 position, material m) {
  return make_box(half_extents, position, 0, m, true);
}

inline body_spec make_sphere(double radius, vec3 position, double mass, material m) {
  body_spec b;
  b.shape = shape_kind::sphere;
  b.radius = radius;
  b.position = position;
  b.mass = mass;
  b.surface = m;
  return b;
}

/// The standard ground: a static box whose top face is y = 0.
inline body_spec make_ground(material m, double half_extent_xz = 100) {
  return make_static_box({half_extent_xz, 1, half_extent_xz}, {0, -1, 0}, m);
}

inline scene_spec make_scene_base(std::string_view name, int steps, bool sleeping, metric_set metrics) {
  scene_spec s;
  s.name = std::string(name);
  s.steps = steps;
  s.sleeping = sleeping;
  s.metrics = metrics;
  return s;
}

inline scene_spec make_pile(std::string_view name, bool sleeping) {
  const material m{0.6, 0};
  scene_spec s = make_scene_base(name, 600, sleeping, metric_set::pile);
  s.bodies.push_back(make_ground(m));
  using L = pile_layout;
  const double h = L::half_extent;
  for (int i = 0; i < L::side; ++i)
    for (int j = 0; j < L::side; ++j)
      for (int k = 0; k < L::side; ++k)
        s.bodies.push_back(make_box({h, h, h},
                                    {(i - L::center_offset) * L::spacing, L::first_y + L::spacing * j,
                                     (k - L::center_offset) * L::spacing},
                                    1, m));
  return s;
}

/// Row k (0..base−1) has n = base − k boxes at x = i − (n − 1)/2, y = 0.5 + k,
/// z = 0: unit boxes touching side by side and face to face, no gaps. The
/// top box is the last body.
inline void add_pyramid(scene_spec& s, int base, double mass, material m) {
  for (int k = 0; k < base; ++k) {
    const int n = base - k;
    for (int i = 0; i < n; ++i)
      s.bodies.push_back(make_box({0.5, 0.5, 0.5}, {i - (n - 1) / 2.0, 0.5 + k, 0}, mass, m));
  }
}

inline scene_spec make_pyramid(std::string_view name, bool sleeping) {
  const material m{0.6, 0};  // choice: restitution 0, as in every stacking scene
  scene_spec s = make_scene_base(name, 1200, sleeping, metric_set::pyramid);
  s.bodies.push_back(make_ground(m));
  add_pyramid(s, 20, 1, m);
  return s;
}

/// `pile_asleep`, `pyramid_asleep`: the scene with sleeping on, settled
/// until every body sleeps (at most 60 s), then 300 steps timed: what a
/// step costs with nothing to do.
inline scene_spec make_asleep(scene_spec s, std::string_view name) {
  s.name = std::string(name);
  s.steps = 300;
  s.settle_limit = 3600;
  return s;
}

/// Box3D's large_pyramid: the pyramid with a 100-box base, mass 100 each.
inline scene_spec make_large_pyramid() {
  const material m{0.6, 0};
  scene_spec s = make_scene_base("large_pyramid", 200, false, metric_set::pyramid);
  s.bodies.push_back(make_ground(m, 400));
  add_pyramid(s, 100, 100, m);
  return s;
}

inline scene_spec make_spheres(std::string_view name, bool sleeping) {
  const material m{0.6, 0};
  scene_spec s = make_scene_base(name, 600, sleeping, metric_set::spheres);
  s.bodies.push_back(make_ground(m));
  s.bodies.push_back(make_static_box({0.5, 10, 8}, {7.5, 10, 0}, m));
  s.bodies.push_back(make_static_box({0.5, 10, 8}, {-7.5, 10, 0}, m));
  s.bodies.push_back(make_static_box({8, 10, 0.5}, {0, 10, 7.5}, m));
  s.bodies.push_back(make_static_box({8, 10, 0.5}, {0, 10, -7.5}, m));
  // choice: "grid order" is i (x) outermost, then j (y), then k (z), the
  // order the grid's indices are written in; two draws per sphere, x then z.
  impulse::lcg32 rng{12345};
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 25; ++j)
      for (int k = 0; k < 20; ++k) {
        const double jitter_x = (rng.uniform<double>() - 0.5) * 0.1;
        const double jitter_z = (rng.uniform<double>() - 0.5) * 0.1;
        s.bodies.push_back(
            make_sphere(0.25, {(i - 9.5) * 0.6 + jitter_x, 1.0 + 0.6 * j, (k - 9.5) * 0.6 + jitter_z}, 1, m));
      }
  return s;
}

/// A ball dropped from center height 10 onto the ground; the first rebound
/// peaks at 0.5 + e²·9.5 = 6.58 without losses. 240 steps (4 s) cover the
/// fall (1.39 s), the rise (1.11 s) and the second descent to the ground.
inline scene_spec make_bounce() {
  const material m{0.6, 0.8};
  scene_spec s = make_scene_base("bounce", 240, false, metric_set::bounce);
  s.bodies.push_back(make_ground(m));
  s.bodies.push_back(make_sphere(0.5, {0, 10, 0}, 1, m));
  return s;
}

/// No ground: a static slab, half extents (15, 0.5, 5), centered at the
/// origin and turned +30° about +z, so that its top face's normal is
/// (−sin 30°, cos 30°, 0) and it descends toward −x. The box has the same
/// turn and sits on the top face 5 m up-slope, at slab-local (5, 1, 0).
/// With friction μ a box slides when tan 30° = 0.577 > μ, at
/// g(sin 30° − μ cos 30°): 0.657 m/s² for μ = 0.5; μ = 0.7 holds it.
inline scene_spec make_incline(std::string_view name, double friction, int steps, metric_set metrics) {
  const material m{friction, 0};
  scene_spec s = make_scene_base(name, steps, false, metrics);
  constexpr double pi = 3.14159265358979323846;
  const quat turn = rotation_about_z(pi / 6);
  body_spec slab = make_static_box({15, 0.5, 5}, {0, 0, 0}, m);
  slab.orientation = turn;
  s.bodies.push_back(slab);
  body_spec box = make_box({0.5, 0.5, 0.5}, rotate(turn, {5, 1.0, 0}), 1, m);
  box.orientation = turn;
  s.bodies.push_back(box);
  return s;
}

/// Ten unit boxes stacked exactly touching, centers y = 0.5 + k: a tall
/// stack tests drift under many iterations' worth of accumulated error.
inline scene_spec make_tower(std::string_view name, int boxes, int steps) {
  const material m{0.6, 0};
  scene_spec s = make_scene_base(name, steps, false, metric_set::tower);
  s.bodies.push_back(make_ground(m));
  for (int k = 0; k < boxes; ++k) s.bodies.push_back(make_box({0.5, 0.5, 0.5}, {0, 0.5 + k, 0}, 1, m));
  return s;
}

/// A 100 kg box on a 1 kg box: a mass ratio of 100 is where iterative
/// solvers converge slowest, so the heavy box sinks into the light one.
inline scene_spec make_heavy_on_light() {
  const material m{0.6, 0};
  scene_spec s = make_scene_base("heavy_on_light", 600, false, metric_set::heavy_on_light);
  s.bodies.push_back(make_ground(m));
  s.bodies.push_back(make_box({0.5, 0.5, 0.5}, {0, 0.5, 0}, 1, m));
  s.bodies.push_back(make_box({0.5, 0.5, 0.5}, {0, 1.5, 0}, 100, m));
  return s;
}

/// Fast landings: a ball of radius 0.5 and a unit box (1 kg, friction 0.6,
/// restitution 0) at each of 2, 5, 10 and 20 m/s straight down, each
/// started with its bottom 0.6 m above the ground; bodies k = 0..7 at
/// x = 3k, ball then box at each speed in turn. At 60 Hz they cross 3.3 to
/// 33 cm a step. 120 steps.
inline scene_spec make_landing() {
  const material m{0.6, 0};
  scene_spec s = make_scene_base("landing", 120, false, metric_set::landing);
  s.bodies.push_back(make_ground(m));
  const double speeds[] = {2, 5, 10, 20};
  for (int k = 0; k < 8; ++k) {
    const vec3 at{3.0 * k, 1.1, 0};
    body_spec b = k % 2 == 0 ? make_sphere(0.5, at, 1, m) : make_box({0.5, 0.5, 0.5}, at, 1, m);
    b.linear_velocity = {0, -speeds[k / 2], 0};
    s.bodies.push_back(b);
  }
  return s;
}

/// `stack_1000to1`: four unit boxes stacked exactly touching (centers
/// y = 0.5 + k), 1, 1000, 1 and 1000 kg from the bottom, friction 0.6.
inline scene_spec make_stack_1000to1() {
  const material m{0.6, 0};
  scene_spec s = make_scene_base("stack_1000to1", 600, false, metric_set::stack);
  s.bodies.push_back(make_ground(m));
  for (int k = 0; k < 4; ++k) s.bodies.push_back(make_box({0.5, 0.5, 0.5}, {0, 0.5 + k, 0}, k % 2 == 0 ? 1 : 1000, m));
  return s;
}

/// Newton's cradle without strings: no gravity, no ground; a ball at
/// x = −1 moving +x at 1 m/s meets four touching balls at x = 1..4 after
/// 1 s. With restitution 1 and equal masses the last ball should leave at
/// 1 m/s and the others stop.
inline scene_spec make_cradle() {
  const material m{0, 1};
  scene_spec s = make_scene_base("cradle", 120, false, metric_set::cradle);
  s.gravity = {0, 0, 0};
  body_spec first = make_sphere(0.5, {-1, 0, 0}, 1, m);
  first.linear_velocity = {1, 0, 0};
  s.bodies.push_back(first);
  for (int i = 1; i <= 4; ++i) s.bodies.push_back(make_sphere(0.5, {double(i), 0, 0}, 1, m));
  return s;
}

}  // namespace detail

/// Every scene, in the order the benchmark runs them.
inline const std::vector<std::string_view>& scene_names() {
  static const std::vector<std::string_view> names{
      "pile",    "pile_nosleep",   "pyramid",        "pyramid_nosleep", "spheres", "spheres_nosleep", "large_pyramid",
      "bounce",  "incline",        "incline_static", "tower10",         "heavy_on_light", "cradle",
      "pile_asleep", "pyramid_asleep", "tower20", "tower30", "stack_1000to1", "landing"};
  return names;
}

/// The scene called `name`; throws std::invalid_argument for another name.
inline scene_spec make_scene(std::string_view name) {
  using namespace detail;
  if (name == "pile") return make_pile(name, true);
  if (name == "pile_nosleep") return make_pile(name, false);
  if (name == "pyramid") return make_pyramid(name, true);
  if (name == "pyramid_nosleep") return make_pyramid(name, false);
  if (name == "spheres") return make_spheres(name, true);
  if (name == "spheres_nosleep") return make_spheres(name, false);
  if (name == "large_pyramid") return make_large_pyramid();
  if (name == "bounce") return make_bounce();
  // incline measures v(2 s) − v(1 s); incline_static the drift after 5 s.
  if (name == "incline") return make_incline(name, 0.5, 120, metric_set::incline_sliding);
  if (name == "incline_static") return make_incline(name, 0.7, 300, metric_set::incline_static);
  if (name == "tower10") return make_tower(name, 10, 1200);
  // tower20 and tower30: the same, 60 s (docs/standard_scenes.md).
  if (name == "tower20") return make_tower(name, 20, 3600);
  if (name == "tower30") return make_tower(name, 30, 3600);
  if (name == "heavy_on_light") return make_heavy_on_light();
  if (name == "cradle") return make_cradle();
  if (name == "stack_1000to1") return make_stack_1000to1();
  if (name == "landing") return make_landing();
  if (name == "pile_asleep") return make_asleep(make_pile(name, true), name);
  if (name == "pyramid_asleep") return make_asleep(make_pyramid(name, true), name);
  throw std::invalid_argument("unknown scene: " + std::string(name));
}

}  // namespace bench::scenes
