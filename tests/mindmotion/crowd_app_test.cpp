// End-to-end tests of `mindmap crowd` (issue #9 §2) on the example crowd, with a small motion graph.
#include <filesystem>
#include <iostream>
#include <string>

#include <gtest/gtest.h>

#include "cli_harness.hpp"
#include "emoface/core/csv.hpp"
#include "emoface/core/video.hpp"
#include "emoface/mindmap/io.hpp"
#include "emoface/mindmotion/crowd.hpp"
#include "emoface/motiongraph/io.hpp"
#include "emoface/muscles/io.hpp"

namespace fs = std::filesystem;
namespace mg = emoface::motiongraph;

namespace {

const std::string kData = std::string(EMOFACE_SOURCE_DIR) + "/data/mindmap";

class MindmapCrowdApp : public emoface::test::CliTest {
 protected:
  // A small graph (the default one takes ~6 s to build); written once per test.
  std::string graph() {
    static const mg::MotionGraph g = [] {
      mg::SyntheticOptions o;
      o.sequences_per_label = 2;
      o.subjects = 3;
      o.min_frames = 6;
      o.max_frames = 12;
      return emoface::mindmotion::default_motion_graph(o);
    }();
    const std::string p = path("graph.json");
    if (!fs::exists(p)) mg::write_graph(p, g);
    return p;
  }
  std::string crowd_args(const std::string& out) {
    return "crowd --maps " + kData + "/crowd --events " + kData + "/crowd_events.ndjson --graph " + graph() +
           " --duration 8 --fps 10 --width 40 --seed 2 --out " + out;
  }
  emoface::test::CliResult mindmap(const std::string& args) { return run_tool(MINDMAP_EXE, args); }
};

}  // namespace

TEST_F(MindmapCrowdApp, WritesTracksMoodChartsAndTheKeyMomentSheet) {
  const bool video = emoface::core::ffmpeg_available();
  if (!video) std::cerr << "ffmpeg not found: the --video part is skipped\n";
  const auto r = mindmap(crowd_args(path("out")) + (video ? " --video" : ""));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("4 characters, 81 frames at 10 fps"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("time (wall / CPU): simulation"), std::string::npos);
  for (const char* name : {"ana", "ben", "rex", "tess"}) {
    const std::string stem = path("out/") + name;
    // faceanim-ready tracks: one row per frame, 40 named parameters.
    const auto frames = emoface::muscles::read_parameter_frames(stem + "_muscles.csv");
    EXPECT_EQ(frames.size(), 81u) << name;
    EXPECT_EQ(lines(slurp(stem + "_mood.csv")), 83u) << name;  // "# emoface x.y.z" + header + 81 rows
    EXPECT_EQ(slurp(stem + "_mood.png").substr(1, 3), "PNG");
    EXPECT_TRUE(fs::exists(stem + "_segments.csv"));
  }
  const auto actions = emoface::mindmap::parse_actions(slurp(path("out/actions.ndjson")));
  EXPECT_GE(actions.size(), 4u);  // everyone reacts to the bang
  // Key moments: the bang at 1 s and the gift at 7 s fall inside the 8 s.
  const std::string stamped = slurp(path("out/key_moments.csv"));
  ASSERT_EQ(stamped.rfind(emoface::core::csv_stamp(), 0), 0u);
  const std::string km = stamped.substr(emoface::core::csv_stamp().size());
  EXPECT_EQ(lines(km), 3u) << km;
  EXPECT_EQ(km.substr(0, km.find('\n')),
            "time,stimuli,ana_frame,ben_frame,rex_frame,tess_frame,ana_time,ben_time,rex_time,tess_time");
  EXPECT_EQ(slurp(path("out/key_moments.png")).substr(1, 3), "PNG");
  if (video) {
    const std::string mp4 = slurp(path("out/crowd.mp4"));
    ASSERT_GT(mp4.size(), 1000u);
    EXPECT_EQ(mp4.substr(4, 4), "ftyp");
  }
  // Same seed, same bytes.
  ASSERT_EQ(mindmap(crowd_args(path("again"))).code, 0);
  for (const char* f : {"ana_muscles.csv", "tess_mood.csv", "key_moments.png", "actions.ndjson"})
    EXPECT_EQ(slurp(path("out/") + f), slurp(path("again/") + f)) << f;
}

// Issue 19: variation is on by default (--no-vary switches it off), and the distinctness is printed.
TEST_F(MindmapCrowdApp, VariationFlagAndFaceDistances) {
  const auto on = mindmap(crowd_args(path("on")) + " --no-charts");
  ASSERT_EQ(on.code, 0) << on.err;
  EXPECT_NE(on.out.find("face distance (mean per-frame parameter distance): ana-ben "), std::string::npos) << on.out;
  const auto off = mindmap(crowd_args(path("off")) + " --no-charts --no-vary --return-after 0");
  ASSERT_EQ(off.code, 0) << off.err;
  EXPECT_NE(slurp(path("on/ana_muscles.csv")), slurp(path("off/ana_muscles.csv")));
  // The library with variation switched off gives what --no-vary wrote (same graph, seed, fps).
  emoface::mindmotion::CrowdOptions o;
  o.simulation.duration = 8;
  o.fps = 10;
  o.seed = 2;
  o.motion.synthesis = mg::SynthesisOptions{};
  o.motion.return_after = 0.0;
  const auto maps = emoface::mindmap::read_mind_map_dir(kData + "/crowd", {});
  const emoface::mindmotion::CrowdFaces faces(maps, {});
  const auto crowd = emoface::mindmotion::animate_crowd(
      maps, emoface::mindmap::read_events(kData + "/crowd_events.ndjson"), mg::read_graph(graph()), faces.rigs(), o);
  EXPECT_EQ(slurp(path("off/ana_muscles.csv")), emoface::muscles::format_parameter_frames_csv(crowd.characters[0].tracks));
  EXPECT_EQ(mindmap(crowd_args(path("bad")) + " --replace 1.5").code, 1);
  EXPECT_EQ(mindmap(crowd_args(path("bad")) + " --return-after -1").code, 1);
}

TEST_F(MindmapCrowdApp, ErrorsHaveTheirExitCodesAndWriteNothing) {
  EXPECT_EQ(mindmap("crowd --maps " + kData + "/crowd --out " + path("o")).code, 1);  // --events missing
  EXPECT_EQ(mindmap(crowd_args(path("o")) + " --fps 1000").code, 1);
  EXPECT_EQ(mindmap(crowd_args(path("o")) + " --width 8").code, 1);
  EXPECT_EQ(mindmap(crowd_args(path("o")) + " --view side").code, 1);
  // A single character is not a crowd.
  fs::create_directories(path("one"));
  fs::copy_file(kData + "/crowd/ana.json", path("one/ana.json"));
  auto r = mindmap("crowd --maps " + path("one") + " --events " + kData + "/crowd_events.ndjson --graph " + graph() +
                   " --out " + path("o"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("at least 2"), std::string::npos) << r.err;
  // A bad event names its file and line; nothing is written.
  const std::string bad = write("bad.ndjson", "{\"time\": 1, \"to\": \"*\", \"stimulus\": \"bang\"}\n{\"time\": nan}\n");
  r = mindmap("crowd --maps " + kData + "/crowd --events " + bad + " --graph " + graph() + " --out " + path("o"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("bad.ndjson:2"), std::string::npos) << r.err;
  EXPECT_EQ(mindmap(crowd_args(path("o")) + " --rig " + path("missing.rig")).code, 2);
  EXPECT_FALSE(fs::exists(path("o")));
}
