#include "emoface/runtime/streaming.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "emoface/channels/dominance.hpp"
#include "emoface/channels/mixer.hpp"
#include "emoface/channels/parameters.hpp"
#include "emoface/channels/script.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/rng.hpp"

namespace emoface::runtime {
namespace {

namespace ch = emoface::channels;

// A random chain in channel order with overlapping and separate movements, signed targets.
std::vector<ch::Movement> random_chain(std::uint64_t seed, std::size_t n) {
  core::Rng rng(seed);
  std::vector<ch::Movement> ms;
  double start = 0.1, end = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    start += rng.uniform(0.05, 1.5);
    const double len = rng.uniform(0.4, 3.0);
    end = std::max(end + 0.01, start + len);
    const double on = rng.uniform(0.05, 0.3), off = rng.uniform(0.05, 0.3);
    if (on + off > end - start) continue;
    ch::Movement m;
    m.timing = ch::Timing{start, end, on, off};
    m.targets = {{"a", rng.uniform(-1, 1)}, {"b", rng.uniform(0, 1)}};
    m.label = "m" + std::to_string(k);
    ms.push_back(m);
  }
  return ms;
}

TEST(StreamingChannel, EqualsConcatenatedChannelBitForBit) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const auto ms = random_chain(seed, 30);
    const ch::ConcatenatedChannel offline(ms);
    StreamingChannel s({"a", "b"});
    std::size_t next = 0;
    const double fps = 50;
    for (std::size_t f = 0; f < 3000; ++f) {
      const double t = static_cast<double>(f) / fps;
      // movements arrive just in time (before the first frame after their start), old ones are
      // pruned
      while (next < ms.size() && ms[next].timing.start < t + 0.5) s.append(ms[next++]);
      s.prune(t);
      double v[2];
      s.sample(t, v);
      ASSERT_EQ(v[0], offline.value("a", t)) << "seed " << seed << " t " << t;
      ASSERT_EQ(v[1], offline.value("b", t)) << "seed " << seed << " t " << t;
    }
    EXPECT_LE(s.size(), 5u);  // pruned as time went on
  }
}

TEST(StreamingChannel, BadInput) {
  StreamingChannel s({"a"});
  EXPECT_THROW(StreamingChannel({"a", "a"}), InvalidInput);
  EXPECT_THROW(s.append({{{"zzz", 1.0}}, ch::Timing{0, 1, 0.1, 0.1}, "x"}), InvalidInput);
  EXPECT_THROW(s.append({{{"a", NAN}}, ch::Timing{0, 1, 0.1, 0.1}, "x"}), InvalidInput);
  EXPECT_THROW(s.append({{{"a", 1}}, ch::Timing{0, 1, 0.8, 0.8}, "x"}), InvalidInput);
  s.append({{{"a", 1.0}}, ch::Timing{1, 2, 0.1, 0.1}, "x"});
  EXPECT_THROW(s.append({{{"a", 1.0}}, ch::Timing{0.5, 3, 0.1, 0.1}, "y"}),
               InvalidInput);  // earlier start
  EXPECT_THROW(s.append({{{"a", 1.0}}, ch::Timing{1.5, 1.9, 0.1, 0.1}, "y"}),
               InvalidInput);  // earlier end
  EXPECT_THROW(s.value(3, 0.0), InvalidInput);
}

// Samples a timeline's channels as channels::render does, in channel index order.
std::vector<ch::ChannelSamples> sample_channels(const ch::Timeline& tl, const ch::VisemeSet& vis,
                                                double fps, std::size_t frames) {
  std::vector<ch::ChannelSamples> out;
  for (std::size_t c = 0; c < ch::kChannelCount; ++c) {
    ch::ChannelSamples s;
    s.channel = static_cast<ch::Channel>(c);
    if (s.channel == ch::Channel::Lip) {
      if (tl.lip.empty()) continue;
      const ch::Coarticulation lip(vis, tl.lip);
      s.parameters = lip.parameters();
      s.values.resize(s.parameters.size() * frames);
      for (std::size_t p = 0; p < s.parameters.size(); ++p)
        lip.sample(p, 0.0, fps, frames, s.values.data() + p * frames);
    } else {
      if (tl.movements[c].empty()) continue;
      const ch::ConcatenatedChannel cc(tl.movements[c]);
      s.parameters = cc.parameters();
      s.values.resize(s.parameters.size() * frames);
      for (std::size_t p = 0; p < s.parameters.size(); ++p)
        cc.sample(p, 0.0, fps, frames, s.values.data() + p * frames);
    }
    out.push_back(std::move(s));
  }
  return out;
}

// Feeds the samples frame by frame and returns the number of (frame, parameter) values that differ
// from the offline mixer.
std::size_t streaming_differences(const std::vector<ch::ChannelSamples>& samples, double fps,
                                  std::size_t frames, std::size_t lookahead,
                                  const ch::MixOptions& mo) {
  const auto& params = ch::default_parameter_names();
  const ch::ConflictTable conflicts = ch::default_conflict_table();
  const ch::Tracks offline = ch::mix(samples, params, fps, frames, conflicts, mo);
  std::array<std::vector<std::size_t>, ch::kChannelCount> cp;
  std::array<const ch::ChannelSamples*, ch::kChannelCount> by{};
  for (const auto& s : samples) {
    const auto c = static_cast<std::size_t>(s.channel);
    by[c] = &s;
    for (const auto& p : s.parameters)
      cp[c].push_back(
          static_cast<std::size_t>(std::find(params.begin(), params.end(), p) - params.begin()));
  }
  StreamingMixer mixer(params, cp, conflicts, mo, fps, lookahead);
  std::array<std::vector<double>, ch::kChannelCount> raw;
  for (std::size_t c = 0; c < ch::kChannelCount; ++c) raw[c].assign(cp[c].size(), 0.0);
  std::size_t differences = 0;
  for (std::size_t f = 0; f < frames + lookahead; ++f) {
    std::array<const double*, ch::kChannelCount> ptr{};
    for (std::size_t c = 0; c < ch::kChannelCount; ++c) {
      for (std::size_t i = 0; i < cp[c].size(); ++i)
        raw[c][i] = f < frames ? by[c]->values[i * frames + f] : 0.0;
      ptr[c] = raw[c].data();
    }
    mixer.push(ptr);
    if (f < lookahead) {
      EXPECT_EQ(mixer.frames_out(), 0u);
      continue;
    }
    const std::size_t out = f - lookahead;
    EXPECT_EQ(mixer.frames_out(), out + 1);
    for (std::size_t p = 0; p < params.size(); ++p)
      if (mixer.output()[p] != offline.at(out, p)) ++differences;
  }
  return differences;
}

ch::Timeline thesis_timeline(const std::string& file, bool with_speech) {
  const ch::Script script =
      ch::read_script(std::string(EMOFACE_SOURCE_DIR) + "/data/channels/examples/" + file);
  std::vector<std::vector<ch::PhonemeTiming>> utterances;
  if (with_speech) {
    // "Oh, really? I like it very much.": libespeak-ng 1.51's phoneme events (en-us, 160
    // words/min), fixed here so the test needs no speech program
    const std::vector<std::pair<std::string, int>> ev{
        {"oU", 0},   {"_:", 316},  {"r", 491},  {"i@", 604},  {"l", 772},  {"i", 839},
        {"_:", 905}, {"aI", 1255}, {"l", 1379}, {"aI", 1451}, {"k", 1613}, {"I", 1672},
        {"t", 1789}, {"v", 1850},  {"E", 1917}, {"r", 2036},  {"i", 2091}, {"m", 2157},
        {"V", 2273}, {"tS", 2459}, {"_:", 2554}};
    std::vector<ch::PhonemeTiming> p;
    for (std::size_t k = 0; k < ev.size(); ++k)
      p.push_back({ev[k].first, ev[k].second / 1000.0,
                   (k + 1 < ev.size() ? ev[k + 1].second : 2562) / 1000.0});
    utterances.assign(script.speech.size(), p);
  }
  const auto mapper = [](const std::array<double, 6>& e) {
    // a hand mapping with conflicting muscles: happiness smiles, surprise raises the brows and
    // opens
    return std::vector<ch::Target>{
        {"zygomatic_major_l", e[1]},       {"zygomatic_major_r", e[1]},
        {"frontalis_medialis_l", e[5]},    {"frontalis_medialis_r", e[5]},
        {"orbicularis_oris_pressor", 0.0}, {"masseter", 0.5 * e[5]}};
  };
  ch::TimelineOptions to;
  return ch::build_timeline(script, utterances, ch::default_viseme_set(), mapper, to, 3);
}

TEST(StreamingMixer, EqualsOfflineMixerOnThesisExamplesOnceTheLookAheadCoversDminMinus) {
  const ch::MixOptions mo;  // Dmin− = 0.3 s
  for (const auto& [file, speech] :
       {std::pair<std::string, bool>{"fig4_7.xml", false}, {"oh_really.xml", true}}) {
    const ch::Timeline tl = thesis_timeline(file, speech);
    for (double fps : {25.0, 100.0}) {
      const auto frames = static_cast<std::size_t>(std::floor(tl.end_time() * fps)) + 1;
      const auto samples = sample_channels(tl, ch::default_viseme_set(), fps, frames);
      const auto enough = static_cast<std::size_t>(std::ceil(mo.dmin_minus * fps));
      EXPECT_EQ(streaming_differences(samples, fps, frames, enough, mo), 0u)
          << file << " fps " << fps;
      EXPECT_EQ(streaming_differences(samples, fps, frames, enough + 5, mo), 0u)
          << file << " fps " << fps;
      // a look-ahead shorter than Dmin− cannot see the inhibition coming: the release starts late
      EXPECT_GT(streaming_differences(samples, fps, frames, enough / 3, mo), 0u)
          << file << " fps " << fps;
    }
  }
}

TEST(StreamingMixer, SnapshotStateRoundTripAndBadSizes) {
  const auto& params = ch::default_parameter_names();
  std::array<std::vector<std::size_t>, ch::kChannelCount> cp;
  cp[1] = {0};
  StreamingMixer a(params, cp, ch::default_conflict_table(), {}, 50, 3);
  const double one = 0.5;
  std::array<const double*, ch::kChannelCount> ptr{};
  ptr[1] = &one;
  for (int i = 0; i < 5; ++i) a.push(ptr);
  StreamingMixer b(params, cp, ch::default_conflict_table(), {}, 50, 3);
  b.restore(a.state());
  a.push(ptr);
  b.push(ptr);
  EXPECT_EQ(a.output(), b.output());
  StreamingMixer other(params, cp, ch::default_conflict_table(), {}, 50, 7);
  EXPECT_THROW(other.restore(a.state()), InvalidInput);
  std::array<std::vector<std::size_t>, ch::kChannelCount> bad;
  bad[0] = {999};
  EXPECT_THROW(StreamingMixer(params, bad, ch::default_conflict_table(), {}, 50, 3), InvalidInput);
  EXPECT_THROW(StreamingMixer(params, cp, ch::default_conflict_table(), {}, 0, 3), InvalidInput);
}

}  // namespace
}  // namespace emoface::runtime
