// Graphviz export of region motion graphs (issue 19, item 4), parsed by the `dot` program.
#include "emoface/motiongraph/dot.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/core/graphviz.hpp"
#include "emoface/motiongraph/graph.hpp"
#include "emoface/motiongraph/layout.hpp"
#include "fixtures.hpp"

namespace emoface::motiongraph {
namespace {

// source 0 → 1 (happiness, sadness) → 2 (happiness peak) → 3 (far away, depth 3)
RegionGraph tiny() {
  RegionGraph r;
  r.name = "mouth";
  r.nodes.resize(4);
  r.nodes[0].frame_count = 7;
  r.nodes[1].labels = {Label::Happiness, Label::Sadness};
  r.nodes[2].labels = {Label::Happiness};
  r.nodes[2].peak_labels = {Label::Happiness};
  r.nodes[2].peak_length_mean = 12.4;
  r.nodes[2].peak_length_std = 2.6;
  r.nodes[3].labels = {Label::Fear};
  r.edges = {{0, 1, 0.25}, {1, 2, 0.5}, {2, 3, 1.0}};
  r.neutral_node = 0;
  return r;
}

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

TEST(GraphDot, NodesEdgesAndPeaks) {
  GraphDotOptions o;
  o.edge_weights = true;
  const std::string dot = region_graph_dot(tiny(), o);
  EXPECT_EQ(dot.rfind("digraph \"motion graph mouth\" {", 0), 0u);
  EXPECT_NE(
      dot.find("n0 [shape=box, fillcolor=\"#dddddd\", label=\"source\\n(neutral, 7 frames)\"]"),
      std::string::npos)
      << dot;
  EXPECT_NE(dot.find("n1 [shape=circle, fillcolor=\"#cccccc80\", label=\"hasa\"]"),
            std::string::npos)
      << dot;
  EXPECT_NE(dot.find("n2 [shape=doublecircle, fillcolor=\"#1f77b4\", fontcolor=white, "
                     "label=\"happiness\\n12±3 f\"]"),
            std::string::npos)
      << dot;
  EXPECT_NE(dot.find("n0 -> n1 [label=\"0.25\"];"), std::string::npos);
  EXPECT_NE(dot.find("n2 -> n3 [label=\"1.00\"];"), std::string::npos);
  GraphDotOptions near;
  near.depth = 2;
  const std::string cut = region_graph_dot(tiny(), near);
  EXPECT_EQ(cut.find("n3 ["), std::string::npos);
  EXPECT_EQ(cut.find("-> n3"), std::string::npos);
  EXPECT_NE(cut.find("n1 -> n2;"), std::string::npos);
  RegionGraph bad = tiny();
  bad.neutral_node = 9;
  EXPECT_THROW(region_graph_dot(bad), InvalidInput);
}

TEST(GraphDot, DotParsesAGraphBuiltFromData) {
  if (!core::graphviz_available()) GTEST_SKIP() << "Graphviz (dot) not installed: scripts/setup.sh";
  const MotionGraph g = build_graph(test::small_prepared());
  const std::string path =
      (std::filesystem::temp_directory_path() / "emoface_graph_dot_test.svg").string();
  for (const auto& region : g.regions) {
    GraphDotOptions o;
    o.edge_weights = true;
    ASSERT_NO_THROW(core::render_dot(region_graph_dot(region, o), path)) << region.name;
    const std::string svg = slurp(path);
    EXPECT_NE(svg.find("<svg"), std::string::npos);
    EXPECT_NE(svg.find("source"), std::string::npos);
  }
  // Broken DOT is reported with dot's own message.
  try {
    core::render_dot("digraph { a -> }", path);
    ADD_FAILURE() << "no error";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("failed"), std::string::npos) << e.what();
  }
  EXPECT_THROW(core::render_dot("digraph {}", path + ".jpg"), InvalidInput);
  EXPECT_THROW(core::render_dot("digraph {}", path, "no-such-graphviz-binary"), IoError);
  std::filesystem::remove(path);
}

TEST(GraphDot, QuotingEscapesQuotesBackslashesAndNewlines) {
  EXPECT_EQ(core::dot_quote("a\"b\\c\nd"), "\"a\\\"b\\\\c\\nd\"");
}

}  // namespace
}  // namespace emoface::motiongraph
