// impulse/core/error.hpp — how bad input is reported at the API boundary.
//
// Invalid input never silently corrupts a world (docs/architecture.md,
// "Errors and bad input"): a function that receives a NaN position, a zero mass or a
// degenerate shape reports it before changing any state. With exceptions
// enabled the report is an impulse::invalid_argument carrying an error code,
// a message and, where one exists, the id of the object concerned. Built with
// -fno-exceptions the same report goes to the handler installed with
// set_error_handler (the default prints and aborts), and callers that need to
// recover use the functions that return an error_code instead.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace impulse {

/// What was wrong with an argument. Stable values: they appear in logs.
enum class error_code : std::uint8_t {
  none = 0,
  non_finite,          ///< NaN or infinity in a position, velocity, force or parameter
  non_positive_mass,   ///< zero or negative mass or density
  degenerate_shape,    ///< zero or negative extent, coplanar hull, zero-length normal
  not_normalized,      ///< a direction or plane normal that must have unit length
  capacity_exceeded,   ///< more elements than the container was created for
  out_of_range,        ///< an index or handle that does not name a live object
  invalid_parameter,   ///< any other value outside its documented range
};

/// A short, stable name for an error code ("non_finite", ...).
constexpr const char* to_string(error_code code) noexcept {
  switch (code) {
    case error_code::none: return "none";
    case error_code::non_finite: return "non_finite";
    case error_code::non_positive_mass: return "non_positive_mass";
    case error_code::degenerate_shape: return "degenerate_shape";
    case error_code::not_normalized: return "not_normalized";
    case error_code::capacity_exceeded: return "capacity_exceeded";
    case error_code::out_of_range: return "out_of_range";
    case error_code::invalid_parameter: return "invalid_parameter";
  }
  return "unknown";
}

/// Sentinel for "no particular object": the error concerns the call as a whole.
inline constexpr std::uint32_t no_object = 0xffffffffu;

/// Thrown for invalid input. what() is a full sentence naming the argument;
/// code() and object() let a program react without parsing it.
class invalid_argument : public std::invalid_argument {
 public:
  invalid_argument(error_code code, const char* message, std::uint32_t object = no_object)
      : std::invalid_argument(message), code_(code), object_(object) {}

  [[nodiscard]] error_code code() const noexcept { return code_; }
  /// Index or id of the body/particle/shape concerned, or impulse::no_object.
  [[nodiscard]] std::uint32_t object() const noexcept { return object_; }

 private:
  error_code code_;
  std::uint32_t object_;
};

/// Called instead of throwing when exceptions are disabled.
using error_handler = void (*)(error_code code, const char* message, std::uint32_t object);

namespace detail {

inline void default_error_handler(error_code code, const char* message, std::uint32_t object) {
  std::fprintf(stderr, "impulse: %s (%s, object %u)\n", message, to_string(code),
               static_cast<unsigned>(object));
  std::abort();
}

inline error_handler& current_error_handler() noexcept {
  static error_handler handler = &default_error_handler;
  return handler;
}

}  // namespace detail

/// Installs the handler used in builds without exceptions; returns the old one.
inline error_handler set_error_handler(error_handler handler) noexcept {
  error_handler old = detail::current_error_handler();
  detail::current_error_handler() = handler ? handler : &detail::default_error_handler;
  return old;
}

namespace detail {

/// Reports invalid input: throws impulse::invalid_argument, or calls the
/// installed handler when built with -fno-exceptions.
[[noreturn]] inline void report_error(error_code code, const char* message,
                                      std::uint32_t object = no_object) {
#if defined(__cpp_exceptions) || defined(__EXCEPTIONS)
  throw invalid_argument(code, message, object);
#else
  current_error_handler()(code, message, object);
  std::abort();  // a handler that returns cannot resume the operation
#endif
}

}  // namespace detail
}  // namespace impulse
