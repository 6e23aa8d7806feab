#include "emoface/channels/mixer.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "emoface/channels/parameters.hpp"
#include "emoface/core/errors.hpp"

namespace emoface::channels {
namespace {

ChannelSamples sampled(Channel c, const std::vector<Movement>& ms, double fps, std::size_t frames) {
  const ConcatenatedChannel ch(ms);
  ChannelSamples s{c, ch.parameters(), std::vector<double>(ch.parameters().size() * frames)};
  for (std::size_t p = 0; p < s.parameters.size(); ++p) ch.sample(p, 0, fps, frames, s.values.data() + p * frames);
  return s;
}

struct Fig47 : ::testing::Test {
  // Fig. 4.7: a speech funneler (channel 2) at 3–4 s inhibits a smile (channel 4) held 0–8 s.
  static constexpr double kFps = 1000.0;
  static constexpr std::size_t kFrames = 9001;
  std::vector<std::string> params{"zygomatic_major_l", "orbicularis_oris_funneler", "frontalis_lateralis_l"};
  std::vector<ChannelSamples> channels{
      sampled(Channel::Lip, {{{{"orbicularis_oris_funneler", 0.8}}, Timing{3, 4, 0.1, 0.1}, "oo"}}, kFps, kFrames),
      sampled(Channel::EmotionDisplay,
              {{{{"zygomatic_major_l", 1.0}, {"frontalis_lateralis_l", 0.4}}, Timing{0, 8, 0.5, 0.5}, "smile"}},
              kFps, kFrames)};
};

TEST_F(Fig47, SmileReleasesEarlyAndReturnsGradually) {
  MixOptions o;
  o.dmin_plus = 0.5;
  o.dmin_minus = 0.3;
  o.active_threshold = 0.01;
  std::vector<ChannelSamples> modified;
  const Tracks t = mix(channels, params, kFps, kFrames, default_conflict_table(), o, &modified);
  const auto zyg = t.series("zygomatic_major_l");
  ASSERT_EQ(modified.size(), 2u);
  EXPECT_EQ(modified[0].values, channels[0].values);  // the lip channel is not touched
  EXPECT_EQ(modified[1].values[3500], 0.0);           // aF of the smile during the funneler
  const auto oo = t.series("orbicularis_oris_funneler");
  // activation crossings of the funneler: 0.8·φ+(x, 0.1) > 0.01
  std::size_t first = 0, last = 0;
  for (std::size_t f = 0; f < kFrames; ++f)
    if (oo[f] > 0.01) {
      if (!first) first = f;
      last = f;
    }
  const double t_on = first / kFps, t_off = last / kFps;
  EXPECT_NEAR(t_on, 3.0 + 0.1 * std::log2(1.0 + 0.01 / 0.8), 2e-3);
  for (std::size_t f = first; f <= last; ++f) ASSERT_EQ(zyg[f], 0.0) << f;
  EXPECT_DOUBLE_EQ(zyg[2000], 1.0);  // before T→ − Dmin−: untouched
  // Ψ→: φ−(Dmin− − (T→ − t), Dmin−) at T→ − 0.15 s = 2^{0.5} − 1
  EXPECT_NEAR(zyg[first - 150], std::sqrt(2.0) - 1.0, 1e-9);
  // Ψ←: φ+(t − T←, Dmin+) at T← + 0.25 s
  EXPECT_NEAR(zyg[last + 250], std::sqrt(2.0) - 1.0, 1e-9);
  EXPECT_DOUBLE_EQ(zyg[last + 600], 1.0);
  // the funneler (higher priority) and the non-conflicting frontalis are untouched
  EXPECT_NEAR(oo[3500], 0.8, 1e-12);
  EXPECT_NEAR(t.series("frontalis_lateralis_l")[3500], 0.4, 1e-12);
  // continuity of the inhibited smile (no jump larger than one frame of the Ψ slopes)
  for (std::size_t f = 1; f < kFrames; ++f) EXPECT_LT(std::abs(zyg[f] - zyg[f - 1]), 0.01) << f;
}

TEST_F(Fig47, PriorityDecidesWhoIsInhibited) {
  MixOptions o;
  o.priority = {1, 5, 3, 2, 6, 7};  // emotion display above speech
  const Tracks t = mix(channels, params, kFps, kFrames, default_conflict_table(), o);
  EXPECT_DOUBLE_EQ(t.series("zygomatic_major_l")[3500], 1.0);
  EXPECT_EQ(t.series("orbicularis_oris_funneler")[3500], 0.0);
}

// §4.1: "The smile may also have higher priority than the visual speech when the subject is too
// happy": per-movement (per-frame) priority. Per-frame priorities equal to the channels' give the
// plain result; the smile at priority 1 during 3–4 s inhibits the funneler instead.
TEST_F(Fig47, PerMovementPriority) {
  MixOptions o;
  o.active_threshold = 0.01;
  std::vector<ChannelSamples> same = channels;
  same[0].frame_priority.assign(kFrames, 2);
  same[1].frame_priority.assign(kFrames, 4);
  std::vector<ChannelSamples> m0, m1;
  const Tracks plain = mix(channels, params, kFps, kFrames, default_conflict_table(), o, &m0);
  const Tracks also = mix(same, params, kFps, kFrames, default_conflict_table(), o, &m1);
  EXPECT_EQ(plain.values, also.values);
  EXPECT_EQ(m0[1].values, m1[1].values);
  std::vector<ChannelSamples> happy = channels;
  happy[1].frame_priority.assign(kFrames, 4);
  for (std::size_t f = 3000; f <= 4000; ++f) happy[1].frame_priority[f] = 1;
  std::vector<ChannelSamples> m2;
  const Tracks t = mix(happy, params, kFps, kFrames, default_conflict_table(), o, &m2);
  EXPECT_EQ(m2[1].values, channels[1].values);  // the smile is never inhibited
  EXPECT_DOUBLE_EQ(t.series("zygomatic_major_l")[3500], 1.0);
  for (std::size_t f = 3000; f <= 4000; ++f) ASSERT_EQ(m2[0].values[f], 0.0) << f;  // funneler
  EXPECT_EQ(t.series("orbicularis_oris_funneler")[3500], 0.0);
  // through render(): a funneler in channel 3 (priority 3) against the smile (channel 4); the smile
  // movement with its own priority 1 wins instead
  Timeline tl;
  Movement smile{{{"zygomatic_major_l", 1.0}, {"frontalis_lateralis_l", 0.4}},
                 Timing{0, 8, 0.5, 0.5},
                 "smile"};
  Movement purse{{{"orbicularis_oris_funneler", 0.8}}, Timing{3, 4, 0.1, 0.1}, "purse"};
  tl.movements[static_cast<std::size_t>(Channel::EmotionDisplay)] = {smile};
  tl.movements[static_cast<std::size_t>(Channel::ConversationalSignal)] = {purse};
  RenderOptions ro;
  ro.fps = kFps;
  ro.parameters = params;
  ro.mix = o;
  const auto base = render(tl, default_viseme_set(), default_conflict_table(), ro);
  EXPECT_EQ(base.series("zygomatic_major_l")[3500], 0.0);
  EXPECT_NEAR(base.series("orbicularis_oris_funneler")[3500], 0.8, 1e-12);
  tl.movements[static_cast<std::size_t>(Channel::EmotionDisplay)][0].priority = 1;
  const auto raised = render(tl, default_viseme_set(), default_conflict_table(), ro);
  EXPECT_DOUBLE_EQ(raised.series("zygomatic_major_l")[3500], 1.0);
  EXPECT_EQ(raised.series("orbicularis_oris_funneler")[3500], 0.0);
  tl.movements[static_cast<std::size_t>(Channel::EmotionDisplay)][0].priority = 101;
  EXPECT_THROW(render(tl, default_viseme_set(), default_conflict_table(), ro), InvalidInput);
  happy[0].frame_priority.assign(3, 2);  // wrong size
  EXPECT_THROW(mix(happy, params, kFps, kFrames, default_conflict_table(), o), InvalidInput);
}

TEST(Mixer, MaximumOverChannelsAndSignedMagnitude) {
  const std::size_t frames = 11;
  std::vector<ChannelSamples> ch{
      {Channel::ConversationalSignal, {"masseter", "head_yaw"}, std::vector<double>(2 * frames, 0.2)},
      {Channel::Head, {"masseter", "head_yaw"}, std::vector<double>(2 * frames, 0.0)}};
  for (std::size_t f = 0; f < frames; ++f) {
    ch[1].values[f] = 0.5;            // masseter
    ch[1].values[frames + f] = -0.4;  // head_yaw
  }
  const Tracks t = mix(ch, {"masseter", "head_yaw"}, 10.0, frames, ConflictTable{}, MixOptions{});
  EXPECT_DOUBLE_EQ(t.at(3, 0), 0.5);
  EXPECT_DOUBLE_EQ(t.at(3, 1), -0.4);
}

TEST(Mixer, RejectsBadInput) {
  std::vector<ChannelSamples> ch{{Channel::Head, {"masseter"}, std::vector<double>(5)}};
  EXPECT_THROW(mix(ch, {"masseter"}, 10, 6, ConflictTable{}, MixOptions{}), InvalidInput);
  EXPECT_THROW(mix(ch, {"risorius_l"}, 10, 5, ConflictTable{}, MixOptions{}), InvalidInput);
  MixOptions bad;
  bad.dmin_plus = 0;
  EXPECT_THROW(mix(ch, {"masseter"}, 10, 5, ConflictTable{}, bad), InvalidInput);
  EXPECT_THROW(mix(ch, {"masseter"}, 0, 5, ConflictTable{}, MixOptions{}), InvalidInput);
}

TEST(Render, TimelineToTracks) {
  Timeline tl;
  tl.movements[static_cast<std::size_t>(Channel::EmotionDisplay)] = {
      {{{"zygomatic_major_l", 1.0}}, Timing{0, 2, 0.5, 0.5}, "a"}, {{{"zygomatic_major_l", 0.5}}, Timing{1, 3, 0.5, 0.5}, "b"}};
  VisemeSet vs;
  vs.visemes = {{"sil", {}, Dominance{}, {}}};
  RenderOptions o;
  o.fps = 15;
  const Tracks t = render(tl, vs, default_conflict_table(), o);
  EXPECT_EQ(t.names, default_parameter_names());
  EXPECT_EQ(t.frames(), 46u);  // 0..3 s at 15 fps
  const auto z = t.series("zygomatic_major_l");
  EXPECT_DOUBLE_EQ(z[14], 1.0);  // Fig. 4.6: full smile before frame 15
  EXPECT_DOUBLE_EQ(z[20], 0.5);  // half smile from frame 20
  tl.movements[static_cast<std::size_t>(Channel::Lip)] = tl.movements[3];
  EXPECT_THROW(render(tl, vs, default_conflict_table(), o), InvalidInput);
}

TEST(Tracks, Validate) {
  Tracks t{10, {"a", "b"}, {0, 1, 2, 3}};
  EXPECT_NO_THROW(t.validate());
  EXPECT_EQ(t.frames(), 2u);
  EXPECT_EQ(t.series("b")[1], 3.0);
  EXPECT_THROW(t.series("c"), InvalidInput);
  t.values.push_back(1);
  EXPECT_THROW(t.validate(), InvalidInput);
  EXPECT_THROW((Tracks{10, {"a", "a"}, {}}.validate()), InvalidInput);
  EXPECT_THROW((Tracks{10, {"time"}, {}}.validate()), InvalidInput);
  EXPECT_THROW((Tracks{10, {"a"}, {NAN}}.validate()), InvalidInput);
  EXPECT_THROW((Tracks{-1, {"a"}, {}}.validate()), InvalidInput);
}

}  // namespace
}  // namespace emoface::channels
