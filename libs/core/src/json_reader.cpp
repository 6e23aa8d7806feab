#include "emoface/core/json_reader.hpp"

#include <cmath>

#include "emoface/core/text.hpp"

namespace emoface::core {

namespace {

const char* kind_name(const nlohmann::ordered_json& j) {
  switch (j.type()) {
    case nlohmann::ordered_json::value_t::null:
      return "null";
    case nlohmann::ordered_json::value_t::object:
      return "an object";
    case nlohmann::ordered_json::value_t::array:
      return "an array";
    case nlohmann::ordered_json::value_t::string:
      return "a string";
    case nlohmann::ordered_json::value_t::boolean:
      return "a boolean";
    case nlohmann::ordered_json::value_t::binary:
      return "binary data";
    case nlohmann::ordered_json::value_t::discarded:
      return "nothing";
    default:
      return "a number";
  }
}

std::string expected(const char* what, const nlohmann::ordered_json& got) {
  return std::string("expected ") + what + ", got " + kind_name(got);
}

}  // namespace

// --- JsonValue
// ---------------------------------------------------------------------------------------

void JsonValue::fail(const std::string& message) const { reader_->fail(pointer_, message); }

JsonValue JsonValue::child(const Json& json, std::string_view token) const {
  return JsonValue(reader_, &json, pointer_ + "/" + json_pointer_token(token));
}

JsonValue JsonValue::child(const Json& json, std::size_t index) const {
  return JsonValue(reader_, &json, pointer_ + "/" + std::to_string(index));
}

const JsonValue& JsonValue::expect_object() const {
  if (!json_->is_object()) fail(expected("an object", *json_));
  return *this;
}

bool JsonValue::has(std::string_view key) const {
  return json_->is_object() && json_->find(key) != json_->end();
}

JsonValue JsonValue::at(std::string_view key) const {
  expect_object();
  auto it = json_->find(key);
  if (it == json_->end()) fail("missing field \"" + std::string(key) + "\"");
  return child(*it, key);
}

std::optional<JsonValue> JsonValue::find(std::string_view key) const {
  expect_object();
  auto it = json_->find(key);
  if (it == json_->end()) return std::nullopt;
  return child(*it, key);
}

std::vector<std::pair<std::string, JsonValue>> JsonValue::members() const {
  expect_object();
  std::vector<std::pair<std::string, JsonValue>> out;
  out.reserve(json_->size());
  for (auto it = json_->begin(); it != json_->end(); ++it)
    out.emplace_back(it.key(), child(*it, it.key()));
  return out;
}

void JsonValue::only_keys(std::initializer_list<std::string_view> keys) const {
  expect_object();
  if (!reader_->strict()) return;  // a newer minor version may add fields: ignore them
  const bool root = pointer_.empty() && reader_->versioned();
  for (auto it = json_->begin(); it != json_->end(); ++it) {
    const std::string& k = it.key();
    bool known = root && (k == "format" || k == "version" || k == "generator");
    for (std::string_view key : keys) known = known || k == key;
    if (!known) child(*it, k).fail("unknown field \"" + k + "\"");
  }
}

void JsonValue::only_keys(const std::vector<std::string>& keys) const {
  expect_object();
  if (!reader_->strict()) return;
  const bool root = pointer_.empty() && reader_->versioned();
  for (auto it = json_->begin(); it != json_->end(); ++it) {
    const std::string& k = it.key();
    bool known = root && (k == "format" || k == "version" || k == "generator");
    for (const std::string& key : keys) known = known || k == key;
    if (!known) child(*it, k).fail("unknown field \"" + k + "\"");
  }
}

const JsonValue& JsonValue::expect_array() const {
  if (!json_->is_array()) fail(expected("an array", *json_));
  return *this;
}

const JsonValue& JsonValue::expect_array(std::size_t size) const {
  expect_array();
  if (json_->size() != size)
    fail("expected " + std::to_string(size) + " elements, got " + std::to_string(json_->size()));
  return *this;
}

JsonValue JsonValue::operator[](std::size_t i) const {
  expect_array();
  if (i >= json_->size())
    fail("index " + std::to_string(i) + " out of range (" + std::to_string(json_->size()) +
         " elements)");
  return child((*json_)[i], i);
}

std::vector<JsonValue> JsonValue::items() const {
  expect_array();
  std::vector<JsonValue> out;
  out.reserve(json_->size());
  for (std::size_t i = 0; i < json_->size(); ++i) out.push_back(child((*json_)[i], i));
  return out;
}

std::string JsonValue::string() const {
  if (!json_->is_string()) fail(expected("a string", *json_));
  return json_->get<std::string>();
}

std::string JsonValue::non_empty_string() const {
  std::string s = string();
  if (s.empty()) fail("must not be empty");
  return s;
}

bool JsonValue::boolean() const {
  if (!json_->is_boolean()) fail(expected("true or false", *json_));
  return json_->get<bool>();
}

double JsonValue::number() const {
  if (!json_->is_number()) fail(expected("a number", *json_));
  const double v = json_->get<double>();
  if (!std::isfinite(v)) fail("not a finite number");
  return v;
}

double JsonValue::number(double lo, double hi) const {
  const double v = number();
  if (!(v >= lo && v <= hi))
    fail(format_number(v) + " is out of range [" + format_number(lo) + ", " + format_number(hi) +
         "]");
  return v;
}

std::int64_t JsonValue::integer(std::int64_t lo, std::int64_t hi) const {
  if (!json_->is_number()) fail(expected("an integer", *json_));
  std::int64_t v = 0;
  if (json_->is_number_unsigned()) {
    const auto u = json_->get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(INT64_MAX))
      fail(std::to_string(u) + " is out of range [" + std::to_string(lo) + ", " +
           std::to_string(hi) + "]");
    v = static_cast<std::int64_t>(u);
  } else if (json_->is_number_integer()) {
    v = json_->get<std::int64_t>();
  } else {
    const double d = json_->get<double>();
    if (!std::isfinite(d) || d != std::floor(d))
      fail("expected an integer, got " + format_number(d));
    if (!(d >= static_cast<double>(lo) && d <= static_cast<double>(hi)))
      fail(format_number(d) + " is out of range [" + std::to_string(lo) + ", " +
           std::to_string(hi) + "]");
    v = static_cast<std::int64_t>(d);
  }
  if (v < lo || v > hi)
    fail(std::to_string(v) + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) +
         "]");
  return v;
}

std::size_t JsonValue::index(std::size_t hi) const {
  const auto cap =
      static_cast<std::int64_t>(std::min<std::size_t>(hi, static_cast<std::size_t>(INT64_MAX)));
  return static_cast<std::size_t>(integer(0, cap));
}

double JsonValue::number_or(std::string_view key, double fallback) const {
  auto v = find(key);
  return v ? v->number() : fallback;
}

double JsonValue::number_or(std::string_view key, double fallback, double lo, double hi) const {
  auto v = find(key);
  return v ? v->number(lo, hi) : fallback;
}

std::string JsonValue::string_or(std::string_view key, std::string fallback) const {
  auto v = find(key);
  return v ? v->string() : std::move(fallback);
}

bool JsonValue::boolean_or(std::string_view key, bool fallback) const {
  auto v = find(key);
  return v ? v->boolean() : fallback;
}

// --- JsonReader
// --------------------------------------------------------------------------------------

JsonReader::JsonReader(std::string_view text, std::string file, std::string_view kind,
                       FormatVersion supported)
    : JsonReader(ParsedJson{parse_json(text, file)}, file, kind, supported) {}

JsonReader::JsonReader(ParsedJson document, std::string file, std::string_view kind,
                       FormatVersion supported)
    : document_(std::move(document.json)), file_(std::move(file)), versioned_(true) {
  version_ = check_envelope(document_, kind, supported, file_);
  strict_ = rejects_unknown_fields(version_, supported);
}

JsonReader::JsonReader(ParsedJson document, std::string file, bool strict)
    : document_(std::move(document.json)), file_(std::move(file)), strict_(strict) {}

void JsonReader::fail(const std::string& pointer, const std::string& message) const {
  SourceLocation where;
  where.file = file_;
  where.json_pointer = pointer;
  throw FormatError(where, message);
}

}  // namespace emoface::core
