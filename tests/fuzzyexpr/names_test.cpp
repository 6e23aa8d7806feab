#include "emoface/fuzzyexpr/names.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace emoface::fuzzyexpr {
namespace {

TEST(Names, EmotionRoundTripCaseInsensitive) {
  for (std::size_t i = 0; i < kEmotionCount; ++i) {
    EXPECT_EQ(emotion_from_string(to_string(emotion_at(i))), emotion_at(i));
  }
  EXPECT_EQ(emotion_from_string("Surprise"), Emotion::Surprise);
  EXPECT_EQ(emotion_from_string("SADNESS"), Emotion::Sadness);
  EXPECT_FALSE(emotion_from_string("joy"));
  EXPECT_FALSE(emotion_from_string(""));
}

TEST(Names, MusclesFollowTable21) {
  EXPECT_EQ(to_string(Muscle::ZygomaticMajor), "zygomatic_major");
  EXPECT_EQ(thesis_number(Muscle::ZygomaticMajor), 1);
  EXPECT_EQ(to_string(Muscle::FrontalisMedialis), "frontalis_medialis");
  EXPECT_EQ(thesis_number(Muscle::FrontalisMedialis), 9);
  EXPECT_EQ(thesis_number(Muscle::Masseter), 19);
  for (std::size_t i = 0; i < kMuscleCount; ++i)
    EXPECT_EQ(muscle_from_string(to_string(muscle_at(i))), muscle_at(i));
  EXPECT_FALSE(muscle_from_string("buccinator"));
}

TEST(Names, ThirtyFiveSideParameters) {
  const auto& names = side_parameter_names();
  std::set<std::string> unique(names.begin(), names.end());
  EXPECT_EQ(unique.size(), 35u);
  EXPECT_EQ(names[0], "zygomatic_major_l");
  EXPECT_EQ(names[1], "zygomatic_major_r");
  EXPECT_TRUE(unique.count("orbicularis_oris_funneler"));
  EXPECT_TRUE(unique.count("orbicularis_oris_pressor"));
  EXPECT_TRUE(unique.count("masseter"));
  EXPECT_EQ(names[34], "masseter");
  int unpaired = 0;
  for (std::size_t i = 0; i < kMuscleCount; ++i) unpaired += !is_paired(muscle_at(i));
  EXPECT_EQ(unpaired, 3);
}

TEST(Names, ExpandToSidesCopiesLevels) {
  Fmcv f{};
  for (std::size_t i = 0; i < kMuscleCount; ++i) f[i] = 0.01 * static_cast<double>(i + 1);
  const auto s = expand_to_sides(f);
  const auto& names = side_parameter_names();
  for (std::size_t k = 0; k < kSideParameterCount; ++k) {
    std::string n(names[k]);
    if (n.size() > 2 && (n.substr(n.size() - 2) == "_l" || n.substr(n.size() - 2) == "_r"))
      n = n.substr(0, n.size() - 2);
    auto m = muscle_from_string(n);
    ASSERT_TRUE(m) << n;
    EXPECT_EQ(s[k], f[index(*m)]) << names[k];
  }
}

}  // namespace
}  // namespace emoface::fuzzyexpr
