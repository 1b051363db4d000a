// batch<T, W>: every lane of every operation equals the scalar operation on
// that lane, for every width (wider than the target too, where the compiler
// splits the vector) and for the scalar fallback W = 1. Arithmetic and
// square root are correctly rounded in IEEE 754, so "equal" here is exact.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "impulse/core/batch.hpp"

namespace core_batch_tests {

namespace {

template <class B>
struct lane_data {
  using T = typename B::scalar;
  alignas(64) T a[B::width];
  alignas(64) T b[B::width];
  lane_data() {
    std::uint32_t state = 12345;  // LCG: deterministic, no <random>
    for (int i = 0; i < B::width; ++i) {
      state = state * 1664525u + 1013904223u;
      a[i] = T(int(state >> 20) - 2048) / T(64);  // in [-32, 32), some negative
      state = state * 1664525u + 1013904223u;
      b[i] = T(int(state >> 20)) / T(128) + T(0.5);  // in [0.5, 32.5), never zero
    }
  }
};

}  // namespace

#define IMPULSE_BATCH_TYPES                                                              \
  impulse::batch<float, 1>, impulse::batch<float, 4>, impulse::batch<float, 8>,         \
      impulse::batch<float, 16>, impulse::batch<double, 1>, impulse::batch<double, 2>,  \
      impulse::batch<double, 4>, impulse::batch<double, 8>

TEST_CASE_TEMPLATE("batch arithmetic equals scalar arithmetic lane by lane", B, IMPULSE_BATCH_TYPES) {
  using T = typename B::scalar;
  const lane_data<B> d;
  const B a = B::load(d.a), b = B::load(d.b);
  const T s = T(1.75);
  const B sum = a + b, diff = a - b, prod = a * b, quot = a / b, neg = -a;
  const B affine = a * s + T(3), rev = T(2) - a / s;
  for (int i = 0; i < B::width; ++i) {
    CHECK(sum[i] == d.a[i] + d.b[i]);
    CHECK(diff[i] == d.a[i] - d.b[i]);
    CHECK(prod[i] == d.a[i] * d.b[i]);
    CHECK(quot[i] == d.a[i] / d.b[i]);
    CHECK(neg[i] == -d.a[i]);
    CHECK(affine[i] == doctest::Approx(d.a[i] * s + T(3)));  // may be contracted to an FMA
    CHECK(rev[i] == doctest::Approx(T(2) - d.a[i] / s));
  }
}

TEST_CASE_TEMPLATE("batch sqrt is the correctly rounded square root in every lane", B, IMPULSE_BATCH_TYPES) {
  const lane_data<B> d;
  const B r = impulse::sqrt(B::load(d.b));
  for (int i = 0; i < B::width; ++i) CHECK(r[i] == std::sqrt(d.b[i]));
}

TEST_CASE_TEMPLATE("batch rsqrt is within the estimate's bound squared and the step's roundings, over 2^-100 to 2^100", B,
                   IMPULSE_BATCH_TYPES) {
  using T = typename B::scalar;
  // Float vector lanes refine the hardware estimate, relative error at most
  // e = 1.5·2^-12 (rsqrtps) or 2^-14 (rsqrt14ps) by the instruction set's
  // definition, by one Newton step: (3/2)e² + e³/2, and its roundings, at
  // most 3·2^-24 (the two in a·y² count half): 3.8e-7 for rsqrtps. The estimate differs between
  // processors: the worst found was 1.65e-7 on an AMD Zen 4, and 2.41e-7
  // (2.32e-7 with FMA) on an Intel Ice Lake. W = 1 and double divide by
  // the correctly rounded root, two roundings.
  const double estimate = impulse::detail::rsqrt_estimate_bits<T, B::width>() == 14 ? std::ldexp(1.0, -14)
                                                                                   : 1.5 * std::ldexp(1.0, -12);
  const double bound = impulse::detail::has_rsqrt_estimate<T, B::width>()
                           ? 1.5 * estimate * estimate + 0.5 * estimate * estimate * estimate + 3 * std::ldexp(1.0, -24)
                           : 2 * double(std::numeric_limits<T>::epsilon());
  double worst = 0;
  for (int e = -100; e <= 100; ++e)
    for (int k = 0; k < 256; k += 1) {
      alignas(64) T x[B::width];
      for (int i = 0; i < B::width; ++i) x[i] = std::ldexp(T(1) + T(k * B::width + i) / T(256 * B::width), e);
      const B y = impulse::rsqrt(B::load(x));
      for (int i = 0; i < B::width; ++i) {
        const double exact = 1 / std::sqrt(double(x[i]));
        worst = std::fmax(worst, std::abs(double(y[i]) - exact) / exact);
      }
    }
  CHECK(worst <= bound);
}

TEST_CASE_TEMPLATE("any all and none read every lane of a mask", B, IMPULSE_BATCH_TYPES) {
  using T = typename B::scalar;
  for (int set = 0; set < B::width; ++set) {
    B a = B::broadcast(T(0));
    a.set(set, T(1));
    const auto one = a > B::broadcast(T(0));
    CHECK(impulse::any(one));
    CHECK(!impulse::none(one));
    CHECK(impulse::all(one) == (B::width == 1));
    CHECK(impulse::all(!one) == false);
    CHECK(impulse::none(a > B::broadcast(T(2))));
    CHECK(impulse::all(a < B::broadcast(T(2))));
  }
}

TEST_CASE_TEMPLATE("batch select takes each lane from the side its mask names", B, IMPULSE_BATCH_TYPES) {
  // The masked path that clang 14 miscompiles with <experimental/simd> on
  // AVX-512 (docs/architecture.md, toolchain facts): run it under both
  // compilers at -march=native.
  using T = typename B::scalar;
  const lane_data<B> d;
  const B a = B::load(d.a), b = B::load(d.b);
  const B picked = impulse::select(a < B::broadcast(T(0)), b, a);
  const B low = impulse::min(a, b), high = impulse::max(a, b), magnitude = impulse::abs(a);
  int negatives = 0;
  for (int i = 0; i < B::width; ++i) {
    CHECK(picked[i] == (d.a[i] < 0 ? d.b[i] : d.a[i]));
    CHECK(low[i] == (d.a[i] < d.b[i] ? d.a[i] : d.b[i]));
    CHECK(high[i] == (d.a[i] > d.b[i] ? d.a[i] : d.b[i]));
    CHECK(magnitude[i] == std::abs(d.a[i]));
    negatives += d.a[i] < 0;
  }
  const auto negative = a < B::broadcast(T(0));
  CHECK(impulse::any(negative) == (negatives > 0));
  CHECK(impulse::all(negative) == (negatives == B::width));
  CHECK(impulse::none(negative) == (negatives == 0));
  CHECK(impulse::all(negative | !negative));
  CHECK(impulse::none(negative & !negative));
}

TEST_CASE_TEMPLATE("batch comparisons agree with scalar comparisons", B, IMPULSE_BATCH_TYPES) {
  const lane_data<B> d;
  const B a = B::load(d.a), b = B::load(d.b);
  for (int i = 0; i < B::width; ++i) {
    CHECK((a < b)[i] == (d.a[i] < d.b[i]));
    CHECK((a <= b)[i] == (d.a[i] <= d.b[i]));
    CHECK((a > b)[i] == (d.a[i] > d.b[i]));
    CHECK((a >= b)[i] == (d.a[i] >= d.b[i]));
    CHECK((a == a)[i]);
    CHECK_FALSE((a != a)[i]);
  }
}

TEST_CASE_TEMPLATE("batch load store broadcast and gather move the right values", B, IMPULSE_BATCH_TYPES) {
  using T = typename B::scalar;
  const lane_data<B> d;
  alignas(64) T out[B::width];
  B::load(d.a).store(out);
  const B seven = B::broadcast(T(7));
  int index[B::width];
  for (int i = 0; i < B::width; ++i) index[i] = B::width - 1 - i;  // reversed
  const B gathered = B::gather(d.a, index);
  for (int i = 0; i < B::width; ++i) {
    CHECK(out[i] == d.a[i]);
    CHECK(seven[i] == T(7));
    CHECK(gathered[i] == d.a[B::width - 1 - i]);
  }
}

TEST_CASE("native_width fills the target's widest registers") {
  static_assert(impulse::native_width<float> == 2 * impulse::native_width<double> ||
                impulse::native_width<float> == 1);
#if defined(__AVX512F__)
  CHECK(impulse::native_width<float> == 16);
#elif defined(__AVX__)
  CHECK(impulse::native_width<float> == 8);
#elif defined(__SSE2__)
  CHECK(impulse::native_width<float> == 4);
#endif
  CHECK(impulse::batch<float>::width == impulse::native_width<float>);
}

}  // namespace core_batch_tests
