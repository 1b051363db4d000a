// Tests of impulse/math/transform.hpp: a rigid transform maps body space to
// world space, and its inverse and compositions agree with doing the steps
// one at a time.
#include <impulse/math/transform.hpp>

#include "tolerances.hpp"

namespace math_transform_tests {

using namespace impulse;
using namespace impulse::test;

namespace {

template <class T>
constexpr T pi = T(3.14159265358979323846);

/// A rigid placement within 10 m of the origin.
template <class T>
transform<T> random_transform(lcg& rng) {
  return {rng.vector<T>(-10, 10), rng.rotation<T>()};
}

/// Point coordinates are up to 10 m and transforms move them by up to 10 m
/// more, so the rounding of a rotation scales with their size, 20 m, and with
/// the number of rotations chained (counted where it is used).
template <class T>
inline constexpr T placement_rounding = 20 * rotation_rounding<T>;

}  // namespace

TEST_CASE_TEMPLATE("the identity transform maps every point to itself", T, float, double) {
  const transform<T> t = transform<T>::identity();
  CHECK(t == transform<T>{vec3<T>::zero(), quat<T>::identity()});
  CHECK(transform<T>{} == t);
  const vec3<T> p{1, -2, 3};
  CHECK(apply(t, p) == p);
  CHECK(apply_direction(t, p) == p);
  CHECK(inverse_apply(t, p) == p);
  CHECK(inverse_apply_direction(t, p) == p);
}

TEST_CASE_TEMPLATE("apply rotates a point and then translates it", T, float, double) {
  const transform<T> t{{1, 2, 3}, quat<T>::from_axis_angle(vec3<T>::unit_z(), pi<T> / 2)};
  // A rotation of a unit vector, then a sum into coordinates below 4 (half an
  // ulp there is 2 epsilon).
  const T apply_rounding = rotation_rounding<T> + 2 * epsilon<T>;
  CHECK(max_abs_diff(apply(t, vec3<T>::unit_x()), vec3<T>{1, 3, 3}) <= apply_rounding);
  CHECK(max_abs_diff(apply(t, vec3<T>::unit_z()), vec3<T>{1, 2, 4}) <= apply_rounding);
}

TEST_CASE_TEMPLATE("apply_direction rotates without translating", T, float, double) {
  const transform<T> t{{1, 2, 3}, quat<T>::from_axis_angle(vec3<T>::unit_z(), pi<T> / 2)};
  CHECK(max_abs_diff(apply_direction(t, vec3<T>::unit_x()), vec3<T>::unit_y()) <= rotation_rounding<T>);
  CHECK(apply_direction(t, vec3<T>::unit_z()) == vec3<T>::unit_z());
}

TEST_CASE_TEMPLATE("inverse_apply undoes apply", T, float, double) {
  lcg rng;
  T worst = 0;
  for (int i = 0; i < 1000; ++i) {
    const transform<T> t = random_transform<T>(rng);
    const vec3<T> p = rng.vector<T>(-10, 10);
    worst = std::fmax(worst, std::fmax(max_abs_diff(inverse_apply(t, apply(t, p)), p),
                                       max_abs_diff(apply(t, inverse_apply(t, p)), p)));
  }
  constexpr T round_trip = 2 * placement_rounding<T>;  // there and back: two placements
  CHECK(worst <= round_trip);
}

TEST_CASE_TEMPLATE("inverse_apply_direction undoes apply_direction", T, float, double) {
  lcg rng;
  T worst = 0;
  for (int i = 0; i < 1000; ++i) {
    const transform<T> t = random_transform<T>(rng);
    const vec3<T> d = rng.unit_vector<T>();
    worst = std::fmax(worst, std::fmax(max_abs_diff(inverse_apply_direction(t, apply_direction(t, d)), d),
                                       max_abs_diff(apply_direction(t, inverse_apply_direction(t, d)), d)));
  }
  constexpr T round_trip = 2 * rotation_rounding<T>;  // there and back: two rotations
  CHECK(worst <= round_trip);
}

TEST_CASE_TEMPLATE("the inverse transform maps world points back to body points", T, float, double) {
  lcg rng;
  T worst = 0;
  for (int i = 0; i < 1000; ++i) {
    const transform<T> t = random_transform<T>(rng);
    const transform<T> inv = inverse(t);
    const vec3<T> p = rng.vector<T>(-10, 10);
    worst = std::fmax(worst, std::fmax(max_abs_diff(apply(inv, apply(t, p)), p),
                                       max_abs_diff(apply(inv, p), inverse_apply(t, p))));
  }
  constexpr T round_trip = 3 * placement_rounding<T>;  // inverse rotates the position once more
  CHECK(worst <= round_trip);
}

TEST_CASE_TEMPLATE("the transform composition a times b applies b first and then a", T, float, double) {
  lcg rng;
  T worst = 0;
  for (int i = 0; i < 1000; ++i) {
    const transform<T> a = random_transform<T>(rng);
    const transform<T> b = random_transform<T>(rng);
    const vec3<T> p = rng.vector<T>(-10, 10);
    worst = std::fmax(worst, max_abs_diff(apply(a * b, p), apply(a, apply(b, p))));
  }
  constexpr T two_paths = 3 * placement_rounding<T>;  // the two paths round three rotations between them
  CHECK(worst <= two_paths);
}

TEST_CASE_TEMPLATE("inverse_mul equals the inverse of a times b", T, float, double) {
  lcg rng;
  T worst_position = 0;
  T worst_rotation = 0;
  for (int i = 0; i < 1000; ++i) {
    const transform<T> a = random_transform<T>(rng);
    const transform<T> b = random_transform<T>(rng);
    const transform<T> direct = inverse_mul(a, b);
    const transform<T> composed = inverse(a) * b;
    worst_position = std::fmax(worst_position, max_abs_diff(direct.position, composed.position));
    worst_rotation = std::fmax(worst_rotation, max_abs_diff(direct.rotation, composed.rotation));
  }
  constexpr T two_paths = 2 * placement_rounding<T>;  // each path rotates the difference once
  CHECK(worst_position <= two_paths);
  CHECK(worst_rotation == 0);  // both are conjugate(a.rotation) * b.rotation
}

}  // namespace math_transform_tests
