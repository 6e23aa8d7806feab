#include "emoface/faceweights/tracks.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "emoface/core/errors.hpp"
#include "emoface/faceweights/mapper.hpp"
#include "emoface/faceweights/names.hpp"
#include "emoface/muscles/parameters.hpp"

namespace emoface::faceweights {
namespace {

const std::vector<std::string>& names() { return muscles::parameter_names(); }

TEST(Tracks, LiveLinkTimecodeHandValues) {
  EXPECT_EQ(live_link_timecode(0.0, 60), "00:00:00:00.000");
  EXPECT_EQ(live_link_timecode(1.5, 30), "00:00:01:15.000");
  EXPECT_EQ(live_link_timecode(3661.02, 50), "01:01:01:01.000");
  EXPECT_EQ(live_link_timecode(0.01, 60), "00:00:00:00.600");  // 0.6 of a frame
  EXPECT_EQ(live_link_timecode(59.999999, 25), "00:01:00:00.000");
  EXPECT_NEAR(parse_live_link_timecode("01:01:01:01.000", 50).value(), 3661.02, 1e-12);
  EXPECT_NEAR(parse_live_link_timecode("00:00:00:00.600", 60).value(), 0.01, 1e-12);
  EXPECT_NEAR(parse_live_link_timecode("00:00:02:03", 30).value(), 2.1, 1e-12);
  EXPECT_FALSE(parse_live_link_timecode("00:00:02:30", 30).has_value());  // frame >= fps
  EXPECT_FALSE(parse_live_link_timecode("00:61:02:00", 30).has_value());
  EXPECT_FALSE(parse_live_link_timecode("00:00:02", 30).has_value());
  EXPECT_FALSE(parse_live_link_timecode("00:00:02:01.x", 30).has_value());
  EXPECT_THROW(live_link_timecode(-1.0, 30), InvalidInput);
}

std::vector<std::vector<double>> sample_frames() {
  std::vector<std::vector<double>> f(3, std::vector<double>(names().size(), 0.0));
  f[1][muscles::parameter_index("zygomatic_major_l")] = 0.8;
  f[1][muscles::parameter_index("head_yaw")] = 0.2;
  f[2][muscles::parameter_index("eye_blink_r")] = 1.0;
  f[2][muscles::parameter_index("eye_gaze_pitch")] = -0.19;
  return f;
}

TEST(Tracks, ArkitCsvRoundTrip) {
  const auto frames = sample_frames();
  const std::vector<double> times = {0.0, 0.04, 0.08};
  const std::string text = format_weight_track(TrackFormat::ArkitCsv, names(), times, frames, 25.0);
  EXPECT_EQ(text.rfind("# emoface", 0), 0u);
  EXPECT_NE(text.find("\ntime,browDown_L,browDown_R,"), std::string::npos);
  const auto track = parse_weight_track(text, builtin_weight_set("arkit"), "t.csv");
  ASSERT_EQ(track.weights.size(), 3u);
  const Mapper m(builtin_weight_set("arkit"), names());
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(track.times[i], times[i], 1e-6);
    const auto w = m.forward(frames[i]);
    for (std::size_t k = 0; k < 52; ++k) EXPECT_NEAR(track.weights[i][k], w[k], 1e-6);
  }
  EXPECT_TRUE(track.pose.empty());
}

TEST(Tracks, LiveLinkFaceCsvLayout) {
  const auto frames = sample_frames();
  const std::string text =
      format_weight_track(TrackFormat::LiveLinkFaceCsv, names(), {0.0, 1.0 / 30, 2.0 / 30}, frames, 30);
  const std::string first = text.substr(0, text.find('\n'));
  std::string expected = "Timecode,BlendShapeCount";
  for (const auto& c : live_link_face_columns()) expected += "," + c;
  EXPECT_EQ(first, expected);
  EXPECT_NE(text.find("\n00:00:00:01.000,61,"), std::string::npos);
  // EyeBlinkRight is the 8th value column; frame 2 closes the right eye
  const std::size_t row2 = text.find("00:00:00:02.000,61,");
  ASSERT_NE(row2, std::string::npos);
  const std::string row = text.substr(row2, text.find('\n', row2) - row2);
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (std::size_t p = 0; p <= row.size(); ++p) {
    if (p == row.size() || row[p] == ',') fields.push_back(row.substr(start, p - start)), start = p + 1;
  }
  ASSERT_EQ(fields.size(), 63u);
  EXPECT_EQ(fields[2 + 7], "1.000000");                            // EyeBlinkRight
  EXPECT_EQ(fields[2 + 8], "0.500000");                            // EyeLookDownRight: 0.19/0.38
  EXPECT_EQ(fields[2 + 56], "-0.190000");                          // LeftEyePitch
  // reads back, with the angles as parameters
  WeightTrackReadOptions opt;
  opt.fps = 30;
  const auto track = parse_weight_track(text, builtin_weight_set("arkit"), "llf.csv", opt);
  ASSERT_EQ(track.pose.size(), 3u);
  EXPECT_NEAR(track.pose[1].at("head_yaw"), 0.2, 1e-9);
  EXPECT_NEAR(track.pose[2].at("eye_gaze_pitch"), -0.19, 1e-9);
  EXPECT_NEAR(track.times[2], 2.0 / 30, 1e-9);
  EXPECT_THROW(format_weight_track(TrackFormat::LiveLinkFaceCsv, names(), {0, 0, 0}, frames, 29.97),
               InvalidInput);
}

TEST(Tracks, FacsCsvHasEveryRow) {
  const auto text = format_weight_track(TrackFormat::FacsCsv, names(), {0, 1, 2}, sample_frames(), 1);
  EXPECT_NE(text.find("\ntime,AU1_L,AU1_R,"), std::string::npos);
  const auto track = parse_weight_track(text, builtin_weight_set("facs"), "f.csv");
  EXPECT_NEAR(track.weights[1][builtin_weight_set("facs").find("AU12_L").value()], 0.8, 1e-9);
}

void expect_error(const std::string& text, const std::string& needle) {
  try {
    parse_weight_track(text, builtin_weight_set("arkit"), "bad.csv");
    FAIL() << "no error; wanted " << needle;
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("bad.csv"), std::string::npos) << e.what();
  }
}

std::string header_without(const std::string& drop) {
  std::string h = "time";
  for (const auto& n : arkit_names()) {
    if (n != drop) h += "," + n;
  }
  return h + "\n";
}

std::string row(const std::string& first_value, std::size_t n = 52) {
  std::string r = "0";
  r += "," + first_value;
  for (std::size_t i = 1; i < n; ++i) r += ",0";
  return r + "\n";
}

TEST(Tracks, BadInputs) {
  expect_error("", "empty file");
  expect_error(header_without("jawOpen") + row("0", 51), "missing column 'jawOpen'");
  expect_error(header_without("") + "\n", "no rows");
  expect_error(header_without("") + row("nan"), "NaN");
  expect_error(header_without("") + row("1.5"), "outside [0, 1]");
  expect_error(header_without("") + row("-0.1"), "outside [0, 1]");
  expect_error(header_without("") + row("x"), "not a number");
  expect_error(header_without("") + row("0", 50), "fields");
  expect_error("smile," + header_without(""), "unknown column 'smile'");
  expect_error("eyeBlinkLeft," + header_without(""), "repeated");
  expect_error("Timecode,BlendShapeCount," + header_without("").substr(5) + "00:00:99:00.000,61" +
                   row("0").substr(1),
               "bad timecode");
  expect_error(header_without("") + row("0").substr(0, 5) + "\"\n", "bad.csv:2");
  WeightTrackReadOptions ignore;
  ignore.ignore_unknown_columns = true;
  const auto t = parse_weight_track("smile," + header_without("") + "9," + row("0.5"),
                                    builtin_weight_set("arkit"), "ok.csv", ignore);
  EXPECT_NEAR(t.weights[0][0], 0.5, 1e-12);
  EXPECT_THROW(read_weight_track("/nonexistent.csv", builtin_weight_set("arkit")), IoError);
}

}  // namespace
}  // namespace emoface::faceweights
