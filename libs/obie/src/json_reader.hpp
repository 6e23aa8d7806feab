#pragma once
// Private helpers of the obie readers: typed field access that reports FormatError with the file and
// the JSON pointer of the offending value.
#include <cmath>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"

namespace emoface::obie::detail {

using Json = nlohmann::ordered_json;

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void fail(const std::string& pointer, const std::string& message) const {
    SourceLocation where;
    where.file = file_;
    where.json_pointer = pointer;
    throw FormatError(where, message);
  }
  static std::string at(const std::string& pointer, const std::string& key) {
    return pointer + "/" + core::json_pointer_token(key);
  }
  static std::string at(const std::string& pointer, std::size_t index) { return pointer + "/" + std::to_string(index); }

  /// Every key of `obj` must be in `allowed`.
  void only_keys(const Json& obj, const std::string& pointer, const std::set<std::string>& allowed) const {
    for (auto it = obj.begin(); it != obj.end(); ++it)
      if (!allowed.count(it.key())) fail(at(pointer, it.key()), "unknown field \"" + it.key() + "\"");
  }
  const Json& object(const Json& v, const std::string& pointer) const {
    if (!v.is_object()) fail(pointer, "expected an object");
    return v;
  }
  const Json& array(const Json& v, const std::string& pointer, std::size_t max_size) const {
    if (!v.is_array()) fail(pointer, "expected an array");
    if (v.size() > max_size) fail(pointer, "too many entries (" + std::to_string(v.size()) + " > " + std::to_string(max_size) + ")");
    return v;
  }
  std::string string(const Json& v, const std::string& pointer, bool allow_empty = true) const {
    if (!v.is_string()) fail(pointer, "expected a string");
    std::string s = v.get<std::string>();
    if (!allow_empty && s.empty()) fail(pointer, "must not be empty");
    if (s.size() > 4096) fail(pointer, "string too long (> 4096 bytes)");
    return s;
  }
  double number(const Json& v, const std::string& pointer, double lo, double hi) const {
    if (!v.is_number()) fail(pointer, "expected a number");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(pointer, "must be finite");
    if (x < lo || x > hi) fail(pointer, "must be in [" + fmt(lo) + ", " + fmt(hi) + "], got " + fmt(x));
    return x;
  }
  static std::string fmt(double x) {
    std::string s = Json(x).dump();
    return s;
  }
  const std::string& file() const noexcept { return file_; }

 private:
  std::string file_;
};

}  // namespace emoface::obie::detail
