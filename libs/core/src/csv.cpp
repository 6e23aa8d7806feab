#include "emoface/core/csv.hpp"

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

}  // namespace emoface::core
