#include "emoface/motiongraph/graph.hpp"

#include <gtest/gtest.h>

#include <queue>
#include <set>

#include "emoface/core/errors.hpp"
#include "emoface/motiongraph/io.hpp"
#include "fixtures.hpp"

namespace emoface::motiongraph {
namespace {

// One region, 1D-like motion along x: handy for hand-checkable graphs.
PreparedDatabase line_data(const std::vector<std::pair<Label, std::vector<double>>>& samples) {
  PreparedDatabase p;
  p.layout = single_region_layout(1);
  p.neutral = {Eigen::RowVector2d(100, 100)};
  int i = 0;
  for (const auto& [label, xs] : samples) {
    PreparedSample s;
    s.id = "s" + std::to_string(i++);
    s.label = label;
    s.peak_frame = xs.size() - 1;
    Eigen::MatrixXd d = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(xs.size()), 2);
    for (std::size_t f = 0; f < xs.size(); ++f) d(static_cast<Eigen::Index>(f), 0) = xs[f];
    s.displacement = {d};
    p.samples.push_back(s);
  }
  return p;
}

GraphOptions thresholds(double t, double lambda = 0.0) {
  GraphOptions o;
  o.sample_threshold = o.merge_threshold = t;
  o.similarity.lambda = lambda;
  return o;
}

TEST(Graph, ZeroThresholdKeepsEveryDistinctPose) {
  const PreparedDatabase& p = test::small_prepared();
  const MotionGraph g = build_graph(p, thresholds(0.0));
  std::size_t frames = 0;
  for (const auto& s : p.samples) frames += s.peak_frame + 1;
  EXPECT_EQ(g.source_frames, frames);
  // Only identical poses merge: the reversed copies and the first frames (the graph source, §4.1).
  const std::size_t nodes = frames - (p.samples.size() - 1);
  for (const auto& r : g.regions) EXPECT_EQ(r.nodes.size(), nodes);
  EXPECT_NEAR(g.compression_ratio(), 1.0 - static_cast<double>(nodes) / static_cast<double>(frames), 1e-12);
}

TEST(Graph, HandCheckedMerging) {
  // Two happiness samples 0,1,2,3 and 0,1,2,3,4 (x displacement, λ = 0); threshold 0.5 merges equal
  // frames only: nodes {0,1,2,3,4}; reversed copies are not appended here.
  const PreparedDatabase p =
      line_data({{Label::Happiness, {0, 1, 2, 3}}, {Label::Happiness, {0, 1, 2, 3, 4}}});
  GraphBuildReport rep;
  const MotionGraph g = build_graph(p, thresholds(0.5), &rep);
  const RegionGraph& r = g.regions[0];
  ASSERT_EQ(r.nodes.size(), 5u);
  EXPECT_EQ(r.edges.size(), 4u);
  EXPECT_NEAR(g.compression_ratio(), 1.0 - 5.0 / 9.0, 1e-12);
  const std::size_t n3 = rep.frame_nodes[0][0][3], n4 = rep.frame_nodes[0][1][4];
  EXPECT_EQ(rep.frame_nodes[0][1][3], n3);
  EXPECT_EQ(r.nodes[n3].peak_labels, std::vector<Label>{Label::Happiness});
  EXPECT_DOUBLE_EQ(r.nodes[n3].peak_length_mean, 4.0);
  EXPECT_DOUBLE_EQ(r.nodes[n4].peak_length_mean, 5.0);
  EXPECT_EQ(r.nodes[n3].frame_count, 2u);
  EXPECT_DOUBLE_EQ(r.nodes[n3].displacement[0], 3.0);
  EXPECT_DOUBLE_EQ(r.nodes[n3].velocity[0], 1.0);
  EXPECT_EQ(r.neutral_node, rep.frame_nodes[0][0][0]);
  for (const Edge& e : r.edges) EXPECT_DOUBLE_EQ(e.weight, 1.0);  // |Δx| = 1, λ = 0
  // Threshold 1.5 (per landmark, 1 landmark): 0,1 merge, then 2,3 ... consecutive runs.
  const MotionGraph coarse = build_graph(p, thresholds(1.5), &rep);
  EXPECT_LT(coarse.regions[0].nodes.size(), 5u);
  for (const Node& n : coarse.regions[0].nodes) EXPECT_GE(n.mean_run, 1.0);
}

TEST(Graph, PeakStatisticsMeanAndStd) {
  // Two fear samples of lengths 3 and 5 whose peaks coincide at x = 4: peak node mean 4, std 1.
  const PreparedDatabase p = line_data({{Label::Fear, {0, 2, 4}}, {Label::Fear, {0, 1, 2, 3, 4}}});
  GraphBuildReport rep;
  const MotionGraph g = build_graph(p, thresholds(0.5), &rep);
  const Node& peak = g.regions[0].nodes[rep.frame_nodes[0][0][2]];
  EXPECT_EQ(rep.frame_nodes[0][1][4], rep.frame_nodes[0][0][2]);
  EXPECT_DOUBLE_EQ(peak.peak_length_mean, 4.0);
  EXPECT_DOUBLE_EQ(peak.peak_length_std, 1.0);
  EXPECT_DOUBLE_EQ(peak.velocity[0], 1.5);  // mean of 2 and 1
}

TEST(Graph, Invariants) {
  const PreparedDatabase& p = test::small_prepared();
  GraphBuildReport rep;
  const MotionGraph g = build_graph(p, {}, &rep);
  EXPECT_GT(g.compression_ratio(), 0.3);
  for (std::size_t r = 0; r < g.regions.size(); ++r) {
    const RegionGraph& rg = g.regions[r];
    // Frame counts add up (reversed copies included); every node is used.
    std::size_t frames = 0, expected_frames = 0;
    for (const Node& n : rg.nodes) {
      EXPECT_GT(n.frame_count, 0u);
      frames += n.frame_count;
    }
    for (const auto& s : p.samples) expected_frames += s.frame_count();
    EXPECT_EQ(frames, expected_frames);
    // Label propagation: node labels = labels of the samples with a frame there.
    std::vector<std::set<Label>> expected(rg.nodes.size()), peaks(rg.nodes.size());
    for (std::size_t s = 0; s < p.samples.size(); ++s) {
      for (std::size_t node : rep.frame_nodes[r][s]) expected[node].insert(p.samples[s].label);
      peaks[rep.frame_nodes[r][s][p.samples[s].peak_frame]].insert(p.samples[s].label);
    }
    for (std::size_t i = 0; i < rg.nodes.size(); ++i) {
      EXPECT_EQ(std::set<Label>(rg.nodes[i].labels.begin(), rg.nodes[i].labels.end()), expected[i]);
      EXPECT_EQ(std::set<Label>(rg.nodes[i].peak_labels.begin(), rg.nodes[i].peak_labels.end()), peaks[i]);
    }
    // Connectivity: every node is reachable from the neutral node along directed edges
    // (reversed copies lead back), no self loops, no duplicate edges.
    std::set<std::pair<std::size_t, std::size_t>> seen;
    for (const Edge& e : rg.edges) {
      EXPECT_NE(e.from, e.to);
      EXPECT_TRUE(seen.insert({e.from, e.to}).second);
      EXPECT_GE(e.weight, 0.0);
    }
    const auto adj = rg.adjacency(false);
    std::vector<char> reached(rg.nodes.size(), 0);
    std::queue<std::size_t> q;
    q.push(rg.neutral_node);
    reached[rg.neutral_node] = 1;
    while (!q.empty()) {
      const std::size_t u = q.front();
      q.pop();
      for (const auto& [v, w] : adj[u])
        if (!reached[v]) reached[v] = 1, q.push(v);
    }
    for (std::size_t i = 0; i < rg.nodes.size(); ++i) EXPECT_TRUE(reached[i]) << rg.name << " node " << i;
  }
}

TEST(Graph, DeterministicForASeedAndMonotoneInThreshold) {
  const PreparedDatabase& p = test::small_prepared();
  GraphOptions a;
  a.seed = 5;
  EXPECT_EQ(graph_to_json(build_graph(p, a)), graph_to_json(build_graph(p, a)));
  GraphOptions b = a;
  b.seed = 6;
  GraphBuildReport ra, rb;
  build_graph(p, a, &ra);
  build_graph(p, b, &rb);
  EXPECT_NE(ra.seed_sample, rb.seed_sample);
  double last = -1.0;
  for (double t : {0.0, 0.5, 1.0, 2.0, 4.0}) {
    const double c = build_graph(p, thresholds(t, 0.5)).compression_ratio();
    EXPECT_GE(c, last - 0.02) << t;  // greedy merging: nearly monotone
    last = c;
  }
  EXPECT_GT(last, 0.8);
}

TEST(Graph, BadInput) {
  GraphOptions o;
  o.sample_threshold = -1;
  EXPECT_THROW(build_graph(test::small_prepared(), o), InvalidInput);
  o = {};
  o.similarity.lambda = std::nan("");
  EXPECT_THROW(build_graph(test::small_prepared(), o), InvalidInput);
  PreparedDatabase empty = test::small_prepared();
  empty.samples.clear();
  EXPECT_THROW(build_graph(empty, {}), InvalidInput);
  PreparedDatabase broken = test::small_prepared();
  broken.samples[0].peak_frame = 1000;
  EXPECT_THROW(build_graph(broken, {}), InvalidInput);
}

TEST(Graph, RegionByName) {
  const MotionGraph g = build_graph(test::small_prepared(), {});
  EXPECT_EQ(g.region("mouth").name, "mouth");
  EXPECT_EQ(&g.region("eyes"), &g.regions[0]);
  try {
    g.region("lips");
    ADD_FAILURE() << "found lips";
  } catch (const InvalidInput& e) {
    EXPECT_STREQ(e.what(),
                 "no region \"lips\" (the graph has eyes, eyebrows, nose, mouth, cheeks_jaw)");
  }
}

}  // namespace
}  // namespace emoface::motiongraph
