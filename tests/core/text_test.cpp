#include "emoface/core/text.hpp"

#include <gtest/gtest.h>

#include <clocale>
#include <cmath>
#include <limits>
#include <vector>

#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"

namespace emoface::core {
namespace {

std::vector<std::pair<std::size_t, std::string>> all_lines(std::string_view text) {
  std::vector<std::pair<std::size_t, std::string>> out;
  for (const Line& l : Lines(text)) out.emplace_back(l.number, std::string(l.text));
  return out;
}

TEST(Lines, NumbersLinesAndStripsCr) {
  using V = std::vector<std::pair<std::size_t, std::string>>;
  EXPECT_EQ(all_lines(""), V{});
  EXPECT_EQ(all_lines("a"), (V{{1, "a"}}));
  EXPECT_EQ(all_lines("a\n"), (V{{1, "a"}}));
  EXPECT_EQ(all_lines("a\r\n\nb"), (V{{1, "a"}, {2, ""}, {3, "b"}}));
  EXPECT_EQ(all_lines("\n\n"), (V{{1, ""}, {2, ""}}));
}

TEST(ParseNumber, AcceptsDecimalAndScientific) {
  EXPECT_EQ(parse_number("1.5"), 1.5);
  EXPECT_EQ(parse_number(" -2.25e1\t"), -22.5);
  EXPECT_EQ(parse_number("+3"), 3.0);
  EXPECT_EQ(parse_number(".5"), 0.5);
  EXPECT_EQ(parse_number("0.1"), 0.1);        // the same double as the literal: correctly rounded
  EXPECT_EQ(parse_number("1e-320"), 1e-320);  // subnormal
}

TEST(ParseNumber, RefusesJunkNonFiniteAndOverflow) {
  for (const char* bad : {"", " ", "abc", "1.5x", "1,5", "--1", "+-1", "+", "0x10", "1e400", "nan",
                          "inf", "-inf", "1 2"})
    EXPECT_FALSE(parse_number(bad).has_value()) << bad;
  EXPECT_TRUE(std::isinf(*parse_number("inf", true)));
  EXPECT_TRUE(std::isnan(*parse_number("nan", true)));
}

TEST(ParseNumber, IgnoresTheCLocale) {
  // A locale with a decimal comma would make strtod stop at '.'; from_chars does not care.
  if (std::setlocale(LC_NUMERIC, "de_DE.UTF-8") == nullptr &&
      std::setlocale(LC_NUMERIC, "fr_FR.UTF-8") == nullptr)
    GTEST_SKIP() << "no decimal-comma locale installed";
  EXPECT_EQ(parse_number("1.5"), 1.5);
  EXPECT_FALSE(parse_number("1,5").has_value());
  std::setlocale(LC_NUMERIC, "C");
}

TEST(AsciiLower, OnlyAsciiLettersChange) {
  EXPECT_EQ(ascii_lower("JawOpen_L.GLB"), "jawopen_l.glb");
  EXPECT_EQ(ascii_lower(""), "");
  EXPECT_EQ(ascii_lower("@[`{ 09"), "@[`{ 09");    // the bytes next to A–Z and a–z stay
  EXPECT_EQ(ascii_lower("\xC4\xD6"), "\xC4\xD6");  // not ASCII: unchanged (Latin-1 Ä Ö)
}

TEST(ParseInteger, RangeAndJunk) {
  EXPECT_EQ(parse_integer("42"), 42);
  EXPECT_EQ(parse_integer(" -7 "), -7);
  EXPECT_EQ(parse_integer("9223372036854775807"), std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ(parse_integer("-9223372036854775808"), std::numeric_limits<std::int64_t>::min());
  for (const char* bad :
       {"", "9223372036854775808", "-9223372036854775809", "1.0", "1e3", "x", "-"})
    EXPECT_FALSE(parse_integer(bad).has_value()) << bad;
}

TEST(FormatNumber, ShortestRoundTrip) {
  EXPECT_EQ(format_number(0.1), "0.1");
  EXPECT_EQ(format_number(2.5), "2.5");
  EXPECT_EQ(format_number(-3), "-3");
  EXPECT_EQ(format_number(std::nan("")), "nan");
  EXPECT_EQ(format_number(-INFINITY), "-inf");
  const double third = 1.0 / 3.0;
  EXPECT_EQ(parse_number(format_number(third)), third);
}

TEST(OnError, StringRoundTrip) {
  for (OnError v : {OnError::Stop, OnError::Skip}) EXPECT_EQ(on_error_from_string(to_string(v)), v);
  EXPECT_FALSE(on_error_from_string("Stop").has_value());
  EXPECT_FALSE(on_error_from_string("").has_value());
}

std::string csv_error(std::string_view text) {
  try {
    CsvTable::parse(text, "t.csv");
  } catch (const FormatError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(CsvTable, SkipsStampCommentsBlankLinesAndRepeatedHeaders) {
  const std::string text =
      "\xEF\xBB\xBF# emoface 0.1.0\nid,x\r\na,1\n\n# emoface 0.1.0\nid,x\nb,2.5\n";
  const CsvTable t = CsvTable::parse(text, "t.csv");
  EXPECT_EQ(t.header(), (std::vector<std::string>{"id", "x"}));
  EXPECT_EQ(t.header_line(), 2u);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.rows()[0].line, 3u);
  EXPECT_EQ(t.rows()[1].line, 7u);
  EXPECT_EQ(t.field(1, 0), "b");
  EXPECT_EQ(t.number(1, *t.column("x")), 2.5);
  EXPECT_EQ(t.column("X", true), 1u);
  EXPECT_FALSE(t.column("X").has_value());
}

TEST(CsvTable, ErrorsNameFileLineAndColumn) {
  EXPECT_EQ(csv_error(""), "t.csv:1: no header row");
  EXPECT_EQ(csv_error("# only a stamp\n"), "t.csv:1: no header row");
  EXPECT_EQ(csv_error("a,b\n1\n"), "t.csv:2: expected 2 fields (as the header), got 1");
  EXPECT_EQ(csv_error("a,b\n1,\"x\n"), "t.csv:2:5: malformed CSV: unterminated quoted field");
  EXPECT_EQ(csv_error("a,a\n"), "t.csv:1:2: duplicate column \"a\"");
  EXPECT_EQ(csv_error("a,\n"), "t.csv:1:2: empty column name");
  EXPECT_EQ(csv_error("a\n\xFF\n"), "t.csv:2: not valid UTF-8");
  const CsvTable t = CsvTable::parse("a,b\n1,nan\n2,x\n", "t.csv");
  try {
    t.number(0, 1);
    FAIL();
  } catch (const FormatError& e) {
    EXPECT_STREQ(e.what(), "t.csv:2:2: column \"b\": expected a finite number, got \"nan\"");
    EXPECT_EQ(e.where().line, 2u);
  }
  EXPECT_THROW(t.number(1, 1), FormatError);
  EXPECT_THROW(t.require_column("c"), FormatError);
  EXPECT_THROW(t.field(5, 0), InvalidInput);
}

TEST(CsvTable, HugeRowCountStaysLinear) {
  std::string text = "id,v\n";
  for (int i = 0; i < 100000; ++i) text += std::to_string(i) + "," + std::to_string(i * 0.5) + "\n";
  const CsvTable t = CsvTable::parse(text, "big.csv");
  ASSERT_EQ(t.size(), 100000u);
  EXPECT_EQ(t.number(99999, 1), 99999 * 0.5);
}

}  // namespace
}  // namespace emoface::core
