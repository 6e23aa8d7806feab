#pragma once
// Text helpers every reader shares (issue 18, item 1): one numbered-line iterator, one locale-free
// number parser and formatter (std::from_chars / std::to_chars: "1.5" means 1.5 whatever the C
// locale says), and one OnError policy for streams.
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>

namespace emoface::core {

/// One line of a text: its 1-based number and its content without the '\n' (and without a trailing
/// '\r', so CRLF files read like LF files).
struct Line {
  std::size_t number = 0;
  std::string_view text;
};

/// The lines of a text, for range-for: `for (core::Line line : core::Lines(text)) ...`. A final
/// line without '\n' counts; a text ending in '\n' has no empty last line; an empty text has no
/// lines. The Lines object and `text` must outlive the iteration (the views point into `text`).
class Lines {
 public:
  class iterator {
   public:
    using iterator_category = std::input_iterator_tag;
    using value_type = Line;
    using difference_type = std::ptrdiff_t;
    using pointer = const Line*;
    using reference = const Line&;

    iterator() = default;
    const Line& operator*() const noexcept { return line_; }
    const Line* operator->() const noexcept { return &line_; }
    iterator& operator++() noexcept;
    iterator operator++(int) noexcept {
      iterator old = *this;
      ++*this;
      return old;
    }
    bool operator==(const iterator& o) const noexcept {
      return at_end_ == o.at_end_ && (at_end_ || next_ == o.next_);
    }
    bool operator!=(const iterator& o) const noexcept { return !(*this == o); }

   private:
    friend class Lines;
    explicit iterator(std::string_view text) noexcept;
    std::string_view text_;
    std::size_t next_ = 0;  // offset of the line after line_
    Line line_;
    bool at_end_ = true;
  };

  explicit Lines(std::string_view text) noexcept : text_(text) {}
  iterator begin() const noexcept { return iterator(text_); }
  iterator end() const noexcept { return iterator(); }

 private:
  std::string_view text_;
};

/// Removes leading and trailing spaces and tabs.
std::string_view trim(std::string_view s) noexcept;

/// ASCII lower case (A–Z → a–z; every other byte unchanged, whatever the C locale says): names,
/// keywords and file extensions compared without regard to case.
std::string ascii_lower(std::string_view s);

/// Locale-free decimal number: optional surrounding spaces/tabs, an optional sign ('+' or '-'),
/// then what std::from_chars accepts (fixed or scientific; no hex). The whole field must be used.
/// NaN and infinities ("nan", "inf") are refused unless allow_non_finite; values out of the range
/// of double are refused. Returns nothing on any failure.
std::optional<double> parse_number(std::string_view text, bool allow_non_finite = false) noexcept;

/// Locale-free integer (optional surrounding spaces/tabs, optional sign, decimal digits only).
std::optional<std::int64_t> parse_integer(std::string_view text) noexcept;

/// Shortest text that parses back to exactly `value` (std::to_chars), e.g. 0.1 → "0.1", 1e-07 →
/// "1e-07". NaN → "nan", infinities → "inf" / "-inf".
std::string format_number(double value);

/// What a stream reader or batch does with a bad record: stop at the first one (its FormatError
/// propagates, nothing is written) or skip it (counted and reported) and go on.
enum class OnError : std::uint8_t {
  Stop,  ///< the first bad record ends the batch
  Skip,  ///< bad records are counted and skipped; the good ones go on
};
std::string_view to_string(OnError value) noexcept;  ///< "stop" | "skip"
/// "stop" | "skip" (exact spelling); nothing otherwise.
std::optional<OnError> on_error_from_string(std::string_view text) noexcept;

}  // namespace emoface::core
