#include "emoface/core/csv.hpp"

#include <cstdint>
#include <set>

#include "emoface/core/errors.hpp"
#include "emoface/core/text.hpp"
#include "emoface/core/version.hpp"

namespace emoface::core {

std::size_t split_csv_line(std::string_view line, std::vector<std::string>& fields,
                           std::string* error) {
  fields.clear();
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  auto fail = [&](std::size_t pos, const char* why) {
    if (error) *error = why;
    return pos + 1;
  };
  std::string field;
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (true) {
    field.clear();
    if (i < n && line[i] == '"') {
      ++i;
      bool closed = false;
      while (i < n) {
        char c = line[i];
        if (c == '"') {
          if (i + 1 < n && line[i + 1] == '"') {
            field += '"';
            i += 2;
          } else {
            ++i;
            closed = true;
            break;
          }
        } else {
          field += c;
          ++i;
        }
      }
      if (!closed) return fail(n, "unterminated quoted field");
      if (i < n && line[i] != ',') return fail(i, "text after a closing quote");
    } else {
      while (i < n && line[i] != ',') {
        if (line[i] == '"') return fail(i, "quote inside an unquoted field");
        field += line[i++];
      }
    }
    fields.push_back(field);
    if (i >= n) break;
    ++i;  // skip the comma
  }
  return 0;
}

void append_csv_field(std::string& out, std::string_view field) {
  if (field.find_first_of(",\"\r\n") == std::string_view::npos) {
    out.append(field);
    return;
  }
  out += '"';
  for (char c : field) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
}

bool is_valid_utf8(std::string_view text, std::size_t* bad_offset) {
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  std::size_t i = 0;
  auto bad = [&](std::size_t at) {
    if (bad_offset) *bad_offset = at;
    return false;
  };
  while (i < n) {
    unsigned char c = s[i];
    if (c < 0x80) {
      ++i;
      continue;
    }
    std::size_t len;
    unsigned cp;
    if ((c & 0xE0) == 0xC0) {
      len = 2;
      cp = c & 0x1F;
    } else if ((c & 0xF0) == 0xE0) {
      len = 3;
      cp = c & 0x0F;
    } else if ((c & 0xF8) == 0xF0) {
      len = 4;
      cp = c & 0x07;
    } else {
      return bad(i);
    }
    if (i + len > n) return bad(i);
    for (std::size_t k = 1; k < len; ++k) {
      if ((s[i + k] & 0xC0) != 0x80) return bad(i);
      cp = (cp << 6) | (s[i + k] & 0x3F);
    }
    if ((len == 2 && cp < 0x80) || (len == 3 && cp < 0x800) || (len == 4 && cp < 0x10000) ||
        cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF))
      return bad(i);
    i += len;
  }
  return true;
}

std::string csv_stamp() { return std::string("# ") + kGenerator + "\n"; }

bool is_csv_comment(std::string_view line) noexcept {
  if (line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);
  return !line.empty() && line.front() == '#';
}

namespace {

bool equal_ignore_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

[[noreturn]] void fail_at(const std::string& file, std::size_t line, std::size_t column,
                          const std::string& message) {
  SourceLocation where;
  where.file = file;
  where.line = line;
  where.column = column;
  throw FormatError(where, message);
}

}  // namespace

CsvTable CsvTable::parse(std::string_view text, std::string file) {
  CsvTable t;
  t.file_ = std::move(file);
  std::size_t bad = 0;
  if (!is_valid_utf8(text, &bad)) {
    std::size_t line = 1;
    for (std::size_t i = 0; i < bad; ++i) line += text[i] == '\n';
    fail_at(t.file_, line, 0, "not valid UTF-8");
  }
  std::vector<std::string> fields;
  std::string why;
  bool have_header = false;
  for (const Line& line : Lines(text)) {
    if (is_csv_comment(line.text) || trim(line.text).empty()) continue;
    std::string_view body = line.text;
    if (!have_header && body.substr(0, 3) == "\xEF\xBB\xBF") body.remove_prefix(3);
    if (std::size_t col = split_csv_line(body, fields, &why))
      fail_at(t.file_, line.number, col, "malformed CSV: " + why);
    if (!have_header) {
      std::set<std::string> seen;
      for (std::size_t i = 0; i < fields.size(); ++i) {
        if (trim(fields[i]).empty()) fail_at(t.file_, line.number, i + 1, "empty column name");
        if (!seen.insert(fields[i]).second)
          fail_at(t.file_, line.number, i + 1, "duplicate column \"" + fields[i] + "\"");
      }
      t.header_ = fields;
      t.header_line_ = line.number;
      have_header = true;
      continue;
    }
    if (fields == t.header_) continue;  // the header of a concatenated shard
    if (fields.size() != t.header_.size())
      fail_at(t.file_, line.number, 0,
              "expected " + std::to_string(t.header_.size()) + " fields (as the header), got " +
                  std::to_string(fields.size()));
    t.rows_.push_back(Row{line.number, fields});
  }
  if (!have_header) fail_at(t.file_, 1, 0, "no header row");
  return t;
}

std::optional<std::size_t> CsvTable::column(std::string_view name, bool ignore_case) const {
  for (std::size_t i = 0; i < header_.size(); ++i)
    if (ignore_case ? equal_ignore_case(header_[i], name) : header_[i] == name) return i;
  return std::nullopt;
}

std::size_t CsvTable::require_column(std::string_view name, bool ignore_case) const {
  auto c = column(name, ignore_case);
  if (!c) fail_at(file_, header_line_, 0, "missing column \"" + std::string(name) + "\"");
  return *c;
}

const std::string& CsvTable::field(std::size_t row, std::size_t col) const {
  if (row >= rows_.size() || col >= header_.size())
    throw InvalidInput("CsvTable::field: row or column out of range");
  return rows_[row].fields[col];
}

double CsvTable::number(std::size_t row, std::size_t col) const {
  const std::string& f = field(row, col);
  auto v = parse_number(f);
  if (!v)
    fail(row, col, "column \"" + header_[col] + "\": expected a finite number, got \"" + f + "\"");
  return *v;
}

void CsvTable::fail(std::size_t row, std::size_t col, const std::string& message) const {
  if (row >= rows_.size()) throw InvalidInput("CsvTable::fail: row out of range");
  fail_at(file_, rows_[row].line, col == SIZE_MAX ? 0 : col + 1, message);
}

}  // namespace emoface::core
