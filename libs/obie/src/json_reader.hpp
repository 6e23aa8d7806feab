#pragma once
// Private helpers of the obie readers on top of core::JsonReader (issue 18: one located reader,
// the unknown-field rule of docs/formats.md): the size limits obie puts on its documents.
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "emoface/core/json_reader.hpp"

namespace emoface::obie::detail {

using Json = nlohmann::ordered_json;
using core::JsonValue;

/// An array of at most `max_size` entries.
inline const JsonValue& array(const JsonValue& v, std::size_t max_size) {
  v.expect_array();
  if (v.size() > max_size)
    v.fail("too many entries (" + std::to_string(v.size()) + " > " + std::to_string(max_size) +
           ")");
  return v;
}

/// A string of at most 4096 bytes (optionally not empty).
inline std::string string(const JsonValue& v, bool allow_empty = true) {
  std::string s = allow_empty ? v.string() : v.non_empty_string();
  if (s.size() > 4096) v.fail("string too long (> 4096 bytes)");
  return s;
}

/// The member `key`, or a "missing field" error at this object with an explanation.
inline JsonValue required(const JsonValue& obj, const char* key, const char* hint = nullptr) {
  if (!obj.expect_object().has(key))
    obj.fail(std::string("missing field \"") + key + "\"" + (hint ? std::string(" ") + hint : ""));
  return obj.at(key);
}

inline std::string fmt(double x) { return Json(x).dump(); }

}  // namespace emoface::obie::detail
