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
//   integrator,scalar,width,threads,n,msteps_per_s,gb_per_s,bandwidth_fraction,
//   speedup,independent_speedup
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
//                      first and one untimed run, then 5 runs of 2·10^7
//                      particle-steps each going on from where the last
//                      stopped, median; the way a kernel timed in a loop
//                      over many steps sees it
//   --emitter          instead of the above: the cost of ageing and of an
//                      emitter at a steady population against the plain
//                      scene, in the same run (its own CSV, below)
//   --budget           instead of the above: the most particles stepped
//                      within 1, 4 and 16 ms (one 60 Hz frame's share) per
//                      integrator, scalar and thread count (its own CSV)
//   --springs          instead of the above: a 320 × 320 cloth of springs
//                      (102 400 particles, 204 160 springs) per integrator,
//                      scalar and thread count (its own CSV; in_runs is how
//                      many springs the step takes as runs, relist_step_ms
//                      the median of 5 steps each after one spring's ends
//                      changed, which lists the springs afresh; on W > 1
//                      workers, a run of 2·10^7 particle-steps through a
//                      hook that clocks every range: loops_per_step,
//                      busy_us_per_step, the time ranges ran summed over
//                      the workers, and waiting_share, the share of the
//                      workers' time that no range ran; 0 on one worker)
//   --root M           how float lanes take the attractors' (|d|² + ε)^(-3/2)
//                      (point_forces::root_method): automatic (the default:
//                      the estimate of 1/√ under AVX-512, a square root and
//                      a division under AVX and SSE), estimate or exact
//   --threads A,B,...  step the SoA kernel on each of these worker counts
//                      (impulse::thread_pool; 1, the default, runs on the
//                      calling thread with no pool)
// The threads column is the number of workers the kernel ran on. On a row
// of W > 1 workers, speedup is the pool's over one worker and
// independent_speedup the machine's own ceiling for W workers on the same
// work: W copies of the system, each stepped on a thread of its own with
// nothing shared. Both are medians of five rounds that step a one-worker
// copy, the pooled system and the W copies in turn (1 on a row of one
// worker). Read the first against the second, not against W: on a shared
// virtual machine two cores seldom do twice one core's work even when they
// share nothing.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "impulse/thread_pool.hpp"
#include "particles_scene.hpp"

namespace {

using clock_type = std::chrono::steady_clock;
namespace ps = particles_scene;

struct settings {
  std::vector<std::size_t> sizes{1000, 10000, 100000, 1000000, 4000000};
  std::vector<std::string> integrators{"euler", "symplectic_euler", "midpoint", "rk4"};
  std::vector<std::string> scalars{"float", "double"};
  std::vector<std::uint32_t> threads{1};
  int repeats = 7;
  double min_seconds = 0.1;
  bool aos = true, steady = false, emitter = false, budget = false, springs = false;
  std::string root = "automatic";
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
/// sees it. One run as long as a timed one goes first, untimed: at small N
/// the settling takes a few milliseconds, and the first cell of a process
/// then ran up to a fifth slower than the same cell after it.
template <class System>
double seconds_per_steady_step(System& system, std::size_t n) {
  using T = typename System::scalar;
  const long steps = std::max(1L, long(2e7 / double(n)));
  for (long k = 0; k < steps; ++k) system.step(T(particles_scene::dt));
  std::vector<double> per_step;
  for (int r = 0; r < 5; ++r) {
    const auto t0 = clock_type::now();
    for (long k = 0; k < steps; ++k) system.step(T(particles_scene::dt));
    per_step.push_back(std::chrono::duration<double>(clock_type::now() - t0).count() / double(steps));
  }
  return median(per_step);
}

/// Speed-ups over one worker, measured in the same rounds.
struct scaling {
  double pool = 1.0;         ///< the system on its pool of W workers
  double independent = 1.0;  ///< W copies, each on a thread of its own
};

/// For a system on a pool of `workers` workers: five rounds, each stepping
/// for 2·10^7 particle-steps a copy of it on one worker, then the system on
/// its pool, then `workers` copies at once, each on a thread of its own with
/// nothing shared. Returns the medians of the rounds' speed-ups over the
/// one-worker copy; `independent` is the machine's own ceiling for
/// `workers` cores on this work (`workers` where they share nothing at all).
template <class System>
scaling speedups(System& system, std::uint32_t workers) {
  using T = typename System::scalar;
  std::vector<System> copies(workers, system);
  for (System& copy : copies) copy.set_task_system({});
  const long steps = std::max(1L, long(2e7 / double(system.size())));
  auto step = [steps](System& s) {
    for (long k = 0; k < steps; ++k) s.step(T(particles_scene::dt));
  };
  auto seconds = [](const auto& f) {
    const auto t0 = clock_type::now();
    f();
    return std::chrono::duration<double>(clock_type::now() - t0).count();
  };
  std::vector<double> pool, independent;
  for (int r = 0; r < 5; ++r) {
    const double alone = seconds([&] { step(copies[0]); });
    pool.push_back(alone / seconds([&] { step(system); }));
    std::atomic<bool> go{false};
    std::vector<std::thread> others;
    for (std::uint32_t c = 1; c < workers; ++c)
      others.emplace_back([&, c] {
        while (!go.load()) std::this_thread::yield();
        step(copies[c]);
      });
    independent.push_back(double(workers) * alone / seconds([&] {
      go = true;
      step(copies[0]);
      for (std::thread& t : others) t.join();
    }));
  }
  return {median(pool), median(independent)};
}

/// Where a system's step on a pool goes: loops through the task hook per
/// step, and the share of the workers' time in a step that no range of a
/// loop was running on them (waiting at loops' ends, handing loops over,
/// and what the step does outside its loops).
struct loop_profile {
  double loops_per_step = 0;
  double busy_us_per_step = 0;  ///< summed over the workers
  double waiting_share = 0;     ///< 1 − busy / (workers × the step's time)
};

/// A task hook that forwards to another and clocks each range it runs,
/// per worker (bench only: the library never times its loops).
class clocked_hook {
 public:
  explicit clocked_hook(const impulse::task_system& inner) : inner_(inner), busy_(inner.workers, 0.0) {}
  impulse::task_system tasks() { return {inner_.workers, &enqueue, &finish, this}; }
  [[nodiscard]] long loops() const { return loops_; }
  [[nodiscard]] double busy_seconds() const {
    double sum = 0;
    for (double b : busy_) sum += b;
    return sum;
  }

 private:
  struct loop {
    clocked_hook* hook;
    impulse::task_function* task;
    void* context;
    void* handle;
  };
  static void run(std::uint32_t begin, std::uint32_t end, std::uint32_t worker, void* context) {
    loop& l = *static_cast<loop*>(context);
    const auto t0 = clock_type::now();
    l.task(begin, end, worker, l.context);
    l.hook->busy_[worker] += std::chrono::duration<double>(clock_type::now() - t0).count();
  }
  static void* enqueue(impulse::task_function* task, std::uint32_t count, std::uint32_t min_range, void* context,
                       void* user) {
    clocked_hook& h = *static_cast<clocked_hook*>(user);
    h.loop_ = {&h, task, context, nullptr};
    h.loop_.handle = h.inner_.enqueue(&run, count, min_range, &h.loop_, h.inner_.user_context);
    return &h.loop_;
  }
  static void finish(void* handle, void* user) {
    clocked_hook& h = *static_cast<clocked_hook*>(user);
    h.inner_.finish(static_cast<loop*>(handle)->handle, h.inner_.user_context);
    ++h.loops_;
  }

  impulse::task_system inner_;
  std::vector<double> busy_;  // per worker; a worker runs one range at a time
  loop loop_{};               // the one loop in flight: impulse issues them one after another
  long loops_ = 0;
};

/// The system stepped for 2·10^7 particle-steps on `pool` through a
/// clocked_hook, then handed `pool` back.
template <class System>
loop_profile profile_loops(System& system, impulse::thread_pool& pool) {
  clocked_hook hook{pool.tasks()};
  system.set_task_system(hook.tasks());
  const long steps = std::max(1L, long(2e7 / double(system.size())));
  const auto t0 = clock_type::now();
  for (long k = 0; k < steps; ++k) system.step(typename System::scalar(particles_scene::dt));
  const double seconds = std::chrono::duration<double>(clock_type::now() - t0).count();
  system.set_task_system(pool.tasks());
  return {double(hook.loops()) / double(steps), hook.busy_seconds() / double(steps) * 1e6,
          1 - hook.busy_seconds() / (double(pool.workers()) * seconds)};
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
  static constexpr bool particle_masses = false;    // and unit masses
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
  std::uint32_t threads;
  std::size_t n;
  double steps_per_s, bytes_per_step, roof;
  scaling speedup{};  // over one worker, for `threads` workers
};

void print(const row& r) {
  const double gb_per_s = r.steps_per_s * r.bytes_per_step / 1e9;
  const double fraction = r.roof > 0 ? gb_per_s * 1e9 / r.roof : 0.0;
  std::printf("%s,%s,%s,%u,%zu,%.1f,%.2f,%.3f,%.2f,%.2f\n", r.integrator, r.scalar, r.width.c_str(), r.threads, r.n,
              r.steps_per_s / 1e6, gb_per_s, fraction, r.speedup.pool, r.speedup.independent);
  std::fflush(stdout);
}

template <class T, class I>
void run(const char* integrator_name, std::size_t n, double roof_soa, double roof_aos, const settings& s) {
  using system_type = ps::system<config<T, I>>;
  const char* scalar_name = sizeof(T) == 4 ? "float" : "double";
  const T dt = T(ps::dt);
  for (std::uint32_t threads : s.threads) {
    impulse::thread_pool pool{threads};
    system_type system = ps::make<config<T, I>>(n);
    system.set_task_system(pool.tasks());
    using points = impulse::particles::point_forces<T>;
    system.template force<impulse::particles::point_forces>().root =
        s.root == "exact" ? points::root_method::exact
        : s.root == "estimate" ? points::root_method::estimate : points::root_method::automatic;
    for (int k = 0; k < (s.steady ? settle_steps : warm_steps); ++k) system.step(dt);
    const double t = s.steady ? seconds_per_steady_step(system, n) : seconds_per_scene_step(system, n, s);
    // Read and written: x, y, z, vx, vy, vz (unit masses: no mass column).
    print({integrator_name, scalar_name, std::to_string(system_type::width), threads, n, double(n) / t,
           double(12 * sizeof(T)), roof_soa, threads > 1 ? speedups(system, threads) : scaling{}});
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
    print({integrator_name, scalar_name, "aos", 1, n, double(n) / t, double(2 * sizeof(particle<T>)), roof_aos});
  }
}

/// Calls f.operator()<T, I>(name) for the scalar and integrator named.
template <class F>
void with_types(const std::string& scalar, const std::string& integrator, F&& f) {
  namespace in = impulse::integrators;
  auto with = [&]<class T>() {
    if (integrator == "euler") f.template operator()<T, in::euler>("euler");
    if (integrator == "symplectic_euler") f.template operator()<T, in::symplectic_euler>("symplectic_euler");
    if (integrator == "midpoint") f.template operator()<T, in::midpoint>("midpoint");
    if (integrator == "rk4") f.template operator()<T, in::rk4>("rk4");
  };
  if (scalar == "float") with.template operator()<float>();
  if (scalar == "double") with.template operator()<double>();
}

template <class T>
void run_scalar(std::size_t n, const settings& s) {
  if (!listed(s.scalars, sizeof(T) == 4 ? "float" : "double")) return;
  const double roof_soa = s.aos ? copy_bandwidth(n * 12 * sizeof(T), s) : 0.0;
  const double roof_aos = s.aos ? copy_bandwidth(n * 2 * sizeof(particle<T>), s) : 0.0;
  for (const char* integrator : {"euler", "symplectic_euler", "midpoint", "rk4"})
    if (listed(s.integrators, integrator))
      with_types(sizeof(T) == 4 ? "float" : "double", integrator, [&]<class U, class I>(const char* name) {
        if constexpr (std::is_same_v<U, T>) run<T, I>(name, n, roof_soa, roof_aos, s);
      });
  if (s.aos)
    std::fprintf(stderr, "copy roof at n = %zu (%s): %.2f GB/s soa footprint, %.2f GB/s aos footprint\n", n,
                 sizeof(T) == 4 ? "float" : "double", roof_soa / 1e9, roof_aos / 1e9);
}

// ---- --emitter: what ageing and recycling cost ------------------------------------

template <class T, class I>
struct life_config : config<T, I> {
  static constexpr bool particle_lifetime = true;
};

/// The scene's particles with lives spread evenly over (0, 2 s], and an
/// emitter that replaces them at n / 2 s, drawing in the scene's start box:
/// the population stays at n while n / 240 particles die and are born at
/// every step. With `recycle` false the lives are infinite and the emitter
/// is off: the age and lifetime columns are paid for, nothing dies.
template <class T, class I>
ps::system<life_config<T, I>> make_recycling(std::size_t n, bool recycle) {
  using C = life_config<T, I>;
  const T life = T(2);
  ps::system<C> system{n + n / 16 + 64, ps::scene_gravity<T>(), ps::scene_drag<T>(), ps::scene_attractors<T>()};
  for (const auto& p : ps::scene_planes<T>())
    system.add_plane(impulse::particles::plane_collider<T>::half_space(p.normal, p.offset, T(ps::restitution),
                                                                       T(ps::friction)));
  impulse::lcg32 random{12345};
  for (std::size_t i = 0; i < n; ++i) {
    const auto start = ps::draw<T>(random);
    const T lifetime = recycle ? life * T(i + 1) / T(n) : std::numeric_limits<T>::infinity();
    system.add(start.position, start.velocity, T(1), lifetime);
  }
  if (recycle) {
    impulse::particles::emitter<T> source;
    source.position = {T(0), T(7.75), T(0)};
    source.half_extents = {T(8), T(7.25), T(8)};
    source.velocity_spread = {T(5), T(5), T(5)};
    source.rate = T(double(n) / double(life));
    source.lifetime = life;
    system.add_emitter(source);
  }
  return system;
}

template <class T, class I>
void emitter_rows(const char* integrator_name, std::size_t n, std::uint32_t threads) {
  const char* scalar_name = sizeof(T) == 4 ? "float" : "double";
  impulse::thread_pool pool{threads};
  auto plain = ps::make<config<T, I>>(n);
  auto ageing = make_recycling<T, I>(n, false);
  auto recycling = make_recycling<T, I>(n, true);
  plain.set_task_system(pool.tasks());
  ageing.set_task_system(pool.tasks());
  recycling.set_task_system(pool.tasks());
  for (int k = 0; k < settle_steps; ++k) {
    plain.step(T(ps::dt));
    ageing.step(T(ps::dt));
    recycling.step(T(ps::dt));
  }
  // Three rounds taking turns, so that the machine's drift falls on all three.
  std::vector<double> t_plain, t_ageing, t_recycling;
  for (int round = 0; round < 3; ++round) {
    t_plain.push_back(seconds_per_steady_step(plain, n));
    t_ageing.push_back(seconds_per_steady_step(ageing, n));
    t_recycling.push_back(seconds_per_steady_step(recycling, n));
  }
  const double base = median(t_plain);
  auto print_row = [&](const char* scene, double t, std::size_t size) {
    std::printf("%s,%s,%s,%u,%zu,%.1f,%.3f\n", scene, integrator_name, scalar_name, threads, size,
                double(size) / t / 1e6, t / base);
  };
  print_row("plain", base, plain.size());
  print_row("ageing", median(t_ageing), ageing.size());
  print_row("emitter", median(t_recycling), recycling.size());
  std::fflush(stdout);
}

int run_emitter_table(const settings& s) {
  std::printf("scene,integrator,scalar,threads,n,msteps_per_s,time_relative_to_plain\n");
  for (std::size_t n : s.sizes)
    for (std::uint32_t threads : s.threads)
      for (const std::string& scalar : s.scalars)
        for (const std::string& integrator : s.integrators)
          with_types(scalar, integrator,
                     [&]<class T, class I>(const char* name) { emitter_rows<T, I>(name, n, threads); });
  return 0;
}

// ---- --budget: how many particles fit a frame's share ---------------------------

/// Seconds per step of the scene with n particles, settled for 1 s.
template <class T, class I>
double budget_step(std::size_t n, std::uint32_t threads) {
  impulse::thread_pool pool{threads};
  auto system = ps::make<config<T, I>>(n);
  system.set_task_system(pool.tasks());
  for (int k = 0; k < 120; ++k) system.step(T(ps::dt));
  return seconds_per_steady_step(system, n);
}

/// The most particles (to 1 000) stepped within `budget` seconds: an
/// estimate from the rate at 10^5, corrected once by the time measured at
/// it; the row gives the corrected n and the time measured at that n.
template <class T, class I>
void budget_rows(const char* integrator_name, std::uint32_t threads) {
  const char* scalar_name = sizeof(T) == 4 ? "float" : "double";
  const double rate = 1e5 / budget_step<T, I>(100000, threads);
  for (double budget : {1e-3, 4e-3, 16e-3}) {
    double n = rate * budget, t = 0;
    for (int k = 0; k < 2; ++k) {
      n = std::max(1000.0, std::floor(n / 1000) * 1000);
      t = budget_step<T, I>(std::size_t(n), threads);
      if (k == 0) n *= budget / t;
    }
    std::printf("%s,%s,%u,%.0f,%.0f,%.3f\n", integrator_name, scalar_name, threads, budget * 1e3, n, t * 1e3);
    std::fflush(stdout);
  }
}

int run_budget_table(const settings& s) {
  std::printf("integrator,scalar,threads,budget_ms,n,ms_per_step\n");
  for (std::uint32_t threads : s.threads)
    for (const std::string& scalar : s.scalars)
      for (const std::string& integrator : s.integrators)
        with_types(scalar, integrator, [&]<class T, class I>(const char* name) { budget_rows<T, I>(name, threads); });
  return 0;
}

// ---- --springs: a cloth, the staged path ---------------------------------------------

template <class T, class I>
void springs_row(const char* integrator_name, std::uint32_t threads) {
  using namespace impulse::particles;
  const std::uint32_t side = 320;
  impulse::thread_pool pool{threads};
  particle_system<config<T, I>, gravity, drag, springs> cloth{side * side, ps::scene_gravity<T>(),
                                                              ps::scene_drag<T>(), springs<T>{}};
  cloth.set_task_system(pool.tasks());
  for (std::uint32_t i = 0; i < side; ++i)
    for (std::uint32_t j = 0; j < side; ++j) cloth.add({T(0.1) * T(i), T(5), T(0.1) * T(j)});
  auto& list = cloth.template force<springs>();
  for (std::uint32_t i = 0; i < side; ++i)
    for (std::uint32_t j = 0; j < side; ++j) {
      if (i + 1 < side) list.add(i * side + j, (i + 1) * side + j, T(0.1), T(200), T(0.5));
      if (j + 1 < side) list.add(i * side + j, i * side + j + 1, T(0.1), T(200), T(0.5));
    }
  cloth.add_plane(plane_collider<T>::half_space({T(0), T(1), T(0)}, T(0), T(0.2), T(0.5)));
  for (int k = 0; k < 60; ++k) cloth.step(T(ps::dt));
  const double t = seconds_per_steady_step(cloth, cloth.size());
  const scaling speedup = threads > 1 ? speedups(cloth, threads) : scaling{};
  std::vector<double> relist;
  for (int k = 0; k < 5; ++k) {
    spring<T> turned = list[0];
    std::swap(turned.a, turned.b);
    list.set(0, turned);
    const auto start = clock_type::now();
    cloth.step(T(ps::dt));
    relist.push_back(std::chrono::duration<double, std::milli>(clock_type::now() - start).count());
  }
  std::sort(relist.begin(), relist.end());
  const loop_profile loops = threads > 1 ? profile_loops(cloth, pool) : loop_profile{};
  std::printf("%s,%s,%u,%zu,%zu,%zu,%.1f,%.2f,%.2f,%.2f,%.1f,%.0f,%.3f\n", integrator_name,
              sizeof(T) == 4 ? "float" : "double", threads, cloth.size(), list.size(), list.springs_in_runs(),
              double(cloth.size()) / t / 1e6, speedup.pool, speedup.independent, relist[2], loops.loops_per_step,
              loops.busy_us_per_step, loops.waiting_share);
  std::fflush(stdout);
}

int run_springs_table(const settings& s) {
  std::printf("integrator,scalar,threads,n,springs,in_runs,msteps_per_s,speedup,independent_speedup,relist_step_ms,"
              "loops_per_step,busy_us_per_step,waiting_share\n");
  for (const std::string& scalar : s.scalars)
    for (const std::string& integrator : s.integrators)
      for (std::uint32_t threads : s.threads)
        with_types(scalar, integrator, [&]<class T, class I>(const char* name) { springs_row<T, I>(name, threads); });
  return 0;
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
    } else if (std::strcmp(argv[i], "--threads") == 0 && value) {
      s.threads.clear();
      for (const std::string& t : split(argv[++i])) s.threads.push_back(std::uint32_t(std::stoul(t)));
    } else if (std::strcmp(argv[i], "--no-aos") == 0) {
      s.aos = false;
    } else if (std::strcmp(argv[i], "--steady") == 0) {
      s.steady = true;
    } else if (std::strcmp(argv[i], "--root") == 0 && value &&
               (std::strcmp(argv[i + 1], "automatic") == 0 || std::strcmp(argv[i + 1], "estimate") == 0 ||
                std::strcmp(argv[i + 1], "exact") == 0)) {
      s.root = argv[++i];
    } else if (std::strcmp(argv[i], "--emitter") == 0) {
      s.emitter = true;
    } else if (std::strcmp(argv[i], "--budget") == 0) {
      s.budget = true;
    } else if (std::strcmp(argv[i], "--springs") == 0) {
      s.springs = true;
    } else {
      std::fprintf(stderr,
                   "usage: %s [--quick] [--n A,B,...] [--integrators euler,symplectic_euler,midpoint,rk4] "
                   "[--scalars float,double] [--threads 1,2] [--no-aos] [--steady] [--root automatic|estimate|exact] [--emitter | --budget | --springs]\n",
                   argv[0]);
      return 2;
    }
  }
  if (s.emitter) return run_emitter_table(s);
  if (s.budget) return run_budget_table(s);
  if (s.springs) return run_springs_table(s);
  std::printf("integrator,scalar,width,threads,n,msteps_per_s,gb_per_s,bandwidth_fraction,speedup,independent_speedup\n");
  for (std::size_t n : s.sizes) {
    run_scalar<float>(n, s);
    run_scalar<double>(n, s);
  }
}
