#include "emoface/muscles/io.hpp"

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "emoface/muscles/parameters.hpp"

namespace emoface::muscles {
namespace {

std::vector<ParameterFrame> csv(const std::string& text, FrameReadOptions o = {}) {
  return parse_parameter_frames(text, FrameFormat::Csv, "p.csv", o);
}

TEST(ParameterFrames, CsvWithMetadataAndTimes) {
  const auto frames = csv("id,time,masseter,zygomatic_major_l,happiness\n0,0.5,0.25,1,0.9\n1,1.0,0,0.5,0.2\n");
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].time, 0.5);
  EXPECT_EQ(frames[0].values[parameter_index("masseter")], 0.25);
  EXPECT_EQ(frames[1].values[parameter_index("zygomatic_major_l")], 0.5);
  EXPECT_EQ(frames[1].values[parameter_index("risorius_r")], 0.0);
  // no time column: index / fps
  FrameReadOptions o;
  o.fps = 10;
  const auto f2 = csv("masseter\n0.1\n0.2\n", o);
  EXPECT_DOUBLE_EQ(f2[1].time, 0.1);
}

TEST(ParameterFrames, RoundTrips) {
  std::vector<ParameterFrame> frames(3);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    frames[i].time = 0.1 * static_cast<double>(i) + 1.0 / 3.0;
    frames[i].values.assign(kParameterCount, 0.0);
    frames[i].values[i] = 1.0 / 7.0;
    frames[i].values[36] = -0.123456789;
  }
  for (auto format : {FrameFormat::Csv, FrameFormat::Json}) {
    const std::string text = format == FrameFormat::Csv ? format_parameter_frames_csv(frames) : format_parameter_frames_json(frames, 25);
    const auto back = parse_parameter_frames(text, format, "x");
    ASSERT_EQ(back.size(), frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) {
      EXPECT_EQ(back[i].time, frames[i].time);
      EXPECT_EQ(back[i].values, frames[i].values);
    }
  }
}

TEST(ParameterFrames, NdjsonAndJson) {
  const auto nd = parse_parameter_frames("{\"time\": 0.2, \"parameters\": {\"masseter\": 0.5}}\n\n{\"masseter\": 1}\n",
                                         FrameFormat::Ndjson, "p.ndjson");
  ASSERT_EQ(nd.size(), 2u);
  EXPECT_EQ(nd[0].time, 0.2);
  EXPECT_EQ(nd[1].values[parameter_index("masseter")], 1.0);
  const auto one = parse_parameter_frames("{\"risorius_l\": 0.3}", FrameFormat::Json, "p.json");
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].values[parameter_index("risorius_l")], 0.3);
  EXPECT_EQ(frame_format_from_path("a.jsonl"), FrameFormat::Ndjson);
  EXPECT_THROW(frame_format_from_path("a.txt"), InvalidInput);
  EXPECT_EQ(frame_format_from_string(to_string(FrameFormat::Json)), FrameFormat::Json);
}

void expect_error(const std::string& text, FrameFormat format, std::size_t line) {
  try {
    parse_parameter_frames(text, format, "bad");
    FAIL() << text;
  } catch (const FormatError& e) {
    EXPECT_EQ(e.where().file, "bad");
    EXPECT_EQ(e.where().line, line) << text << " -> " << e.what();
  }
}

TEST(ParameterFrames, RejectsBadInput) {
  expect_error("smile\n1\n", FrameFormat::Csv, 1);                    // unknown column
  expect_error("masseter,masseter\n1,1\n", FrameFormat::Csv, 1);      // duplicate column
  expect_error("masseter\n1\nnan\n", FrameFormat::Csv, 3);            // NaN
  expect_error("masseter\n1e400\n", FrameFormat::Csv, 2);             // overflow
  expect_error("masseter\n1.5\n", FrameFormat::Csv, 2);               // out of range
  expect_error("masseter\nabc\n", FrameFormat::Csv, 2);               // not a number
  expect_error("masseter,risorius_l\n1\n", FrameFormat::Csv, 2);      // wrong field count
  expect_error("masseter\n\"1\n", FrameFormat::Csv, 2);               // malformed quoting
  expect_error("", FrameFormat::Csv, 1);                              // no header
  expect_error("{\"masseter\": 1}\n{\"masseter\": \n", FrameFormat::Ndjson, 2);  // truncated
  expect_error("{\"masseter\": \"x\"}\n", FrameFormat::Ndjson, 1);
  expect_error("{\"smile\": 1}\n", FrameFormat::Ndjson, 1);
  expect_error("[1, 2]", FrameFormat::Json, 0);
  expect_error("{\"format\": \"emoface.params\", \"version\": \"9.0\", \"frames\": []}", FrameFormat::Json, 0);
  expect_error("{\"format\": \"emoface.params\", \"version\": \"1.0\", \"frames\": [{\"parameters\": {\"masseter\": -1}}]}", FrameFormat::Json, 0);
  FrameReadOptions lenient;
  lenient.ignore_unknown_columns = true;
  EXPECT_NO_THROW(csv("smile,masseter\n1,0.5\n", lenient));
  lenient.fps = 0.0;
  EXPECT_THROW(csv("masseter\n1\n", lenient), InvalidInput);
}

}  // namespace
}  // namespace emoface::muscles
