// talkinghead --weights and obie --weights end to end: the shared faceweights writer behind thin flags.
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_harness.hpp"
#include "emoface/faceweights/names.hpp"
#include "emoface/faceweights/tracks.hpp"

namespace {

class WeightsApps : public emoface::test::CliTest {};

std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

std::string live_link_header() {
  std::string h = "Timecode,BlendShapeCount";
  for (const auto& c : emoface::faceweights::live_link_face_columns()) h += "," + c;
  return h;
}

TEST_F(WeightsApps, TalkingheadWritesLiveLinkFaceCsv) {
  const std::string script = std::string(EMOFACE_SOURCE_DIR) + "/data/channels/examples/oh_really.xml";
  auto r = run_tool(TALKINGHEAD_EXE, "--script " + script + " --fps 30 --out " + path("t.csv") +
                                         " --weights livelink --weights-out " + path("llf.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string llf = slurp(path("llf.csv"));
  EXPECT_EQ(first_line(llf), live_link_header());
  emoface::faceweights::WeightTrackReadOptions o;
  o.fps = 30;
  const auto track = emoface::faceweights::parse_weight_track(
      llf, emoface::faceweights::builtin_weight_set("arkit"), "llf.csv", o);
  EXPECT_GT(track.weights.size(), 30u);
  EXPECT_NEAR(track.times[30], 1.0, 1e-9);
  double jaw = 0;
  for (const auto& w : track.weights) jaw = std::max(jaw, w[24]);  // jawOpen: the speech opens it
  EXPECT_GT(jaw, 0.1);
  EXPECT_EQ(run_tool(TALKINGHEAD_EXE, "--script " + script + " --out " + path("u.csv") +
                                          " --weights arkit").code, 1);  // needs --weights-out
}

TEST_F(WeightsApps, ObieWritesArkitFacsAndLiveLink) {
  const std::string src = EMOFACE_SOURCE_DIR;
  auto r = run_tool(OBIE_EXE, "--match " + src + "/data/obie/match_7_4.json --agent " + src +
                                  "/data/parlee/agents/neutral.json --out " + path("o") +
                                  " --no-video --no-speech --quiet --weights arkit,facs,livelink");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(first_line(slurp(path("o/livelink_face.csv"))), live_link_header());
  const std::string arkit = slurp(path("o/arkit.csv"));
  EXPECT_EQ(arkit.rfind("# emoface", 0), 0u);
  EXPECT_NE(arkit.find("\ntime,browDown_L,"), std::string::npos);
  EXPECT_NE(slurp(path("o/facs.csv")).find("\ntime,AU1_L,"), std::string::npos);
  EXPECT_EQ(run_tool(OBIE_EXE, "--match " + src + "/data/obie/match_7_4.json --agent " + src +
                                   "/data/parlee/agents/neutral.json --out " + path("p") +
                                   " --no-video --weights vrm").code, 1);
}

}  // namespace
