#pragma once
// Private JSON helpers of the runtime's readers: typed field access with FormatError naming the
// file and the JSON pointer.
#include <cmath>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"

namespace emoface::runtime::detail {

using Json = nlohmann::ordered_json;

struct Reader {
  std::string file;
  [[noreturn]] void fail(const std::string& pointer, const std::string& msg) const {
    throw FormatError({file, pointer.empty() ? "/" : pointer, 0, 0}, msg);
  }
  const Json& object(const Json& j, const std::string& ptr) const {
    if (!j.is_object()) fail(ptr, "expected an object");
    return j;
  }
  void only(const Json& j, const std::string& ptr,
            std::initializer_list<std::string_view> keys) const {
    for (auto it = j.begin(); it != j.end(); ++it) {
      bool ok = false;
      for (auto k : keys) ok |= it.key() == k;
      if (!ok) fail(ptr + "/" + core::json_pointer_token(it.key()), "unknown field");
    }
  }
  double number(const Json& j, const std::string& ptr) const {
    if (j.is_null())
      return -INFINITY;  // the writers store −inf (never inhibited, no previous) as null
    if (!j.is_number()) fail(ptr, "expected a number");
    return j.get<double>();
  }
  double finite(const Json& j, const std::string& ptr) const {
    if (!j.is_number()) fail(ptr, "expected a number");
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(ptr, "expected a finite number");
    return v;
  }
  void get(const Json& o, const std::string& ptr, const char* key, double& out) const {
    if (o.contains(key)) out = finite(o[key], ptr + "/" + key);
  }
  void get(const Json& o, const std::string& ptr, const char* key, bool& out) const {
    if (!o.contains(key)) return;
    if (!o[key].is_boolean()) fail(ptr + "/" + key, "expected true or false");
    out = o[key].get<bool>();
  }
  void get(const Json& o, const std::string& ptr, const char* key, int& out) const {
    if (!o.contains(key)) return;
    if (!o[key].is_number_integer()) fail(ptr + "/" + key, "expected an integer");
    const auto v = o[key].get<long long>();
    if (v < -1000000000LL || v > 1000000000LL) fail(ptr + "/" + key, "integer out of range");
    out = static_cast<int>(v);
  }
  void get(const Json& o, const std::string& ptr, const char* key, std::uint64_t& out) const {
    if (!o.contains(key)) return;
    if (!o[key].is_number_unsigned()) fail(ptr + "/" + key, "expected a non-negative integer");
    out = o[key].get<std::uint64_t>();
  }
  void get(const Json& o, const std::string& ptr, const char* key, std::string& out) const {
    if (!o.contains(key)) return;
    if (!o[key].is_string()) fail(ptr + "/" + key, "expected a string");
    out = o[key].get<std::string>();
  }
};

inline Json num(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

}  // namespace emoface::runtime::detail
