// impulse/io/detail/json_reader.hpp — reading a JSON document value by value,
// each read knowing the file and the JSON path (RFC 6901 pointer) it is at,
// so that every error says where it is and what was expected:
//
//   domino.json: /bodies/3/shape/radius: expected a number > 0, got -1
//
// Objects are read strictly: a key the reader does not know is an error, not
// ignored, so that a misspelt "restitutoin" is found when the file is loaded
// rather than when the ball fails to bounce.
#pragma once

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "../../core/error.hpp"
#include "../../math/vec3.hpp"

namespace impulse::io {

/// A scene file that could not be read: what() is "<file>: <JSON path>:
/// <what was expected, and what was found>". file() and path() give the two
/// parts on their own.
class scene_error : public invalid_argument {
 public:
  scene_error(std::string file, std::string path, const std::string& message,
              error_code code = error_code::invalid_parameter)
      : invalid_argument(code, compose(file, path, message).c_str()),
        file_(std::move(file)),
        path_(std::move(path)) {}
  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  /// A JSON pointer (RFC 6901) to the value at fault; empty for the whole file.
  [[nodiscard]] const std::string& path() const noexcept { return path_; }

 private:
  static std::string compose(const std::string& file, const std::string& path, const std::string& message) {
    return file + ": " + (path.empty() ? std::string("(document)") : path) + ": " + message;
  }
  std::string file_;
  std::string path_;
};

namespace detail {

using json = nlohmann::json;

/// What a value is, in the words an error message uses.
inline std::string describe(const json& j) {
  switch (j.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return j.get<bool>() ? "true" : "false";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float: {
      std::string text = j.dump();
      return text.size() > 24 ? text.substr(0, 24) + "..." : text;
    }
    case json::value_t::string: {
      const std::string& s = j.get_ref<const std::string&>();
      return '"' + (s.size() > 32 ? s.substr(0, 32) + "..." : s) + '"';
    }
    case json::value_t::array: return "an array of " + std::to_string(j.size());
    case json::value_t::object: return "an object";
    default: return "an unreadable value";
  }
}

/// A value of the document and where it is.
struct json_at {
  const json& value;
  std::string path;
  const std::string* file;  ///< for errors; outlives every json_at

  /// The member `key` of this object; a missing key is an error.
  json_at operator[](std::string_view key) const {
    if (!value.is_object()) throw scene_error(*file, path, "expected an object, got " + describe(value));
    const auto it = value.find(key);
    if (it == value.end()) throw scene_error(*file, path, "expected the key \"" + std::string(key) + "\"");
    return {*it, path + "/" + escape(key), file};
  }
  /// Element i of this array.
  json_at operator[](std::size_t i) const {
    if (!value.is_array() || i >= value.size())
      throw scene_error(*file, path, "expected an array of more than " + std::to_string(i) + ", got " + describe(value));
    return {value[i], path + "/" + std::to_string(i), file};
  }
  [[nodiscard]] bool has(std::string_view key) const { return value.is_object() && value.contains(key); }

  /// RFC 6901: '~' is written "~0" and '/' "~1" in a pointer's tokens.
  static std::string escape(std::string_view key) {
    std::string out;
    for (const char c : key) {
      if (c == '~') out += "~0";
      else if (c == '/') out += "~1";
      else out += c;
    }
    return out;
  }
};

/// Reads values of one file, in scalar type T, and reports the first fault.
template <class T>
class json_reader {
 public:
  explicit json_reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const json_at& at, const std::string& expected,
                         error_code code = error_code::invalid_parameter) const {
    throw scene_error(file_, at.path, expected, code);
  }
  [[noreturn]] void fail_expected(const json_at& at, const std::string& expected) const {
    fail(at, "expected " + expected + ", got " + describe(at.value));
  }
  [[nodiscard]] const std::string& file() const noexcept { return file_; }

  /// An object whose keys are all among `known`.
  void object(const json_at& at, std::initializer_list<std::string_view> known) const {
    if (!at.value.is_object()) fail_expected(at, "an object");
    for (const auto& item : at.value.items()) {
      bool found = false;
      for (const std::string_view k : known) found = found || item.key() == k;
      if (found) continue;
      std::string list;
      for (const std::string_view k : known) list += (list.empty() ? "" : ", ") + std::string(k);
      fail({item.value(), at.path + "/" + json_at::escape(item.key()), at.file},
           "unknown key \"" + item.key() + "\" (expected one of: " + list + ")");
    }
  }
  void array(const json_at& at, std::size_t min_size = 0) const {
    if (!at.value.is_array()) fail_expected(at, "an array");
    if (at.value.size() < min_size) fail_expected(at, "an array of at least " + std::to_string(min_size));
  }

  /// A finite number that T holds (1e300 does not fit a float).
  T number(const json_at& at) const {
    if (!at.value.is_number()) fail_expected(at, "a number");
    const double x = at.value.get<double>();
    if (!std::isfinite(x) || std::abs(x) > double(std::numeric_limits<T>::max()))
      fail(at, "expected a finite number, got " + describe(at.value), error_code::non_finite);
    return T(x);
  }
  T positive(const json_at& at) const {
    const T x = number(at);
    if (!(x > T(0))) fail_expected(at, "a number > 0");
    return x;
  }
  T non_negative(const json_at& at) const {
    const T x = number(at);
    if (x < T(0)) fail_expected(at, "a number >= 0");
    return x;
  }
  T within(const json_at& at, T lo, T hi) const {
    const T x = number(at);
    if (x < lo || x > hi) fail_expected(at, "a number in [" + format(lo) + ", " + format(hi) + "]");
    return x;
  }
  /// A whole number in [lo, hi].
  std::int64_t integer(const json_at& at, std::int64_t lo, std::int64_t hi) const {
    const std::string range = "a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (at.value.is_number_integer()) {
      if (at.value.is_number_unsigned() && at.value.get<std::uint64_t>() > std::uint64_t(hi)) fail_expected(at, range);
      const std::int64_t n = at.value.get<std::int64_t>();
      if (n < lo || n > hi) fail_expected(at, range);
      return n;
    }
    if (at.value.is_number_float()) {
      const double x = at.value.get<double>();
      if (std::isfinite(x) && x == std::floor(x) && x >= double(lo) && x <= double(hi)) return std::int64_t(x);
    }
    fail_expected(at, range);
  }
  bool boolean(const json_at& at) const {
    if (!at.value.is_boolean()) fail_expected(at, "true or false");
    return at.value.get<bool>();
  }
  const std::string& string(const json_at& at) const {
    if (!at.value.is_string()) fail_expected(at, "a string");
    return at.value.get_ref<const std::string&>();
  }
  vec3<T> vector(const json_at& at) const {
    if (!at.value.is_array() || at.value.size() != 3) fail_expected(at, "an array of 3 numbers [x, y, z]");
    return {number(at[0]), number(at[1]), number(at[2])};
  }
  /// A vector of length > 0 (an axis, a normal), made unit.
  vec3<T> direction(const json_at& at) const {
    const vec3<T> v = vector(at);
    const T n = length(v);
    if (!(n > T(0)) || !std::isfinite(n)) fail_expected(at, "a direction (a vector of non-zero length)");
    return v / n;
  }

 private:
  static std::string format(T x) {
    std::string s = std::to_string(double(x));
    while (s.size() > 1 && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
  }
  std::string file_;
};

}  // namespace detail
}  // namespace impulse::io
