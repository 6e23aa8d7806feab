#include "emoface/channels/conflicts.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "emoface/channels/parameters.hpp"
#include "emoface/core/errors.hpp"

namespace emoface::channels {
namespace {

TEST(Parameters, DefaultNames) {
  const auto& n = default_parameter_names();
  ASSERT_EQ(n.size(), 42u);
  EXPECT_EQ(n[0], "zygomatic_major_l");
  EXPECT_EQ(n[1], "zygomatic_major_r");
  EXPECT_EQ(std::count(n.begin(), n.end(), "orbicularis_oris_funneler"), 1);
  EXPECT_EQ(n[39], "head_roll");
  EXPECT_EQ(n.back(), "eye_blink_r");
  EXPECT_TRUE(is_signed_parameter("eye_gaze_yaw"));
  EXPECT_FALSE(is_signed_parameter("masseter"));
  EXPECT_EQ(parameter_muscle("risorius_r"), "risorius");
  EXPECT_EQ(parameter_muscle("masseter"), "masseter");
  EXPECT_EQ(parameter_muscle("masseter_l"), "");
  EXPECT_EQ(parameter_muscle("risorius"), "");
  EXPECT_THROW(muscle_parameters("nose"), InvalidInput);
}

TEST(Conflicts, DefaultTableReproducesSurvivingRowCounts) {
  const ConflictTable t = default_conflict_table();
  EXPECT_NO_THROW(t.validate());
  // thesis Table 4.1: marks per row (muscle numbers 1..19)
  const std::map<int, int> expected = {{1, 4}, {2, 4}, {3, 3}, {4, 3}, {5, 2}, {6, 3}, {7, 5},
                                       {8, 4}, {9, 1}, {11, 3}, {12, 1}, {16, 2}, {17, 1}};
  std::map<int, int> count;
  const auto number = [](const std::string& m) {
    const auto& n = muscle_names();
    return static_cast<int>(std::find(n.begin(), n.end(), m) - n.begin()) + 1;
  };
  for (const auto& p : t.pairs) {
    ++count[number(p.a)];
    ++count[number(p.b)];
    EXPECT_FALSE(p.rationale.empty());
  }
  EXPECT_EQ(count, expected);
}

TEST(Conflicts, ExpandSidesAndUnpaired) {
  const auto& names = default_parameter_names();
  const auto c = default_conflict_table().expand(names);
  const auto idx = [&](const char* n) {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), n) - names.begin());
  };
  const auto has = [&](const char* a, const char* b) {
    const auto& v = c[idx(a)];
    return std::find(v.begin(), v.end(), idx(b)) != v.end();
  };
  EXPECT_TRUE(has("zygomatic_major_l", "orbicularis_oris_funneler"));
  EXPECT_TRUE(has("orbicularis_oris_funneler", "zygomatic_major_r"));
  EXPECT_TRUE(has("zygomatic_major_l", "triangularis_l"));
  EXPECT_FALSE(has("zygomatic_major_l", "triangularis_r"));
  EXPECT_TRUE(has("orbicularis_oculi_palpebralis_r", "levator_palpebrae_superioris_r"));
  EXPECT_TRUE(c[idx("masseter")].empty());
  EXPECT_TRUE(c[idx("head_yaw")].empty());
}

TEST(Conflicts, Validation) {
  EXPECT_THROW((ConflictTable{{{"masseter", "masseter", ""}}}.validate()), InvalidInput);
  EXPECT_THROW((ConflictTable{{{"masseter", "nose", ""}}}.validate()), InvalidInput);
  EXPECT_THROW((ConflictTable{{{"masseter", "head_yaw", ""}}}.validate()), InvalidInput);
  EXPECT_THROW((ConflictTable{{{"masseter", "risorius", ""}, {"risorius", "masseter", ""}}}.validate()),
               InvalidInput);
  EXPECT_NO_THROW((ConflictTable{{{"masseter", "risorius_l", ""}}}.validate()));
}

}  // namespace
}  // namespace emoface::channels
