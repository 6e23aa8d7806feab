#include "emoface/core/errors.hpp"

namespace emoface {

std::string to_string(const SourceLocation& where) {
  std::string out = where.file.empty() ? std::string("<input>") : where.file;
  if (where.line > 0) {
    out += ':' + std::to_string(where.line);
    if (where.column > 0) out += ':' + std::to_string(where.column);
  }
  if (!where.json_pointer.empty()) out += ": at " + where.json_pointer;
  return out;
}

FormatError::FormatError(SourceLocation where, const std::string& message)
    : Error(to_string(where) + ": " + message), where_(std::move(where)), message_(message) {}

}  // namespace emoface
