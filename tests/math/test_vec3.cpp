// Tests of impulse/math/vec3.hpp. Inputs made of small integers keep every
// sum and product exact, so those facts are checked with ==; the rest carry
// a named tolerance.
#include <impulse/math/vec3.hpp>

#include <limits>
#include <vector>

#include "tolerances.hpp"

namespace math_vec3_tests {

using namespace impulse;
using namespace impulse::test;

TEST_CASE_TEMPLATE("the factories build the zero vector and the unit axes and a splat", T, float, double) {
  CHECK(vec3<T>{} == vec3<T>{0, 0, 0});
  CHECK(vec3<T>::zero() == vec3<T>{0, 0, 0});
  CHECK(vec3<T>::unit_x() == vec3<T>{1, 0, 0});
  CHECK(vec3<T>::unit_y() == vec3<T>{0, 1, 0});
  CHECK(vec3<T>::unit_z() == vec3<T>{0, 0, 1});
  CHECK(vec3<T>::splat(T(2.5)) == vec3<T>{T(2.5), T(2.5), T(2.5)});
}

TEST_CASE_TEMPLATE("indexing reads and writes x then y then z", T, float, double) {
  vec3<T> v{1, 2, 3};
  const vec3<T>& c = v;
  CHECK(c[0] == 1);
  CHECK(c[1] == 2);
  CHECK(c[2] == 3);
  v[0] = 4;
  v[1] = 5;
  v[2] = 6;
  CHECK(v == vec3<T>{4, 5, 6});
}

TEST_CASE_TEMPLATE("negation and addition and subtraction act componentwise", T, float, double) {
  const vec3<T> a{1, -2, 3};
  const vec3<T> b{4, 5, -6};
  CHECK(-a == vec3<T>{-1, 2, -3});
  CHECK(a + b == vec3<T>{5, 3, -3});
  CHECK(a - b == vec3<T>{-3, -7, 9});
}

TEST_CASE_TEMPLATE("scaling from either side and dividing by a scalar act componentwise", T, float, double) {
  const vec3<T> a{1, -2, 3};
  CHECK(a * T(2) == vec3<T>{2, -4, 6});
  CHECK(T(2) * a == vec3<T>{2, -4, 6});
  CHECK(a / T(4) == vec3<T>{T(0.25), T(-0.5), T(0.75)});
}

TEST_CASE_TEMPLATE("vector compound assignments agree with their binary operators", T, float, double) {
  const vec3<T> a{1, -2, 3};
  const vec3<T> b{4, 5, -6};
  vec3<T> v = a;
  CHECK((v += b) == a + b);
  v = a;
  CHECK((v -= b) == a - b);
  v = a;
  CHECK((v *= T(3)) == a * T(3));
  v = a;
  CHECK((v /= T(4)) == a / T(4));
}

TEST_CASE_TEMPLATE("mul and div are the componentwise product and quotient", T, float, double) {
  const vec3<T> a{1, -2, 3};
  const vec3<T> b{4, 8, -2};
  CHECK(mul(a, b) == vec3<T>{4, -16, -6});
  CHECK(div(a, b) == vec3<T>{T(0.25), T(-0.25), T(-1.5)});
}

TEST_CASE_TEMPLATE("dot product sums the componentwise products", T, float, double) {
  CHECK(dot(vec3<T>{1, 2, 3}, vec3<T>{4, -5, 6}) == 12);
  CHECK(dot(vec3<T>::unit_x(), vec3<T>::unit_y()) == 0);
}

TEST_CASE_TEMPLATE("cross product of the axes follows the right-hand rule", T, float, double) {
  CHECK(cross(vec3<T>::unit_x(), vec3<T>::unit_y()) == vec3<T>::unit_z());
  CHECK(cross(vec3<T>::unit_y(), vec3<T>::unit_z()) == vec3<T>::unit_x());
  CHECK(cross(vec3<T>::unit_z(), vec3<T>::unit_x()) == vec3<T>::unit_y());
  CHECK(cross(vec3<T>{1, 2, 3}, vec3<T>{4, 5, 6}) == vec3<T>{-3, 6, -3});
}

TEST_CASE_TEMPLATE("cross product is anticommutative and vanishes for parallel factors", T, float, double) {
  const vec3<T> a{1, -2, 3};
  const vec3<T> b{-4, 5, 7};
  CHECK(cross(a, b) == -cross(b, a));
  CHECK(cross(a, a * T(-3)) == vec3<T>::zero());
}

TEST_CASE_TEMPLATE("cross product is perpendicular to both factors", T, float, double) {
  // dot(a × b, a) for unit a and b: each component of a × b is a difference
  // of two rounded products (1.5 ulp), and the dot rounds three products and
  // two sums, all of size at most 1.
  constexpr T perpendicular = 4 * epsilon<T>;
  lcg rng;
  T worst = 0;
  for (int i = 0; i < 1000; ++i) {
    const vec3<T> a = rng.unit_vector<T>();
    const vec3<T> b = rng.unit_vector<T>();
    const vec3<T> c = cross(a, b);
    worst = std::fmax(worst, std::fmax(std::abs(dot(c, a)), std::abs(dot(c, b))));
  }
  CHECK(worst <= perpendicular);
}

TEST_CASE_TEMPLATE("length of a 3 4 12 vector is 13", T, float, double) {
  const vec3<T> v{3, 4, 12};
  CHECK(length_squared(v) == 169);
  CHECK(length(v) == 13);
  CHECK(distance(vec3<T>{1, 1, 1}, vec3<T>{4, 5, 13}) == 13);
  CHECK(distance(v, v) == 0);
}

TEST_CASE_TEMPLATE("normalize gives a unit vector along its input", T, float, double) {
  // The direction of a·(1/|a|) is off by one rounding of each component.
  constexpr T direction = 2 * epsilon<T>;
  lcg rng;
  T worst_length = 0;
  T worst_direction = 0;
  int reversed = 0;
  for (int i = 0; i < 1000; ++i) {
    const vec3<T> a = rng.unit_vector<T>() * rng.in<T>(1e-6, 1e6);
    const vec3<T> n = normalize(a);
    worst_length = std::fmax(worst_length, std::abs(length(n) - 1));
    worst_direction = std::fmax(worst_direction, length(cross(n, a)) / length(a));
    if (!(dot(n, a) > 0)) ++reversed;
  }
  CHECK(worst_length <= normalized_length<T>);
  CHECK(worst_direction <= direction);
  CHECK(reversed == 0);
}

TEST_CASE_TEMPLATE("normalize_or normalizes a vector that has a direction", T, float, double) {
  const vec3<T> a{3, 4, 12};
  CHECK(normalize_or(a, vec3<T>::unit_z()) == normalize(a));
}

TEST_CASE_TEMPLATE("normalize_or returns the fallback for a zero or tiny or NaN vector", T, float, double) {
  const vec3<T> fallback = vec3<T>::unit_y();
  const T tiny = std::sqrt(scalar_traits<T>::zero_length_squared) / 10;
  const T nan = std::numeric_limits<T>::quiet_NaN();
  CHECK(normalize_or(vec3<T>::zero(), fallback) == fallback);
  CHECK(normalize_or(vec3<T>{tiny, 0, 0}, fallback) == fallback);
  CHECK(normalize_or(vec3<T>{nan, 1, 0}, fallback) == fallback);
  CHECK(normalize_or(vec3<T>::splat(nan), fallback) == fallback);
}

TEST_CASE_TEMPLATE("normalize_or gives the direction of a vector whose squared length overflows", T, float, double) {
  // |a|² overflows to infinity, yet a has a direction: (3, 4, 0)/5.
  const T huge = std::numeric_limits<T>::max() / 8;
  const vec3<T> a{3 * (huge / 4), 4 * (huge / 4), 0};
  const vec3<T> n = normalize_or(a, vec3<T>::unit_z());
  CHECK(n.x == doctest::Approx(T(0.6)).epsilon(normalized_length<T>));
  CHECK(n.y == doctest::Approx(T(0.8)).epsilon(normalized_length<T>));
  CHECK(n.z == T(0));
}

TEST_CASE_TEMPLATE("normalize_or returns the fallback for an infinite vector", T, float, double) {
  const T inf = std::numeric_limits<T>::infinity();
  CHECK(normalize_or(vec3<T>{inf, 1, 0}, vec3<T>::unit_y()) == vec3<T>::unit_y());
  CHECK(normalize_or(vec3<T>{-inf, inf, 0}, vec3<T>::unit_y()) == vec3<T>::unit_y());
}

TEST_CASE_TEMPLATE("is_normalized accepts lengths within the unit tolerance and no further", T, float, double) {
  const T tolerance = scalar_traits<T>::unit_tolerance;
  CHECK(is_normalized(vec3<T>::unit_x()));
  CHECK(is_normalized(normalize(vec3<T>{1, 2, 3})));
  CHECK(is_normalized(vec3<T>{0, T(1) + T(0.9) * tolerance, 0}));
  CHECK(is_normalized(vec3<T>{0, 0, T(1) - T(0.9) * tolerance}));
  CHECK_FALSE(is_normalized(vec3<T>{0, T(1) + T(1.1) * tolerance, 0}));
  CHECK_FALSE(is_normalized(vec3<T>{0, 0, T(1) - T(1.1) * tolerance}));
  CHECK_FALSE(is_normalized(vec3<T>::zero()));
  CHECK_FALSE(is_normalized(vec3<T>{1, 1, 0}));
}

TEST_CASE_TEMPLATE("a vector is not finite when any component is NaN or infinite", T, float, double) {
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const T inf = std::numeric_limits<T>::infinity();
  CHECK(is_finite(vec3<T>{1, -2, std::numeric_limits<T>::max()}));
  for (int i = 0; i < 3; ++i) {
    vec3<T> v{1, 2, 3};
    v[i] = nan;
    CHECK_FALSE(is_finite(v));
    v[i] = -inf;
    CHECK_FALSE(is_finite(v));
  }
}

TEST_CASE_TEMPLATE("min and max pick the smaller and the larger of each component", T, float, double) {
  const vec3<T> a{1, 5, -3};
  const vec3<T> b{2, -4, -3};
  CHECK(min(a, b) == vec3<T>{1, -4, -3});
  CHECK(max(a, b) == vec3<T>{2, 5, -3});
}

TEST_CASE_TEMPLATE("abs makes every component non-negative", T, float, double) {
  CHECK(abs(vec3<T>{-1, 2, -3}) == vec3<T>{1, 2, 3});
}

TEST_CASE_TEMPLATE("min_component and max_component find the extreme wherever it sits", T, float, double) {
  const vec3<T> orders[] = {{1, 2, 3}, {1, 3, 2}, {2, 1, 3}, {2, 3, 1}, {3, 1, 2}, {3, 2, 1}};
  for (const vec3<T>& v : orders) {
    CHECK(min_component(v) == 1);
    CHECK(max_component(v) == 3);
  }
  CHECK(min_component(vec3<T>{2, 2, 2}) == 2);
  CHECK(max_component(vec3<T>{-1, 4, 4}) == 4);
}

TEST_CASE_TEMPLATE("lerp returns its endpoints exactly and the midpoint halfway", T, float, double) {
  const vec3<T> a{T(0.1), T(-7.3), T(1e3)};
  const vec3<T> b{T(2.9), T(0.7), T(-1e-3)};
  CHECK(lerp(a, b, T(0)) == a);
  CHECK(lerp(a, b, T(1)) == b);
  CHECK(lerp(vec3<T>{0, 2, -4}, vec3<T>{2, 4, 4}, T(0.5)) == vec3<T>{1, 3, 0});
}

TEST_CASE_TEMPLATE("any_perpendicular is a unit vector perpendicular to its input", T, float, double) {
  // n × axis is exact (each component is ± a component of n), so only the
  // scaling by 1/|n × axis| (half an ulp per component) and the dot product's
  // own rounding (1.5 ulp of values near 0) make dot(p, n) nonzero.
  constexpr T perpendicular = 2 * epsilon<T>;
  const T r = T(1) / std::sqrt(T(3));
  std::vector<vec3<T>> directions = {
      vec3<T>::unit_x(), vec3<T>::unit_y(), vec3<T>::unit_z(),    -vec3<T>::unit_x(),
      -vec3<T>::unit_y(), -vec3<T>::unit_z(), vec3<T>::splat(r),  vec3<T>{r, -r, r},
      normalize(vec3<T>{1, 0, 1}), normalize(vec3<T>{1, 0, -1}),  normalize(vec3<T>{1, T(1e-3), 0}),
  };
  lcg rng;
  for (int i = 0; i < 1000; ++i) directions.push_back(rng.unit_vector<T>());
  T worst_length = 0;
  T worst_dot = 0;
  for (const vec3<T>& n : directions) {
    const vec3<T> p = any_perpendicular(n);
    worst_length = std::fmax(worst_length, std::abs(length(p) - 1));
    worst_dot = std::fmax(worst_dot, std::abs(dot(p, n)));
  }
  CHECK(worst_length <= normalized_length<T>);
  CHECK(worst_dot <= perpendicular);
}

}  // namespace math_vec3_tests
