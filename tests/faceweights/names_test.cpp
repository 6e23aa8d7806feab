#include "emoface/faceweights/names.hpp"

#include <gtest/gtest.h>

#include <set>

#include "emoface/faceweights/weight_set.hpp"

namespace emoface::faceweights {
namespace {

TEST(Names, FiftyTwoUniqueArkitShapes) {
  const auto& n = arkit_names();
  EXPECT_EQ(n.size(), 52u);
  EXPECT_EQ(std::set<std::string>(n.begin(), n.end()).size(), 52u);
  EXPECT_EQ(n.front(), "browDown_L");
  EXPECT_EQ(n.back(), "tongueOut");
}

TEST(Names, ThreeSpellings) {
  EXPECT_EQ(arkit_swift_name("eyeBlink_L"), "eyeBlinkLeft");
  EXPECT_EQ(arkit_swift_name("mouthSmile_R"), "mouthSmileRight");
  EXPECT_EQ(arkit_swift_name("jawOpen"), "jawOpen");
  EXPECT_EQ(live_link_face_name("eyeBlink_L"), "EyeBlinkLeft");
  EXPECT_EQ(live_link_face_name("browInnerUp"), "BrowInnerUp");
  EXPECT_EQ(arkit_raw_name("eyeBlinkLeft").value(), "eyeBlink_L");
  EXPECT_EQ(arkit_raw_name("EyeBlinkLeft").value(), "eyeBlink_L");
  EXPECT_EQ(arkit_raw_name("EYEBLINK_L").value(), "eyeBlink_L");
  EXPECT_EQ(arkit_raw_name("mouthRight").value(), "mouthRight");  // not a side suffix
  EXPECT_FALSE(arkit_raw_name("eyeBlink").has_value());
  EXPECT_FALSE(arkit_raw_name("").has_value());
}

TEST(Names, LiveLinkFaceColumnsArePermutationOfArkit) {
  const auto& cols = live_link_face_columns();
  ASSERT_EQ(cols.size(), 61u);
  EXPECT_EQ(cols[0], "EyeBlinkLeft");
  EXPECT_EQ(cols[51], "TongueOut");
  EXPECT_EQ(cols[52], "HeadYaw");
  EXPECT_EQ(cols[60], "RightEyeRoll");
  const auto& map = live_link_face_to_arkit();
  ASSERT_EQ(map.size(), 52u);
  EXPECT_EQ(std::set<int>(map.begin(), map.end()).size(), 52u);
  for (std::size_t i = 0; i < 52; ++i)
    EXPECT_EQ(live_link_face_name(arkit_names()[static_cast<std::size_t>(map[i])]), cols[i]);
}

TEST(Names, BuiltinArkitSetHasEveryShapeInOrder) {
  EXPECT_EQ(builtin_weight_set("arkit").target_names(), arkit_names());
}

}  // namespace
}  // namespace emoface::faceweights
