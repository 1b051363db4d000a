// free_rotation.hpp on its own: principal axes by Jacobi rotations, and the
// split torque-free turn against a reference integrated in ten thousand
// RK4 steps: exact for a symmetric body at five radians a step, second
// order (fourth with Yoshida's weights) for any other.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "impulse/dynamics/free_rotation.hpp"

namespace dynamics_free_turn_tests {

namespace {

using namespace impulse;

/// R·diag(moments)·Rᵀ, R the principal axes: the tensor they stand for.
mat3<double> tensor_of(const principal_inertia<double>& p) {
  const mat3<double> r = to_mat3(p.axes);
  return r * mat3<double>::diagonal(p.moments) * transpose(r);
}

double largest_difference(const mat3<double>& a, const mat3<double>& b) {
  double d = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) d = std::max(d, std::abs(a(i, j) - b(i, j)));
  return d;
}

std::array<double, 3> sorted(const vec3<double>& v) {
  std::array<double, 3> s{v.x, v.y, v.z};
  std::sort(s.begin(), s.end());
  return s;
}

/// q' = ½·ω⊗q with ω = R·I⁻¹·Rᵀ·L, L held, by classical RK4 in `steps`
/// steps: the reference the split turn is measured against.
quat<double> reference_turn(quat<double> q, const vec3<double>& moments, const vec3<double>& l, double h, int steps) {
  const auto rate = [&](const quat<double>& x) {
    const mat3<double> r = to_mat3(normalize(x));
    const vec3<double> body = transpose_mul(r, l);
    const vec3<double> w = r * vec3<double>{body.x / moments.x, body.y / moments.y, body.z / moments.z};
    return quat<double>{w.x, w.y, w.z, 0} * x * 0.5;
  };
  const double k = h / steps;
  for (int i = 0; i < steps; ++i) {
    const quat<double> k1 = rate(q), k2 = rate(q + k1 * (k / 2)), k3 = rate(q + k2 * (k / 2)), k4 = rate(q + k3 * k);
    q = normalize(q + (k1 + (k2 + k3) * 2.0 + k4) * (k / 6));
  }
  return q;
}

/// ½·Lᵀ·I_w⁻¹·L at orientation q.
double energy(const quat<double>& q, const vec3<double>& moments, const vec3<double>& l) {
  const vec3<double> body = inverse_rotate(q, l);
  return 0.5 * (body.x * body.x / moments.x + body.y * body.y / moments.y + body.z * body.z / moments.z);
}

const quat<double> tilted = normalize(quat<double>{0.3, -0.5, 0.2, 0.8});

}  // namespace

TEST_CASE("the principal axes of a diagonal inertia are the body's own, its moments unchanged to the bit") {
  const principal_inertia<double> p = principal_inertia_of(mat3<double>::diagonal({0.0225, 0.045, 0.0225}));
  CHECK(p.moments == vec3<double>{0.0225, 0.045, 0.0225});
  CHECK(p.axes == quat<double>::identity());
}

TEST_CASE("the principal axes of a turned inertia give back its moments and, turned back, the tensor itself") {
  const mat3<double> r = to_mat3(tilted);
  for (const vec3<double> moments : {vec3<double>{1, 2, 3}, vec3<double>{2, 2, 3.5}, vec3<double>{4e-3, 1e-3, 4.5e-3}}) {
    const mat3<double> tensor = r * mat3<double>::diagonal(moments) * transpose(r);
    const principal_inertia<double> p = principal_inertia_of(tensor);
    const double scale = moments.x + moments.y + moments.z;
    const std::array<double, 3> found = sorted(p.moments), wanted = sorted(moments);
    for (int i = 0; i < 3; ++i) CHECK(std::abs(found[std::size_t(i)] - wanted[std::size_t(i)]) < 1e-14 * scale);
    CHECK(largest_difference(tensor_of(p), tensor) < 1e-14 * scale);
    CHECK(std::abs(length(p.axes) - 1) < 1e-15);
  }
}

TEST_CASE("a symmetric body's free turn is exact at five radians a step") {
  // A disc (moments ¼, ½, ¼ of m·r², r = 0.3 m) spun at 300 rad/s about its
  // axis with a slight wobble, over 1/60 s: the turn is the closed form,
  // so it matches the reference however far it goes in one step.
  const vec3<double> moments{0.0225, 0.045, 0.0225};
  const principal_inertia<double> p = principal_inertia_of(mat3<double>::diagonal(moments));
  const vec3<double> spin_body{0.4, 300, -0.3};
  const vec3<double> l = rotate(tilted, vec3<double>{spin_body.x * moments.x, spin_body.y * moments.y, spin_body.z * moments.z});
  const quat<double> split = free_turn(tilted, p, l, 1.0 / 60);
  const quat<double> reference = reference_turn(tilted, moments, l, 1.0 / 60, 20000);
  CHECK(angle_between(split, reference) < 1e-10);
  CHECK(angle_between(split, tilted) > 1);  // it went far: the check is not of a small turn
}

TEST_CASE("an asymmetric body's free turn is second order, and fourth with Yoshida's weights") {
  // Moments 1, 2, 3 (the intermediate axis), spun at 2 rad/s mostly about
  // the intermediate one: the error of one step falls 2³ times when the
  // step halves at second order (local error h³) and 2⁵ at fourth.
  const vec3<double> moments{1, 2, 3};
  const principal_inertia<double> p = principal_inertia_of(mat3<double>::diagonal(moments));
  const vec3<double> l = rotate(tilted, vec3<double>{0.05, 4, 0.09});
  const auto error = [&](double h, bool fourth) {
    return angle_between(free_turn(tilted, p, l, h, fourth), reference_turn(tilted, moments, l, h, 2000));
  };
  const double second = error(0.1, false) / error(0.05, false), fourth = error(0.1, true) / error(0.05, true);
  MESSAGE("error ratio for half the step: " << second << " (second order), " << fourth << " (fourth)");
  CHECK(second > 7.5);  // 8 as h -> 0; measured 8.04
  CHECK(second < 8.5);
  CHECK(fourth > 28);  // 32 as h -> 0; measured 30.4 at these steps
  CHECK(fourth < 36);
}

TEST_CASE("10⁴ free turns keep a body on its intermediate axis within 1e-4 of its energy, at any speed") {
  // The split flow is symplectic: its energy error stays bounded instead of
  // growing, and a fast spin is cut into pieces of at most a quarter
  // radian of the splitting's turns, so it stays as small at 100 rad/s.
  // A step that holds ω for the step gains 259 % and ends on the minor axis.
  const vec3<double> moments{1.25, 1.04, 0.29};  // a box of half-extents 0.2, 0.5, 1 (per 0.8 kg/3)
  const principal_inertia<double> p = principal_inertia_of(mat3<double>::diagonal(moments));
  for (const double spin : {2.0, 10.0, 30.0, 100.0}) {
    const vec3<double> l{0.005 * spin * moments.x, spin * moments.y, 0.005 * spin * moments.z};
    const double e0 = energy(quat<double>::identity(), moments, l);
    quat<double> q = quat<double>::identity();
    double worst = 0;
    for (int i = 0; i < 10000; ++i) {
      q = free_turn(q, p, l, 1.0 / 60);
      worst = std::max(worst, std::abs(energy(q, moments, l) / e0 - 1));
    }
    CAPTURE(spin);
    CHECK(worst < 1e-4);
  }
}

}  // namespace dynamics_free_turn_tests
