// Time of impact by conservative advancement: spheres meeting head on and
// at an angle (closed forms), a bullet against a thin wall, a spinning rod
// reaching a cube (closed form) and sweeping past one, pairs that part or
// overlap from the start, the iteration cap, far from the origin, and
// random sweeps checked against sampled distances: never a contact missed
// before the time found.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "impulse/core/random.hpp"
#include "impulse/narrowphase/time_of_impact.hpp"
#include "impulse/shapes/box.hpp"
#include "impulse/shapes/convex_hull.hpp"

#include "poses.hpp"

namespace narrowphase_time_of_impact_tests {

namespace {

using namespace impulse;
using narrowphase::gjk_distance;
using narrowphase::sweep;
using narrowphase::time_of_impact;
using narrowphase::toi_options;
using narrowphase::toi_state;
using test::at;
using test::random_rotation;

/// Rounding of GJK's distances and of the poses at t for 1 m shapes: a few
/// float spacings, or a few thousand double ones (GJK's own tolerance).
template <class T>
constexpr T tolerance = sizeof(T) == 4 ? T(1e-5) : T(1e-10);

template <class T>
sweep<T> moving(const vec3<T>& from, const vec3<T>& translation, const quat<T>& turn = quat<T>::identity(),
                const vec3<T>& angle = {}) {
  return {at<T>(from, turn), at<T>(from + translation, integrate(turn, angle, T(1))), {}};
}

template <class T>
sweep<T> still(const vec3<T>& at_position) {
  return moving<T>(at_position, {});
}

}  // namespace

TEST_CASE_TEMPLATE("toi: two spheres head on meet at the closed-form time in two steps", T, float, double) {
  const sphere<T> a{T(0.5)}, b{T(0.3)};
  const toi_options<T> o;
  // A from 0 moves +10, B from 5 moves −2: the gap 4.2 closes at 12 per
  // unit time. The bound is exact head on, so the first step lands on the
  // target.
  const auto r = time_of_impact(a, moving<T>({}, {10, 0, 0}), b, moving<T>({5, 0, 0}, {-2, 0, 0}));
  REQUIRE(r.state == toi_state::hit);
  const T expected = (T(4.2) - o.target) / T(12);
  CHECK(std::abs(r.t - expected) <= tolerance<T>);
  CHECK(r.iterations <= 2);
  CHECK(r.distance == doctest::Approx(double(o.target)).epsilon(tolerance<T> * 100));
  CHECK(length(r.normal - vec3<T>::unit_x()) <= tolerance<T>);
  CHECK(std::abs(r.on_a.x - (T(0.5) + T(10) * r.t)) <= tolerance<T> * 10);
  CHECK(std::abs(r.on_b.x - (T(5) - T(0.3) - T(2) * r.t)) <= tolerance<T> * 10);
}

TEST_CASE_TEMPLATE("toi: spheres passing at an angle stop within the tolerance before the target", T, float, double) {
  // B sits 0.6 off A's path: |Δ(t)|² = (4 − 8t)² + 0.36 reaches
  // (0.8 + d)² at t(d) = (4 − √((0.8 + d)² − 0.36))/8. Conservative
  // advancement stops between t(target + tolerance) and t(target).
  const sphere<T> a{T(0.5)}, b{T(0.3)};
  const toi_options<T> o;
  const auto r = time_of_impact(a, moving<T>({}, {8, 0, 0}), b, still<T>({4, T(0.6), 0}));
  REQUIRE(r.state == toi_state::hit);
  const auto time_at = [](T d) { return (T(4) - std::sqrt((T(0.8) + d) * (T(0.8) + d) - T(0.36))) / T(8); };
  CHECK(r.t >= time_at(o.target + o.tolerance) - tolerance<T>);
  CHECK(r.t <= time_at(o.target) + tolerance<T>);
  CHECK(r.distance >= o.target - tolerance<T>);
  CHECK(r.distance < o.target + o.tolerance);
  MESSAGE("iterations " << r.iterations);
  CHECK(r.iterations <= 10);
}

TEST_CASE_TEMPLATE("toi: a bullet at 500 m/s is stopped in front of a 1 cm wall", T, float, double) {
  // A 5 cm ball at 500 m/s covers 8.33 m in a 1/60 s step; the wall is 1 cm
  // thick, 4 m ahead: a discrete test at the step's ends sees no contact.
  const sphere<T> bullet{T(0.05)};
  const box<T> wall{{T(0.005), 1, 1}};
  const T step = T(500) / T(60);
  const toi_options<T> o;
  const auto discrete = gjk_distance(bullet, at<T>({step, 0, 0}), wall, at<T>({4, 0, 0}));
  CHECK_FALSE(discrete.overlapping);
  const auto r = time_of_impact(bullet, moving<T>({}, {step, 0, 0}), wall, still<T>({4, 0, 0}));
  REQUIRE(r.state == toi_state::hit);
  const T front = T(4) - T(0.005);  // the wall's near face
  const T center = step * r.t;      // the bullet's center at the time found
  CHECK(center + T(0.05) <= front);  // in front of the wall, not through it
  // Exactly the target short of the face (head on: exact in one step).
  CHECK(std::abs(front - (center + T(0.05)) - o.target) <= tolerance<T> * 10);
  CHECK(r.iterations <= 2);
  CHECK(length(r.normal - vec3<T>::unit_x()) <= tolerance<T>);
}

TEST_CASE_TEMPLATE("toi: a spinning rod reaches a cube at the closed-form angle", T, float, double) {
  // A rod of half extents (1, 0.02, 0.02) turns 2 rad about z over the
  // step. A cube of half extent 0.1 at (0, 0.6, 0): its corner edge at
  // (0.1, 0.5) is R·cos(φ + α) from the rod's axis at angle φ, R = √0.26,
  // α = atan(0.1/0.5), so the rod's face is within d of it at
  // φ(d) = acos((0.02 + d)/R) − α, at t = φ/2.
  const box<T> rod{{1, T(0.02), T(0.02)}}, cube{vec3<T>::splat(T(0.1))};
  const toi_options<T> o;
  const auto r = time_of_impact(rod, moving<T>({}, {}, quat<T>::identity(), {0, 0, 2}), cube, still<T>({0, T(0.6), 0}));
  REQUIRE(r.state == toi_state::hit);
  const T big_r = std::sqrt(T(0.26)), alpha = std::atan2(T(0.1), T(0.5));
  const auto time_at = [&](T d) { return (std::acos((T(0.02) + d) / big_r) - alpha) / T(2); };
  CHECK(r.t >= time_at(o.target + o.tolerance) - tolerance<T>);
  CHECK(r.t <= time_at(o.target) + tolerance<T>);
  // The distance GJK gives at t is the closed form's there.
  const T phi = T(2) * r.t;
  CHECK(std::abs(r.distance - (big_r * std::cos(phi + alpha) - T(0.02))) <= tolerance<T> * 10);
  // Conservative advancement crawls here: the bound takes the rod's tip
  // (1 m from the axis), the contact is half as far out. Measured: 11
  // iterations.
  MESSAGE("spinning rod: t " << r.t << ", iterations " << r.iterations);
  CHECK(r.iterations <= 20);
}

TEST_CASE_TEMPLATE("toi: a spinning rod sweeping past a cube and short of one does not hit", T, float, double) {
  const box<T> rod{{1, T(0.02), T(0.02)}}, cube{vec3<T>::splat(T(0.1))};
  const sweep<T> spin = moving<T>({}, {}, quat<T>::identity(), {0, 0, 2});
  // Beside the rod's plane of rotation: the cube spans z in [0.1, 0.3], the
  // rod ±0.02; it passes 8 cm from it.
  auto r = time_of_impact(rod, spin, cube, still<T>({0, T(0.6), T(0.2)}));
  CHECK(r.state == toi_state::separated);
  CHECK(r.t == T(1));
  const int past = r.iterations;
  // Out of reach: the cube's near face at 1.1 m, the rod's corner at 1.0004 m.
  r = time_of_impact(rod, spin, cube, still<T>({0, T(1.2), 0}));
  CHECK(r.state == toi_state::separated);
  const int beyond = r.iterations;
  // In reach, but the rod turns only 1 rad, short of the 1.32 rad it needs.
  r = time_of_impact(rod, moving<T>({}, {}, quat<T>::identity(), {0, 0, 1}), cube, still<T>({0, T(0.6), 0}));
  CHECK(r.state == toi_state::separated);
  // Measured: 6, 7 and 3 iterations.
  MESSAGE("iterations: past " << past << ", beyond " << beyond << ", short " << r.iterations);
  CHECK(std::max({past, beyond, r.iterations}) <= 16);
}

TEST_CASE_TEMPLATE("toi: a pair moving apart is separated at once and an overlapping pair is reported", T, float, double) {
  const sphere<T> a{T(0.5)};
  const box<T> b{vec3<T>::splat(T(0.5))};
  // Apart and parting: the bound is negative after one distance.
  auto r = time_of_impact(a, moving<T>({}, {-3, 0, 0}), b, moving<T>({2, 0, 0}, {3, 1, 0}));
  CHECK(r.state == toi_state::separated);
  CHECK(r.t == T(1));
  CHECK(r.iterations == 1);
  // Approaching but too slowly to close the 1 m gap in the step.
  r = time_of_impact(a, moving<T>({}, {T(0.9), 0, 0}), b, still<T>({2, 0, 0}));
  CHECK(r.state == toi_state::separated);
  CHECK(r.iterations == 1);
  // Overlapping at t = 0: nothing to advance, and no normal.
  r = time_of_impact(a, moving<T>({}, {1, 0, 0}), b, still<T>({T(0.9), 0, 0}));
  CHECK(r.state == toi_state::overlapping);
  CHECK(r.t == T(0));
  CHECK(r.normal == vec3<T>{});
  CHECK(r.iterations == 1);
  // Within the target at t = 0 but not overlapping: a hit at 0 with a normal.
  r = time_of_impact(a, moving<T>({}, {1, 0, 0}), b, still<T>({T(1.002), 0, 0}));
  CHECK(r.state == toi_state::hit);
  CHECK(r.t == T(0));
  CHECK(length(r.normal - vec3<T>::unit_x()) <= tolerance<T> * 10);
}

TEST_CASE_TEMPLATE("toi: out of iterations the answer is the last safe time", T, float, double) {
  const box<T> rod{{1, T(0.02), T(0.02)}}, cube{vec3<T>::splat(T(0.1))};
  toi_options<T> o;
  o.max_iterations = 3;
  const sweep<T> spin = moving<T>({}, {}, quat<T>::identity(), {0, 0, 2});
  const auto r = time_of_impact(rod, spin, cube, still<T>({0, T(0.6), 0}), o);
  CHECK(r.state == toi_state::failed);
  CHECK(r.iterations == 3);
  CHECK(r.t > T(0));
  // Safe: still at least the target apart there, and before the impact.
  const narrowphase::sweep_motion<T> m{spin};
  CHECK(gjk_distance(rod, m.at(r.t), cube, at<T>({0, T(0.6), 0})).distance >= o.target);
  CHECK(r.distance >= o.target);
}

TEST_CASE_TEMPLATE("toi: a sweep's pose is its start at 0 and its end at 1 and turns about its center", T, float, double) {
  const quat<T> q0 = quat<T>::from_axis_angle(normalize(vec3<T>{1, 2, 3}), T(0.4));
  const quat<T> q1 = quat<T>::from_axis_angle(normalize(vec3<T>{-1, 0, 2}), T(1.9));
  const sweep<T> s{at<T>({1, 2, 3}, q0), at<T>({4, 0, -1}, q1), {T(0.2), T(-0.1), T(0.3)}};
  const narrowphase::sweep_motion<T> m{s};
  CHECK(length(m.at(0).position - s.start.position) <= tolerance<T>);
  CHECK(length(m.at(1).position - s.end.position) <= tolerance<T> * 10);
  CHECK(angle_between(m.at(1).rotation, q1) <= tolerance<T> * 10);
  // The center (not the shape's origin) moves on a straight line.
  const vec3<T> c0 = apply(s.start, s.local_center), c1 = apply(s.end, s.local_center);
  CHECK(length(apply(m.at(T(0.3)), s.local_center) - lerp(c0, c1, T(0.3))) <= tolerance<T> * 10);
}

TEST_CASE_TEMPLATE("toi: head on far from the origin", T, float, double) {
  // At 1e4 m the float spacing is 1 mm, so the poses at t are good to
  // about that: 2 mm over a closing speed of 12 is 2e-4 in t.
  const vec3<T> far{T(1e4), T(-1e4), T(5e3)};
  const sphere<T> a{T(0.5)}, b{T(0.3)};
  toi_options<T> o;
  o.tolerance = sizeof(T) == 4 ? T(2e-3) : o.tolerance;  // above the rounding of the poses
  const auto r = time_of_impact(a, moving<T>(far, {10, 0, 0}), b, moving<T>(far + vec3<T>{5, 0, 0}, {-2, 0, 0}), o);
  REQUIRE(r.state == toi_state::hit);
  CHECK(std::abs(r.t - (T(4.2) - o.target) / T(12)) <= (sizeof(T) == 4 ? T(2e-4) : T(1e-9)));
}

TEST_CASE_TEMPLATE("toi: random sweeps never pass a contact before the time found", T, float, double) {
  // Each random pair (boxes, capsules, spheres, a hull) moves up to 4 m and
  // turns up to 3 rad. Sampled at 200 times over [0, t], the distance never
  // drops below the target (less 10 times the rounding of GJK and of the
  // poses); at a hit it is within the tolerance of the target; when
  // separated it stays above the target over the whole step; out of
  // iterations, the time given is still safe. Measured (float and double
  // alike): 241 hits, 318 separated, 41 overlapping, none failed; at most
  // 52 iterations, 6.6 on average; the smallest sampled distance was
  // 1.8e-4 m above the target.
  lcg32 random{2718};
  std::vector<vec3<T>> corners = test::box_corners<T>({T(0.3), T(0.5), T(0.2)});
  const auto hull = convex_hull<T>::from_points(corners);
  const toi_options<T> o;
  int pairs = 0, hits = 0, separated = 0, failed = 0, overlapping = 0, most = 0;
  long total = 0;
  T lowest = T(1e9);
  const auto in = [&](T r) { return vec3<T>{random.uniform<T>(-r, r), random.uniform<T>(-r, r), random.uniform<T>(-r, r)}; };
  const auto check = [&](const auto& a, const auto& b) {
    const sweep<T> sa{at<T>(in(2), random_rotation<T>(random)), {}, in(T(0.1))};
    const sweep<T> sb{at<T>(in(2), random_rotation<T>(random)), {}, in(T(0.1))};
    sweep<T> ma = sa, mb = sb;
    ma.end = at<T>(sa.start.position + in(2), integrate(sa.start.rotation, in(T(1.7)), T(1)));
    // Every other pair, B ends near where A ends, so that most of those meet.
    const vec3<T> b_end = (++pairs % 2 == 0) ? ma.end.position + in(1) : sb.start.position + in(2);
    mb.end = at<T>(b_end, integrate(sb.start.rotation, in(T(1.7)), T(1)));
    const auto r = time_of_impact(a, ma, b, mb, o);
    most = std::max(most, r.iterations);
    total += r.iterations;
    switch (r.state) {
      case toi_state::hit: ++hits; break;
      case toi_state::separated: ++separated; break;
      case toi_state::failed: ++failed; break;
      case toi_state::overlapping: ++overlapping; return;
    }
    const narrowphase::sweep_motion<T> pa{ma}, pb{mb};
    const T until = r.state == toi_state::separated ? T(1) : r.t;
    for (int k = 0; k <= 200; ++k) {
      const T t = until * T(k) / T(200);
      const auto g = gjk_distance(a, pa.at(t), b, pb.at(t));
      const T d = g.overlapping ? T(0) : g.distance;
      lowest = std::min(lowest, d - o.target);
      CHECK(d >= o.target - tolerance<T> * 10);
    }
    if (r.state == toi_state::hit && r.t > T(0)) CHECK(r.distance < o.target + o.tolerance);
  };
  for (int k = 0; k < 150; ++k) {
    const box<T> b{{random.uniform<T>(T(0.05), T(1)), random.uniform<T>(T(0.05), T(1)), random.uniform<T>(T(0.05), T(1))}};
    const capsule<T> c{random.uniform<T>(T(0.05), T(0.5)), random.uniform<T>(T(0), T(1))};
    const sphere<T> s{random.uniform<T>(T(0.05), T(1))};
    check(b, c);
    check(s, b);
    check(hull, c);
    check(b, hull);
  }
  MESSAGE("hits " << hits << " separated " << separated << " overlapping " << overlapping << " failed " << failed
                  << "; iterations: most " << most << ", mean " << double(total) / 600 << "; least sampled margin over the target "
                  << lowest);
  CHECK(hits > 150);
  CHECK(separated > 150);
  // A near miss (the gap's minimum a little above the target) makes
  // conservative advancement crawl: the bound stays large while the true
  // approach slows to nothing. Those few run out of iterations, at a time
  // still safe (checked above): 0 of these 600, 1 of 4 000 in a longer
  // run; one is allowed here, for a compiler that rounds differently.
  CHECK(failed <= 1);
}

}  // namespace narrowphase_time_of_impact_tests
