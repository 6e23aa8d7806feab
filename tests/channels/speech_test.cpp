#include "emoface/channels/speech.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "emoface/channels/talking_head.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/version.hpp"

namespace emoface::channels {
namespace {

TEST(Speech, PhonemeTimingMatchesAudio) {
  const Utterance u = synthesize("Oh really? I like it very much.");
  ASSERT_GT(u.samples.size(), 0u);
  ASSERT_GT(u.phonemes.size(), 10u);
  EXPECT_EQ(u.sample_rate, 22050);
  EXPECT_DOUBLE_EQ(u.phonemes.front().start, 0.0);
  EXPECT_NEAR(u.phonemes.back().end, u.duration(), 1e-12);
  for (std::size_t k = 1; k < u.phonemes.size(); ++k) EXPECT_DOUBLE_EQ(u.phonemes[k].start, u.phonemes[k - 1].end);
  // a later call in the same process gives the same phonemes with timing within a few percent
  // (espeak-ng keeps state between utterances, see speech.hpp)
  const Utterance v = synthesize("Oh really? I like it very much.");
  ASSERT_EQ(u.phonemes.size(), v.phonemes.size());
  for (std::size_t k = 0; k < u.phonemes.size(); ++k) EXPECT_EQ(u.phonemes[k].phoneme, v.phonemes[k].phoneme);
  EXPECT_NEAR(v.duration(), u.duration(), 0.1 * u.duration());
  // the "v" of "very" is there
  bool has_v = false;
  for (const auto& p : u.phonemes) has_v |= p.phoneme == "v";
  EXPECT_TRUE(has_v);
}

TEST(Speech, BadInput) {
  EXPECT_THROW(synthesize("   "), InvalidInput);
  EXPECT_THROW(synthesize("\xff"), InvalidInput);
  SpeechOptions o;
  o.voice = "no-such-voice-xyz";
  EXPECT_THROW(synthesize("hello", o), InvalidInput);
  o = SpeechOptions{};
  o.rate = 10;
  EXPECT_THROW(synthesize("hello", o), InvalidInput);
}

TEST(Speech, WavHeader) {
  const std::string w = format_wav({1, -2, 3}, 22050);
  std::string isft(emoface::kGenerator);
  isft.push_back('\0');
  if (isft.size() % 2) isft.push_back('\0');
  ASSERT_EQ(w.size(), 44u + 6u + 8u + 4u + 8u + isft.size());  // header, samples, LIST+size, INFO, ISFT+size, text
  EXPECT_EQ(w.substr(0, 4), "RIFF");
  EXPECT_EQ(static_cast<std::size_t>(static_cast<unsigned char>(w[4])) + 8u, w.size());  // RIFF size (< 256 here)
  EXPECT_EQ(w.substr(50, 12), "LIST" + std::string(1, static_cast<char>(4 + 8 + isft.size())) + std::string(3, '\0') + "INFO");
  EXPECT_EQ(w.substr(62, 4), "ISFT");
  EXPECT_EQ(w.substr(70), isft);
  EXPECT_EQ(w.substr(8, 8), "WAVEfmt ");
  EXPECT_EQ(static_cast<unsigned char>(w[40]), 6u);  // data bytes
  EXPECT_EQ(static_cast<unsigned char>(w[46]), 0xFEu);  // -2 little-endian
  EXPECT_THROW(place_utterances({Utterance{22050, std::vector<std::int16_t>(100), {}}, Utterance{22050, std::vector<std::int16_t>(100), {}}},
                                {0.0, 0.001}, 22050),
               InvalidInput);
}

TEST(TalkingHead, AudioAndTracksEndTogether) {
  const Script s = parse_script(
      "<PHONEME time=\"0.5\" text=\"Oh really? I like it very much.\"/>\n"
      "<EMOTIONDISPLAY time=\"0\" duration=\"2\" Surprise=\"1\"/>\n<EMOTIONDISPLAY time=\"1\" duration=\"3\" Happiness=\"1\"/>");
  TalkingHeadOptions o;
  o.render.fps = 25;
  o.seed = 4;
  const auto mapper = [](const std::array<double, 6>& e) {
    return std::vector<Target>{{"zygomatic_major_l", e[1]}, {"frontalis_medialis_l", e[5]}};
  };
  const TalkingHead a = run_talking_head(s, default_viseme_set(), default_conflict_table(), mapper, o);
  const double duration = a.tracks.time(a.tracks.frames() - 1);
  EXPECT_EQ(a.audio.size(), static_cast<std::size_t>(std::llround(duration * a.sample_rate)));
  // the last phoneme ends inside the tracks; the audio before 0.5 s is silent
  EXPECT_LE(a.timeline.lip.back().end, duration + 1e-9);
  for (std::size_t i = 0; i < 11025; ++i) ASSERT_EQ(a.audio[i], 0);
  // the funneler of "very" inhibits the smile (Fig. 4.8)
  const auto zyg = a.tracks.series("zygomatic_major_l");
  const auto oo = a.tracks.series("orbicularis_oris_funneler");
  bool inhibited = false;
  for (std::size_t f = 0; f < zyg.size(); ++f) inhibited |= oo[f] > 0.2 && zyg[f] == 0.0 && a.tracks.time(f) > 1.5;
  EXPECT_TRUE(inhibited);
}

}  // namespace
}  // namespace emoface::channels
