#pragma once
// Private JSON helpers of the runtime's readers, on core::JsonReader (issue 18 item 1: one located
// reader, one unknown-field rule, one message style): optional members read into their defaults,
// FormatError naming the file and the JSON pointer.
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "emoface/core/errors.hpp"
#include "emoface/core/json_reader.hpp"

namespace emoface::runtime::detail {

using Json = nlohmann::ordered_json;
using core::JsonValue;

inline void get(const JsonValue& o, std::string_view key, double& out) {
  if (auto v = o.find(key)) out = v->number();
}
inline void get(const JsonValue& o, std::string_view key, bool& out) {
  if (auto v = o.find(key)) out = v->boolean();
}
inline void get(const JsonValue& o, std::string_view key, int& out) {
  if (auto v = o.find(key)) out = static_cast<int>(v->integer(-1000000000, 1000000000));
}
inline void get(const JsonValue& o, std::string_view key, std::string& out) {
  if (auto v = o.find(key)) out = v->string();
}
/// A count, seed or frame number: any non-negative JSON integer up to 2^64 − 1.
inline std::uint64_t unsigned_integer(const JsonValue& v) {
  if (!v.json().is_number_unsigned()) v.fail("expected a non-negative integer");
  return v.json().get<std::uint64_t>();
}
inline void get(const JsonValue& o, std::string_view key, std::uint64_t& out) {
  if (auto v = o.find(key)) out = unsigned_integer(*v);
}
/// A finite number, or null for −∞ (the writers store −∞ — never inhibited, no previous — as null).
inline double number_or_null(const JsonValue& v) { return v.is_null() ? -INFINITY : v.number(); }

inline Json num(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

}  // namespace emoface::runtime::detail
