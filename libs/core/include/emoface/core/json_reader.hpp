#pragma once
// The one located JSON reader of emoface (issue 18, item 1). Every library reads its documents
// through it, so they agree on three things:
//
// * the unknown-field rule of docs/formats.md: a document whose version has a *newer minor* than
// the
//   reader's may add fields, and they are ignored; a document of the same or an older minor version
//   rejects unknown fields with a located error (typos do not pass silently);
// * JSON pointers (RFC 6901, "~" → "~0", "/" → "~1") naming the value an error is about;
// * one message style, that of FormatError: "FILE: at /pointer: message".
//
//   core::JsonReader doc(text, "rig.json", "fuzzyrules", {1, 0});   // parses, checks the envelope
//   core::JsonValue root = doc.root();
//   root.only_keys({"input_sets", "single"});   // envelope fields are always allowed at the root
//   for (const core::JsonValue& s : root.at("input_sets").items()) s.at("name").string();
//   double x = root.at("gain").number(0.0, 10.0);  // "FILE: at /gain: 12 is out of range [0, 10]"
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"

namespace emoface::core {

class JsonReader;

/// A document parsed already, handed to a JsonReader (a distinct type, so a JSON text and a parsed
/// document never compete for the same constructor).
struct ParsedJson {
  nlohmann::ordered_json json;
};

/// One value of a document read by a JsonReader, with the pointer that names it. A JsonValue refers
/// to its reader and to the parsed document: it is valid while the reader lives. Every accessor
/// that finds something wrong throws FormatError naming the file and this value's (or the child's)
/// pointer.
class JsonValue {
 public:
  using Json = nlohmann::ordered_json;

  const Json& json() const noexcept { return *json_; }
  /// RFC 6901 pointer of this value ("" for the root).
  const std::string& pointer() const noexcept { return pointer_; }
  const JsonReader& reader() const noexcept { return *reader_; }
  /// Throws FormatError at this value.
  [[noreturn]] void fail(const std::string& message) const;

  bool is_null() const noexcept { return json_->is_null(); }
  bool is_object() const noexcept { return json_->is_object(); }
  bool is_array() const noexcept { return json_->is_array(); }
  bool is_string() const noexcept { return json_->is_string(); }
  bool is_number() const noexcept { return json_->is_number(); }
  bool is_boolean() const noexcept { return json_->is_boolean(); }

  // --- objects
  // -------------------------------------------------------------------------------------
  /// Throws unless this is an object; returns *this.
  const JsonValue& expect_object() const;
  /// True if this is an object with member `key`.
  bool has(std::string_view key) const;
  /// The member `key` of this object ("expected an object" / "missing field \"key\"").
  JsonValue at(std::string_view key) const;
  /// The member `key`, or nothing if absent (a null member counts as present).
  std::optional<JsonValue> find(std::string_view key) const;
  /// The members of this object, in document order.
  std::vector<std::pair<std::string, JsonValue>> members() const;
  /// The unknown-field rule: if the reader is strict (document version ≤ reader version), every
  /// member must be one of `keys`, else FormatError at the first unknown one ("unknown field
  /// \"x\""). At the root of a versioned document "format", "version" and "generator" are always
  /// allowed.
  void only_keys(std::initializer_list<std::string_view> keys) const;
  void only_keys(const std::vector<std::string>& keys) const;

  // --- arrays
  // --------------------------------------------------------------------------------------
  /// Throws unless this is an array (optionally of exactly `size` elements); returns *this.
  const JsonValue& expect_array() const;
  const JsonValue& expect_array(std::size_t size) const;
  /// Element `i` of this array ("expected an array" / "index i out of range").
  JsonValue operator[](std::size_t i) const;
  /// The elements of this array.
  std::vector<JsonValue> items() const;
  /// Number of elements of an array or members of an object (0 for anything else).
  std::size_t size() const noexcept { return json_->size(); }

  // --- scalars
  // -------------------------------------------------------------------------------------
  std::string string() const;            ///< "expected a string"
  std::string non_empty_string() const;  ///< and "must not be empty"
  bool boolean() const;                  ///< "expected true or false"
  /// A finite number ("expected a number"; NaN/inf, which nlohmann can hold, "not a finite
  /// number").
  double number() const;
  /// A finite number in [lo, hi] ("12 is out of range [0, 10]").
  double number(double lo, double hi) const;
  /// An integer in [lo, hi] (a number with a fractional part is "expected an integer").
  std::int64_t integer(std::int64_t lo, std::int64_t hi) const;
  /// integer() for a count or an index.
  std::size_t index(std::size_t hi) const;

  // --- optional members with defaults
  // --------------------------------------------------------------
  double number_or(std::string_view key, double fallback) const;
  double number_or(std::string_view key, double fallback, double lo, double hi) const;
  std::string string_or(std::string_view key, std::string fallback) const;
  bool boolean_or(std::string_view key, bool fallback) const;

 private:
  friend class JsonReader;

  /// A document parsed already, handed to a JsonReader (a distinct type, so a JSON text and a
  /// parsed document never compete for the same constructor).
  struct ParsedJson {
    nlohmann::ordered_json json;
  };
  JsonValue(const JsonReader* reader, const Json* json, std::string pointer)
      : reader_(reader), json_(json), pointer_(std::move(pointer)) {}
  JsonValue child(const Json& json, std::string_view token) const;
  JsonValue child(const Json& json, std::size_t index) const;

  const JsonReader* reader_;
  const Json* json_;
  std::string pointer_;
};

/// A parsed document plus the rule for reading it. Not copyable or movable (JsonValues point into
/// it); construct it where it is used.
class JsonReader {
 public:
  using Json = nlohmann::ordered_json;

  /// Parses `text` (syntax errors: FormatError with line and column) and checks the envelope
  /// {"format": "emoface.<kind>", "version": "M.m"} against `supported` (check_envelope). Unknown
  /// fields are errors unless the document's minor version is newer than supported.minor.
  JsonReader(std::string_view text, std::string file, std::string_view kind,
             FormatVersion supported);
  /// The same for a document parsed already.
  JsonReader(ParsedJson document, std::string file, std::string_view kind, FormatVersion supported);
  /// A document without the emoface envelope (a third-party format): `strict` says whether unknown
  /// fields are errors.
  JsonReader(ParsedJson document, std::string file, bool strict);

  JsonReader(const JsonReader&) = delete;
  JsonReader& operator=(const JsonReader&) = delete;

  JsonValue root() const { return JsonValue(this, &document_, ""); }
  const std::string& file() const noexcept { return file_; }
  /// The version the document declares ({0, 0} for an unversioned document).
  FormatVersion version() const noexcept { return version_; }
  /// True if unknown fields are errors.
  bool strict() const noexcept { return strict_; }
  bool versioned() const noexcept { return versioned_; }
  /// Throws FormatError at `pointer`.
  [[noreturn]] void fail(const std::string& pointer, const std::string& message) const;

 private:
  Json document_;
  std::string file_;
  FormatVersion version_{0, 0};
  bool strict_ = true;
  bool versioned_ = false;
};

/// The unknown-field rule on its own: true if a document of version `found` read by a reader of
/// version `supported` (same major) must reject unknown fields, i.e. found.minor <=
/// supported.minor.
constexpr bool rejects_unknown_fields(FormatVersion found, FormatVersion supported) noexcept {
  return found.minor <= supported.minor;
}

}  // namespace emoface::core
