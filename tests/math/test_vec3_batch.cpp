// vec3_batch: lane i of every operation equals the vec3 operation on lane i.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "impulse/math/vec3_batch.hpp"

namespace math_vec3_batch_tests {

namespace {

template <class T>
impulse::vec3<T> sample(int i) {
  return {T(i) - T(2.5), T(0.5) * T(i * i) - T(3), T(7) - T(1.25) * T(i)};
}

template <class T, int W>
void check_lanes() {
  using vb = impulse::vec3_batch<T, W>;
  alignas(64) T xs[W], ys[W], zs[W], out_x[W], out_y[W], out_z[W];
  for (int i = 0; i < W; ++i) {
    const impulse::vec3<T> a = sample<T>(i);
    xs[i] = a.x, ys[i] = a.y, zs[i] = a.z;
  }
  const vb a = vb::load(xs, ys, zs);
  const impulse::vec3<T> c{T(0.25), T(-1.5), T(2)};
  const vb b = vb::broadcast(c);
  const vb combined = (a + b) * T(2) - (-a) * a.x;  // last term scales lane i by a_i.x
  combined.store(out_x, out_y, out_z);
  const auto d = impulse::dot(a, b);
  const auto l = impulse::length(a);
  // length is a sqrt of the same dot product: one correctly rounded result.
  const T length_rounding = 2 * std::numeric_limits<T>::epsilon();
  for (int i = 0; i < W; ++i) {
    const impulse::vec3<T> ai = sample<T>(i);
    const impulse::vec3<T> expected = (ai + c) * T(2) - (-ai) * ai.x;
    CAPTURE(i);
    CHECK(a.lane(i) == ai);
    CHECK(b.lane(i) == c);
    CHECK(out_x[i] == doctest::Approx(expected.x));  // FMA contraction may differ by an ulp
    CHECK(out_y[i] == doctest::Approx(expected.y));
    CHECK(out_z[i] == doctest::Approx(expected.z));
    CHECK(d[i] == doctest::Approx(impulse::dot(ai, c)));
    CHECK(std::abs(l[i] - impulse::length(ai)) <= length_rounding * impulse::length(ai));
  }
}

}  // namespace

TEST_CASE_TEMPLATE("vec3_batch operations equal vec3 operations lane by lane", T, float, double) {
  check_lanes<T, 1>();
  check_lanes<T, impulse::native_width<T>>();
  check_lanes<T, 64 / int(sizeof(T))>();
}

}  // namespace math_vec3_batch_tests
