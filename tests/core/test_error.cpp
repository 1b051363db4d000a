// Error reporting at the API boundary: what an impulse::invalid_argument carries.
#include <doctest/doctest.h>

#include <cstring>
#include <stdexcept>

#include "impulse/core/error.hpp"

namespace core_error_tests {

TEST_CASE("report_error throws invalid_argument with its code and object") {
  bool caught = false;
  try {
    impulse::detail::report_error(impulse::error_code::non_positive_mass,
                                  "body mass must be positive", 42);
  } catch (const impulse::invalid_argument& e) {
    caught = true;
    CHECK(e.code() == impulse::error_code::non_positive_mass);
    CHECK(e.object() == 42u);
    CHECK(std::strcmp(e.what(), "body mass must be positive") == 0);
  }
  CHECK(caught);
}

TEST_CASE("invalid_argument is a std::invalid_argument") {
  CHECK_THROWS_AS(impulse::detail::report_error(impulse::error_code::non_finite, "NaN"),
                  std::invalid_argument);
}

TEST_CASE("an error without an object names no object") {
  const impulse::invalid_argument e(impulse::error_code::capacity_exceeded, "full");
  CHECK(e.object() == impulse::no_object);
}

TEST_CASE("every error code has a distinct name") {
  using impulse::error_code;
  const error_code codes[] = {error_code::none,
                              error_code::non_finite,
                              error_code::non_positive_mass,
                              error_code::degenerate_shape,
                              error_code::not_normalized,
                              error_code::capacity_exceeded,
                              error_code::out_of_range,
                              error_code::invalid_parameter};
  for (const error_code a : codes) {
    CHECK(std::strcmp(impulse::to_string(a), "unknown") != 0);
    for (const error_code b : codes)
      if (a != b) CHECK(std::strcmp(impulse::to_string(a), impulse::to_string(b)) != 0);
  }
}

}  // namespace core_error_tests
