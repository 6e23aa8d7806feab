// Graphviz export of mind maps (issue 19, item 4), parsed by the `dot` program.
#include "emoface/mindmap/dot.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "emoface/core/errors.hpp"
#include "emoface/core/graphviz.hpp"
#include "emoface/mindmap/chart.hpp"
#include "fixtures.hpp"

namespace emoface::mindmap {
namespace {

TEST(MindMapDot, NodesEdgesWeightsAndMood) {
  MindMapDotOptions o;
  o.mood = {0.25, 0.5};
  const std::string dot = mind_map_dot(test::make_alice(), o);
  EXPECT_EQ(dot.rfind("digraph \"mind map alice\" {", 0), 0u);
  EXPECT_NE(dot.find("character [shape=doubleoctagon"), std::string::npos);
  // Emotion nodes in the mood-chart colours, with the mood; border 1 + 4·mood.
  char colour[16];
  std::snprintf(colour, sizeof colour, "#%06x", emotion_colour(1));
  EXPECT_NE(
      dot.find(std::string("e1 [shape=ellipse, style=filled, fillcolor=\"") + colour +
               "40\", color=\"" + colour + "\", penwidth=3.00, label=\"sadness\\nmood 0.50\"]"),
      std::string::npos)
      << dot;
  EXPECT_NE(dot.find("a0 [shape=note, label=\"gift\"]"), std::string::npos);  // stimulus
  EXPECT_NE(dot.find("a2 [shape=box, style=rounded, label=\"smile\\n[happiness]\"]"),
            std::string::npos);
  EXPECT_NE(dot.find("a0 -> e0 [color="), std::string::npos);
  EXPECT_NE(dot.find("label=\"0.80\"];"), std::string::npos);  // gift → happiness
  EXPECT_NE(dot.find("label=\"0.90\"];"), std::string::npos);  // happiness → laugh
  EXPECT_NE(dot.find("a2 -> a5 [style=dashed, label=\"then\"];"),
            std::string::npos);  // chain smile → wave
  EXPECT_NE(dot.find("e1 -> a4 [style=dotted, label=\"decay\"];"),
            std::string::npos);  // representative
  o.mood = {0.1};
  EXPECT_THROW(mind_map_dot(test::make_alice(), o), InvalidInput);
  o.mood = {0.1, 1.5};
  EXPECT_THROW(mind_map_dot(test::make_alice(), o), InvalidInput);
  o.mood.clear();
  o.weights = false;
  EXPECT_EQ(mind_map_dot(test::make_alice(), o).find("0.80"), std::string::npos);
}

TEST(MindMapDot, MoodAtPicksTheLastSampleAtOrBeforeTheTime) {
  SimulationResult r;
  r.times = {0.0, 0.5, 1.0};
  r.mood = {{0.1, 0.2, 0.3, 0.4, 0.5, 0.6}};
  EXPECT_EQ(mood_at(r, 0, 0.7), (std::vector<double>{0.3, 0.4}));
  EXPECT_EQ(mood_at(r, 0, -1.0), (std::vector<double>{0.1, 0.2}));
  EXPECT_EQ(mood_at(r, 0, 9.0), (std::vector<double>{0.5, 0.6}));
  EXPECT_THROW(mood_at(r, 1, 0.0), InvalidInput);
}

// mindmap dot: the map as it stands at a time, with its mood then.
TEST(MindMapDot, AtATime) {
  const std::vector<MindMap> maps{test::make_alice(), test::make_bob()};
  EXPECT_EQ(mind_map_dot_at(maps, "bob", nullptr, -1.0), mind_map_dot(test::make_bob()));
  // No events: the starting mood (alice: happiness 0.2, sadness 0.4).
  const std::string start = mind_map_dot_at(maps, "alice", nullptr, 0.0);
  EXPECT_NE(start.find("label=\"happiness\\nmood 0.20\""), std::string::npos) << start;
  EXPECT_NE(start.find("label=\"sadness\\nmood 0.40\""), std::string::npos) << start;
  // With events: the simulated mood at the time (the simulation runs up to it).
  Event gift;
  gift.time = 1.0;
  gift.target = "alice";
  gift.stimulus = "gift";
  const std::vector<Event> events{gift};
  SimulationOptions sim;
  sim.duration = 2.0;
  MindMapDotOptions o;
  o.mood = mood_at(simulate(maps, events, sim), 0, 2.0);
  EXPECT_GT(o.mood[0], 0.2);  // the gift raised happiness
  EXPECT_EQ(mind_map_dot_at(maps, "alice", &events, 2.0), mind_map_dot(test::make_alice(), o));
  try {
    mind_map_dot_at(maps, "carol", nullptr, 0.0);
    ADD_FAILURE() << "drew carol";
  } catch (const InvalidInput& e) {
    EXPECT_STREQ(e.what(), "no mind map of \"carol\"");
  }
  EXPECT_THROW(mind_map_dot_at(maps, "alice", &events, -1.0), InvalidInput);
}

TEST(MindMapDot, DotParsesIt) {
  if (!core::graphviz_available()) GTEST_SKIP() << "Graphviz (dot) not installed: scripts/setup.sh";
  const std::string path =
      (std::filesystem::temp_directory_path() / "emoface_mindmap_dot_test.svg").string();
  MindMap odd = test::make_alice();
  odd.character = "al\"ice \\ the\nfirst";  // quoting
  ASSERT_NO_THROW(core::render_dot(mind_map_dot(odd, {{0.3, 0.7}, true}), path));
  std::ifstream in(path);
  const std::string svg{std::istreambuf_iterator<char>(in), {}};
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("laugh"), std::string::npos);
  std::filesystem::remove(path);
}

// core::write_dot, the one writer of `mindmap dot` and `mgraph dot`: text by default, rendered by
// the extension.
TEST(MindMapDot, WriteDotWritesTextOrRendersByExtension) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("emoface_write_dot_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string text = mind_map_dot(test::make_alice(), {});
  core::write_dot(text, (dir / "a.dot").string());
  std::ifstream in(dir / "a.dot");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), text);
  testing::internal::CaptureStdout();
  core::write_dot(text, "-");
  EXPECT_EQ(testing::internal::GetCapturedStdout(), text);
  if (core::graphviz_available()) {
    core::write_dot(text, (dir / "a.svg").string());
    EXPECT_TRUE(std::filesystem::exists(dir / "a.svg"));
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace emoface::mindmap
