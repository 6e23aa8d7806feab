#include "emoface/motiongraph/synthesis.hpp"

#include <set>

#include <gtest/gtest.h>

#include <functional>
#include <limits>

#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"
#include "fixtures.hpp"

namespace emoface::motiongraph {
namespace {

using Adjacency = std::vector<std::vector<std::pair<std::size_t, double>>>;

// Brute force: cheapest simple path from source to any target by exhaustive DFS.
double brute_force(const Adjacency& adj, std::size_t source, const std::vector<char>& target) {
  double best = std::numeric_limits<double>::infinity();
  std::vector<char> on(adj.size(), 0);
  std::function<void(std::size_t, double)> dfs = [&](std::size_t u, double cost) {
    if (target[u]) {
      best = std::min(best, cost);
      return;
    }
    on[u] = 1;
    for (const auto& [v, w] : adj[u])
      if (!on[v]) dfs(v, cost + w);
    on[u] = 0;
  };
  dfs(source, 0.0);
  return best;
}

TEST(ShortestPath, MatchesBruteForceOnRandomGraphs) {
  core::Rng rng(42);
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t n = 2 + rng.uniform_int(7);
    Adjacency adj(n);
    for (std::size_t u = 0; u < n; ++u)
      for (std::size_t v = 0; v < n; ++v)
        if (u != v && rng.uniform() < 0.35) adj[u].emplace_back(v, rng.uniform(0.0, 10.0));
    std::vector<char> target(n, 0);
    for (std::size_t i = 0; i < n; ++i) target[i] = rng.uniform() < 0.25;
    const std::size_t source = rng.uniform_int(n);
    double cost = -1.0;
    const auto path = shortest_path(adj, source, target, &cost);
    const double expected = brute_force(adj, source, target);
    if (std::isinf(expected)) {
      EXPECT_TRUE(path.empty());
      continue;
    }
    ASSERT_FALSE(path.empty());
    EXPECT_NEAR(cost, expected, 1e-9);
    EXPECT_EQ(path.front(), source);
    EXPECT_TRUE(target[path.back()]);
    double sum = 0.0;  // the path is made of existing edges and costs what it says
    for (std::size_t i = 1; i < path.size(); ++i) {
      double w = std::numeric_limits<double>::infinity();
      for (const auto& [v, x] : adj[path[i - 1]])
        if (v == path[i]) w = std::min(w, x);
      sum += w;
    }
    EXPECT_NEAR(sum, cost, 1e-9);
  }
  EXPECT_THROW(shortest_path(Adjacency(2), 5, {0, 1}), InvalidInput);
}

const MotionGraph& graph() {
  static const MotionGraph g = build_graph(test::small_prepared(), {});
  return g;
}

TEST(Synthesize, ReachesRequestedPeakAndAdvancesState) {
  SynthesisState state = initial_state(graph());
  SynthesisReport rep;
  const auto frames = synthesize(graph(), state, Label::Surprise, {}, &rep);
  ASSERT_GE(frames.size(), 2u);
  const std::size_t k = graph().landmark_ids().size();
  for (const Pose& p : frames) {
    EXPECT_EQ(static_cast<std::size_t>(p.rows()), k);
    EXPECT_TRUE(p.allFinite());
  }
  for (std::size_t r = 0; r < graph().regions.size(); ++r) {
    EXPECT_TRUE(graph().regions[r].nodes[state.nodes[r]].has_peak_label(Label::Surprise));
    EXPECT_EQ(rep.paths[r].back(), state.nodes[r]);
    EXPECT_EQ(rep.paths[r].front(), graph().regions[r].neutral_node);
  }
  // The first frame is the neutral pose; the mouth opens (surprise = jaw drop, y down).
  const Eigen::Index mouth_bottom = 6 + 12 + 5 + 6;  // eyes 12, brows 6, nose 5, then mouth: 57 is 7th
  EXPECT_GT(frames.back()(mouth_bottom, 1) - frames.front()(mouth_bottom, 1), 10.0);
  // Length near the peaks' mean length (CK+-like 6–12 frames here).
  EXPECT_GE(frames.size(), 5u);
  EXPECT_LE(frames.size(), 14u);
  // Chained: the sink is the next source, and the next animation starts where this one ended.
  const auto next = synthesize(graph(), state, Label::Happiness);
  EXPECT_LT((next.front() - frames.back()).cwiseAbs().maxCoeff(), 1e-9);
  for (std::size_t r = 0; r < graph().regions.size(); ++r)
    EXPECT_TRUE(graph().regions[r].nodes[state.nodes[r]].has_peak_label(Label::Happiness));
}

std::string dump(const std::vector<Pose>& frames) {
  std::string s;
  for (const Pose& p : frames)
    for (Eigen::Index i = 0; i < p.size(); ++i) s += std::to_string(p.data()[i]) + ",";
  return s;
}

TEST(Synthesize, SeededVariation) {
  SynthesisOptions o;
  o.vary_duration = true;
  o.replace_probability = 0.5;
  o.seed = 3;
  auto run = [&](std::uint64_t seed) {
    SynthesisOptions x = o;
    x.seed = seed;
    SynthesisState s = initial_state(graph());
    return dump(synthesize(graph(), s, Label::Fear, x));
  };
  EXPECT_EQ(run(3), run(3));
  bool differs = false;
  for (std::uint64_t seed = 4; seed < 12 && !differs; ++seed) differs = run(seed) != run(3);
  EXPECT_TRUE(differs);
}

TEST(Synthesize, VaryPeakReachesDifferentPeaksOfTheLabel) {
  // Without it every run from neutral ends at the cheapest peak; with it at random peaks of the label.
  std::set<std::vector<std::size_t>> ends;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    SynthesisOptions o;
    o.vary_peak = true;
    o.seed = seed;
    SynthesisState s = initial_state(graph());
    synthesize(graph(), s, Label::Happiness, o);
    for (std::size_t r = 0; r < graph().regions.size(); ++r)
      EXPECT_TRUE(graph().regions[r].nodes[s.nodes[r]].has_peak_label(Label::Happiness));
    ends.insert(s.nodes);
  }
  EXPECT_GE(ends.size(), 6u);
  SynthesisState plain = initial_state(graph());
  synthesize(graph(), plain, Label::Happiness);
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    SynthesisOptions o;
    o.seed = seed;
    SynthesisState s = initial_state(graph());
    synthesize(graph(), s, Label::Happiness, o);
    EXPECT_EQ(s.nodes, plain.nodes);  // off: the cheapest peak, whatever the seed
  }
}

TEST(Synthesize, MoodDecayHintUsesInitialNodes) {
  SynthesisState full_state = initial_state(graph()), hint_state = initial_state(graph());
  SynthesisReport full, hint;
  synthesize(graph(), full_state, Label::Anger, {}, &full);
  SynthesisOptions o;
  o.path_fraction = 0.5;
  synthesize(graph(), hint_state, Label::Anger, o, &hint);
  for (std::size_t r = 0; r < full.paths.size(); ++r) {
    ASSERT_LE(hint.paths[r].size(), full.paths[r].size());
    for (std::size_t i = 0; i < hint.paths[r].size(); ++i) EXPECT_EQ(hint.paths[r][i], full.paths[r][i]);
  }
}

TEST(Synthesize, BadInput) {
  SynthesisState s = initial_state(graph());
  SynthesisState wrong;
  EXPECT_THROW(synthesize(graph(), wrong, Label::Fear), InvalidInput);
  SynthesisOptions o;
  o.path_fraction = 0.0;
  EXPECT_THROW(synthesize(graph(), s, Label::Fear, o), InvalidInput);
  o = {};
  o.smoothing.savgol_window = 4;
  EXPECT_THROW(synthesize(graph(), s, Label::Fear, o), InvalidInput);
  std::vector<Eigen::MatrixXd> frames(graph().regions.size(), Eigen::MatrixXd::Zero(3, 2));
  EXPECT_THROW(assemble(graph(), frames, {}), InvalidInput);  // wrong widths
  EXPECT_THROW(assemble(graph(), {}, {}), InvalidInput);
}

TEST(Synthesize, ThreeDimensionalDatabaseWithOneRegion) {
  Database db;
  db.dimensions = 3;
  db.landmark_count = 4;
  for (int s = 0; s < 6; ++s) {
    Sequence seq;
    seq.id = "q" + std::to_string(s);
    seq.label = s % 2 ? Label::Fear : Label::Sadness;
    for (int f = 0; f < 8 + s; ++f) {
      Pose p(4, 3);
      for (int i = 0; i < 4; ++i) p.row(i) << 10.0 * i, 5.0 * i * i, 3.0 * i;
      const double x = f / (7.0 + s);
      p(0, 2) += (s % 2 ? 6.0 : -6.0) * x;  // landmark 0 moves in depth
      p(3, 1) += 4.0 * x;
      seq.frames.push_back(p);
    }
    db.sequences.push_back(seq);
  }
  const PreparedDatabase data = preprocess(db, single_region_layout(4));
  const MotionGraph g = build_graph(data, {});
  SynthesisState state = initial_state(g);
  const auto frames = synthesize(g, state, Label::Fear);
  ASSERT_GE(frames.size(), 2u);
  EXPECT_EQ(frames.back().cols(), 3);
  EXPECT_GT(frames.back()(0, 2) - frames.front()(0, 2), 3.0);  // towards +z for fear
}

TEST(RecoverPath, RunsAndStretching) {
  RegionGraph r;
  r.neutral = Eigen::RowVector2d(0, 0);
  Node a, b;
  a.displacement = Eigen::RowVector2d(0, 0);
  a.velocity = Eigen::RowVector2d(0, 0);
  b.displacement = Eigen::RowVector2d(10, 0);
  b.velocity = Eigen::RowVector2d(-2, 0);  // opposite to the motion: gets flipped
  b.mean_run = 3.0;
  b.peak_labels = {Label::Fear};
  b.peak_length_mean = 7.0;
  r.nodes = {a, b};
  const Eigen::MatrixXd m = recover_path(r, {0, 1}, 0);
  ASSERT_EQ(m.rows(), 4);
  EXPECT_DOUBLE_EQ(m(1, 0), 8.0);
  EXPECT_DOUBLE_EQ(m(2, 0), 10.0);
  EXPECT_DOUBLE_EQ(m(3, 0), 12.0);
  EXPECT_DOUBLE_EQ(path_length(r, {0, 1}), 7.0);
  const Eigen::MatrixXd s = recover_path(r, {0, 1}, 7);
  EXPECT_EQ(s.rows(), 7);
  EXPECT_DOUBLE_EQ(s(6, 0), 12.0);
  EXPECT_THROW(recover_path(r, {}, 0), InvalidInput);
  EXPECT_THROW(recover_path(r, {0, 5}, 0), InvalidInput);
}

TEST(Idle, HopsOnlyAmongLabelledNeighbours) {
  SynthesisState s = initial_state(graph());
  synthesize(graph(), s, Label::Happiness);
  const SynthesisState home = s;
  IdleOptions o;
  o.duration = 3.0;
  const auto frames = idle(graph(), s, Label::Happiness, o);
  EXPECT_EQ(frames.size(), 90u);  // 3 s at 30 fps
  for (std::size_t r = 0; r < graph().regions.size(); ++r) {
    const RegionGraph& rg = graph().regions[r];
    const bool neighbour_or_home =
        s.nodes[r] == home.nodes[r] ||
        std::any_of(rg.edges.begin(), rg.edges.end(), [&](const Edge& e) {
          return (e.from == home.nodes[r] && e.to == s.nodes[r]) || (e.to == home.nodes[r] && e.from == s.nodes[r]);
        });
    EXPECT_TRUE(neighbour_or_home);
    EXPECT_TRUE(rg.nodes[s.nodes[r]].has_label(Label::Happiness));
  }
  SynthesisState again = home;
  EXPECT_EQ(dump(idle(graph(), again, Label::Happiness, o)), dump(frames));  // seeded
  o.dwell = o.hop_interval;
  EXPECT_THROW(idle(graph(), again, Label::Happiness, o), InvalidInput);
}

// Issue 19: `neutral` returns to rest through the graph source.
TEST(Synthesize, NeutralReturnsToTheSourceNode) {
  SynthesisState s = initial_state(graph());
  const auto up = synthesize(graph(), s, Label::Surprise);
  SynthesisReport rep;
  const auto down = synthesize(graph(), s, Label::Neutral, {}, &rep);
  ASSERT_GE(down.size(), 2u);
  EXPECT_LT((down.front() - up.back()).cwiseAbs().maxCoeff(), 1e-9);  // continuous
  for (std::size_t r = 0; r < graph().regions.size(); ++r) {
    const RegionGraph& rg = graph().regions[r];
    EXPECT_EQ(s.nodes[r], rg.neutral_node);
    EXPECT_EQ(rep.paths[r].back(), rg.neutral_node);
    // Step 2 for a peak-to-neutral path: Ls·(1 − dc/ds) + Lt·(1 − dc/dt) with Ls the source peak's
    // mean length, Lt = 1 (the source node) and dc the smallest displacement norm on the path.
    const auto& path = rep.paths[r];
    const Node& peak = rg.nodes[path.front()];
    if (peak.is_peak() && path.size() > 1) {
      double dc = 1e300;
      for (std::size_t i : path) dc = std::min(dc, rg.nodes[i].displacement.norm());
      const double ds = peak.displacement.norm(), dt = rg.nodes[path.back()].displacement.norm();
      const double expected =
          peak.peak_length_mean * (1.0 - dc / ds) + (dt > 0.0 ? 1.0 - dc / dt : 0.0);
      EXPECT_EQ(rep.region_lengths[r], static_cast<std::size_t>(std::lround(std::max(2.0, expected))))
          << rg.name;
      EXPECT_GE(rep.region_lengths[r] + 1.0, 0.9 * peak.peak_length_mean) << rg.name;
    }
  }
  // The last frame is the averaged neutral of every region (up to the Savitzky–Golay smoothing of
  // the last frames, which is not pinned), while the surprise peak was > 10 px away.
  Eigen::Index row = 0;
  double largest = 0.0;
  for (const RegionGraph& rg : graph().regions) {
    const Eigen::RowVectorXd home = rg.neutral + rg.nodes[rg.neutral_node].displacement;
    for (Eigen::Index l = 0; l < home.size() / 2; ++l, ++row)
      for (int j = 0; j < 2; ++j) largest = std::max(largest, std::abs(down.back()(row, j) - home[l * 2 + j]));
  }
  EXPECT_LT(largest, 0.5);
  // From rest, neutral is one frame (nothing to do).
  SynthesisState rest = initial_state(graph());
  EXPECT_EQ(synthesize(graph(), rest, Label::Neutral).size(), 1u);
}

TEST(Idle, AtRestMovesAroundTheNeutralPose) {
  // Before the first stimulus the face is at the source node; idling there used to freeze it.
  SynthesisState s = initial_state(graph());
  IdleOptions o;
  o.duration = 4.0;
  const auto frames = idle(graph(), s, Label::Neutral, o);
  ASSERT_EQ(frames.size(), 120u);
  double moved = 0.0;
  for (const Pose& p : frames) moved = std::max(moved, (p - frames.front()).cwiseAbs().maxCoeff());
  EXPECT_GT(moved, 0.05);  // it moves ...
  // ... but stays near rest: every hop target is within rest_fraction (0.1) of the region's mean
  // peak displacement norm, so no landmark moves more than that bound (plus the source's own offset).
  double bound = 0.0;
  for (std::size_t r = 0; r < graph().regions.size(); ++r) {
    const RegionGraph& rg = graph().regions[r];
    double sum = 0.0, count = 0.0;
    for (const Node& n : rg.nodes)
      if (n.is_peak()) sum += n.displacement.norm(), count += 1.0;
    const double rest = 0.1 * sum / count;
    const Node& n = rg.nodes[s.nodes[r]];
    EXPECT_TRUE(s.nodes[r] == rg.neutral_node || n.displacement.norm() <= rest) << rg.name;
    bound = std::max(bound, rest + rg.nodes[rg.neutral_node].displacement.norm());
  }
  EXPECT_LE(moved, bound + 1e-9);
  o.rest_fraction = 0.0;
  EXPECT_THROW(idle(graph(), s, Label::Neutral, o), InvalidInput);
}

}  // namespace
}  // namespace emoface::motiongraph
