#pragma once
// Minimal RFC 4180 CSV line handling shared by the stream readers and writers of every library.
// A record is one physical line (quoted fields may contain commas and doubled quotes, not newlines).
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace emoface::core {

/// Splits one CSV line into fields. Returns 0 on success; otherwise the 1-based byte column where the
/// line is malformed (a quote inside an unquoted field, an unterminated quoted field, or text after a
/// closing quote), and `error` says which. A trailing '\r' is ignored.
std::size_t split_csv_line(std::string_view line, std::vector<std::string>& fields,
                           std::string* error = nullptr);

/// Appends `field` to `out`, quoted if it contains a comma, quote, CR or LF.
void append_csv_field(std::string& out, std::string_view field);

/// The version stamp every CSV file emoface writes starts with: "# emoface x.y.z\n". CSV readers skip
/// leading lines for which is_csv_comment() holds (before the header row), so stamped files read back and
/// hand-written files without the stamp read as before.
std::string csv_stamp();
/// True if `line` (after an optional UTF-8 byte-order mark) starts with '#'.
bool is_csv_comment(std::string_view line) noexcept;

/// True if `text` is well-formed UTF-8 (no overlong forms, surrogates or code points past U+10FFFF).
/// On failure `bad_offset` (if given) receives the 0-based offset of the first bad byte.
bool is_valid_utf8(std::string_view text, std::size_t* bad_offset = nullptr);

}  // namespace emoface::core
