// sequential_impulse's support sweep (dynamics/detail/support_sweep.hpp):
// each part's sweeps end with the normal rows once more from the ground
// up, each manifold solved as if its lower body could not move. What it
// holds at default settings that the sweeps alone do not: a heavy box on
// a light one at 10 000:1, and stacks alternating 1 and 10 000 kg. Sleeping
// off.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "scenes.hpp"

namespace world_support_sweep_tests {

using namespace impulse;

namespace {

using awake_world = world<impulse::test::awake_config>;

struct stack_result {
  double sink = 0;   // m: how far the top fell below where it began, at most
  double slide = 0;  // m: how far any box moved across, at most
};

/// Unit boxes (friction 0.6) of the given masses stacked from the ground
/// up, run for `steps` steps at 60 Hz.
stack_result stack(const awake_world::settings_type& settings, const std::vector<float>& masses, int steps) {
  awake_world w(settings);
  impulse::test::add_ground(w);
  std::vector<body_id> boxes;
  for (std::size_t k = 0; k < masses.size(); ++k)
    boxes.push_back(impulse::test::add_cube(w, {0, 0.5f + float(k), 0}, masses[k]));
  const float top = 0.5f + float(masses.size() - 1);
  stack_result r;
  for (int i = 0; i < steps; ++i) {
    w.step(impulse::test::step_dt<float>);
    r.sink = std::max(r.sink, double(top - w.body(boxes.back()).position.y));
    for (const body_id b : boxes) {
      const vec3<float> p = w.body(b).position;
      r.slide = std::max(r.slide, std::hypot(double(p.x), double(p.z)));
    }
  }
  return r;
}

awake_world::settings_type without_support_sweep() {
  awake_world::settings_type s;
  s.solver.support_sweep = false;
  return s;
}

}  // namespace

TEST_CASE("at default settings a 10 000 kg box on a 1 kg box stays on it 10 s, within 0.1 mm") {
  // Measured: sinks 6 µm, slides 85 µm.
  const stack_result r = stack({}, {1, 10000}, 600);
  CHECK(r.sink < 1e-4);
  CHECK(r.slide < 1e-4);
}

TEST_CASE("without the support sweep the 10 000 kg box squeezes the 1 kg box out from under it") {
  // The sweeps take about 1/10 000 of the heavy box's velocity out each:
  // measured, it sank 0.17 m and the boxes slid 0.42 m apart in 10 s.
  const stack_result r = stack(without_support_sweep(), {1, 10000}, 600);
  CHECK(r.slide > 0.1);
}

TEST_CASE("at default settings a 1:10 000:1:10 000 stack stands 10 s, sinking less than 1 mm") {
  // Measured: sinks 18 µm, slides 1.8 mm (the light boxes turn a little
  // under the heavy ones' loads).
  const stack_result r = stack({}, {1, 10000, 1, 10000}, 600);
  CHECK(r.sink < 1e-3);
  CHECK(r.slide < 0.01);
}

TEST_CASE("the support sweep holds a 1:10 000 pair in double as in float") {
  world<impulse::test::awake_double_config> w;
  impulse::test::add_ground(w);
  impulse::test::add_cube(w, {0, 0.5, 0}, 1.0);
  const body_id heavy = impulse::test::add_cube(w, {0, 1.5, 0}, 10000.0);
  impulse::test::run(w, 600);
  const vec3<double> p = w.body(heavy).position;
  CHECK(1.5 - p.y < 1e-4);
  CHECK(std::hypot(p.x, p.z) < 1e-4);
}

}  // namespace world_support_sweep_tests
