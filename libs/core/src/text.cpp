#include "emoface/core/text.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

namespace emoface::core {

Lines::iterator::iterator(std::string_view text) noexcept : text_(text), at_end_(false) { ++*this; }

Lines::iterator& Lines::iterator::operator++() noexcept {
  if (at_end_) return *this;
  if (next_ >= text_.size()) {
    at_end_ = true;
    return *this;
  }
  const std::size_t start = next_;
  std::size_t nl = text_.find('\n', start);
  const std::size_t stop = nl == std::string_view::npos ? text_.size() : nl;
  next_ = nl == std::string_view::npos ? text_.size() : nl + 1;
  std::string_view line = text_.substr(start, stop - start);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  line_.text = line;
  ++line_.number;
  return *this;
}

std::string_view trim(std::string_view s) noexcept {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::string ascii_lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

std::optional<double> parse_number(std::string_view text, bool allow_non_finite) noexcept {
  text = trim(text);
  bool negative = false;
  if (!text.empty() && (text.front() == '+' || text.front() == '-')) {
    negative = text.front() == '-';
    text.remove_prefix(1);
  }
  // from_chars takes its own '-'; a second sign ("+-1", "--1") must fail.
  if (text.empty() || text.front() == '+' || text.front() == '-') return std::nullopt;
  double value = 0.0;
  const char* first = text.data();
  const char* last = first + text.size();
  const auto [ptr, ec] = std::from_chars(first, last, value, std::chars_format::general);
  if (ec != std::errc() || ptr != last) return std::nullopt;
  if (!allow_non_finite && !std::isfinite(value)) return std::nullopt;
  return negative ? -value : value;
}

std::optional<std::int64_t> parse_integer(std::string_view text) noexcept {
  text = trim(text);
  bool negative = false;
  if (!text.empty() && (text.front() == '+' || text.front() == '-')) {
    negative = text.front() == '-';
    text.remove_prefix(1);
  }
  if (text.empty() || text.front() < '0' || text.front() > '9') return std::nullopt;
  // Parse the magnitude as unsigned so that INT64_MIN reads.
  std::uint64_t magnitude = 0;
  const char* last = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), last, magnitude);
  if (ec != std::errc() || ptr != last) return std::nullopt;
  constexpr std::uint64_t kMax = static_cast<std::uint64_t>(INT64_MAX);
  if (negative) {
    if (magnitude > kMax + 1) return std::nullopt;
    if (magnitude == kMax + 1) return INT64_MIN;
    return -static_cast<std::int64_t>(magnitude);
  }
  if (magnitude > kMax) return std::nullopt;
  return static_cast<std::int64_t>(magnitude);
}

std::string format_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buf[32];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, value);
  (void)ec;  // 32 bytes always hold the shortest form of a double
  return std::string(buf, ptr);
}

std::string_view to_string(OnError value) noexcept {
  return value == OnError::Skip ? "skip" : "stop";
}

std::optional<OnError> on_error_from_string(std::string_view text) noexcept {
  if (text == "stop") return OnError::Stop;
  if (text == "skip") return OnError::Skip;
  return std::nullopt;
}

}  // namespace emoface::core
