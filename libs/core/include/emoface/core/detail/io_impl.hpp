#pragma once
// Template part of io.hpp (works for nlohmann::json and nlohmann::ordered_json).
#include <string>

namespace emoface::core {

template <class Json>
FormatVersion check_envelope(const Json& doc, std::string_view kind, FormatVersion supported,
                             const std::string& file) {
  const std::string expected = "emoface." + std::string(kind);
  auto fail = [&](const std::string& pointer, const std::string& message) {
    SourceLocation where;
    where.file = file;
    where.json_pointer = pointer;
    throw FormatError(where, message);
  };
  if (!doc.is_object()) fail("", "expected a JSON object (" + expected + " document)");
  auto fmt = doc.find("format");
  if (fmt == doc.end() || !fmt->is_string())
    fail("/format", "missing string field \"format\" (expected \"" + expected + "\")");
  if (fmt->template get<std::string>() != expected)
    fail("/format", "unknown format \"" + fmt->template get<std::string>() + "\" (expected \"" +
                        expected + "\")");
  auto ver = doc.find("version");
  if (ver == doc.end() || !ver->is_string())
    fail("/version", "missing string field \"version\" (\"MAJOR.MINOR\")");
  FormatVersion found;
  try {
    found = parse_format_version(ver->template get<std::string>());
  } catch (const InvalidInput& e) {
    fail("/version", e.what());
  }
  if (found.major > supported.major)
    fail("/version", "version " + found.to_string() + " is newer than this reader (" +
                         supported.to_string() + "); upgrade emoface");
  if (found.major < supported.major)
    fail("/version", "version " + found.to_string() + " is an old major version; this reader reads " +
                         std::to_string(supported.major) + ".x");
  return found;
}

}  // namespace emoface::core
