// The compile-time configuration: which configs are accepted. The loud form
// (check_config's messages) is proven by the compile-fail tests in
// tests/compile_fail/; here the quiet concept is checked on the same cases.
#include <doctest/doctest.h>

#include <cstring>
#include <type_traits>

#include "impulse/config.hpp"
#include "impulse/core/version.hpp"

namespace core_config_tests {

namespace {

struct rk_like {
  static constexpr impulse::policy_kind kind = impulse::policy_kind::integrator;
  static constexpr int order = 4;
  static constexpr int stages = 4;
  template <class S, class H, class A>
  static void step(S&, S&, H, A&&) {}
};
struct sap_like {
  static constexpr impulse::policy_kind kind = impulse::policy_kind::broadphase;
};
template <class T>
struct ball_like {
  static constexpr impulse::policy_kind kind = impulse::policy_kind::shape;
  T radius;
};
template <class T>
struct mislabelled_ball {  // says it is a broad phase
  static constexpr impulse::policy_kind kind = impulse::policy_kind::broadphase;
  T radius;
};

struct double_config : impulse::default_config {
  using scalar = double;
};
struct full_config : impulse::default_config {
  using integrator = rk_like;
  using broadphase = sap_like;
  using shapes = impulse::shape_list<ball_like>;
  static constexpr bool sleeping = true;
  static constexpr bool ccd = false;
};
struct no_scalar {};
struct int_scalar {
  using scalar = int;
};
struct integrator_as_broadphase : impulse::default_config {
  using broadphase = rk_like;
};
struct non_bool_flag : impulse::default_config {
  static constexpr int ccd = 0;
};

}  // namespace

TEST_CASE("the default config and configs derived from it are valid") {
  static_assert(impulse::world_config<impulse::default_config>);
  static_assert(impulse::world_config<double_config>);
  static_assert(impulse::world_config<full_config>);
  static_assert(impulse::check_config<full_config>());
  CHECK(std::is_same_v<impulse::default_config::scalar, float>);
  CHECK(std::is_same_v<impulse::default_config::integrator, impulse::integrators::symplectic_euler>);
}

TEST_CASE("configs with a missing or mistyped member are rejected") {
  static_assert(!impulse::world_config<no_scalar>);
  static_assert(!impulse::world_config<int_scalar>);
  static_assert(!impulse::world_config<integrator_as_broadphase>);
  static_assert(!impulse::world_config<non_bool_flag>);
  CHECK_FALSE(impulse::world_config<no_scalar>);
}

TEST_CASE("policy concepts tell policy kinds apart") {
  static_assert(impulse::integrator_policy<rk_like>);
  static_assert(!impulse::broadphase_policy<rk_like>);
  static_assert(impulse::broadphase_policy<sap_like>);
  static_assert(!impulse::solver_policy<sap_like>);
  static_assert(impulse::shape_set<impulse::shape_list<ball_like, ball_like>>);
  static_assert(!impulse::shape_set<impulse::shape_list<ball_like, mislabelled_ball>>);
  static_assert(impulse::shape_set<impulse::shape_list<>>);
  CHECK(impulse::shape_list<ball_like, ball_like>::size == 2);
}

TEST_CASE("the version macros agree with the VERSION file") {
  // IMPULSE_EXPECTED_VERSION is passed by the build system, which reads VERSION.
  CHECK(std::strcmp(IMPULSE_VERSION_STRING, IMPULSE_EXPECTED_VERSION) == 0);
  CHECK(impulse::version.major == IMPULSE_VERSION_MAJOR);
  CHECK(impulse::version.minor == IMPULSE_VERSION_MINOR);
  CHECK(impulse::version.patch == IMPULSE_VERSION_PATCH);
}

}  // namespace core_config_tests
