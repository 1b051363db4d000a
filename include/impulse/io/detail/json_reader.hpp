// impulse/io/detail/json_reader.hpp — reading a JSON document value by value,
// each read knowing the file and the JSON path (RFC 6901 pointer) it is at,
// so that every error says where it is and what was expected:
//
//   domino.json: /bodies/3/shape/radius: expected a number > 0, got -1
//
// Objects are read strictly: a key the reader does not know is an error, not
// ignored, so that a misspelt "restitutoin" is found when the file is loaded
// rather than when the ball fails to bounce. A key given twice in one object
// is an error too: JSON leaves open which of the two counts.
//
// Before the document is built in memory, scan_document() reads the text once
// without building it, counting its values and levels and checking its keys,
// so that a file which would take gigabytes as a document is refused at the
// value that crosses the limit, having cost little more than the reading.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <set>
#include <string>
#include <string_view>
#include <vector>

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
      // double(hi) rounds up to 2^63 for hi near INT64_MAX, where converting
      // x would be undefined behaviour; 2^63 itself is the first double past
      // int64_t, so x must also stay below it.
      constexpr double past_int64 = 9223372036854775808.0;
      const double x = at.value.get<double>();
      if (std::isfinite(x) && x == std::floor(x) && x >= double(lo) && x <= double(hi) && x < past_int64)
        return std::int64_t(x);
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

/// The first reading of a document, as nlohmann's SAX events. Nothing is
/// built: it keeps only the keys of the objects it is inside, to find one
/// given twice, which is at most what the document would keep of them. It
/// refuses, with the JSON path of the value at fault, a value past
/// `max_values` (the document built from the text takes memory in proportion
/// to its values), nesting deeper than `max_depth`, and a key given twice in
/// one object (the built document would silently keep one of the two).
class document_scan final : public nlohmann::json_sax<json> {
 public:
  document_scan(const std::string& file, std::size_t max_values, int max_depth)
      : file_(&file), max_values_(max_values), max_depth_(max_depth) {}

  bool null() override { return scalar(); }
  bool boolean(bool) override { return scalar(); }
  bool number_integer(number_integer_t) override { return scalar(); }
  bool number_unsigned(number_unsigned_t) override { return scalar(); }
  bool number_float(number_float_t, const string_t&) override { return scalar(); }
  bool string(string_t&) override { return scalar(); }
  bool binary(binary_t&) override { return scalar(); }
  bool start_object(std::size_t) override { return open(false); }
  bool start_array(std::size_t) override { return open(true); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(string_t& name) override {
    level& object = levels_.back();
    object.key = name;
    if (!object.keys.insert(name).second)
      throw scene_error(*file_, path(), "the key \"" + name + "\" is given twice in this object (JSON leaves open which one counts)");
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const json::exception& e) override {
    // parse_error for bad syntax; out_of_range for a number past double's
    // range (1e400), which is not a syntax error. (The fuzzer found the second.)
    throw scene_error(*file_, "", std::string("not JSON: ") + e.what());
  }

 private:
  /// An array or object being read: where in it the reader is, and an
  /// object's keys so far.
  struct level {
    bool array = false;
    std::size_t elements = 0;  ///< arrays: elements begun, so the current one is elements - 1
    std::string key;           ///< objects: the key of the current member
    std::set<std::string, std::less<>> keys;
  };

  /// Every value, container or not, begins here.
  void begin_value() {
    if (!levels_.empty() && levels_.back().array) ++levels_.back().elements;
    if (++values_ > max_values_)
      throw scene_error(*file_, path(),
                        "more than " + std::to_string(max_values_) + " JSON values in the document (scene_limits::json_values)",
                        error_code::capacity_exceeded);
  }
  bool scalar() {
    begin_value();
    return true;
  }
  bool open(bool array) {
    begin_value();
    if (levels_.size() >= std::size_t(max_depth_))
      throw scene_error(*file_, path(), "nested deeper than " + std::to_string(max_depth_) + " levels (scene_limits::depth)",
                        error_code::capacity_exceeded);
    levels_.push_back({array, 0, {}, {}});
    return true;
  }
  bool close() {
    levels_.pop_back();
    return true;
  }
  /// The JSON pointer of the value being read; built only for an error.
  [[nodiscard]] std::string path() const {
    std::string out;
    for (const level& l : levels_) {
      out += '/';  // appended on its own: GCC 12 at -O3 warns falsely on "/" + std::string (-Wrestrict)
      out += l.array ? std::to_string(l.elements - 1) : json_at::escape(l.key);
    }
    return out;
  }

  const std::string* file_;
  std::size_t max_values_;
  int max_depth_;
  std::size_t values_ = 0;
  std::vector<level> levels_;
};

/// Reads `text` once with document_scan; throws its scene_error, or returns
/// when the text may be built into a document.
inline void scan_document(std::string_view text, const std::string& file, std::size_t max_values, int max_depth) {
  document_scan scan(file, max_values, max_depth);
  (void)json::sax_parse(text.begin(), text.end(), &scan);
}

}  // namespace detail
}  // namespace impulse::io
