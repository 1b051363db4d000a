// bench/rigid_motion/rigid_motion_speed_vs_error.cpp — error after 10 s of
// free rotation against cost per body-step, for every integrator × scalar ×
// time step.
//
// Two torque-free bodies of mass 1 kg, the problems of
// tests/dynamics/test_free_rotation.cpp (rebuilt here: a benchmark does not
// include test files):
//   spinning body   principal moments 1, 2, 3 kg·m², spun at (0.01, 2, 0.01)
//                   rad/s in body axes, near the intermediate axis, about
//                   which it tumbles (ω₂ changes sign with a period of
//                   22.0 s). Its kinetic energy is constant exactly, so
//                   energy_error = |E(10 s) − E(0)| / E(0).
//   symmetric top   I⊥ = 1, I₃ = 1.8 kg·m², turned 0.6 rad about
//                   (1, 0.3, −0.2), spun at (0.7, −0.4, 3) rad/s in body
//                   axes. Its motion is known in closed form (below), so
//                   orientation_error = the angle, rad, between its
//                   orientation at 10 s and the closed form's.
// Both errors are evaluated in double from the state the scalar under test
// reached, against the problem as stored in that scalar (its rounded
// momenta and orientation), so a float error is the integration's own.
//
// For dt = 1/15 · 2^-k s (k = 0 … 9: 1/15 s down to 1/7680 s, 150 to 76 800
// steps to 10 s) it prints one CSV row per integrator and scalar:
//   integrator,scalar,dt,steps,ns_per_body_step,energy_error,orientation_error
// ns_per_body_step: median of 7 runs, each ≥ 20 ms, of a world without
// collision holding 512 spinning bodies and 512 tops (no springs: the fast
// path), stepped through the same 30 steps from the start again and again.
// The errors come from one body of each kind alone in such a world, stepped
// to 10 s by the same code.
//
// Usage: rigid_motion_speed_vs_error [--quick] > rigid_motion_speed_vs_error.csv
//   --quick  3 time steps, 3 repeats of ≥ 2 ms: a smoke run, not figures.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <tuple>
#include <vector>

#include "impulse/math/quat.hpp"
#include "impulse/shapes/sphere.hpp"

#include "stretch_timing.hpp"

namespace {

using namespace impulse;
using rigid_motion::settings;
using rigid_motion::stretch_timing;

constexpr double t_end = 10;                 // s, as in the energy test of test_free_rotation.cpp
constexpr long timed_steps = 30;             // per stretch of a timed run
constexpr std::size_t bodies_of_each = 512;  // in the timed world, per problem

constexpr double spinning_moments[3] = {1, 2, 3}, spin[3] = {0.01, 2, 0.01};
constexpr double top_perpendicular = 1, top_axial = 1.8;

template <class T>
vec3<double> widen(const vec3<T>& v) {
  return {double(v.x), double(v.y), double(v.z)};
}
template <class T>
quat<double> widen(const quat<T>& q) {
  return {double(q.x), double(q.y), double(q.z), double(q.w)};
}

/// Mass 1 kg, principal moments i along the body axes, at orientation q0,
/// spinning at omega (body axes). The body_def's inertia replaces its
/// shape's (carrier below).
template <class T>
body_def<T> principal_body(const vec3<T>& i, const quat<T>& q0, const vec3<T>& omega) {
  body_def<T> def;
  def.pose.rotation = q0;
  def.angular_velocity = rotate(q0, omega);
  def.mass = T(1);
  def.inertia = mat3<T>::diagonal(i);
  return def;
}

/// The shape the bodies are made of: a sphere, whose center of mass is its
/// origin. Without collision its size plays no part.
template <class T>
constexpr sphere<T> carrier{T(0.5)};

template <class T>
body_def<T> spinning_body() {
  const double* m = spinning_moments;
  return principal_body<T>({T(m[0]), T(m[1]), T(m[2])}, quat<T>::identity(), {T(spin[0]), T(spin[1]), T(spin[2])});
}

template <class T>
body_def<T> symmetric_top() {
  const quat<T> tilt = quat<T>::from_axis_angle(normalize(vec3<T>{1, T(0.3), T(-0.2)}), T(0.6));
  return principal_body<T>({T(top_perpendicular), T(top_perpendicular), T(top_axial)}, tilt,
                           {T(0.7), T(-0.4), T(3)});
}

/// ½·Lᵀ·I_w⁻¹·L in double: L in body axes over the principal moments.
template <class T>
double kinetic_energy(const rigid_body<T>& b) {
  const vec3<double> l = inverse_rotate(normalize(widen(b.orientation)), widen(b.angular_momentum));
  return 0.5 * (l.x * l.x / double(b.inertia(0, 0)) + l.y * l.y / double(b.inertia(1, 1)) +
                l.z * l.z / double(b.inertia(2, 2)));
}

/// The top's orientation at time t: R(t) = Rot(L̂, Ω_p·t) · R₀ · Rot(e₃, ν·t),
/// precessing about the constant L at Ω_p = |L|/I⊥ while turning about its
/// own axis e₃ at ν = L₃·(1/I₃ − 1/I⊥), L₃ = L·e₃ (then ω = Ω_p·L̂ + ν·e₃ =
/// I_w⁻¹·L). Landau & Lifshitz, Mechanics §33.
template <class T>
quat<double> top_orientation(const rigid_body<T>& start, double t) {
  const quat<double> q0 = widen(start.orientation);
  const vec3<double> l = widen(start.angular_momentum);
  const double l3 = dot(l, rotate(q0, vec3<double>{0, 0, 1}));
  const double precession = length(l) / top_perpendicular, nu = l3 * (1 / top_axial - 1 / top_perpendicular);
  return quat<double>::from_axis_angle(normalize(l), precession * t) * q0 *
         quat<double>::from_axis_angle({0, 0, 1}, nu * t);
}

/// The body `def` makes, alone in a world without gravity, after `steps`
/// steps of h (0: as made, its state rounded to T).
template <class T, class I>
rigid_body<T> advanced(const body_def<T>& def, long steps, T h) {
  rigid_motion::world<T, I> w;
  w.set_gravity({});
  const body_id id = w.create_body(def, carrier<T>);
  for (long i = 0; i < steps; ++i) w.step(h);
  return w.body(id);
}

struct errors {
  double energy, orientation;
};

template <class T, class I>
errors errors_after(long steps, T h) {
  const body_def<T> body = spinning_body<T>(), top = symmetric_top<T>();
  const double e0 = kinetic_energy(advanced<T, I>(body, 0, h));
  // The world makes `steps` steps of h as rounded to T, so the end time is
  // steps·h in that precision: in float every h of the ladder ends 10 s
  // 5.2e-7 s late, 2.8e-6 rad of the top's precession, above float's floor.
  const double t = double(steps) * double(h);
  return {std::abs(kinetic_energy(advanced<T, I>(body, steps, h)) - e0) / e0,
          angle_between(widen(advanced<T, I>(top, steps, h).orientation),
                        top_orientation(advanced<T, I>(top, 0, h), t))};
}

/// The timed world: spinning bodies and tops in turn.
template <class T, class I>
stretch_timing<rigid_motion::world<T, I>> timing_of(T h) {
  rigid_motion::world<T, I> w;
  w.set_gravity({});
  for (std::size_t i = 0; i < bodies_of_each; ++i) {
    w.create_body(spinning_body<T>(), carrier<T>);
    w.create_body(symmetric_top<T>(), carrier<T>);
  }
  return {w, timed_steps, h};
}

template <class T, class... I>
void measure(const std::vector<int>& ladder, const settings& s) {
  std::fprintf(stderr, "%s\n", rigid_motion::scalar_name<T>);
  for (const int k : ladder) {
    const double h = std::ldexp(1.0 / 15, -k);
    const long steps = std::lround(t_end / h);
    const T h_t = T(h);
    std::tuple<stretch_timing<rigid_motion::world<T, I>>...> timings{timing_of<T, I>(h_t)...};
    std::apply([&](auto&... t) { rigid_motion::time_in_turns(s, t...); }, timings);
    const auto print = [&]<class World>(const stretch_timing<World>& timing) {
      using integrator = typename World::integrator;
      const errors e = errors_after<T, integrator>(steps, h_t);
      std::printf("%s,%s,%.9g,%ld,%.2f,%.6e,%.6e\n", rigid_motion::integrator_name<integrator>,
                  rigid_motion::scalar_name<T>, h, steps, rigid_motion::median(timing.seconds_per_step()) * 1e9 /
                  double(timing.bodies()), e.energy, e.orientation);
    };
    std::apply([&](const auto&... t) { (print(t), ...); }, timings);
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  settings s;
  std::vector<int> ladder{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) {
      ladder = {0, 3, 6};
      s = {3, 0.002};
    } else {
      std::fprintf(stderr, "usage: %s [--quick] > rigid_motion_speed_vs_error.csv\n", argv[0]);
      return 2;
    }
  }
  namespace in = integrators;
  std::printf("integrator,scalar,dt,steps,ns_per_body_step,energy_error,orientation_error\n");
  measure<float, in::euler, in::symplectic_euler, in::midpoint, in::rk4>(ladder, s);
  measure<double, in::euler, in::symplectic_euler, in::midpoint, in::rk4>(ladder, s);
  std::fprintf(stderr, "checksum %.17g\n", rigid_motion::checksum);
}
