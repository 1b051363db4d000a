// Tests of impulse/math/trigonometry.hpp: sin, cos, atan2, acos and cbrt
// from IEEE-754's correctly rounded operations alone, against the C
// library's to a few ulp, at their special values exactly, and at recorded
// bits that every machine must reproduce.
#include <impulse/math/trigonometry.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "tolerances.hpp"

namespace math_trigonometry_tests {

using namespace impulse;

namespace {

/// How many doubles lie between a and b (0 when equal): the distance in ulp.
std::uint64_t ulps_apart(double a, double b) {
  if (a == b) return 0;
  auto ordered = [](double v) {
    std::int64_t i;
    std::memcpy(&i, &v, sizeof i);
    return i < 0 ? std::numeric_limits<std::int64_t>::min() - i : i;
  };
  const std::int64_t ia = ordered(a), ib = ordered(b);
  return ia > ib ? std::uint64_t(ia) - std::uint64_t(ib) : std::uint64_t(ib) - std::uint64_t(ia);
}

std::uint64_t bits(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

/// A 64-bit LCG's top 53 bits as a double in [0, 1): a fixed sample.
struct uniform {
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  double operator()(double lo, double hi) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * double(state >> 11) * 0x1p-53;
  }
};

/// The C library is not exact either (glibc's sin, cos, atan2 and cbrt are
/// within 1 or 2 ulp); ours are within 2 ulp. Together: 4.
constexpr std::uint64_t library_ulps = 4;

}  // namespace

TEST_CASE("portable sin and cos are within 4 ulp of the C library's from 1e-8 to 1e5 rad") {
  uniform u;
  std::uint64_t worst_sin = 0, worst_cos = 0;
  for (int i = 0; i < 200000; ++i) {
    const double scale = i < 50000 ? 1e-8 : i < 100000 ? 1.0 : i < 150000 ? 10.0 : 1e5;
    const double x = u(-scale, scale);
    const sine_cosine<double> r = portable_sin_cos(x);
    // Where the result is near zero the comparison is absolute: the
    // reduction's error is an ulp of the argument's size, not the result's.
    if (std::abs(std::sin(x)) > 1e-3) worst_sin = std::max(worst_sin, ulps_apart(r.sin, std::sin(x)));
    else CHECK(std::abs(r.sin - std::sin(x)) <= 4e-16 * std::max(1.0, std::abs(x)));
    if (std::abs(std::cos(x)) > 1e-3) worst_cos = std::max(worst_cos, ulps_apart(r.cos, std::cos(x)));
    else CHECK(std::abs(r.cos - std::cos(x)) <= 4e-16 * std::max(1.0, std::abs(x)));
  }
  CHECK(worst_sin <= library_ulps);
  CHECK(worst_cos <= library_ulps);
  MESSAGE("largest distance from the C library: sin ", worst_sin, " ulp, cos ", worst_cos, " ulp");
}

TEST_CASE("portable sin and cos keep sin² + cos² = 1 and exact values at 0 and ±π/2") {
  uniform u;
  for (int i = 0; i < 10000; ++i) {
    const sine_cosine<double> r = portable_sin_cos(u(-100.0, 100.0));
    CHECK(std::abs(r.sin * r.sin + r.cos * r.cos - 1.0) <= 4 * test::epsilon<double>);
  }
  CHECK(bits(portable_sin(0.0)) == bits(0.0));
  CHECK(bits(portable_sin(-0.0)) == bits(-0.0));
  CHECK(portable_cos(0.0) == 1.0);
  CHECK(portable_sin(0x1.921fb54442d18p+0) == 1.0);  // the double nearest π/2
  CHECK(std::abs(portable_cos(0x1.921fb54442d18p+0)) < 1e-16);
  CHECK(std::isnan(portable_sin(std::numeric_limits<double>::infinity())));
  CHECK(std::isnan(portable_cos(std::numeric_limits<double>::quiet_NaN())));
  // Past 2^19 rad the argument is first reduced by the rounded 2π: still
  // finite and on the unit circle, far from the truth as any such angle is.
  const sine_cosine<double> far = portable_sin_cos(1e12);
  CHECK(std::abs(far.sin * far.sin + far.cos * far.cos - 1.0) <= 4 * test::epsilon<double>);
}

TEST_CASE("portable atan2 is within 4 ulp of the C library's in every quadrant and equals it at zeros and infinities") {
  uniform u;
  std::uint64_t worst = 0;
  for (int i = 0; i < 200000; ++i) {
    const double scale = i % 3 == 0 ? 1e-6 : i % 3 == 1 ? 1.0 : 1e6;
    const double y = u(-scale, scale), x = u(-1.0, 1.0) * (i % 2 ? 1.0 : scale);
    worst = std::max(worst, ulps_apart(portable_atan2(y, x), std::atan2(y, x)));
  }
  CHECK(worst <= library_ulps);
  MESSAGE("largest distance from the C library: ", worst, " ulp");
  const double inf = std::numeric_limits<double>::infinity();
  const double special[] = {0.0, -0.0, 1.0, -1.0, inf, -inf};
  for (double y : special)
    for (double x : special) {
      CAPTURE(y);
      CAPTURE(x);
      CHECK(bits(portable_atan2(y, x)) == bits(std::atan2(y, x)));
    }
  CHECK(std::isnan(portable_atan2(std::numeric_limits<double>::quiet_NaN(), 1.0)));
}

TEST_CASE("portable acos is within 4 ulp of the C library's on [-1, 1] and NaN outside") {
  uniform u;
  std::uint64_t worst = 0;
  for (int i = 0; i < 100000; ++i) {
    // Half the sample near ±1, where acos is steep.
    const double x = i % 2 ? u(-1.0, 1.0) : std::copysign(1.0 - u(0.0, 1e-6), u(-1.0, 1.0));
    worst = std::max(worst, ulps_apart(portable_acos(x), std::acos(x)));
  }
  CHECK(worst <= library_ulps);
  CHECK(portable_acos(1.0) == 0.0);
  CHECK(portable_acos(-1.0) == 0x1.921fb54442d18p+1);
  CHECK(std::isnan(portable_acos(1.0 + 1e-15)));
}

TEST_CASE("portable cbrt is within 4 ulp of the C library's from 1e-300 to 1e300") {
  uniform u;
  std::uint64_t worst = 0;
  for (int i = 0; i < 20000; ++i) {
    const double x = std::copysign(std::pow(10.0, u(-300.0, 300.0)), u(-1.0, 1.0));
    worst = std::max(worst, ulps_apart(portable_cbrt(x), std::cbrt(x)));
  }
  CHECK(worst <= library_ulps);  // Newton's last step leaves up to 2 ulp; glibc's cbrt is not exact either
  CHECK(portable_cbrt(27.0) == 3.0);
  CHECK(portable_cbrt(-8.0) == -2.0);
}

TEST_CASE("float results are within 1 ulp of the C library's double results rounded to float") {
  // Computed in double and rounded once: atan2 from the double path, sin and
  // cos from shorter series whose error (7e-12) is far below float's ulp.
  uniform u;
  auto float_ulps = [](float a, float b) { return ulps_apart(double(a), double(b)) >> 29; };  // 29 = 52 − 23
  std::uint64_t worst = 0;
  for (int i = 0; i < 100000; ++i) {
    const float x = float(u(-10.0, 10.0)), y = float(u(-10.0, 10.0));
    worst = std::max(worst, float_ulps(portable_sin(x), float(std::sin(double(x)))));
    worst = std::max(worst, float_ulps(portable_cos(x), float(std::cos(double(x)))));
    worst = std::max(worst, float_ulps(portable_atan2(y, x), float(std::atan2(double(y), double(x)))));
  }
  CHECK(worst <= 1);
  CHECK(portable_atan2(0.3f, -0.7f) == float(portable_atan2(0.3, -0.7)));
}

TEST_CASE("portable trigonometry gives the recorded bits: the same on every IEEE-754 machine") {
  // Recorded on x86-64 (g++ and clang, SSE2 and AVX2). A machine or
  // compiler that gives other bits here breaks lockstep determinism
  // (docs/world.md): most likely it fused a multiply and an add.
  // Volatile, so that the compiler cannot fold the calls at compile time.
  volatile double one = 1.0, hundred = 100.0, y = 0.3, x = -0.7, quarter = 0.25;
  CHECK(bits(portable_sin(one)) == 0x3feaed548f090ceeull);
  CHECK(bits(portable_cos(one)) == 0x3fe14a280fb5068cull);
  CHECK(bits(portable_sin(hundred)) == 0xbfe03425b78c4db8ull);
  CHECK(bits(portable_atan2(y, x)) == 0x4005e4c36ca0118aull);
  CHECK(bits(portable_acos(quarter)) == 0x3ff51700e0c14b25ull);
  volatile float one_f = 1.0f;
  const float sin_one = portable_sin(float(one_f));
  std::uint32_t sin_one_bits;
  std::memcpy(&sin_one_bits, &sin_one, sizeof sin_one_bits);
  CHECK(sin_one_bits == 0x3f576aa4u);
}

}  // namespace math_trigonometry_tests
