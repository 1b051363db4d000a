// bench/rigid_motion/rigid_motion.cpp — body-steps per second of a world
// without collision (config `collision = false`: bodies moved by forces
// alone) under gravity and springs, per integrator and scalar.
//
// Two scenes of unit boxes (half-extent 0.5 m, density 1: mass 1 kg) under
// gravity (0, −9.81, 0), with the same damped spring (k = 100 N/m,
// c = 2 N·s/m, rest length 0.5 m) once per body, at dt = 1/60 s:
//   independent  N boxes, each hung by its corner (½, ½, ½) from its own
//                world anchor, released at rest off to one side so that it
//                swings and turns. No spring joins two moving bodies: the
//                world steps each body alone (the fast path).
//   coupled      a chain of N boxes in a row 1.5 m apart, the middle of
//                each one's top +x edge (½, ½, 0) joined to the middle of
//                the next one's top −x edge (−½, ½, 0), the two end boxes
//                held by anchors the same way; released straight, every
//                spring at its rest length, it sags. The springs couple
//                the bodies: the world steps every body as one state
//                (the coupled path).
//
// Output: CSV on stdout,
//   scene,integrator,scalar,bodies,mbody_steps_per_s,cost_vs_symplectic_euler,cost_vs_independent
// mbody_steps_per_s: N / (median over 7 runs of the seconds per step), in
// millions. The two scenes and four integrators of one N and scalar take
// turns within each of 7 repeats, and the ratios are medians over the
// repeats of ratios within one repeat: cost_vs_symplectic_euler, this
// integrator's time per step over symplectic Euler's on the same scene;
// cost_vs_independent, its time per step on this scene over its time on
// the independent one (the price of the coupled path, 1 on independent rows).
//
// Every run times the same stretch of motion, steps 10 to 40 (t = 1/6 s to
// 2/3 s), restarted from a copy of the step-10 state, as many times as fill
// ≥ 20 ms. --quick: N = 1000 only, 3 repeats of ≥ 2 ms: a smoke run.
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <vector>

#include "impulse/shapes/box.hpp"

#include "stretch_timing.hpp"

namespace {

using namespace impulse;
using rigid_motion::settings;
using rigid_motion::stretch_timing;

constexpr double dt = 1.0 / 60;  // the standard scenes' fixed step (docs/standard_scenes.md)
constexpr long warm_steps = 10, timed_steps = 30;
constexpr double stiffness = 100, damping = 2, rest_length = 0.5;

/// A unit box (density 1: mass 1 kg) at `at`, unturned and at rest.
template <class World, class T = typename World::scalar>
body_id add_unit_box(World& w, const vec3<T>& at) {
  body_def<T> def;
  def.pose.position = at;
  return w.create_body(def, box<T>{{T(0.5), T(0.5), T(0.5)}});
}

template <class T>
body_spring<T> scene_spring(body_id a, const vec3<T>& pa, body_id b, const vec3<T>& pb) {
  return {a, pa, b, pb, T(stiffness), T(damping), T(rest_length)};
}

/// Boxes on a square grid 3 m apart, each 1 m below and (0.3, 0.1) m to the
/// side of its anchor (the hanging cube of tests/dynamics/test_body_springs).
template <class World>
void hang_boxes(World& w, std::size_t n) {
  using T = typename World::scalar;
  const std::size_t side = std::size_t(std::ceil(std::sqrt(double(n))));
  for (std::size_t i = 0; i < n; ++i) {
    const vec3<T> anchor{T(3.0 * double(i % side)), T(3), T(3.0 * double(i / side))};
    const body_id id = add_unit_box(w, anchor + vec3<T>{T(0.3), T(-1), T(0.1)});
    w.create_spring(scene_spring<T>(id, {T(0.5), T(0.5), T(0.5)}, body_id{}, anchor));
  }
}

/// Boxes 1.5 m apart along x at a height of 10 m: each spring spans the
/// 0.5 m gap between neighbours at its rest length.
template <class World>
void hang_chain(World& w, std::size_t n) {
  using T = typename World::scalar;
  const vec3<T> right{T(0.5), T(0.5), T(0)}, left{T(-0.5), T(0.5), T(0)};
  std::vector<body_id> ids;
  for (std::size_t i = 0; i < n; ++i) ids.push_back(add_unit_box(w, vec3<T>{T(1.5 * double(i)), T(10), T(0)}));
  for (std::size_t i = 0; i + 1 < n; ++i) w.create_spring(scene_spring<T>(ids[i], right, ids[i + 1], left));
  const vec3<T> first_anchor{T(-1), T(10.5), T(0)}, last_anchor{T(1.5 * double(n - 1) + 1), T(10.5), T(0)};
  w.create_spring(scene_spring<T>(ids.front(), left, body_id{}, first_anchor));
  w.create_spring(scene_spring<T>(ids.back(), right, body_id{}, last_anchor));
}

enum class scene { independent, coupled };

/// The scene, stepped to the start of the timed stretch.
template <class T, class I>
stretch_timing<rigid_motion::world<T, I>> timing_of(scene which, std::size_t n) {
  rigid_motion::world<T, I> w;
  if (which == scene::independent) {
    hang_boxes(w, n);
  } else {
    hang_chain(w, n);
  }
  for (long i = 0; i < warm_steps; ++i) w.step(T(dt));
  return {w, timed_steps, T(dt)};
}

/// One integrator on both scenes of the same N.
template <class T, class I>
struct scene_timings {
  stretch_timing<rigid_motion::world<T, I>> independent, coupled;
  explicit scene_timings(std::size_t n)
      : independent(timing_of<T, I>(scene::independent, n)), coupled(timing_of<T, I>(scene::coupled, n)) {}
};

/// Both scenes with every integrator at one N, all eight taking turns.
template <class T>
void measure(std::size_t n, const settings& s) {
  namespace in = integrators;
  scene_timings<T, in::euler> euler(n);
  scene_timings<T, in::symplectic_euler> symplectic(n);
  scene_timings<T, in::midpoint> midpoint(n);
  scene_timings<T, in::rk4> rk4(n);
  rigid_motion::time_in_turns(s, euler.independent, euler.coupled, symplectic.independent, symplectic.coupled,
                              midpoint.independent, midpoint.coupled, rk4.independent, rk4.coupled);
  const auto print = [&]<class World>(const char* scene_name, const stretch_timing<World>& timing,
                                      const stretch_timing<World>& independent, const auto& symplectic_euler) {
    std::printf("%s,%s,%s,%zu,%.3f,%.3f,%.3f\n", scene_name, rigid_motion::integrator_name<typename World::integrator>,
                rigid_motion::scalar_name<T>, n, double(n) / rigid_motion::median(timing.seconds_per_step()) / 1e6,
                rigid_motion::median_ratio(timing, symplectic_euler), rigid_motion::median_ratio(timing, independent));
  };
  // Rows of one scene: each integrator against symplectic Euler on that
  // scene and against itself on the independent scene.
  const auto print_scene = [&](const char* scene_name, bool coupled) {
    const auto on_scene = [&](const auto& t) -> const auto& { return coupled ? t.coupled : t.independent; };
    print(scene_name, on_scene(euler), euler.independent, on_scene(symplectic));
    print(scene_name, on_scene(symplectic), symplectic.independent, on_scene(symplectic));
    print(scene_name, on_scene(midpoint), midpoint.independent, on_scene(symplectic));
    print(scene_name, on_scene(rk4), rk4.independent, on_scene(symplectic));
  };
  print_scene("independent", false);
  print_scene("coupled", true);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  settings s;
  std::vector<std::size_t> sizes{1000, 10000};
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) {
      sizes = {1000};
      s = {3, 0.002};
    } else {
      std::fprintf(stderr, "usage: %s [--quick] > rigid_motion.csv\n", argv[0]);
      return 2;
    }
  }
  std::printf("scene,integrator,scalar,bodies,mbody_steps_per_s,cost_vs_symplectic_euler,cost_vs_independent\n");
  for (const std::size_t n : sizes) {
    measure<float>(n, s);
    measure<double>(n, s);
  }
  std::fprintf(stderr, "checksum %.17g\n", rigid_motion::checksum);
}
