// The forces, checked through the particle kernel itself: the measured
// convergence order of each integrator on closed-form problems (projectile
// with linear drag, circular orbit about a softened attractor, and a spring
// oscillator through the staged springs path), and the inverse-square law of
// a point force with its run-time switches, and the accuracy of the float
// force computed from the hardware's 1/√ estimate.
#include <cmath>
#include <cstdio>
#include <random>

#include "particle_test.hpp"

namespace particles_forces_tests {

namespace {

using namespace impulse::particles;
using impulse::vec3;
namespace in = impulse::integrators;

template <class I>
using config = particle_test::config<double, particle_test::native<double>, I>;

/// v' = g − k v: x(t) = x0 + v∞ t + (v0 − v∞)(1 − e^{−kt})/k, v∞ = g/k.
template <class I>
double projectile_error(double h) {
  const double k = 0.7, t_end = 2;
  const vec3<double> g{0, -9.81, 0}, x0{0, 1, 0}, v0{3, 5, -2};
  particle_system<config<I>, gravity, drag> s{1, gravity<double>{g}, drag<double>{k}};
  s.add(x0, v0);
  for (long i = 0; i < std::lround(t_end / h); ++i) s.step(h);
  const vec3<double> v_inf = g / k;
  const vec3<double> exact = x0 + v_inf * t_end + (v0 - v_inf) * ((1 - std::exp(-k * t_end)) / k);
  return impulse::length(s.position(0) - exact);
}

/// A softened attractor of strength s still holds a circular orbit of any
/// radius r, at angular rate ω² = s/(r² + ε)^{3/2}.
template <class I>
double orbit_error(double h) {
  const double strength = 4, softening = 0.05, r = 2, t_end = 2;
  const double omega = std::sqrt(strength / std::pow(r * r + softening, 1.5));
  particle_system<config<I>, point_forces> s{1};
  s.template force<point_forces>().softening = softening;
  s.template force<point_forces>().add({0, 0, 0}, strength);
  s.add({r, 0, 0}, {0, omega * r, 0});
  for (long i = 0; i < std::lround(t_end / h); ++i) s.step(h);
  const double angle = omega * t_end;
  return impulse::length(s.position(0) - vec3<double>{r * std::cos(angle), r * std::sin(angle), 0});
}

/// Two unit masses on a spring k, released stretched by a: the separation is
/// L + a·cos ωt, ω² = 2k.
template <class I>
double spring_error(double h) {
  const double k = 2, a = 0.3, t_end = 2, omega = std::sqrt(2 * k);
  particle_system<config<I>, springs> s{2};
  s.add({0, 0, 0});
  s.add({1 + a, 0, 0});
  s.template force<springs>().add(0, 1, 1, k);
  for (long i = 0; i < std::lround(t_end / h); ++i) s.step(h);
  return std::abs((s.position(1).x - s.position(0).x) - (1 + a * std::cos(omega * t_end)));
}

template <class I, class F>
void check_order(F&& error, double h) {
  const double coarse = error(h), fine = error(h / 2);
  const double order = std::log2(coarse / fine);
  CAPTURE(coarse);
  CAPTURE(fine);
  // The slope between two step sizes carries the next term of the error
  // series, O(h) relative to the leading one: 0.15 covers it at these h.
  CHECK(order == doctest::Approx(I::order).epsilon(0.15 / I::order));
}

TEST_CASE_TEMPLATE("each integrator converges at its order through the particle kernel", I, in::euler,
                   in::symplectic_euler, in::midpoint, in::rk4) {
  // RK4 reaches double rounding fast; it is measured at larger steps.
  const double h = I::order == 4 ? 0.05 : 0.00625;
  SUBCASE("projectile with linear drag") { check_order<I>(projectile_error<I>, h); }
  SUBCASE("circular orbit about a softened attractor") { check_order<I>(orbit_error<I>, h); }
  SUBCASE("spring oscillator through the staged springs pass") { check_order<I>(spring_error<I>, h); }
}

TEST_CASE_TEMPLATE("a point force pulls with the softened inverse-square law and can be re-signed or switched off", C, PARTICLE_CONFIGS) {
  using T = typename C::scalar;
  const T strength = 30, softening = T(0.05), dt = T(1e-3);
  particle_system<C, point_forces> s{4};
  auto& points = s.template force<point_forces>();
  points.softening = softening;
  points.add({0, 0, 0}, strength);
  for (T r : {T(0.1), T(1), T(10)}) s.add({r, 0, 0}, {}, 2);  // mass 2
  // One symplectic Euler step from rest: v = a·dt = s·r/(r² + ε)^{3/2}/m·dt.
  s.step(dt);
  const T radii[3] = {T(0.1), T(1), T(10)};
  for (std::uint32_t i = 0; i < 3; ++i) {
    const T r = radii[i];
    const T expected = -strength * r / std::pow(r * r + softening, T(1.5)) / 2 * dt;
    CAPTURE(r);
    // The float kernel's rsqrt is good to 3 ulp; cubed, 10 ulp.
    CHECK(std::abs(s.velocity(i).x - expected) <= 16 * particle_test::epsilon<T> * std::abs(expected));
  }
  // Re-signed: a repeller pushes outward with the same magnitude.
  const T before = s.velocity(2).x;
  points.points[0].strength = -strength;
  s.step(dt);
  CHECK(s.velocity(2).x - before > 0);
  // Switched off: no force at all.
  points.points[0].enabled = false;
  const vec3<T> v = s.velocity(2);
  s.step(dt);
  CHECK(s.velocity(2).x == v.x);
}

/// The worst relative error of one point's force, over particles at
/// distances 10^-3 … 10^3 m in random directions (and at the point), of
/// float lanes W wide against the law evaluated in double from the same
/// float inputs.
template <int W>
double worst_point_force_error(point_forces<float>::root_method method) {
  using batch3 = impulse::vec3_batch<float, W>;
  point_forces<float> points;
  points.root = method;
  const vec3<float> at{0.3f, 5.0f, -0.2f};
  points.add(at, 20.0f);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(-1, 1), decade(-3, 3);
  double worst = 0;
  for (int round = 0; round < 4000; ++round) {
    batch3 x = batch3::broadcast(at);
    for (int lane = 0; lane < W; ++lane) {
      vec3<float> direction{unit(random), unit(random), unit(random)};
      if (impulse::length(direction) < 0.1f) direction = {1, 0, 0};
      const float r = round == 0 && lane == 0 ? 0.0f : std::pow(10.0f, decade(random));
      x.set_lane(lane, at + impulse::normalize(direction) * r);
    }
    const batch3 f = points.evaluate(x, x, particle_lanes<float, W>{});
    for (int lane = 0; lane < W; ++lane) {
      const vec3<float> xi = x.lane(lane);
      const vec3<double> d{double(at.x) - xi.x, double(at.y) - xi.y, double(at.z) - xi.z};
      const double r2 = impulse::length_squared(d) + double(points.softening);
      const vec3<double> exact = d * (20.0 / (r2 * std::sqrt(r2)));
      const vec3<float> fi = f.lane(lane);
      const vec3<double> got{fi.x, fi.y, fi.z};
      if (impulse::length(exact) > 0) worst = std::max(worst, impulse::length(got - exact) / impulse::length(exact));
    }
  }
  return worst;
}

TEST_CASE("the float force from the 1/sqrt estimate is within 5e-7 of the law, at every width") {
  using method = point_forces<float>::root_method;
  // The estimate (rsqrt14ps at 16 lanes with AVX-512, rsqrtps at 8 and 4)
  // and its polynomial correction (point_forces::inverse_root_cubed),
  // against a square root and a division. Both carry the roundings of d,
  // |d|² + ε, the root and the products, about eight of 2^-24 each (r² and
  // the root count 1.5 times): 3.2e-7 measured for the exact form. The
  // estimate's correction leaves 3e-8 (rsqrt14ps) or 1e-9 (rsqrtps) more,
  // and a product or two more: 3.3e-7 to 3.9e-7 measured (g++ and clang).
  const double estimate_16 = worst_point_force_error<16>(method::estimate);
  const double estimate_8 = worst_point_force_error<8>(method::estimate);
  const double estimate_4 = worst_point_force_error<4>(method::estimate);
  const double exact_8 = worst_point_force_error<8>(method::exact);
  std::printf("point force, worst relative error: estimate W=16 %.3g, W=8 %.3g, W=4 %.3g; exact %.3g\n",
              estimate_16, estimate_8, estimate_4, exact_8);
  CHECK(estimate_16 <= 5e-7);
  CHECK(estimate_8 <= 5e-7);
  CHECK(estimate_4 <= 5e-7);
  CHECK(exact_8 <= 4e-7);
}

/// Whether `automatic` gives, bit for bit, what `expected` gives on W float
/// lanes, over particles scattered around two points.
template <int W>
bool automatic_matches(point_forces<float>::root_method expected) {
  using batch3 = impulse::vec3_batch<float, W>;
  point_forces<float> automatic, chosen;
  chosen.root = expected;
  for (point_forces<float>* p : {&automatic, &chosen}) {
    p->add({0.3f, 5.0f, -0.2f}, 20.0f);
    p->add({-2.0f, 1.0f, 4.0f}, -3.0f);
  }
  std::mt19937 random(11);
  std::uniform_real_distribution<float> coordinate(-10, 10);
  for (int round = 0; round < 100; ++round) {
    batch3 x = batch3::broadcast({});
    for (int lane = 0; lane < W; ++lane) x.set_lane(lane, {coordinate(random), coordinate(random), coordinate(random)});
    const batch3 a = automatic.evaluate(x, x, particle_lanes<float, W>{});
    const batch3 b = chosen.evaluate(x, x, particle_lanes<float, W>{});
    for (int lane = 0; lane < W; ++lane)
      if (!(a.lane(lane) == b.lane(lane))) return false;
  }
  return true;
}

TEST_CASE("the automatic root is the estimate where it has 14 bits and the exact form elsewhere") {
  using method = point_forces<float>::root_method;
  CHECK(point_forces<float>{}.root == method::automatic);
  const auto rule = [](int bits) { return bits >= 14 ? method::estimate : method::exact; };
  CHECK(automatic_matches<16>(rule(impulse::detail::rsqrt_estimate_bits<float, 16>())));
  CHECK(automatic_matches<8>(rule(impulse::detail::rsqrt_estimate_bits<float, 8>())));
  CHECK(automatic_matches<4>(rule(impulse::detail::rsqrt_estimate_bits<float, 4>())));
  CHECK(automatic_matches<1>(method::exact));
  // The two forms differ in their last bits, so the checks above tell them apart.
  if constexpr (impulse::detail::rsqrt_estimate_bits<float, 8>() > 0) {
    const method other = rule(impulse::detail::rsqrt_estimate_bits<float, 8>()) == method::exact ? method::estimate : method::exact;
    CHECK_FALSE(automatic_matches<8>(other));
  }
}

}  // namespace

}  // namespace particles_forces_tests
