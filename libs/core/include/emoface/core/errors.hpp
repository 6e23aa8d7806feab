#pragma once
// The one error hierarchy of emoface (docs/CODING_STYLE.md, "Errors").
//
//   Error          : std::runtime_error      — base of everything a library throws at run time
//   InvalidInput   : std::invalid_argument   — a caller's mistake (bad argument, bad option)
//   IoError        : Error                   — a file could not be opened, read or written
//   FormatError    : Error                   — a file or stream has bad content; names file + location
//   NumericalError : Error                   — a computation produced NaN/inf or could not proceed
//
// Every emoface exception can be caught as std::exception; code that must tell emoface errors
// from others catches emoface::Error and emoface::InvalidInput.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace emoface {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class InvalidInput : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class IoError : public Error {
 public:
  using Error::Error;
};

class NumericalError : public Error {
 public:
  using Error::Error;
};

/// Where in a file a problem is: a JSON pointer ("/rules/sadness/0") or a line and column (1-based,
/// 0 = unknown). Either, both or neither may be set.
struct SourceLocation {
  std::string file;          ///< path or a stream name such as "<stdin>"; may be empty
  std::string json_pointer;  ///< RFC 6901 pointer into a JSON document; may be empty
  std::size_t line = 0;      ///< 1-based line, 0 if unknown
  std::size_t column = 0;    ///< 1-based column (CSV: field number), 0 if unknown
};

/// Bad content in a file or stream. what() reads "file:line:column: message" or
/// "file: at /json/pointer: message", so a CLI can print it as it is.
class FormatError : public Error {
 public:
  FormatError(SourceLocation where, const std::string& message);

  const SourceLocation& where() const noexcept { return where_; }
  /// The message without the location prefix.
  const std::string& message() const noexcept { return message_; }

 private:
  SourceLocation where_;
  std::string message_;
};

/// Formats a location as the prefix used by FormatError ("file:12:3", "file: at /a/0").
std::string to_string(const SourceLocation& where);

}  // namespace emoface
