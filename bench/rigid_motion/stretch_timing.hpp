// bench/rigid_motion/stretch_timing.hpp — what the two rigid-motion
// benchmarks share: the configurations they compare, and the timing of a
// fixed stretch of steps restarted from one state.
//
// A run steps a copy of the start state through `stretch` steps, as many
// times as it takes to fill the run (the copy is not timed). Restarting
// keeps every run on the same stretch of motion: run on instead, Euler's
// growing oscillations would change the state being timed, and with it
// nothing but the figures.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "impulse/config.hpp"
#include "impulse/dynamics.hpp"
#include "impulse/integrators.hpp"
#include "impulse/world.hpp"

namespace rigid_motion {

/// A world without collision: no broad phase, contacts, joints or solver;
/// gravity and springs move the bodies, evaluated at every stage of I.
template <class T, class I>
struct config : impulse::default_config {
  using scalar = T;
  using integrator = I;
  static constexpr bool collision = false;
};

template <class T, class I>
using world = impulse::world<config<T, I>>;

template <class I> constexpr const char* integrator_name = nullptr;
template <> inline constexpr const char* integrator_name<impulse::integrators::euler> = "euler";
template <> inline constexpr const char* integrator_name<impulse::integrators::symplectic_euler> = "symplectic_euler";
template <> inline constexpr const char* integrator_name<impulse::integrators::midpoint> = "midpoint";
template <> inline constexpr const char* integrator_name<impulse::integrators::rk4> = "rk4";

template <class T>
constexpr const char* scalar_name = std::is_same_v<T, float> ? "float" : "double";

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct settings {
  int repeats = 7;
  double min_run_seconds = 0.020;
};

/// Sum of the bodies' positions and orientations: printed to stderr at the
/// end, so that no timed step can be optimised away.
inline double checksum = 0;

template <class World>
class stretch_timing {
 public:
  using T = typename World::scalar;

  stretch_timing(const World& start, long stretch, T dt) : start_(start), stretch_(stretch), dt_(dt) {}

  /// Doubles the stretches per run until a run lasts min_run_seconds; also
  /// the warm-up (caches, branch predictors, the world's scratch buffers).
  void calibrate(const settings& s) {
    while (run() < s.min_run_seconds) stretches_ *= 2;
  }
  void record() { seconds_per_step_.push_back(run() / double(stretches_ * stretch_)); }
  /// Seconds per step of each recorded run, in the order recorded.
  [[nodiscard]] const std::vector<double>& seconds_per_step() const { return seconds_per_step_; }
  [[nodiscard]] std::size_t bodies() const { return start_.body_count(); }

 private:
  double run() {
    using clock = std::chrono::steady_clock;
    double seconds = 0;
    for (long k = 0; k < stretches_; ++k) {
      World w = start_;
      const auto t0 = clock::now();
      for (long i = 0; i < stretch_; ++i) w.step(dt_);
      seconds += std::chrono::duration<double>(clock::now() - t0).count();
      for (const impulse::body_id id : w.body_ids()) {
        const impulse::rigid_body<T>& b = w.body(id);
        checksum += double(b.position.x + b.position.y + b.position.z) + double(b.orientation.w);
      }
    }
    return seconds;
  }

  World start_;
  long stretch_;
  T dt_;
  long stretches_ = 1;
  std::vector<double> seconds_per_step_;
};

/// Runs `record` on every timing in turn, `repeats` times: the integrators
/// take turns within each repeat, so that load from other work on a shared
/// machine falls on all of them alike and the ratios of one repeat hold
/// even when the repeat is slowed.
template <class... Timing>
void time_in_turns(const settings& s, Timing&... timings) {
  (timings.calibrate(s), ...);
  for (int r = 0; r < s.repeats; ++r) (timings.record(), ...);
}

/// Median over repeats of a's time per step over b's in the same repeat.
template <class A, class B>
double median_ratio(const stretch_timing<A>& a, const stretch_timing<B>& b) {
  std::vector<double> ratios;
  for (std::size_t r = 0; r < a.seconds_per_step().size(); ++r)
    ratios.push_back(a.seconds_per_step()[r] / b.seconds_per_step()[r]);
  return median(ratios);
}

}  // namespace rigid_motion
