#include "emoface/core/csv.hpp"

#include <gtest/gtest.h>

#include "emoface/core/version.hpp"

namespace emoface::core {
namespace {

using Fields = std::vector<std::string>;

TEST(SplitCsvLine, PlainQuotedAndEmptyFields) {
  Fields f;
  EXPECT_EQ(split_csv_line("a,b,,c", f), 0u);
  EXPECT_EQ(f, (Fields{"a", "b", "", "c"}));
  EXPECT_EQ(split_csv_line("\"x,y\",\"he said \"\"hi\"\"\",z\r", f), 0u);
  EXPECT_EQ(f, (Fields{"x,y", "he said \"hi\"", "z"}));
  EXPECT_EQ(split_csv_line("", f), 0u);
  EXPECT_EQ(f, (Fields{""}));
  EXPECT_EQ(split_csv_line("a,", f), 0u);
  EXPECT_EQ(f, (Fields{"a", ""}));
}

TEST(SplitCsvLine, MalformedLinesGiveColumn) {
  Fields f;
  std::string why;
  EXPECT_EQ(split_csv_line("ab\"c", f, &why), 3u);
  EXPECT_EQ(why, "quote inside an unquoted field");
  EXPECT_EQ(split_csv_line("\"abc", f, &why), 5u);
  EXPECT_EQ(why, "unterminated quoted field");
  EXPECT_EQ(split_csv_line("\"a\"b", f, &why), 4u);
  EXPECT_EQ(why, "text after a closing quote");
}

TEST(AppendCsvField, QuotesOnlyWhenNeeded) {
  std::string out;
  append_csv_field(out, "plain");
  out += ',';
  append_csv_field(out, "a,\"b\"");
  EXPECT_EQ(out, "plain,\"a,\"\"b\"\"\"");
  Fields f;
  EXPECT_EQ(split_csv_line(out, f), 0u);
  EXPECT_EQ(f, (Fields{"plain", "a,\"b\""}));
}

TEST(Utf8, AcceptsValidRejectsInvalid) {
  EXPECT_TRUE(is_valid_utf8("plain ascii"));
  EXPECT_TRUE(is_valid_utf8("\xC3\xA9t\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80"));
  std::size_t at = 99;
  EXPECT_FALSE(is_valid_utf8("ab\xFF", &at));
  EXPECT_EQ(at, 2u);
  EXPECT_FALSE(is_valid_utf8("\xC0\xAF"));          // overlong '/'
  EXPECT_FALSE(is_valid_utf8("\xED\xA0\x80"));      // surrogate
  EXPECT_FALSE(is_valid_utf8("\xE2\x82"));          // truncated
  EXPECT_FALSE(is_valid_utf8("\xF4\x90\x80\x80"));  // > U+10FFFF
}

}  // namespace
}  // namespace emoface::core

namespace emoface::core {
namespace {
TEST(CsvStamp, IsACommentLineWithTheVersion) {
  const std::string s = csv_stamp();
  EXPECT_EQ(s, std::string("# ") + kGenerator + "\n");
  EXPECT_TRUE(is_csv_comment(s));
  EXPECT_TRUE(is_csv_comment("\xEF\xBB\xBF# bom"));
  EXPECT_FALSE(is_csv_comment(""));
  EXPECT_FALSE(is_csv_comment("a,#b"));
  EXPECT_FALSE(is_csv_comment(" #indented"));
}
}  // namespace
}  // namespace emoface::core
