// tests/error_code_of.hpp — the error a call reports, for the bad-input tests.
#pragma once

#include "impulse/core/error.hpp"

namespace impulse::test {

/// Calls f and returns the code of the impulse::invalid_argument it throws,
/// or error_code::none when it returns normally.
template <class F>
error_code error_code_of(F&& f) {
  try {
    f();
  } catch (const invalid_argument& e) {
    return e.code();
  }
  return error_code::none;
}

}  // namespace impulse::test
