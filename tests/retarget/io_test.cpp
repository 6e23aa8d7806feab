// The user landmarks file on core::JsonReader (issue 18, item 1): the unknown-field rule of
// docs/formats.md and located errors. Round trip and bad input: transfer_test.cpp, LandmarksFile.
#include "emoface/retarget/io.hpp"

#include <gtest/gtest.h>

#include <string>

#include "emoface/core/errors.hpp"

namespace rt = emoface::retarget;

namespace {

// A landmarks document of `version` whose "points" are 67 nulls and `last`, then `extra` members.
std::string landmarks(const std::string& version, const std::string& last,
                      const std::string& extra = "") {
  std::string s = R"({"format": "emoface.landmarks", "version": ")" + version +
                  R"(", "scheme": "ibug68", "points": [)";
  for (int k = 0; k < 67; ++k) s += "null, ";
  return s + last + "]" + extra + "}";
}

std::string error_of(const std::string& text) {
  try {
    rt::parse_landmarks(text, "lm.json");
  } catch (const emoface::FormatError& e) {
    return e.what();
  }
  return "no error";
}

TEST(LandmarksFile, NewerMinorVersionMayAddFields) {
  const rt::UserLandmarks lm = rt::parse_landmarks(
      landmarks("1.1", "[1, 2, 3]", R"(, "confidence": [0.5], "tool": "x")"), "lm.json");
  ASSERT_EQ(lm.points.size(), 68u);
  EXPECT_EQ(lm.points[67].kind, rt::UserLandmarkKind::Point);
  EXPECT_EQ(lm.points[67].point, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(lm.points[0].kind, rt::UserLandmarkKind::Missing);
}

TEST(LandmarksFile, SameVersionRejectsAnUnknownFieldAtItsPointer) {
  EXPECT_EQ(error_of(landmarks("1.0", "5", R"(, "pionts": [])")),
            "lm.json: at /pionts: unknown field \"pionts\"");
  EXPECT_EQ(error_of(landmarks("1.0", "5", R"(, "a/b": 1)")),
            "lm.json: at /a~1b: unknown field \"a/b\"");  // RFC 6901 escape
  EXPECT_NE(error_of(landmarks("2.0", "5")).find("version"), std::string::npos);
}

TEST(LandmarksFile, LocatedErrorsInTheCoreStyle) {
  EXPECT_EQ(error_of(landmarks("1.0", "-4")),
            "lm.json: at /points/67: -4 is out of range [0, 2147483647]");
  EXPECT_EQ(error_of(landmarks("1.0", "2147483648")),
            "lm.json: at /points/67: 2147483648 is out of range [0, 2147483647]");
  EXPECT_EQ(error_of(landmarks("1.0", "1.5")),
            "lm.json: at /points/67: expected an integer, got 1.5");
  EXPECT_EQ(error_of(landmarks("1.0", "[1, 2]")),
            "lm.json: at /points/67: expected 3 elements, got 2");
  EXPECT_EQ(error_of(landmarks("1.0", "true")),
            "lm.json: at /points/67: expected a vertex id, [x, y, z] or null");
  EXPECT_EQ(error_of(R"({"format": "emoface.landmarks", "version": "1.0", "scheme": "ibug68"})"),
            "lm.json: missing field \"points\"");
  EXPECT_EQ(error_of(R"({"format": "emoface.landmarks", "version": "1.0", "points": []})"),
            "lm.json: missing field \"scheme\"");
  EXPECT_EQ(rt::parse_landmarks(landmarks("1.0", "2147483647"), "lm.json").points[67].vertex,
            2147483647);
}

}  // namespace
