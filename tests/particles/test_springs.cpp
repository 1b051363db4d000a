// Damped springs: the largest stable time step of each integrator for a
// given stiffness, found from the method itself and checked on a particle
// system stepped just inside and just outside it.
//
// Two particles of mass m joined by a spring of stiffness k and damping c
// oscillate in their separation r like one body of the reduced mass m/2:
//     r'' = −ω²·(r − L) − 2ζω·r',   ω² = 2k/m,   2ζω = 2c/m.
// Every integrator here is linear on this equation, so one step is a 2×2
// matrix M(h) acting on (r − L, r'); the step is stable while M's spectral
// radius is at most 1. The largest such h is the method's limit:
//   - explicit Euler: ρ = √(1 − 2ζωh + ω²h²) (for ζ < 1), stable for h < 2ζ/ω,
//     and never when undamped;
//   - symplectic Euler: h < 2/ω undamped (the leapfrog limit);
//   - midpoint: ρ² = 1 + (ωh)⁴/4 undamped, never stable without damping;
//   - RK4: h < 2√2/ω undamped.
// docs/particles.md tabulates ω·h_max for ζ = 0 and ζ = 0.05.
#include <array>
#include <cmath>
#include <complex>
#include <vector>

#include "particle_test.hpp"

namespace particles_springs_tests {

namespace {

using namespace impulse::particles;
using particle_test::epsilon;
namespace in = impulse::integrators;

/// Spectral radius of one step of integrator I on x'' = −ω²x − 2ζωx'.
template <class I>
double spectral_radius(double omega, double zeta, double h) {
  auto accel = [&](const double& x, const double& v) { return -omega * omega * x - 2 * zeta * omega * v; };
  double x1 = 1, v1 = 0, x2 = 0, v2 = 1;
  I::step(x1, v1, h, accel);
  I::step(x2, v2, h, accel);
  // Eigenvalues of [[x1, x2], [v1, v2]].
  const double trace = x1 + v2, det = x1 * v2 - x2 * v1;
  const std::complex<double> root = std::sqrt(std::complex<double>(trace * trace / 4 - det));
  return std::fmax(std::abs(trace / 2 + root), std::abs(trace / 2 - root));
}

/// Largest h with ρ(M(h)) ≤ 1, by bisection between a stable and an unstable
/// step (0 when no step is stable).
template <class I>
double largest_stable_step(double omega, double zeta) {
  double lo = 1e-6 / omega, hi = 10 / omega;
  if (spectral_radius<I>(omega, zeta, lo) > 1) return 0;
  for (int i = 0; i < 200; ++i) {
    const double mid = (lo + hi) / 2;
    (spectral_radius<I>(omega, zeta, mid) <= 1 ? lo : hi) = mid;
  }
  return lo;
}

TEST_CASE("the stability limits found by bisection match each method's closed form") {
  const double omega = 10;
  CHECK(largest_stable_step<in::symplectic_euler>(omega, 0) * omega == doctest::Approx(2).epsilon(1e-9));
  CHECK(largest_stable_step<in::rk4>(omega, 0) * omega == doctest::Approx(2 * std::sqrt(2.0)).epsilon(1e-9));
  // Undamped explicit Euler and midpoint grow at every step size, too slowly
  // for bisection to see at small h (midpoint's excess is (ωh)⁴/16): check
  // their growth factors, √(1 + (ωh)²) and √(1 + (ωh)⁴/4), instead.
  for (double wh : {0.05, 0.5, 1.0}) {
    CHECK(spectral_radius<in::euler>(omega, 0, wh / omega) == doctest::Approx(std::sqrt(1 + wh * wh)).epsilon(1e-12));
    CHECK(spectral_radius<in::midpoint>(omega, 0, wh / omega) ==
          doctest::Approx(std::sqrt(1 + wh * wh * wh * wh / 4)).epsilon(1e-12));
  }
  CHECK(largest_stable_step<in::euler>(omega, 0.05) * omega == doctest::Approx(0.1).epsilon(1e-9));
  MESSAGE("zeta = 0.05: omega*h_max euler " << largest_stable_step<in::euler>(omega, 0.05) * omega
                                          << ", symplectic euler "
                                          << largest_stable_step<in::symplectic_euler>(omega, 0.05) * omega
                                          << ", midpoint " << largest_stable_step<in::midpoint>(omega, 0.05) * omega
                                          << ", rk4 " << largest_stable_step<in::rk4>(omega, 0.05) * omega);
}

/// Largest |r − L| over the first and over the last tenth of a run of two
/// particles joined by a spring, released with the spring stretched by `stretch`.
struct amplitudes {
  double early = 0, late = 0;
};
template <class C>
amplitudes amplitude(double k, double c, double h, int steps, double stretch) {
  using T = typename C::scalar;
  particle_system<C, springs> s{2};
  s.add({0, 0, 0});
  s.add({T(1 + stretch), 0, 0});
  s.template force<springs>().add(0, 1, 1, T(k), T(c));
  amplitudes a;
  for (int i = 0; i < steps; ++i) {
    s.step(T(h));
    const double stretch_now = std::abs(double(s.position(1).x - s.position(0).x) - 1);
    if (i < steps / 10) a.early = std::fmax(a.early, stretch_now);
    if (i >= steps - steps / 10) a.late = std::fmax(a.late, stretch_now);
  }
  return a;
}

template <class I>
void check_limit_on_particles(double zeta) {
  using T = double;
  using C = particle_test::config<T, particle_test::native<T>, I>;
  const double k = 1000, m = 1, omega = std::sqrt(2 * k / m), c = zeta * omega * m;
  const double h_max = largest_stable_step<I>(omega, zeta);
  REQUIRE(h_max > 0);
  const double stretch = 0.01;
  // Just inside: the oscillation does not grow from the first tenth of the
  // run to the last (undamped symplectic Euler swings inside a fixed band
  // wider than the release stretch, by 1/√(1 − (ωh/2)²), whose peak the
  // steps sample to within 1 %; the others decay).
  const amplitudes inside = amplitude<C>(k, c, 0.95 * h_max, 4000, stretch);
  CHECK(inside.late <= inside.early * 1.01);
  // Just outside: it grows by ρ per step; run until ρ^N = 10^3.
  const double rho = spectral_radius<I>(omega, zeta, 1.05 * h_max);
  const int steps = int(std::ceil(std::log(1e3) / std::log(rho)));
  CAPTURE(rho);
  CAPTURE(steps);
  const amplitudes outside = amplitude<C>(k, c, 1.05 * h_max, steps, stretch);
  CHECK(outside.late >= 10 * outside.early);
}

TEST_CASE("a stiff spring is stable just inside each integrator's limit and grows just outside it") {
  SUBCASE("symplectic Euler, undamped") { check_limit_on_particles<in::symplectic_euler>(0); }
  SUBCASE("RK4, undamped") { check_limit_on_particles<in::rk4>(0); }
  SUBCASE("explicit Euler, damping ratio 0.05") { check_limit_on_particles<in::euler>(0.05); }
  SUBCASE("midpoint, damping ratio 0.05") { check_limit_on_particles<in::midpoint>(0.05); }
  SUBCASE("symplectic Euler, damping ratio 0.05") { check_limit_on_particles<in::symplectic_euler>(0.05); }
  SUBCASE("RK4, damping ratio 0.05") { check_limit_on_particles<in::rk4>(0.05); }
}

TEST_CASE_TEMPLATE("a spring oscillates at its natural frequency and conserves momentum", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  // Undamped, symplectic Euler at ωh = 0.05: the period is 2π/ω to O((ωh)²).
  const T k = 50, omega = std::sqrt(2 * k), h = T(0.05) / omega;
  particle_system<C, springs> s{2};
  s.add({0, 0, 0});
  s.add({T(1.2), 0, 0});
  s.template force<springs>().add(0, 1, 1, k);
  // Count upward crossings of the rest length over 10 periods' worth of steps.
  const int steps = int(std::lround(10 * 2 * 3.141592653589793 / (omega * h)));
  int crossings = 0;
  T previous = 0.2;
  for (int i = 0; i < steps; ++i) {
    s.step(h);
    const vec3_columns<T> p = s.positions();
    const T stretch = impulse::length(p[1] - p[0]) - 1;
    if (previous < 0 && stretch >= 0) ++crossings;
    previous = stretch;
    // Equal and opposite forces: the total momentum stays zero.
    const vec3_columns<T> v = s.velocities();
    REQUIRE(impulse::length(v[0] + v[1]) <= 64 * epsilon<T>);
  }
  CHECK(crossings == 10);
}

struct body {
  double x, y, z, vx, vy, vz, mass;
};
struct link {
  std::uint32_t a, b;
  double rest, k, c;
};

/// Each particle's acceleration after one explicit Euler step of a system
/// of `bodies` and `links`, against Hooke's law with damping along each
/// spring summed in double. Returns how many springs the system stepped
/// in runs' groups.
template <class T>
std::size_t check_hookes_law(const std::vector<body>& bodies, const std::vector<link>& links) {
  using C = particle_test::config<T, particle_test::native<T>, impulse::integrators::euler>;
  particle_system<C, springs> s{bodies.size()};
  for (const body& b : bodies) s.add({T(b.x), T(b.y), T(b.z)}, {T(b.vx), T(b.vy), T(b.vz)}, T(b.mass));
  for (const link& l : links) s.template force<springs>().add(l.a, l.b, T(l.rest), T(l.k), T(l.c));
  std::vector<std::array<double, 3>> force(bodies.size(), {0, 0, 0});
  std::vector<double> scale(bodies.size(), 0);  // what the terms' roundings are relative to
  for (const link& l : links) {
    const body &a = bodies[l.a], &b = bodies[l.b];
    const double d[3] = {a.x - b.x, a.y - b.y, a.z - b.z}, dv[3] = {a.vx - b.vx, a.vy - b.vy, a.vz - b.vz};
    const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (length == 0) continue;
    const double along = (dv[0] * d[0] + dv[1] * d[1] + dv[2] * d[2]) / length;
    const double magnitude = -(l.k * (length - l.rest) + l.c * along);
    for (int j = 0; j < 3; ++j) force[l.a][j] += magnitude * d[j] / length, force[l.b][j] -= magnitude * d[j] / length;
    const double term = l.k * (length + l.rest) + l.c * std::sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]);
    scale[l.a] += term;
    scale[l.b] += term;
  }
  const T h = T(1) / T(1024);  // a power of two: v + a·h and (v' − v)/h add no rounding of their own
  s.step(h);
  const vec3_columns<T> v = s.velocities();
  for (std::uint32_t i = 0; i < bodies.size(); ++i) {
    CAPTURE(i);
    const double velocity[3] = {bodies[i].vx, bodies[i].vy, bodies[i].vz};
    const impulse::vec3<T> now = v[i];
    const double got[3] = {double(now.x), double(now.y), double(now.z)};
    for (int j = 0; j < 3; ++j) {
      const double expected = force[i][j] / bodies[i].mass;
      // Each term in T is within a few roundings of its scale (length,
      // stretch, damping, the unit vector, the sum); v' = v + a·h rounds
      // once more, which (v' − v)/h magnifies by 1/h.
      const double tolerance = double(epsilon<T>) * (16 * scale[i] / bodies[i].mass + 2 * std::abs(got[j]) / double(h));
      CHECK(std::abs((got[j] - velocity[j]) / double(h) - expected) <= tolerance);
    }
  }
  return s.template force<springs>().springs_in_runs();
}

/// 21 springs (not a whole number of the springs' lanes) among 9 particles
/// of differing masses, one spring with coincident ends (no force) and a
/// hub with 8.
TEST_CASE_TEMPLATE("every spring pulls by Hooke's law with damping along it, whole lanes or not", T, float, double) {
  const std::vector<body> bodies = {{0, 0, 0, 0, 0, 0, 2},          {1.1, 0.2, -0.3, 0.5, 0, 0, 1},
                                    {-0.7, 1.3, 0.4, 0, -1, 0.25, 3}, {0.3, -0.9, 1.7, 0.1, 0.2, 0.3, 0.5},
                                    {2.0, 2.0, 2.0, -0.4, 0, 0, 1.5}, {-1.5, -0.5, 0.8, 0, 0, -0.7, 1},
                                    {0.6, 0.6, -1.2, 0.3, 0.3, 0, 4}, {0.6, 0.6, -1.2, -0.2, 0, 0, 1},
                                    {3.0, -1.0, 0.5, 0, 0.8, 0, 0.25}};
  std::vector<link> links;
  for (std::uint32_t i = 1; i < 9; ++i) links.push_back({0, i, 0.5 + 0.1 * i, 40.0 + 5 * i, 0.3 * i});  // the hub
  for (std::uint32_t i = 1; i < 8; ++i) links.push_back({i, i + 1, 1.0, 25.0 * i, 0.5});
  links.push_back({6, 7, 0.4, 80, 1});  // coincident ends: no direction, no force
  for (std::uint32_t i = 2; i < 7; ++i) links.push_back({i + 2, i - 1, 0.75, 60, 0.2 * i});
  REQUIRE(links.size() == 21);
  check_hookes_law<T>(bodies, links);
}

/// A 37 × 23 lattice, jittered and moving, of differing masses, with
/// springs of differing parameters along its rows (every third row listed
/// from b to a), its columns and one diagonal, interleaved in list order
/// as a cloth is usually built; one row's springs twice; and a few springs
/// between far particles. Most springs are in runs, whose groups load
/// their ends as rows and add their forces a row at a time; the runs'
/// tails, the duplicates and the far springs are summed one by one.
TEST_CASE_TEMPLATE("a lattice's springs in runs pull by Hooke's law as springs listed one by one do", T, float,
                   double) {
  const std::uint32_t columns = 37, rows = 23;
  std::vector<body> bodies;
  impulse::lcg32 random{7};
  auto jitter = [&] { return random.uniform<double>(-0.02, 0.02); };
  for (std::uint32_t i = 0; i < rows; ++i)
    for (std::uint32_t j = 0; j < columns; ++j)
      bodies.push_back({0.1 * j + jitter(), 0.1 * i + jitter(), jitter(), 10 * jitter(), 10 * jitter(), 10 * jitter(),
                        1 + 0.25 * ((i + 2 * j) % 5)});
  std::vector<link> links;
  for (std::uint32_t i = 0; i < rows; ++i)
    for (std::uint32_t j = 0; j < columns; ++j) {
      const std::uint32_t p = i * columns + j;
      const double k = 150 + 10 * ((i * 7 + j) % 9), c = 0.1 * ((i + j) % 4);
      if (j + 1 < columns) links.push_back(i % 3 == 2 ? link{p + 1, p, 0.1, k, c} : link{p, p + 1, 0.1, k, c});
      if (i + 1 < rows) links.push_back({p, p + columns, 0.1, k + 5, c});
      if (i + 1 < rows && j + 1 < columns) links.push_back({p, p + columns + 1, 0.14, k / 2, c});
      if (i == 4 && j + 1 < columns) links.push_back({p, p + 1, 0.09, 80, 0.3});
    }
  for (std::uint32_t t = 0; t < 11; ++t) links.push_back({t * 61 % 851, (t * 389 + 100) % 851, 1.5, 30, 0.2});
  const std::size_t in_runs = check_hookes_law<T>(bodies, links);
  CHECK(in_runs >= links.size() * 3 / 4);
}

/// Kutta's third-order method, three evaluations: an integrator the
/// library does not ship, as a user would write one.
struct kutta3 {
  static constexpr impulse::policy_kind kind = impulse::policy_kind::integrator;
  static constexpr int order = 3;
  static constexpr int stages = 3;
  template <class S, class H, class Accel>
  static constexpr void step(S& x, S& v, H h, Accel&& accel) {
    const S a1 = accel(x, v);
    const S x2 = x + v * (h / H(2)), v2 = v + a1 * (h / H(2));
    const S a2 = accel(x2, v2);
    const S x3 = x + (v2 * H(2) - v) * h, v3 = v + (a2 * H(2) - a1) * h;
    const S a3 = accel(x3, v3);
    x = x + (v + v2 * H(4) + v3) * (h / H(6));
    v = v + (a1 + a2 * H(4) + a3) * (h / H(6));
  }
};

/// 300 particles of differing masses under gravity and drag, stepped 60
/// times at 1/60 s by the kernel without springs and by the staged step
/// with 400 springs that pull with no force (stiffness and damping 0).
template <class T, class I>
void check_staged_against_fused() {
  using C = particle_test::config<T, particle_test::native<T>, I>;
  particle_system<C, gravity, drag> fused{300};
  particle_system<C, gravity, drag, springs> staged{300};
  impulse::lcg32 random{11};
  for (int i = 0; i < 300; ++i) {
    const impulse::vec3<T> p{random.uniform<T>(-5, 5), random.uniform<T>(0, 10), random.uniform<T>(-5, 5)};
    const impulse::vec3<T> v{random.uniform<T>(-3, 3), random.uniform<T>(-3, 3), random.uniform<T>(-3, 3)};
    const T mass = random.uniform<T>(T(0.5), T(4));
    fused.add(p, v, mass);
    staged.add(p, v, mass);
  }
  for (std::uint32_t k = 0; k < 400; ++k)
    staged.template force<springs>().add(k % 300, (k * 7 + 1) % 300, T(1), T(0), T(0));
  const int steps = 60;
  for (int i = 0; i < steps; ++i) {
    fused.step(T(1) / 60);
    staged.step(T(1) / 60);
  }
  // The same integrator code on the same accelerations (each plus the
  // springs' zero). The two copies of it are compiled apart, and may fuse a
  // multiply and an add differently: a rounding of the state's scale at
  // most, per operation, about 16 a step.
  const vec3_columns<T> p0 = fused.positions(), p1 = staged.positions();
  const vec3_columns<T> v0 = fused.velocities(), v1 = staged.velocities();
  for (std::uint32_t i = 0; i < 300; ++i) {
    CAPTURE(i);
    const T scale = T(1) + impulse::length(p0[i]) + impulse::length(v0[i]);
    CHECK(impulse::length(p1[i] - p0[i]) <= 16 * steps * epsilon<T> * scale);
    CHECK(impulse::length(v1[i] - v0[i]) <= 16 * steps * epsilon<T> * scale);
  }
}

TEST_CASE_TEMPLATE("springs with no force leave each integrator's step as the kernel without springs takes it", T,
                   float, double) {
  SUBCASE("explicit Euler") { check_staged_against_fused<T, in::euler>(); }
  SUBCASE("symplectic Euler") { check_staged_against_fused<T, in::symplectic_euler>(); }
  SUBCASE("midpoint") { check_staged_against_fused<T, in::midpoint>(); }
  SUBCASE("RK4") { check_staged_against_fused<T, in::rk4>(); }
  SUBCASE("Kutta's third-order method, written outside the library") { check_staged_against_fused<T, kutta3>(); }
}

}  // namespace

}  // namespace particles_springs_tests
