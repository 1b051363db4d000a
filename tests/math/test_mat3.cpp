// Tests of impulse/math/mat3.hpp. Integer entries keep products exact, so
// the algebra is checked with ==; inversion carries a named tolerance.
#include <impulse/math/mat3.hpp>

#include <limits>
#include <optional>

#include "tolerances.hpp"

namespace math_mat3_tests {

using namespace impulse;
using namespace impulse::test;

namespace {

/// A general matrix with condition number 2.3 and determinant 263.
template <class T>
mat3<T> general() {
  return mat3<T>::from_rows({4, -2, 1}, {3, 6, -4}, {2, 1, 8});
}

template <class T>
mat3<T> other() {
  return mat3<T>::from_rows({1, 0, -2}, {3, -1, 1}, {0, 2, 5});
}

/// m·m⁻¹ and m⁻¹·m differ from I by the rounding of each inverse entry (a
/// cross product, then a multiply by 1/det) carried through a three-term
/// sum: a few roundings of size 1, which a condition number of 2.3 barely
/// amplifies.
template <class T>
inline constexpr T inverse_rounding = 4 * epsilon<T>;

}  // namespace

TEST_CASE_TEMPLATE("identity and zero and diagonal have the expected entries", T, float, double) {
  const mat3<T> i = mat3<T>::identity();
  const mat3<T> d = mat3<T>::diagonal({2, 3, 4});
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      CHECK(i(r, c) == (r == c ? 1 : 0));
      CHECK(mat3<T>::zero()(r, c) == 0);
      CHECK(mat3<T>{}(r, c) == 0);
      CHECK(d(r, c) == (r == c ? T(r + 2) : 0));
    }
  }
}

TEST_CASE_TEMPLATE("from_rows and from_columns place their vectors as rows and columns", T, float, double) {
  const vec3<T> a{1, 2, 3}, b{4, 5, 6}, c{7, 8, 9};
  const mat3<T> by_rows = mat3<T>::from_rows(a, b, c);
  const mat3<T> by_columns = mat3<T>::from_columns(a, b, c);
  CHECK(by_rows(0, 1) == 2);
  CHECK(by_rows(1, 0) == 4);
  CHECK(by_rows(2, 1) == 8);
  CHECK(by_columns(0, 1) == 4);
  CHECK(by_columns(1, 0) == 2);
  CHECK(by_columns(2, 1) == 6);
  CHECK(by_rows.row(1) == b);
  CHECK(by_columns.col[1] == b);
  CHECK(by_rows == transpose(by_columns));
}

TEST_CASE_TEMPLATE("the call operator writes the entry at a row and column", T, float, double) {
  mat3<T> m = mat3<T>::zero();
  m(0, 2) = 5;
  m(2, 0) = -1;
  CHECK(m.col[2].x == 5);
  CHECK(m.col[0].z == -1);
  CHECK(m.row(0) == vec3<T>{0, 0, 5});
}

TEST_CASE_TEMPLATE("sum and difference and negation and scaling act entrywise", T, float, double) {
  const mat3<T> a = general<T>();
  const mat3<T> b = other<T>();
  CHECK(a + b == mat3<T>::from_rows({5, -2, -1}, {6, 5, -3}, {2, 3, 13}));
  CHECK(a - b == mat3<T>::from_rows({3, -2, 3}, {0, 7, -5}, {2, -1, 3}));
  CHECK(-b == mat3<T>::from_rows({-1, 0, 2}, {-3, 1, -1}, {0, -2, -5}));
  CHECK(b * T(2) == mat3<T>::from_rows({2, 0, -4}, {6, -2, 2}, {0, 4, 10}));
  CHECK(T(2) * b == b * T(2));
}

TEST_CASE_TEMPLATE("matrix compound assignments agree with their binary operators", T, float, double) {
  const mat3<T> a = general<T>();
  const mat3<T> b = other<T>();
  mat3<T> m = a;
  CHECK((m += b) == a + b);
  m = a;
  CHECK((m -= b) == a - b);
  m = a;
  CHECK((m *= T(-3)) == a * T(-3));
}

TEST_CASE_TEMPLATE("a matrix times a vector takes the dot product with each row", T, float, double) {
  const mat3<T> m = general<T>();
  const vec3<T> v{1, -1, 2};
  CHECK(m * v == vec3<T>{8, -11, 17});
  CHECK(m * v == vec3<T>{dot(m.row(0), v), dot(m.row(1), v), dot(m.row(2), v)});
}

TEST_CASE_TEMPLATE("a matrix product applies the right factor first", T, float, double) {
  const mat3<T> a = general<T>();
  const mat3<T> b = other<T>();
  const vec3<T> v{1, -1, 2};
  CHECK(a * b == mat3<T>::from_rows({-2, 4, -5}, {21, -14, -20}, {5, 15, 37}));
  CHECK((a * b) * v == a * (b * v));
  CHECK(a * mat3<T>::identity() == a);
  CHECK(mat3<T>::identity() * a == a);
}

TEST_CASE_TEMPLATE("transpose swaps rows and columns and undoes itself", T, float, double) {
  const mat3<T> m = general<T>();
  const mat3<T> t = transpose(m);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) CHECK(t(r, c) == m(c, r));
  }
  CHECK(transpose(t) == m);
  CHECK(transpose(general<T>() * other<T>()) == transpose(other<T>()) * transpose(general<T>()));
}

TEST_CASE_TEMPLATE("transpose_mul equals the transpose times the vector", T, float, double) {
  const mat3<T> m = general<T>();
  const vec3<T> v{2, -3, 5};
  CHECK(transpose_mul(m, v) == transpose(m) * v);
}

TEST_CASE_TEMPLATE("trace sums the diagonal", T, float, double) {
  CHECK(trace(general<T>()) == 18);
  CHECK(trace(mat3<T>::identity()) == 3);
}

TEST_CASE_TEMPLATE("determinant is multiplicative and known for simple matrices", T, float, double) {
  CHECK(determinant(mat3<T>::identity()) == 1);
  CHECK(determinant(mat3<T>::diagonal({2, -3, 4})) == -24);
  CHECK(determinant(general<T>()) == 263);
  CHECK(determinant(other<T>()) == -19);
  CHECK(determinant(general<T>() * other<T>()) == 263 * -19);
  CHECK(determinant(transpose(general<T>())) == 263);
}

TEST_CASE_TEMPLATE("skew of a times b equals the cross product of a and b", T, float, double) {
  const vec3<T> a{1, -2, 3};
  const vec3<T> vectors[] = {{4, 5, 6}, {-1, 0, 2}, {1, -2, 3}, {0, 0, 0}};
  for (const vec3<T>& b : vectors) CHECK(skew(a) * b == cross(a, b));
  CHECK(transpose(skew(a)) == -skew(a));
}

TEST_CASE_TEMPLATE("outer product of a and b maps v to a times the dot of b and v", T, float, double) {
  const vec3<T> a{1, -2, 3};
  const vec3<T> b{4, 0, -1};
  const vec3<T> v{2, 7, -5};
  const mat3<T> o = outer(a, b);
  CHECK(o * v == a * dot(b, v));
  CHECK(o(2, 0) == 12);
  CHECK(trace(o) == dot(a, b));
}

TEST_CASE_TEMPLATE("a general matrix times its inverse is the identity", T, float, double) {
  const mat3<T> m = general<T>();
  const std::optional<mat3<T>> inv = try_inverse(m);
  REQUIRE(inv.has_value());
  CHECK(max_abs_diff(m * *inv, mat3<T>::identity()) <= inverse_rounding<T>);
  CHECK(max_abs_diff(*inv * m, mat3<T>::identity()) <= inverse_rounding<T>);
  CHECK(max_abs_diff(inverse(m), *inv) == 0);
}

TEST_CASE_TEMPLATE("a tiny or huge but well-conditioned matrix inverts as accurately", T, float, double) {
  // An inertia tensor of a gram-sized body is 1e-8 kg·m²; the singularity
  // test is relative to the column lengths, so the scale must not matter.
  for (const T scale : {T(1e-8), T(1e8)}) {
    const mat3<T> m = general<T>() * scale;
    CHECK(max_abs_diff(m * inverse(m), mat3<T>::identity()) <= inverse_rounding<T>);
  }
  // Columns whose lengths differ by 1e8: scaling a column leaves both the
  // relative singularity test and the rounding of m·m⁻¹ unchanged.
  const mat3<T> g = general<T>();
  const mat3<T> m = mat3<T>::from_columns(g.col[0] * T(1e-4), g.col[1], g.col[2] * T(1e4));
  CHECK(max_abs_diff(m * inverse(m), mat3<T>::identity()) <= inverse_rounding<T>);
}

TEST_CASE_TEMPLATE("try_inverse returns nothing for a rank-2 matrix", T, float, double) {
  CHECK_FALSE(try_inverse(mat3<T>::from_columns({1, 2, 3}, {4, 5, 6}, {7, 8, 9})).has_value());
  CHECK_FALSE(try_inverse(mat3<T>::zero()).has_value());
  CHECK_FALSE(try_inverse(outer(vec3<T>{1, 2, 3}, vec3<T>{-1, 1, 2})).has_value());
  // A third column combined from the other two in rounded arithmetic: its
  // determinant is rounding noise of a few epsilon, far below the tolerance.
  lcg rng;
  int inverted = 0;
  for (int i = 0; i < 1000; ++i) {
    const vec3<T> a = rng.vector<T>(-1, 1);
    const vec3<T> b = rng.vector<T>(-1, 1);
    const vec3<T> c = a * rng.in<T>(-2, 2) + b * rng.in<T>(-2, 2);
    if (try_inverse(mat3<T>::from_columns(a, b, c)).has_value()) ++inverted;
  }
  CHECK(inverted == 0);
}

TEST_CASE_TEMPLATE("a matrix is not finite when any entry is NaN or infinite", T, float, double) {
  CHECK(is_finite(general<T>()));
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      mat3<T> m = general<T>();
      m(r, c) = std::numeric_limits<T>::quiet_NaN();
      CHECK_FALSE(is_finite(m));
      m(r, c) = std::numeric_limits<T>::infinity();
      CHECK_FALSE(is_finite(m));
    }
  }
}

}  // namespace math_mat3_tests
