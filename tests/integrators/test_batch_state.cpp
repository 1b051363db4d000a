// One integrator implementation serves every state: W orbits integrated as
// one vec3_batch give, lane by lane, what W scalar vec3 runs give.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "impulse/integrators.hpp"
#include "impulse/math.hpp"

namespace integrators_batch_state_tests {

namespace {

using impulse::vec3;
using impulse::vec3_batch;

constexpr double mu = 4;        // attractor strength, m³/s²
constexpr int steps = 200;      // 2 s at h = 0.01
constexpr double h = 0.01;

// Circular orbit of radius r about the origin, one lane per radius.
template <class T>
vec3<T> start_position(int lane) { return {T(1) + T(0.25) * T(lane), 0, 0}; }
template <class T>
vec3<T> start_velocity(int lane) { return {0, T(std::sqrt(mu / (1 + 0.25 * lane))), T(0.1)}; }

template <class I, class T, int W>
void check_lanes_match_scalar_runs() {
  using state = vec3_batch<T, W>;
  state x{}, v{};
  for (int i = 0; i < W; ++i) {
    x.set_lane(i, start_position<T>(i));
    v.set_lane(i, start_velocity<T>(i));
  }
  for (int s = 0; s < steps; ++s)
    I::step(x, v, T(h), [](const state& p, const state&) {
      const auto d2 = length_squared(p);
      return p * (T(-mu) / (d2 * impulse::sqrt(d2)));
    });

  // Reordering and FMA contraction may differ between the vector and scalar
  // code: allow a few roundings per step of the O(1) position.
  const T rounding = T(8 * steps) * std::numeric_limits<T>::epsilon();
  for (int i = 0; i < W; ++i) {
    vec3<T> xs = start_position<T>(i), vs = start_velocity<T>(i);
    for (int s = 0; s < steps; ++s)
      I::step(xs, vs, T(h), [](const vec3<T>& p, const vec3<T>&) {
        const T d2 = impulse::length_squared(p);
        return p * (T(-mu) / (d2 * std::sqrt(d2)));
      });
    CAPTURE(i);
    CHECK(impulse::max_component(impulse::abs(x.lane(i) - xs)) <= rounding);
    CHECK(impulse::max_component(impulse::abs(v.lane(i) - vs)) <= rounding * T(2));
  }
}

}  // namespace

TEST_CASE_TEMPLATE("each lane of a batched integration equals the scalar integration", T, float, double) {
  using namespace impulse::integrators;
  constexpr int native = impulse::native_width<T>;
  check_lanes_match_scalar_runs<euler, T, native>();
  check_lanes_match_scalar_runs<symplectic_euler, T, native>();
  check_lanes_match_scalar_runs<midpoint, T, native>();
  check_lanes_match_scalar_runs<rk4, T, native>();
  check_lanes_match_scalar_runs<rk4, T, 1>();
  check_lanes_match_scalar_runs<rk4, T, 64 / int(sizeof(T))>();  // wider than most targets
}

}  // namespace integrators_batch_state_tests
