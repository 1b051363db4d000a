// impulse/core/detail/assert.hpp — internal assertions for preconditions the caller owns.
//
// IMPULSE_ASSERT checks invariants inside the library (a non-zero vector handed
// to normalize, an index in range). It is on in debug builds and compiled out
// when NDEBUG is defined, like <cassert>, so release hot loops pay nothing.
// Bad *user input* at the API boundary is not asserted: it is reported with
// impulse::invalid_argument (core/error.hpp) in every build.
#pragma once

#include <cstdio>
#include <cstdlib>

namespace impulse::detail {

[[noreturn]] inline void assertion_failed(const char* expression, const char* file, int line) {
  std::fprintf(stderr, "impulse: assertion failed: %s (%s:%d)\n", expression, file, line);
  std::abort();
}

}  // namespace impulse::detail

#if defined(NDEBUG) && !defined(IMPULSE_ENABLE_ASSERTS)
#define IMPULSE_ASSERT(expression) static_cast<void>(0)
#else
#define IMPULSE_ASSERT(expression)                                                   \
  ((expression) ? static_cast<void>(0)                                               \
                : ::impulse::detail::assertion_failed(#expression, __FILE__, __LINE__))
#endif
