// End-to-end tests of the mindmap CLI: run the built binary on the example characters.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "emoface/core/csv.hpp"
#include "emoface/core/io.hpp"
#include "emoface/mindmap/io.hpp"
#include "emoface/motiongraph/io.hpp"
#include "emoface/motiongraph/layout.hpp"
#include "emoface/motiongraph/preprocess.hpp"
#include "emoface/motiongraph/synthetic.hpp"

namespace fs = std::filesystem;
namespace mg = emoface::motiongraph;

namespace {

const std::string kData = std::string(EMOFACE_SOURCE_DIR) + "/data/mindmap";

int run(const std::string& args) {
  const std::string cmd = std::string(MINDMAP_EXE) + " " + args + " >/dev/null 2>&1";
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

fs::path scratch(const char* name) {
  const fs::path p = fs::temp_directory_path() / (std::string("emoface_mindmap_app_") + name);
  fs::remove_all(p);
  return p;
}

}  // namespace

TEST(MindmapApp, SimulatesTheExampleCharacters) {
  const fs::path out = scratch("sim");
  const std::string args = "simulate --maps " + kData + "/characters --events " + kData + "/events.ndjson --seed 3 --out ";
  ASSERT_EQ(run(args + out.string()), 0);
  for (const char* f : {"actions.ndjson", "actions.csv", "ana_mood.csv", "ben_mood.csv", "ana_mood.png", "ben_mood.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto actions = emoface::mindmap::parse_actions(emoface::core::read_file((out / "actions.ndjson").string()));
  EXPECT_GT(actions.size(), 8u);
  EXPECT_EQ(emoface::core::read_file((out / "ana_mood.png").string()).substr(1, 3), "PNG");
  // Same seed, same bytes.
  const fs::path again = scratch("sim2");
  ASSERT_EQ(run(args + again.string()), 0);
  for (const char* f : {"actions.ndjson", "ana_mood.csv", "ben_mood.png"})
    EXPECT_EQ(emoface::core::read_file((out / f).string()), emoface::core::read_file((again / f).string())) << f;
  fs::remove_all(out);
  fs::remove_all(again);
}

// Issue 18: a run writes all its files or none (core::OutputBundle). ben_mood.png is a directory
// here, so it cannot be written: no other output appears.
TEST(MindmapApp, SimulateWritesNothingWhenAnOutputCannotBeWritten) {
  const fs::path out = scratch("sim_fail");
  fs::create_directories(out / "ben_mood.png");
  EXPECT_EQ(run("simulate --maps " + kData + "/characters --events " + kData +
                "/events.ndjson --out " + out.string()),
            2);
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(out)) {
    ++entries;
    EXPECT_EQ(e.path().filename(), "ben_mood.png") << e.path();
  }
  EXPECT_EQ(entries, 1u);
  fs::remove_all(out);
}

TEST(MindmapApp, SynthesizesMotionWithAGraph) {
  const fs::path dir = scratch("graph");
  fs::create_directories(dir);
  mg::SyntheticOptions o;
  o.sequences_per_label = 2;
  o.subjects = 3;
  o.min_frames = 6;
  o.max_frames = 12;
  const auto db = mg::generate_synthetic_database(mg::ParametricLandmarkModel(), o);
  mg::write_graph((dir / "graph.json").string(), mg::build_graph(mg::preprocess(db, mg::default_layout())));
  ASSERT_EQ(run("simulate --maps " + kData + "/characters --events " + kData + "/events.ndjson --no-charts --duration 12 --graph " +
                (dir / "graph.json").string() + " --out " + (dir / "out").string()),
            0);
  const auto motion = mg::parse_database_json(emoface::core::read_file((dir / "out" / "ana_motion.json").string()));
  std::size_t frames = 0;
  for (const auto& s : motion.sequences) frames += s.frames.size();
  EXPECT_GT(frames, 300u);  // > 10 s at 30 fps
  EXPECT_TRUE(fs::exists(dir / "out" / "ben_segments.csv"));
  // Muscle tracks fitted on the default face, ready for faceanim (one row per landmark frame).
  ASSERT_EQ(run("simulate --maps " + kData + "/characters --events " + kData + "/events.ndjson --no-charts --muscles " +
                "--duration 2 --graph " + (dir / "graph.json").string() + " --out " + (dir / "m").string()),
            0);
  const std::string tracks = emoface::core::read_file((dir / "m" / "ana_muscles.csv").string());
  EXPECT_EQ(tracks.substr(emoface::core::csv_stamp().size(), 22), "time,zygomatic_major_l");
  EXPECT_EQ(run("simulate --maps " + kData + "/characters --events " + kData + "/events.ndjson --muscles --out " +
                (dir / "x").string()),
            1);  // --muscles needs --graph
  EXPECT_FALSE(fs::exists(dir / "out" / "ana_mood.png"));
  EXPECT_EQ(run("check --maps " + kData + "/characters --graph " + (dir / "graph.json").string()), 0);
  fs::remove_all(dir);
}

TEST(MindmapApp, ErrorsHaveTheirExitCodes) {
  const fs::path out = scratch("err");
  EXPECT_EQ(run("simulate --maps " + kData + "/characters --out " + out.string()), 1);  // --events missing
  EXPECT_EQ(run("simulate --maps " + kData + "/characters --events " + kData + "/events.ndjson --mood-form abs --out " +
                out.string()),
            1);
  EXPECT_EQ(run("simulate --maps /nonexistent --events " + kData + "/events.ndjson --out " + out.string()), 2);
  fs::create_directories(out);
  emoface::core::write_file_atomic((out / "bad.ndjson").string(), "{\"time\": 1, \"to\": \"nobody\", \"stimulus\": \"gift\"}\n");
  EXPECT_EQ(run("simulate --maps " + kData + "/characters --events " + (out / "bad.ndjson").string() + " --out " +
                (out / "o").string()),
            2);
  EXPECT_FALSE(fs::exists(out / "o"));  // nothing written on failure
  EXPECT_EQ(run("check --maps " + kData + "/characters"), 0);
  fs::remove_all(out);
}

// Issue 19, item 4: a mind map as a Graphviz picture, with the mood after the events.
TEST(MindmapApp, DotDrawsAMindMapWithItsMood) {
  const fs::path out = scratch("dot");
  fs::create_directories(out);
  const std::string maps = " --maps " + kData + "/crowd";
  ASSERT_EQ(run("dot" + maps + " --character ana --events " + kData + "/crowd_events.ndjson --time 8 --seed 1 --out " +
                (out / "ana.dot").string()),
            0);
  std::ifstream in(out / "ana.dot");
  const std::string dot{std::istreambuf_iterator<char>(in), {}};
  EXPECT_EQ(dot.rfind("digraph \"mind map ana\"", 0), 0u);
  EXPECT_NE(dot.find("mood 0."), std::string::npos);
  EXPECT_EQ(run("dot" + maps + " --character nobody --out " + (out / "x.dot").string()), 1);
  EXPECT_EQ(run("dot" + maps + " --character ana --events " + kData + "/crowd_events.ndjson --out " +
                (out / "x.dot").string()),
            1);  // --events without --time
  if (std::system("dot -V > /dev/null 2>&1") == 0) {
    ASSERT_EQ(run("dot" + maps + " --character rex --out " + (out / "rex.svg").string()), 0);
    EXPECT_TRUE(fs::exists(out / "rex.svg"));
  }
  fs::remove_all(out);
}

// Issue 19: addressees and run-time trait changes through the CLI (the shipped example).
TEST(MindmapApp, AddresseesAndRuntimeTraits) {
  const fs::path out = scratch("traits");
  ASSERT_EQ(run("simulate --maps " + kData + "/characters --events " + kData +
                "/events_traits.ndjson --propagate 1 --to-addressee --no-charts --out " + out.string()),
            0);
  const auto actions = emoface::mindmap::parse_actions(
      emoface::core::read_file(out.string() + "/actions.ndjson"), "actions.ndjson");
  bool at = false;
  for (const auto& a : actions) at = at || a.addressee == "ben";
  EXPECT_TRUE(at);
  // The map drawn at 14 s carries the changed context and affection.
  const fs::path dot = scratch("traits_dot");
  fs::create_directories(dot);
  ASSERT_EQ(run("dot --maps " + kData + "/characters --character ana --events " + kData +
                "/events_traits.ndjson --time 14 --out " + (dot / "ana.dot").string()),
            0);
  const std::string text = emoface::core::read_file((dot / "ana.dot").string());
  EXPECT_NE(text.find("context 0.90"), std::string::npos);
  EXPECT_NE(text.find("anger 0.80"), std::string::npos);
  // A bad trait change is a located input error (exit 2).
  const fs::path bad = scratch("traits_bad");
  fs::create_directories(bad);
  std::ofstream(bad / "e.ndjson") << "{\"time\": 1, \"to\": \"ana\", \"context\": [0.5]}\n";
  EXPECT_EQ(run("simulate --maps " + kData + "/characters --events " + (bad / "e.ndjson").string() +
                " --no-charts --out " + (bad / "out").string()),
            2);
}
