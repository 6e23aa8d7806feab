#include "emoface/channels/timing_io.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "emoface/channels/dominance.hpp"
#include "emoface/core/errors.hpp"

namespace emoface::channels {
namespace {

SpeechTiming sample_timing() {
  SpeechTiming t;
  t.segments = {{"h", 0.0, 0.1}, {"oU", 0.1, 0.3141592653589793}, {"_:", 0.5, 0.625}};
  return t;
}

void expect_same(const SpeechTiming& a, const SpeechTiming& b) {
  EXPECT_EQ(a.kind, b.kind);
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (std::size_t i = 0; i < a.segments.size(); ++i) {
    EXPECT_EQ(a.segments[i].phoneme, b.segments[i].phoneme);
    EXPECT_EQ(a.segments[i].start, b.segments[i].start);  // bit for bit
    EXPECT_EQ(a.segments[i].end, b.segments[i].end);
  }
}

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const FormatError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(TimingIo, TsvRoundTrip) {
  const SpeechTiming t = sample_timing();
  const std::string text = format_timing_tsv(t);
  EXPECT_EQ(text.substr(0, 10), "# emoface ");
  EXPECT_NE(text.find("start\tend\tphoneme\n0\t0.1\th\n"), std::string::npos);
  expect_same(parse_timing_tsv(text), t);
  SpeechTiming v = t;
  v.kind = TimingKind::Viseme;
  expect_same(parse_timing_tsv(format_timing_tsv(v)), v);
  // CRLF and blank lines are accepted
  expect_same(
      parse_timing_tsv("start\tend\tphoneme\r\n\r\n0\t0.1\th\r\n0.1\t0.3141592653589793\toU\r\n"
                       "0.5\t0.625\t_:\r\n"),
      t);
}

TEST(TimingIo, TsvBadInput) {
  EXPECT_NE(error_of([] { parse_timing_tsv("", "t.tsv"); }).find("t.tsv:1"), std::string::npos);
  EXPECT_NE(error_of([] { parse_timing_tsv("begin\tend\tphoneme\n", "t.tsv"); }).find("header"),
            std::string::npos);
  const std::string h = "start\tend\tphoneme\n";
  EXPECT_NE(error_of([&] { parse_timing_tsv(h + "0\t0.1\n", "t.tsv"); }).find("t.tsv:2"),
            std::string::npos);
  EXPECT_NE(error_of([&] { parse_timing_tsv(h + "0\tnan\ta\n", "t.tsv"); }).find("end"),
            std::string::npos);
  EXPECT_NE(error_of([&] { parse_timing_tsv(h + "0\tinf\ta\n", "t.tsv"); }).find("end"),
            std::string::npos);
  EXPECT_NE(error_of([&] { parse_timing_tsv(h + "-1\t0.1\ta\n", "t.tsv"); }).find("start"),
            std::string::npos);
  EXPECT_NE(error_of([&] { parse_timing_tsv(h + "0\t1e9\ta\n", "t.tsv"); }).find("end"),
            std::string::npos);
  EXPECT_NE(error_of([&] { parse_timing_tsv(h + "0.2\t0.1\ta\n", "t.tsv"); }).find("after start"),
            std::string::npos);
  EXPECT_NE(
      error_of([&] { parse_timing_tsv(h + "0\t0.2\ta\n0.1\t0.3\tb\n", "t.tsv"); }).find("t.tsv:3"),
      std::string::npos);
  EXPECT_NE(error_of([&] { parse_timing_tsv(h + "0\t0.1\t\n", "t.tsv"); }).find("t.tsv:2"),
            std::string::npos);
  EXPECT_NE(error_of([&] { parse_timing_tsv(h + "0x\t0.1\ta\n", "t.tsv"); }).find("start"),
            std::string::npos);
  // truncated mid-line
  EXPECT_NE(error_of([&] { parse_timing_tsv(h + "0\t0.", "t.tsv"); }).find("t.tsv:2"),
            std::string::npos);
  SpeechTiming bad;
  bad.segments = {{"a", 0.0, std::numeric_limits<double>::quiet_NaN()}};
  EXPECT_THROW(format_timing_tsv(bad), InvalidInput);
  bad.segments = {{"a\tb", 0.0, 0.1}};
  EXPECT_THROW(format_timing_tsv(bad), InvalidInput);
}

TEST(TimingIo, JsonRoundTripAndBadInput) {
  const SpeechTiming t = sample_timing();
  const std::string text = format_timing_json(t);
  EXPECT_NE(text.find("\"format\": \"emoface.speech_timing\""), std::string::npos);
  expect_same(parse_timing_json(text), t);
  const std::string env = R"({"format":"emoface.speech_timing","version":"1.0",)";
  EXPECT_NE(error_of([] { parse_timing_json("{", "t.json"); }).find("t.json"), std::string::npos);
  EXPECT_NE(error_of([&] {
              parse_timing_json(env + R"("kind":"word","segments":[]})", "t.json");
            }).find("/kind"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              parse_timing_json(env + R"("kind":"phoneme"})", "t.json");
            }).find("missing field \"segments\""),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              parse_timing_json(
                  env + R"("kind":"phoneme","segments":[{"start":0,"end":"x","name":"a"}]})",
                  "t.json");
            }).find("/segments/0/end"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              parse_timing_json(
                  env + R"("kind":"phoneme","segments":[{"start":0,"end":1,"name":"a","x":1}]})",
                  "t.json");
            }).find("/segments/0/x"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              parse_timing_json(
                  env + R"("kind":"phoneme","segments":[{"start":0,"end":1,"name":"a"},)"
                        R"({"start":0.5,"end":2,"name":"b"}]})",
                  "t.json");
            }).find("/segments/1/start"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              parse_timing_json(R"({"format":"emoface.speech_timing","version":"2.0"})", "t.json");
            }).find("/version"),
            std::string::npos);
}

TEST(TimingIo, RhubarbTsvAndJson) {
  // Rhubarb's TSV: each cue until the next, the last one (X) marks the end
  const RhubarbCues r = parse_rhubarb_tsv("0.00\tX\n0.05\tD\n0.27\tC\n0.31\tB\n0.43\tX\n", "r.tsv");
  ASSERT_EQ(r.cues.size(), 4u);
  EXPECT_EQ(r.cues[1].phoneme, "D");
  EXPECT_DOUBLE_EQ(r.cues[1].start, 0.05);
  EXPECT_DOUBLE_EQ(r.cues[1].end, 0.27);
  EXPECT_DOUBLE_EQ(r.cues.back().end, 0.43);
  const RhubarbCues back = parse_rhubarb_tsv(format_rhubarb_tsv(r));
  ASSERT_EQ(back.cues.size(), r.cues.size());
  for (std::size_t i = 0; i < r.cues.size(); ++i) {
    EXPECT_EQ(back.cues[i].phoneme, r.cues[i].phoneme);
    EXPECT_EQ(back.cues[i].start, r.cues[i].start);
    EXPECT_EQ(back.cues[i].end, r.cues[i].end);
  }
  const std::string json = R"({"metadata": {"soundFile": "a.wav", "duration": 0.43},
    "mouthCues": [{"start": 0.00, "end": 0.05, "value": "X"}, {"start": 0.05, "end": 0.27, "value": "D"},
                  {"start": 0.27, "end": 0.31, "value": "C"}, {"start": 0.31, "end": 0.43, "value": "B"}]})";
  const RhubarbCues j = parse_rhubarb_json(json, "r.json");
  EXPECT_EQ(j.sound_file, "a.wav");
  ASSERT_EQ(j.cues.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(j.cues[i].phoneme, r.cues[i].phoneme);
    EXPECT_EQ(j.cues[i].end, r.cues[i].end);
  }
  const RhubarbCues jb = parse_rhubarb_json(format_rhubarb_json(j));
  EXPECT_EQ(jb.sound_file, "a.wav");
  ASSERT_EQ(jb.cues.size(), 4u);
  EXPECT_EQ(jb.cues[3].end, 0.43);
  // shapes → visemes of the default set, each of which exists
  const SpeechTiming v = rhubarb_to_visemes(r);
  EXPECT_EQ(v.kind, TimingKind::Viseme);
  EXPECT_EQ(v.segments[1].phoneme, "AA");
  const VisemeSet set = default_viseme_set();
  for (const auto& [shape, viseme] : default_rhubarb_visemes()) {
    EXPECT_NE(set.find(viseme), nullptr) << shape;
    EXPECT_EQ(set.viseme_for_phoneme(viseme), viseme);
  }
}

TEST(TimingIo, RhubarbBadInput) {
  EXPECT_NE(error_of([] { parse_rhubarb_tsv("", "r.tsv"); }).find("r.tsv"), std::string::npos);
  EXPECT_NE(error_of([] { parse_rhubarb_tsv("0\tX\n0.1\tQ\n", "r.tsv"); }).find("r.tsv:2"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_rhubarb_tsv("0\tX\n0\tA\n", "r.tsv"); }).find("increase"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_rhubarb_tsv("0\tX\nnan\tA\n", "r.tsv"); }).find("r.tsv:2"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_rhubarb_tsv("0 X\n", "r.tsv"); }).find("r.tsv:1"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_rhubarb_json("[]", "r.json"); }).find("r.json"), std::string::npos);
  EXPECT_NE(error_of([] {
              parse_rhubarb_json(R"({"mouthCues":[{"start":0,"end":1,"value":"Z"}]})", "r.json");
            }).find("/mouthCues/0/value"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              parse_rhubarb_json(R"({"mouthCues":[{"start":0,"end":1e12,"value":"A"}]})", "r.json");
            }).find("/mouthCues/0/end"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              parse_rhubarb_json(R"({"mouthCues":[{"start":0,"value":"A"}]})", "r.json");
            }).find("/mouthCues/0/end"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              parse_rhubarb_json(R"({"metadata":{"duration":-1},"mouthCues":[]})", "r.json");
            }).find("/metadata/duration"),
            std::string::npos);
  std::map<std::string, std::string> table{{"A", "PBM"}};
  EXPECT_THROW(rhubarb_to_visemes(parse_rhubarb_tsv("0\tA\n0.1\tB\n0.2\tX\n"), table),
               InvalidInput);
}

TEST(TimingIo, ExternalUtteranceAndFiles) {
  SpeechTiming t;
  t.segments = {{"m", 0.1, 0.2}, {"a", 0.2, 0.4}};
  WavAudio audio{1000, std::vector<std::int16_t>(500, 7)};
  const Utterance u = external_utterance(t, audio);
  ASSERT_EQ(u.phonemes.size(), 4u);  // leading pause, m, a, trailing pause to the audio's end
  EXPECT_EQ(u.phonemes[0].phoneme, "_");
  EXPECT_DOUBLE_EQ(u.phonemes[0].end, 0.1);
  EXPECT_DOUBLE_EQ(u.phonemes.back().end, 0.5);
  ExternalSpeech ext;
  ext.add("ma", u);
  EXPECT_EQ(ext.synthesize("ma").samples.size(), 500u);
  WavAudio short_audio{1000, std::vector<std::int16_t>(100, 7)};
  EXPECT_THROW(external_utterance(t, short_audio), InvalidInput);
  // read_timing_file tells the formats apart by content
  const auto dir =
      std::filesystem::temp_directory_path() / ("emoface_timing_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name, std::ios::binary) << text;
    return (dir / name).string();
  };
  expect_same(read_timing_file(write("a.tsv", format_timing_tsv(t))), t);
  expect_same(read_timing_file(write("a.json", format_timing_json(t))), t);
  const RhubarbCues r = parse_rhubarb_tsv("0\tA\n0.1\tD\n0.2\tX\n");
  EXPECT_EQ(read_timing_file(write("r.tsv", format_rhubarb_tsv(r))).segments[1].phoneme, "AA");
  EXPECT_EQ(read_timing_file(write("r.json", format_rhubarb_json(r))).segments[0].phoneme, "PBM");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace emoface::channels
