// bench/particles — particle-steps per second on the standard `particles` scene
// (docs/standard_scenes.md).
//
// For N = 10^3 … 4·10^6, float and double, and every integrator, times
// particle_system::step (the fused SoA kernel at the native batch width) and
// the same physics written the way a typical engine ships it: an array of
// structs {vec3 pos, vel; T mass, age;} stepped one particle at a time with
// the same integrator policy. Beside each, a STREAM-style copy (b[i] = a[i]
// over arrays of the same total size as the particle data) measured in the
// same run gives the memory roof at that size, so the table reads as a
// fraction of what the machine can move, not as a lone time.
//
// Output: CSV on stdout,
//   integrator,scalar,width,threads,n,msteps_per_s,gb_per_s,bandwidth_fraction
// width is the batch width, or "aos" for the baseline.
//
// The cost of a step depends on the state (a particle on a plane takes the
// contact path), so every N is timed over the same stretch of the scene:
// steps 10 to 40 (t = 1/12 s to 1/3 s), restarted from a copy of the state
// at step 10 for each timed run. Each figure is the median of the runs
// (7, or 3 at N ≥ 10^6), with enough runs at small N that ≥ 0.1 s is timed.
//
// Options:
//   --quick            N ≤ 10^5, for a smoke test
//   --n A,B,...        these N only
//   --integrators L    a comma list of euler, symplectic_euler, midpoint, rk4
//   --scalars L        float, double or both
//   --no-aos           the SoA kernel only (no baseline, no copy roof)
//   --steady           time the settled scene instead: 600 steps (5 s)
//                      first, then 5 runs of at least 0.1 s each going on
//                      from where the last stopped, median; the way a
//                      kernel timed in a loop over many steps sees it
// The threads column is the number of threads the kernel ran on (1).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "particles_scene.hpp"

namespace {

using clock_type = std::chrono::steady_clock;
namespace ps = particles_scene;

struct settings {
  std::vector<std::size_t> sizes{1000, 10000, 100000, 1000000, 4000000};
  std::vector<std::string> integrators{"euler", "symplectic_euler", "midpoint", "rk4"};
  std::vector<std::string> scalars{"float", "double"};
  int repeats = 7;
  double min_seconds = 0.1;
  bool aos = true, steady = false;
};

bool listed(const std::vector<std::string>& list, const std::string& name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

std::vector<std::string> split(const char* text) {
  std::vector<std::string> out;
  std::string item;
  for (const char* c = text;; ++c) {
    if (*c == ',' || *c == 0) {
      if (!item.empty()) out.push_back(item);
      item.clear();
      if (*c == 0) break;
    } else {
      item += *c;
    }
  }
  return out;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// Seconds per call of f, median over repeats of runs of at least min_seconds.
template <class F>
double seconds_per_call(F&& f, const settings& s) {
  f();  // warm the caches and the branch predictors
  auto t0 = clock_type::now();
  f();
  const double once = std::chrono::duration<double>(clock_type::now() - t0).count();
  const long calls = std::max(3L, long(s.min_seconds / std::max(once, 1e-9)));
  std::vector<double> runs;
  for (int r = 0; r < s.repeats; ++r) {
    t0 = clock_type::now();
    for (long c = 0; c < calls; ++c) f();
    runs.push_back(std::chrono::duration<double>(clock_type::now() - t0).count() / double(calls));
  }
  return median(runs);
}

inline constexpr int warm_steps = 10, timed_steps = 30, settle_steps = 600;

/// Seconds per step of the settled scene (--steady): the runs go on from
/// where the last one stopped, as a kernel timed in a loop over many steps
/// sees it.
template <class System>
double seconds_per_steady_step(System& system, std::size_t n) {
  using T = typename System::scalar;
  const long steps = std::max(1L, long(2e7 / double(n)));
  std::vector<double> per_step;
  for (int r = 0; r < 5; ++r) {
    const auto t0 = clock_type::now();
    for (long k = 0; k < steps; ++k) system.step(T(particles_scene::dt));
    per_step.push_back(std::chrono::duration<double>(clock_type::now() - t0).count() / double(steps));
  }
  return median(per_step);
}

/// Seconds per step over the scene's steps warm_steps … warm_steps +
/// timed_steps, each run restarted from a copy of `start` (not timed).
template <class System>
double seconds_per_scene_step(const System& start, std::size_t n, const settings& s) {
  const int runs = std::max(n >= 1000000 ? 3 : s.repeats, 1);
  std::vector<double> per_step;
  double timed = 0;
  for (int r = 0; r < runs || timed < s.min_seconds; ++r) {
    System system = start;
    const auto t0 = clock_type::now();
    for (int k = 0; k < timed_steps; ++k) system.step(typename System::scalar(particles_scene::dt));
    const double t = std::chrono::duration<double>(clock_type::now() - t0).count();
    timed += t;
    per_step.push_back(t / timed_steps);
  }
  return median(per_step);
}

/// The copy roof: bytes moved per second by b[i] = a[i] over `bytes` in total
/// (half read, half written), the way STREAM counts them.
double copy_bandwidth(std::size_t bytes, const settings& s) {
  const std::size_t n = std::max<std::size_t>(bytes / 2 / sizeof(float), 64);
  std::vector<float> a(n, 1.0f), b(n, 0.0f);
  volatile float sink = 0;
  const double t = seconds_per_call(
      [&] {
        float* __restrict out = b.data();
        const float* __restrict in = a.data();
        for (std::size_t i = 0; i < n; ++i) out[i] = in[i];
        sink = sink + b[n / 2];
      },
      s);
  return double(2 * n * sizeof(float)) / t;
}

template <class T, class I>
struct config : impulse::default_config {
  using scalar = T;
  using integrator = I;
  static constexpr bool particle_lifetime = false;  // the scene has no ageing
};

// ---- the array-of-structs baseline ----------------------------------------------

template <class T>
struct particle {
  impulse::vec3<T> pos, vel;
  T mass, age;
};

template <class T, class I>
struct aos_system {
  using scalar = T;
  std::vector<particle<T>> particles;
  std::array<ps::plane_spec<T>, 3> planes = ps::scene_planes<T>();
  std::array<impulse::vec3<T>, 3> attractor_positions{{{0, 5, 0}, {-5, 8, 3}, {5, 3, -4}}};
  std::array<T, 3> strengths{20, 10, 15};

  impulse::vec3<T> acceleration(const impulse::vec3<T>& x, const impulse::vec3<T>& v, T inverse_mass) const {
    impulse::vec3<T> f = v * T(-0.1);
    for (int k = 0; k < 3; ++k) {
      const impulse::vec3<T> d = attractor_positions[k] - x;
      const T r2 = dot(d, d) + T(0.05);
      f = f + d * (strengths[k] / (r2 * std::sqrt(r2)));
    }
    return impulse::vec3<T>{0, T(-9.81), 0} + f * inverse_mass;
  }

  void step(T dt) {
    for (particle<T>& p : particles) {
      const T inverse_mass = T(1) / p.mass;
      I::step(p.pos, p.vel, dt, [&](const impulse::vec3<T>& x, const impulse::vec3<T>& v) {
        return acceleration(x, v, inverse_mass);
      });
      for (const auto& plane : planes) {
        const T s = dot(plane.normal, p.pos) + plane.offset;
        if (s >= T(0)) continue;
        p.pos = p.pos - plane.normal * s;
        T vn = dot(p.vel, plane.normal);
        const impulse::vec3<T> tangential = p.vel - plane.normal * vn;
        if (vn < T(0)) vn = -T(ps::restitution) * vn;
        p.vel = tangential * T(1 - ps::friction) + plane.normal * vn;
      }
      p.age += dt;
    }
  }
};

// ---- one row ----------------------------------------------------------------------

struct row {
  const char* integrator;
  const char* scalar;
  std::string width;
  std::size_t n;
  double steps_per_s, bytes_per_step, roof;
};

void print(const row& r) {
  const double gb_per_s = r.steps_per_s * r.bytes_per_step / 1e9;
  const double fraction = r.roof > 0 ? gb_per_s * 1e9 / r.roof : 0.0;
  std::printf("%s,%s,%s,1,%zu,%.1f,%.2f,%.3f\n", r.integrator, r.scalar, r.width.c_str(), r.n,
              r.steps_per_s / 1e6, gb_per_s, fraction);
  std::fflush(stdout);
}

template <class T, class I>
void run(const char* integrator_name, std::size_t n, double roof_soa, double roof_aos, const settings& s) {
  using system_type = ps::system<config<T, I>>;
  const char* scalar_name = sizeof(T) == 4 ? "float" : "double";
  const T dt = T(ps::dt);
  {
    system_type system = ps::make<config<T, I>>(n);
    for (int k = 0; k < (s.steady ? settle_steps : warm_steps); ++k) system.step(dt);
    const double t = s.steady ? seconds_per_steady_step(system, n) : seconds_per_scene_step(system, n, s);
    // Read and written: x, y, z, vx, vy, vz; read: inverse mass.
    print({integrator_name, scalar_name, std::to_string(system_type::width), n, double(n) / t,
           double(13 * sizeof(T)), roof_soa});
  }
  if (s.aos) {
    aos_system<T, I> aos;
    impulse::lcg32 random{12345};
    aos.particles.resize(n);
    for (particle<T>& p : aos.particles) {
      const auto start = ps::draw<T>(random);
      p = {start.position, start.velocity, T(1), T(0)};
    }
    for (int k = 0; k < warm_steps; ++k) aos.step(dt);
    const double t = seconds_per_scene_step(aos, n, s);
    print({integrator_name, scalar_name, "aos", n, double(n) / t, double(2 * sizeof(particle<T>)), roof_aos});
  }
}

template <class T>
void run_scalar(std::size_t n, const settings& s) {
  if (!listed(s.scalars, sizeof(T) == 4 ? "float" : "double")) return;
  const double roof_soa = s.aos ? copy_bandwidth(n * 13 * sizeof(T), s) : 0.0;
  const double roof_aos = s.aos ? copy_bandwidth(n * 2 * sizeof(particle<T>), s) : 0.0;
  namespace in = impulse::integrators;
  if (listed(s.integrators, "euler")) run<T, in::euler>("euler", n, roof_soa, roof_aos, s);
  if (listed(s.integrators, "symplectic_euler"))
    run<T, in::symplectic_euler>("symplectic_euler", n, roof_soa, roof_aos, s);
  if (listed(s.integrators, "midpoint")) run<T, in::midpoint>("midpoint", n, roof_soa, roof_aos, s);
  if (listed(s.integrators, "rk4")) run<T, in::rk4>("rk4", n, roof_soa, roof_aos, s);
  if (s.aos)
    std::fprintf(stderr, "copy roof at n = %zu (%s): %.2f GB/s soa footprint, %.2f GB/s aos footprint\n", n,
                 sizeof(T) == 4 ? "float" : "double", roof_soa / 1e9, roof_aos / 1e9);
}

}  // namespace

int main(int argc, char** argv) {
  settings s;
  for (int i = 1; i < argc; ++i) {
    const bool value = i + 1 < argc;
    if (std::strcmp(argv[i], "--quick") == 0) {
      s.sizes = {1000, 10000, 100000};
      s.repeats = 3;
      s.min_seconds = 0.02;
    } else if (std::strcmp(argv[i], "--n") == 0 && value) {
      s.sizes.clear();
      for (const std::string& n : split(argv[++i])) s.sizes.push_back(std::size_t(std::stoull(n)));
    } else if (std::strcmp(argv[i], "--integrators") == 0 && value) {
      s.integrators = split(argv[++i]);
    } else if (std::strcmp(argv[i], "--scalars") == 0 && value) {
      s.scalars = split(argv[++i]);
    } else if (std::strcmp(argv[i], "--no-aos") == 0) {
      s.aos = false;
    } else if (std::strcmp(argv[i], "--steady") == 0) {
      s.steady = true;
    } else {
      std::fprintf(stderr,
                   "usage: %s [--quick] [--n A,B,...] [--integrators euler,symplectic_euler,midpoint,rk4] "
                   "[--scalars float,double] [--no-aos] [--steady]\n",
                   argv[0]);
      return 2;
    }
  }
  std::printf("integrator,scalar,width,threads,n,msteps_per_s,gb_per_s,bandwidth_fraction\n");
  for (std::size_t n : s.sizes) {
    run_scalar<float>(n, s);
    run_scalar<double>(n, s);
  }
}
