#pragma once
// Minimal RFC 4180 CSV line handling shared by the stream readers and writers of every library.
// A record is one physical line (quoted fields may contain commas and doubled quotes, not newlines).
#include <cstddef>
#include <optional>
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

/// A whole CSV text read at once: comment lines ('#', e.g. the "# emoface x.y.z" stamp) and blank
/// lines are skipped anywhere, the first other line is the header, and a later line equal to the
/// header is skipped too (so concatenated shards read back). Every row must have as many fields as
/// the header. Every error is a FormatError "FILE:LINE:COLUMN: message" (COLUMN = 1-based field
/// number).
class CsvTable {
 public:
  struct Row {
    std::size_t line = 0;  ///< 1-based line number in the text
    std::vector<std::string> fields;
  };

  /// Parses `text`; `file` names it in errors. Throws FormatError on a malformed line, a row of the
  /// wrong width, a duplicate or empty header name, or a text without a header.
  static CsvTable parse(std::string_view text, std::string file);

  const std::string& file() const noexcept { return file_; }
  const std::vector<std::string>& header() const noexcept { return header_; }
  std::size_t header_line() const noexcept { return header_line_; }
  const std::vector<Row>& rows() const noexcept { return rows_; }
  std::size_t size() const noexcept { return rows_.size(); }

  /// Index of the column named `name` (exact, or ASCII-case-insensitive if `ignore_case`).
  std::optional<std::size_t> column(std::string_view name, bool ignore_case = false) const;
  /// column(), or FormatError at the header line ("missing column \"name\"").
  std::size_t require_column(std::string_view name, bool ignore_case = false) const;

  const std::string& field(std::size_t row, std::size_t col) const;
  /// The field as a finite, locale-free number (parse_number), or FormatError at its line and
  /// column
  /// ("column \"x\": expected a number, got \"abc\"").
  double number(std::size_t row, std::size_t col) const;
  /// FormatError at row `row`, field `col` (col = SIZE_MAX: no column).
  [[noreturn]] void fail(std::size_t row, std::size_t col, const std::string& message) const;

 private:
  std::string file_;
  std::vector<std::string> header_;
  std::size_t header_line_ = 0;
  std::vector<Row> rows_;
};

}  // namespace emoface::core
