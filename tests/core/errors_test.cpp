#include "emoface/core/errors.hpp"

#include <gtest/gtest.h>

namespace emoface {
namespace {

TEST(FormatError, NamesFileLineAndColumn) {
  SourceLocation where{"in.csv", "", 12, 3};
  FormatError e(where, "not a number");
  EXPECT_STREQ(e.what(), "in.csv:12:3: not a number");
  EXPECT_EQ(e.message(), "not a number");
  EXPECT_EQ(e.where().line, 12u);
}

TEST(FormatError, NamesJsonPointer) {
  FormatError e(SourceLocation{"rules.json", "/single/sadness/0", 0, 0}, "unknown muscle");
  EXPECT_STREQ(e.what(), "rules.json: at /single/sadness/0: unknown muscle");
}

TEST(FormatError, IsAnEmofaceError) {
  try {
    throw FormatError(SourceLocation{}, "x");
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "<input>: x");
  }
}

}  // namespace
}  // namespace emoface
