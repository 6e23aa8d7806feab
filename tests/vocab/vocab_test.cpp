// The names of emotions, muscles and parameters are defined once (emoface/core/vocab.hpp); every
// library that speaks them must agree with it, name for name and in the same order.
#include "emoface/core/vocab.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "emoface/channels/parameters.hpp"
#include "emoface/channels/script.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/fuzzyexpr/names.hpp"
#include "emoface/muscles/parameters.hpp"

namespace emoface {
namespace {

TEST(Vocab, CountsAndPairingFromTheThesis) {
  // Table 2.1: 19 muscles; §4.3: all paired except the two Orbicularis Oris parts and the Masseter,
  // so 16 × 2 + 3 = 35 side parameters; + 5 pose + 2 eyelid = 42.
  std::size_t paired = 0;
  for (std::size_t i = 0; i < core::kMuscleCount; ++i) paired += core::is_paired_muscle(i);
  EXPECT_EQ(paired, 16u);
  EXPECT_EQ(core::kSideParameterCount, 2 * paired + (core::kMuscleCount - paired));
  EXPECT_EQ(core::kParameterCount, 42u);
  EXPECT_FALSE(core::is_paired_muscle("masseter"));
  EXPECT_TRUE(core::is_paired_muscle("zygomatic_major"));
  EXPECT_FALSE(core::is_paired_muscle("no_such_muscle"));
  EXPECT_EQ(core::muscle_index("masseter"), 18u);  // thesis number 19
  EXPECT_EQ(core::emotion_index("surprise"), 5u);
  EXPECT_EQ(core::parameter_index("masseter"), 34u);
  EXPECT_EQ(core::parameter_index("eye_blink_r"), 41u);
  EXPECT_FALSE(core::parameter_index("smile").has_value());
  EXPECT_TRUE(core::is_signed_parameter("head_roll"));
  EXPECT_FALSE(core::is_signed_parameter("eye_blink_l"));
  const std::set<std::string> unique(core::parameter_names().begin(),
                                     core::parameter_names().end());
  EXPECT_EQ(unique.size(), core::kParameterCount);
}

TEST(Vocab, FuzzyexprAgrees) {
  ASSERT_EQ(fuzzyexpr::kEmotionCount, core::kEmotionCount);
  ASSERT_EQ(fuzzyexpr::kMuscleCount, core::kMuscleCount);
  for (std::size_t i = 0; i < core::kEmotionCount; ++i)
    EXPECT_EQ(fuzzyexpr::to_string(fuzzyexpr::emotion_at(i)), core::kEmotionNames[i]);
  for (std::size_t i = 0; i < core::kMuscleCount; ++i) {
    EXPECT_EQ(fuzzyexpr::to_string(fuzzyexpr::muscle_at(i)), core::kMuscleNames[i]);
    EXPECT_EQ(fuzzyexpr::is_paired(fuzzyexpr::muscle_at(i)), core::is_paired_muscle(i));
  }
  for (std::size_t i = 0; i < core::kSideParameterCount; ++i)
    EXPECT_EQ(fuzzyexpr::side_parameter_names()[i], core::side_parameter_names()[i]);
}

TEST(Vocab, MusclesAgree) {
  EXPECT_EQ(muscles::parameter_names(), core::parameter_names());
  for (std::size_t i = 0; i < core::kMuscleCount; ++i)
    EXPECT_EQ(muscles::muscle_type_names()[i], core::kMuscleNames[i]);
  for (std::size_t i = 0; i < core::kParameterCount; ++i) {
    EXPECT_EQ(muscles::parameter_index(core::parameter_names()[i]), i);
    EXPECT_EQ(muscles::is_level_parameter(i),
              !core::is_signed_parameter(core::parameter_names()[i]));
  }
}

TEST(Vocab, ChannelsAgree) {
  EXPECT_EQ(channels::default_parameter_names(), core::parameter_names());
  ASSERT_EQ(channels::muscle_names().size(), core::kMuscleCount);
  for (std::size_t i = 0; i < core::kMuscleCount; ++i) {
    const std::string& m = channels::muscle_names()[i];
    EXPECT_EQ(m, core::kMuscleNames[i]);
    EXPECT_EQ(channels::is_paired_muscle(m), core::is_paired_muscle(i));
  }
  for (const std::string& p : core::parameter_names())
    EXPECT_EQ(channels::is_signed_parameter(p), core::is_signed_parameter(p)) << p;
}

TEST(EmotionMapper, SideParameterMapperNamesFuzzyexprsOutput) {
  const channels::EmotionMapper mapper =
      channels::side_parameter_mapper(fuzzyexpr::side_parameter_function());
  const std::array<double, 6> esv{0.0, 0.8, 0.0, 0.0, 0.0, 0.6};  // happiness + surprise
  const std::vector<channels::Target> targets = mapper(esv);
  ASSERT_EQ(targets.size(), core::kSideParameterCount);
  // Independent path: the engine itself, expanded by hand with the thesis pairing.
  const fuzzyexpr::Fmcv f = fuzzyexpr::Engine().convert(esv);
  std::size_t k = 0;
  for (std::size_t m = 0; m < core::kMuscleCount; ++m) {
    const int copies = core::is_paired_muscle(m) ? 2 : 1;
    for (int c = 0; c < copies; ++c, ++k) {
      EXPECT_EQ(targets[k].value, f[m]) << targets[k].parameter;
      const std::string expected = std::string(core::kMuscleNames[m]) + (copies == 1 ? ""
                                                                         : c == 0    ? "_l"
                                                                                     : "_r");
      EXPECT_EQ(targets[k].parameter, expected);
    }
  }
  EXPECT_GT(targets[*core::parameter_index("zygomatic_major_l")].value, 0.3);  // a smile
  EXPECT_THROW(channels::side_parameter_mapper({}), InvalidInput);
}

}  // namespace
}  // namespace emoface
