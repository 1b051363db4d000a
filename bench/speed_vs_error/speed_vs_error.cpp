// bench/speed_vs_error/speed_vs_error.cpp — error at the end time against cost
// per particle-step, for every integrator × scalar × time step.
//
// For each closed-form problem (the three of tests/integrators/problems.hpp,
// copied here because a benchmark does not include test files, and the orbit
// again with the particle kernel's estimated root), integrator,
// scalar and h = 0.1·2^-k s (k = -2 … 15), it prints one CSV row to stdout:
//   error                 |x(t_end) - exact| after integrating to t_end = 2 s,
//   ns_per_particle_step  median of 7 timed runs, each ≳ 20 ms, of N = 4096
//                         particles stepped batch by batch.
// Both go through one function, advance(): SoA columns loaded as
// vec3_batch<T, native_width<T>>, one I::step with the problem's acceleration,
// stored back; the error run is the same loop over a single batch.
//
// Usage: speed_vs_error [--quick] > speed_vs_error.csv
//   --quick  5 time steps, 3 repeats of ≳ 2 ms: a smoke run, not figures.
// A checksum of every timed run goes to stderr so that no step can be
// optimised away.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <new>
#include <tuple>
#include <type_traits>
#include <vector>

#include "impulse/integrators/euler.hpp"
#include "impulse/integrators/midpoint.hpp"
#include "impulse/integrators/rk4.hpp"
#include "impulse/integrators/symplectic_euler.hpp"
#include "impulse/math/vec3.hpp"
#include "impulse/math/vec3_batch.hpp"
#include "impulse/particles/point_forces.hpp"

namespace {

using impulse::vec3;
using impulse::vec3_batch;

constexpr double t_end = 2.0;                // s, as in tests/integrators/test_convergence.cpp
constexpr std::size_t particles = 4096;      // a multiple of every batch width
constexpr std::size_t simd_alignment = 64;   // one cache line: a batch never straddles two

template <class T>
using batch3 = vec3_batch<T, impulse::native_width<T>>;

template <class T>
vec3<double> widen(const vec3<T>& a) {
  return {double(a.x), double(a.y), double(a.z)};
}

// ---- the problems -----------------------------------------------------------------
// Each is an acceleration field over batches, an initial state in T and the
// exact position at time t in double. The exact solution takes the problem's
// constants as rounded to T (9.81f is not 9.81), so a float error is the
// integration's own and not the difference between two problems.

/// x'' = -ω² x with ω = 2, x(0) = (1, 0, 0), v(0) = 0: x(t) = (cos ωt, 0, 0).
/// The test's scalar oscillator, carried in the x lane of a vec3 state.
template <class T>
struct oscillator {
  static constexpr const char* name = "oscillator";
  static constexpr T omega = 2;
  static vec3<T> x0() { return {1, 0, 0}; }
  static vec3<T> v0() { return {0, 0, 0}; }
  template <int W>
  vec3_batch<T, W> operator()(const vec3_batch<T, W>& x, const vec3_batch<T, W>&) const {
    return x * (-omega * omega);
  }
  static vec3<double> exact(double t) { return {std::cos(double(omega) * t), 0, 0}; }
};

/// v' = g - k v, g = (0, -9.81, 0), k = 0.7, x(0) = (0, 1, 0), v(0) = (3, 5, -2):
/// x(t) = x0 + v∞ t + (v0 - v∞)(1 - e^{-kt})/k with v∞ = g/k.
template <class T>
struct projectile_drag {
  static constexpr const char* name = "projectile_drag";
  static constexpr vec3<T> g{0, T(-9.81), 0};
  static constexpr T k = T(0.7);
  static vec3<T> x0() { return {0, 1, 0}; }
  static vec3<T> v0() { return {3, 5, -2}; }
  template <int W>
  vec3_batch<T, W> operator()(const vec3_batch<T, W>&, const vec3_batch<T, W>& v) const {
    return vec3_batch<T, W>::broadcast(g) - v * k;
  }
  static vec3<double> exact(double t) {
    const double kd = k;
    const vec3<double> v_inf = widen(g) / kd;
    return widen(x0()) + v_inf * t + (widen(v0()) - v_inf) * ((1 - std::exp(-kd * t)) / kd);
  }
};

/// Circular orbit of radius r = 2 about an attractor of strength μ = 4 at the
/// origin: a = -μ x/|x|³, speed √(μ/r), angular rate √(μ/r³). The one problem
/// with a square root and a division per evaluation, like the particle
/// kernel's exact root.
template <class T>
struct orbit {
  static constexpr const char* name = "orbit";
  static constexpr T mu = 4, r = 2;
  static vec3<T> x0() { return {r, 0, 0}; }
  static vec3<T> v0() { return {0, std::sqrt(mu / r), 0}; }
  template <int W>
  vec3_batch<T, W> operator()(const vec3_batch<T, W>& x, const vec3_batch<T, W>&) const {
    const auto d2 = length_squared(x);
    return x * (-mu / (d2 * sqrt(d2)));
  }
  static vec3<double> exact(double t) {
    // Rounding √2 to float makes the float orbit very slightly eccentric
    // (relative 3e-8, below float's error floor here), so the circle is kept.
    const double angle = std::sqrt(double(mu) / (double(r) * r * r)) * t;
    return {r * std::cos(angle), r * std::sin(angle), 0};
  }
};

/// The same orbit with |x|^-3 from the hardware's estimate of 1/√ and its
/// polynomial correction, as the particle kernel's point forces compute it
/// in float (point_forces::inverse_root_cubed): no square root and no
/// division. Double has no estimate and takes the exact form.
template <class T>
struct orbit_estimate : orbit<T> {
  static constexpr const char* name = "orbit_estimate";
  template <int W>
  vec3_batch<T, W> operator()(const vec3_batch<T, W>& x, const vec3_batch<T, W>&) const {
    using points = impulse::particles::point_forces<T>;
    return x * (points::inverse_root_cubed(length_squared(x), points::root_method::estimate) * -orbit<T>::mu);
  }
};

template <class I> constexpr const char* integrator_name = nullptr;
template <> constexpr const char* integrator_name<impulse::integrators::euler> = "euler";
template <> constexpr const char* integrator_name<impulse::integrators::symplectic_euler> = "symplectic_euler";
template <> constexpr const char* integrator_name<impulse::integrators::midpoint> = "midpoint";
template <> constexpr const char* integrator_name<impulse::integrators::rk4> = "rk4";

// ---- particle state --------------------------------------------------------------

/// Six SoA columns (x, y, z, vx, vy, vz) in one allocation, each column
/// starting on a 64-byte boundary.
template <class T>
class soa_columns {
 public:
  explicit soa_columns(std::size_t n)
      : size_(n),
        stride_((n * sizeof(T) + simd_alignment - 1) / simd_alignment * simd_alignment / sizeof(T)),
        data_(static_cast<T*>(::operator new(6 * stride_ * sizeof(T), std::align_val_t{simd_alignment}))) {}
  soa_columns(const soa_columns&) = delete;
  soa_columns& operator=(const soa_columns&) = delete;
  ~soa_columns() { ::operator delete(data_, std::align_val_t{simd_alignment}); }

  std::size_t size() const { return size_; }
  T* column(int j) { return data_ + std::size_t(j) * stride_; }

  void fill(const vec3<T>& x, const vec3<T>& v) {
    const T values[6] = {x.x, x.y, x.z, v.x, v.y, v.z};
    for (int j = 0; j < 6; ++j) std::fill_n(column(j), size_, values[j]);
  }
  vec3<T> position(std::size_t i) { return {column(0)[i], column(1)[i], column(2)[i]}; }
  double sum_of_positions() {
    double sum = 0;
    for (int j = 0; j < 3; ++j)
      for (std::size_t i = 0; i < size_; ++i) sum += double(column(j)[i]);
    return sum;
  }

 private:
  std::size_t size_, stride_;
  T* data_;
};

/// `steps` steps of every particle: per step, one pass over the batches that
/// loads, steps and stores each, as a particle system does.
template <class I, class T, class Accel>
void advance(soa_columns<T>& c, long steps, T h, const Accel& accel) {
  using state = batch3<T>;
  T *x = c.column(0), *y = c.column(1), *z = c.column(2);
  T *vx = c.column(3), *vy = c.column(4), *vz = c.column(5);
  for (long s = 0; s < steps; ++s) {
    for (std::size_t i = 0; i < c.size(); i += state::width) {
      state position = state::load(x + i, y + i, z + i);
      state velocity = state::load(vx + i, vy + i, vz + i);
      I::step(position, velocity, h, accel);
      position.store(x + i, y + i, z + i);
      velocity.store(vx + i, vy + i, vz + i);
    }
  }
}

// ---- the two measurements ----------------------------------------------------------

/// Distance to the exact solution after `steps` steps of h, on one batch
/// whose lanes all start from the problem's initial state (lane 0 is read).
template <class I, template <class> class P, class T>
double end_error(long steps, T h) {
  soa_columns<T> c{std::size_t(batch3<T>::width)};
  c.fill(P<T>::x0(), P<T>::v0());
  advance<I>(c, steps, h, P<T>{});
  // The integrator never adds up time; it makes `steps` steps of h as stored
  // in T, so the end time is steps·h in that precision (float's 0.1 is
  // 0.100000001490116: 20 steps end 3e-8 s after 2 s).
  const vec3<double> error = widen(c.position(0)) - P<T>::exact(double(steps) * double(h));
  return impulse::length(error);
}

struct settings {
  int repeats = 7;
  double min_run_seconds = 0.020;
};

double checksum = 0;

/// The timing of one integrator on one problem at one h: runs of `total`
/// steps of every particle, `total` chosen so that a run lasts
/// settings.min_run_seconds.
template <class I, template <class> class P, class T>
class timed_runs {
 public:
  timed_runs(soa_columns<T>& c, long steps, T h) : c_(c), steps_(steps), h_(h) {}

  void calibrate(const settings& s) {  // also the warm-up
    while (run() < s.min_run_seconds) total_ *= 2;
  }
  void record() { seconds_.push_back(run()); }
  double median_ns_per_particle_step() {
    std::sort(seconds_.begin(), seconds_.end());
    return seconds_[seconds_.size() / 2] * 1e9 / (double(total_) * double(c_.size()));
  }

 private:
  // A run makes `total_` steps as whole trajectories to t_end, restarting
  // from the initial state between them (untimed): run on far past t_end,
  // Euler's growing oscillation would overflow float within one run.
  double run() {
    using clock = std::chrono::steady_clock;
    double seconds = 0;
    for (long done = 0; done < total_;) {
      c_.fill(P<T>::x0(), P<T>::v0());
      const long chunk = std::min(steps_, total_ - done);
      const auto start = clock::now();
      advance<I>(c_, chunk, h_, P<T>{});
      seconds += std::chrono::duration<double>(clock::now() - start).count();
      done += chunk;
      checksum += c_.sum_of_positions();
    }
    return seconds;
  }

  soa_columns<T>& c_;
  long steps_;
  T h_;
  long total_ = 16;
  std::vector<double> seconds_;
};

/// Every integrator I... on problem P in scalar T, for each h of the ladder.
/// The integrators take turns within each repeat, so that load from other
/// work on the shared machine falls on all of them alike and the ratios
/// between them hold even when a run is slowed.
template <template <class> class P, class T, class... I>
void measure(const std::vector<int>& ladder, const settings& s) {
  const char* scalar = std::is_same_v<T, float> ? "float" : "double";
  std::fprintf(stderr, "%s %s\n", P<T>::name, scalar);
  soa_columns<T> c(particles);
  for (const int k : ladder) {
    const double h = std::ldexp(0.1, -k);
    const long steps = std::lround(t_end / h);
    if (std::abs(double(steps) * h - t_end) > 1e-12 * t_end) continue;  // not a whole number of steps
    const T h_t = T(h);
    std::tuple<timed_runs<I, P, T>...> runs{timed_runs<I, P, T>(c, steps, h_t)...};
    std::apply([&](auto&... r) { (r.calibrate(s), ...); }, runs);
    for (int repeat = 0; repeat < s.repeats; ++repeat)
      std::apply([](auto&... r) { (r.record(), ...); }, runs);
    auto print = [&](const char* integrator, double error, double ns) {
      std::printf("%s,%s,%s,%d,%.9g,%ld,%.6e,%.4f\n", P<T>::name, integrator, scalar,
                  batch3<T>::width, h, steps, error, ns);
    };
    std::apply([&](auto&... r) {
      (print(integrator_name<I>, end_error<I, P>(steps, h_t), r.median_ns_per_particle_step()), ...);
    }, runs);
    std::fflush(stdout);
  }
}

template <template <class> class P>
void measure_problem(const std::vector<int>& ladder, const settings& s) {
  namespace in = impulse::integrators;
  measure<P, float, in::euler, in::symplectic_euler, in::midpoint, in::rk4>(ladder, s);
  measure<P, double, in::euler, in::symplectic_euler, in::midpoint, in::rk4>(ladder, s);
}

}  // namespace

int main(int argc, char** argv) {
  settings s;
  // h = 0.1·2^-k s. k = -2 (h = 0.4 s, 5 steps) is each method's largest
  // error (euler 2.7, rk4 2.5e-3 on the oscillator); k = 15 (655 360 steps) takes rk4 past double's rounding floor
  // and every float method past float's. k = -3 (h = 0.8 s, 2.5 steps) is
  // skipped: t_end is not a whole number of its steps.
  std::vector<int> ladder;
  for (int k = -3; k <= 15; ++k) ladder.push_back(k);
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) {
      ladder = {-2, 0, 3, 6, 9};
      s = {3, 0.002};
    } else {
      std::fprintf(stderr, "usage: %s [--quick] > speed_vs_error.csv\n", argv[0]);
      return 2;
    }
  }
  std::printf("problem,integrator,scalar,width,dt,steps,error,ns_per_particle_step\n");
  measure_problem<oscillator>(ladder, s);
  measure_problem<projectile_drag>(ladder, s);
  measure_problem<orbit>(ladder, s);
  measure_problem<orbit_estimate>(ladder, s);
  std::fprintf(stderr, "checksum %.17g\n", checksum);
}
