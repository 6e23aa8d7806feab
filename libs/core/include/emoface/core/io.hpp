#pragma once
// File helpers shared by every library: the versioned JSON envelope, bounded reads with located parse
// errors, and atomic writes (temporary file + rename), so a failed run never leaves half a file.
//
// Every JSON document emoface writes starts with
//   {"format": "emoface.<kind>", "version": "MAJOR.MINOR", "generator": "emoface x.y.z", ...}
// Minor versions only add fields; readers accept any minor of a major they know and reject a newer major.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "emoface/core/errors.hpp"

namespace emoface::core {

struct FormatVersion {
  int major = 1;
  int minor = 0;
  std::string to_string() const;
};

/// Parses "MAJOR.MINOR" (both non-negative integers). Throws InvalidInput otherwise.
FormatVersion parse_format_version(std::string_view text);

/// {"format": "emoface.<kind>", "version": "M.m", "generator": "emoface x.y.z"}.
nlohmann::ordered_json make_envelope(std::string_view kind, FormatVersion version);

/// The first line of every NDJSON stream emoface writes: the envelope alone, as one JSON object and '\n'
/// (the stream's version stamp). Readers skip it (is_stream_header) and accept streams without it.
std::string ndjson_header(std::string_view kind, FormatVersion version);
/// True if `record` is a stream header: an object whose only members are "format" (a string starting
/// with "emoface."), "version" and "generator".
bool is_stream_header(const nlohmann::json& record);
bool is_stream_header(const nlohmann::ordered_json& record);

/// Checks that `doc` is an object with format "emoface.<kind>" and a version whose major equals
/// `supported.major` (newer minors are fine, an older or newer major is not). Returns the version found.
/// Throws FormatError naming `file` and the offending field.
template <class Json>
FormatVersion check_envelope(const Json& doc, std::string_view kind, FormatVersion supported,
                             const std::string& file);

/// Default cap on files read into memory (256 MiB): a bigger file is refused, not swallowed.
inline constexpr std::size_t kDefaultMaxFileBytes = std::size_t{256} << 20;

/// Reads a whole file. Throws IoError if it cannot be opened or is larger than max_bytes.
std::string read_file(const std::string& path, std::size_t max_bytes = kDefaultMaxFileBytes);

/// Parses JSON text; a syntax error becomes FormatError with the 1-based line and column.
nlohmann::ordered_json parse_json(std::string_view text, const std::string& file);

/// read_file + parse_json.
nlohmann::ordered_json read_json_file(const std::string& path,
                                      std::size_t max_bytes = kDefaultMaxFileBytes);

/// Writes `content` to `path` atomically: a temporary file in the same directory, flushed, then
/// renamed over `path`. On any failure `path` is untouched and IoError is thrown.
void write_file_atomic(const std::string& path, std::string_view content);

/// Streaming counterpart of write_file_atomic: write() appends to a temporary file beside `path`;
/// commit() flushes and renames it into place; destroying an uncommitted AtomicFile removes the
/// temporary file, so `path` is either the complete new file or untouched. A symbolic link is followed
/// (the file it names is replaced, the link stays). An existing device or FIFO (/dev/null, a pipe) is
/// written directly — never replaced — and there atomicity does not apply; a directory is an IoError.
class AtomicFile {
 public:
  explicit AtomicFile(std::string path);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  void write(std::string_view data);
  void commit();
  const std::string& path() const noexcept { return path_; }

 private:
  std::string path_;
  std::string target_path_;  // path_, or the file a symbolic link at path_ names
  std::string temp_path_;
  int fd_ = -1;
  bool committed_ = false;
  bool direct_ = false;  // writing straight to a device or FIFO

};

/// Escapes a JSON-pointer reference token (RFC 6901: "~" → "~0", "/" → "~1").
std::string json_pointer_token(std::string_view token);

}  // namespace emoface::core

#include "emoface/core/detail/io_impl.hpp"
