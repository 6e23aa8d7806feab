// Weight-space motion graphs (issue 19 item 2): databases of dimensions 1 through preprocessing,
// graph building, synthesis, idle, evaluation and the readers.
#include "emoface/motiongraph/weights.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "emoface/core/errors.hpp"
#include "emoface/motiongraph/capture.hpp"
#include "emoface/motiongraph/io.hpp"

namespace mg = emoface::motiongraph;

namespace {

// Two channels per region, 3 regions; `label` moves its own region from 0 to `peak` (φ+-like ramp
// i²/(n−1)²) and the others stay at `rest`.
mg::Sequence ramp(const std::string& id, mg::Label label, int region, std::size_t n, double peak,
                  double rest = 0.05) {
  mg::Sequence s;
  s.id = id;
  s.subject = "S" + id;
  s.label = label;
  for (std::size_t f = 0; f < n; ++f) {
    const double x = static_cast<double>(f * f) / static_cast<double>((n - 1) * (n - 1));
    mg::Pose p = mg::Pose::Constant(6, 1, rest);
    p(2 * region, 0) = rest + (peak - rest) * x;
    p(2 * region + 1, 0) = rest + 0.5 * (peak - rest) * x;
    s.frames.push_back(p);
  }
  return s;
}

mg::Database weight_db() {
  mg::Database db;
  db.dimensions = 1;
  db.landmark_count = 6;
  db.frame_rate = 30.0;
  db.sequences = {
      ramp("a", mg::Label::Happiness, 0, 12, 0.8), ramp("b", mg::Label::Happiness, 0, 14, 0.7),
      ramp("c", mg::Label::Sadness, 1, 10, 0.6), ramp("d", mg::Label::Sadness, 1, 16, 0.5),
      ramp("e", mg::Label::Surprise, 2, 11, 0.9)};
  return db;
}

mg::LandmarkLayout three_regions() {
  mg::LandmarkLayout l;
  l.source_landmark_count = 6;
  l.regions = {{"r0", {0, 1}, {}}, {"r1", {2, 3}, {}}, {"r2", {4, 5}, {}}};
  return l;
}

mg::PreprocessOptions raw_options() {
  mg::PreprocessOptions o = mg::weight_preprocess_options();
  o.clean = false;
  return o;
}

}  // namespace

TEST(WeightSpace, DatabaseValidatesOneDimension) {
  mg::Database db = weight_db();
  EXPECT_NO_THROW(mg::validate(db));
  db.sequences[0].frames[3] = mg::Pose::Zero(6, 2);
  EXPECT_THROW(mg::validate(db), emoface::InvalidInput);
  db = weight_db();
  db.dimensions = 0;
  EXPECT_THROW(mg::validate(db), emoface::InvalidInput);
}

TEST(WeightSpace, PreprocessNeitherTranslatesNorAligns) {
  const mg::PreparedDatabase data = mg::preprocess(weight_db(), three_regions(), raw_options());
  ASSERT_EQ(data.dimensions, 1);
  // Neutral = plain mean of the first frames (all 0.05), not centred.
  for (const auto& n : data.neutral) {
    EXPECT_NEAR(n.maxCoeff(), 0.05, 1e-15);
    EXPECT_NEAR(n.minCoeff(), 0.05, 1e-15);
  }
  // Displacements are the weights minus the first frame, frame for frame (hand-computed: sample
  // "a", region 0, frame 11 of 12 = 0.8 − 0.05; channel 1 half of it).
  const mg::PreparedSample& a = data.samples[0];
  EXPECT_NEAR(a.displacement[0](11, 0), 0.75, 1e-12);
  EXPECT_NEAR(a.displacement[0](11, 1), 0.375, 1e-12);
  EXPECT_NEAR(a.displacement[1].cwiseAbs().maxCoeff(), 0.0, 1e-15);
  // Reversed copy appended (§7).
  EXPECT_EQ(a.frame_count(), 2u * 12u - 1u);
}

TEST(WeightSpace, Eq1InOneDimensionIsL1PlusStillTerm) {
  // d = 1: dist = |Δw|; both moving → vinfl 0; one still → vinfl 1 (hand-computed).
  const double pa[2] = {0.2, 0.5}, pb[2] = {0.5, 0.4};
  const double va[2] = {0.1, 0.0}, vb[2] = {-0.3, 0.2};
  mg::SimilarityOptions o;
  o.lambda = 0.5;
  // channel 0: |0.3|, both moving → 0.3; channel 1: |0.1|, a still → 0.1 + 0.5·0.1 = 0.15.
  EXPECT_NEAR(mg::similarity(pa, va, pb, vb, 2, 1, o), 0.45, 1e-15);
}

TEST(WeightSpace, GraphSynthesisReachesTheLabelsPeakAndReturnsToRest) {
  const mg::PreparedDatabase data =
      mg::preprocess(weight_db(), three_regions(), mg::weight_preprocess_options());
  const mg::MotionGraph g = mg::build_graph(data, mg::weight_graph_options());
  EXPECT_EQ(g.dimensions, 1);
  EXPECT_GT(g.compression_ratio(), 0.0);
  mg::SynthesisState st = mg::initial_state(g);
  const auto happy = mg::synthesize(g, st, mg::Label::Happiness, mg::weight_synthesis_options());
  ASSERT_GE(happy.size(), 2u);
  EXPECT_EQ(happy.back().rows(), 6);
  EXPECT_EQ(happy.back().cols(), 1);
  // The apex lies between the two happiness samples' peaks (0.7, 0.8) on channel 0.
  EXPECT_GT(happy.back()(0, 0), 0.65);
  EXPECT_LT(happy.back()(0, 0), 0.85);
  EXPECT_NEAR(happy.front()(0, 0), 0.05, 0.02);
  const auto rest = mg::synthesize(g, st, mg::Label::Neutral, mg::weight_synthesis_options());
  EXPECT_NEAR(rest.back()(0, 0), 0.05, 0.02);
  // Idle at rest moves only little.
  const auto idle = mg::idle(g, st, mg::Label::Neutral, mg::weight_idle_options());
  for (const auto& p : idle) EXPECT_LT(p.maxCoeff(), 0.3);
  // Full channel vectors for the face.
  const auto w = mg::weight_frames(g, happy, 8);
  ASSERT_EQ(w.size(), happy.size());
  EXPECT_EQ(w[0].size(), 8u);
  EXPECT_EQ(w.back()[6], 0.0);
  EXPECT_NEAR(w.back()[0], happy.back()(0, 0), 1e-15);
}

TEST(WeightSpace, WeightFramesRejectsBadInput) {
  const mg::PreparedDatabase data = mg::preprocess(weight_db(), three_regions(), raw_options());
  const mg::MotionGraph g = mg::build_graph(data, mg::weight_graph_options());
  EXPECT_THROW(mg::weight_frames(g, {mg::Pose::Zero(5, 1)}, 6), emoface::InvalidInput);
  EXPECT_THROW(mg::weight_frames(g, {mg::Pose::Zero(6, 1)}, 5), emoface::InvalidInput);
  mg::Pose nan = mg::Pose::Zero(6, 1);
  nan(2, 0) = std::nan("");
  EXPECT_THROW(mg::weight_frames(g, {nan}, 6), emoface::InvalidInput);
  mg::MotionGraph landmarks = g;
  landmarks.dimensions = 2;
  EXPECT_THROW(mg::weight_frames(landmarks, {}, 6), emoface::InvalidInput);
}

TEST(WeightSpace, EvaluationComparesWithRawSamplesToo) {
  mg::Database db = weight_db();
  // Jitter on the raw samples: the cleaned and raw comparisons must then differ.
  for (auto& s : db.sequences)
    for (std::size_t f = 1; f + 1 < s.frames.size(); ++f)
      s.frames[f](0, 0) += (f % 2 ? 0.01 : -0.01);
  mg::PreprocessOptions po = mg::weight_preprocess_options();
  po.check_neutral_start = false;
  const mg::PreparedDatabase cleaned = mg::preprocess(db, three_regions(), po);
  po.clean = false;
  const mg::PreparedDatabase raw = mg::preprocess(db, three_regions(), po);
  const mg::EvaluationOptions eo = mg::weight_evaluation_options();
  const mg::EvaluationRow row = mg::evaluate(cleaned, 0.0, eo, &raw);
  EXPECT_TRUE(row.has_raw);
  EXPECT_GT(row.raw_pose_mean, 0.0);
  EXPECT_NE(row.raw_pose_mean, row.pose_mean);
  // Against itself as "raw" the two comparisons agree exactly.
  const mg::EvaluationRow same = mg::evaluate(cleaned, 0.0, eo, &cleaned);
  EXPECT_DOUBLE_EQ(same.raw_pose_mean, same.pose_mean);
  EXPECT_DOUBLE_EQ(same.raw_pose_std, same.pose_std);
  // Shards merge the raw sums exactly.
  mg::EvaluationOptions half = eo;
  half.shard_count = 2;
  std::vector<mg::EvaluationRow> parts;
  for (std::size_t i = 0; i < 2; ++i) {
    half.shard_index = i;
    parts.push_back(mg::evaluate(cleaned, 0.0, half, &raw));
  }
  const mg::EvaluationRow merged = mg::merge_rows(parts);
  EXPECT_NEAR(merged.raw_pose_mean, row.raw_pose_mean, 1e-12);
  EXPECT_NEAR(merged.raw_pose_std, row.raw_pose_std, 1e-12);
  // A raw database that does not match is refused.
  mg::Database fewer = db;
  fewer.sequences.pop_back();
  const mg::PreparedDatabase other = mg::preprocess(fewer, three_regions(), po);
  EXPECT_THROW(mg::evaluate(cleaned, 0.0, eo, &other), emoface::InvalidInput);
  mg::EvaluationRow without = row;
  without.has_raw = false;
  EXPECT_THROW(mg::merge_rows({row, without}), emoface::InvalidInput);
}

TEST(WeightSpace, JsonAndCsvRoundTrip) {
  const mg::Database db = weight_db();
  const mg::Database j = mg::parse_database_json(mg::database_to_json(db));
  EXPECT_EQ(j.dimensions, 1);
  ASSERT_EQ(j.sequences.size(), db.sequences.size());
  EXPECT_EQ(j.sequences[2].frames[4], db.sequences[2].frames[4]);
  const std::string csv = mg::database_to_csv(db);
  EXPECT_NE(csv.find("frame,w0,w1,w2,w3,w4,w5\n"), std::string::npos);
  const mg::Database c = mg::parse_database_csv(csv);
  EXPECT_EQ(c.dimensions, 1);
  EXPECT_EQ(c.landmark_count, 6u);
  EXPECT_EQ(c.sequences[4].frames[10], db.sequences[4].frames[10]);
  // A weight header with a wrong column name is located.
  std::string bad = csv;
  bad.replace(bad.find("w3"), 2, "x3");
  try {
    mg::parse_database_csv(bad, "bad.csv");
    FAIL();
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("w3"), std::string::npos) << e.what();
  }
  // The graph file keeps dimensions 1.
  const mg::MotionGraph g = mg::build_graph(mg::preprocess(db, three_regions(), raw_options()),
                                            mg::weight_graph_options());
  EXPECT_EQ(mg::parse_graph_json(mg::graph_to_json(g)).dimensions, 1);
}

TEST(WeightSpace, WeightTakesAreTrimmedWithWeightThresholds) {
  // A take at rest (0.02 jitter-free) with one expression: 10 rest, 8 onset to 0.6, 4 hold, 10
  // rest.
  mg::TrackedFrames t;
  t.id = "take";
  t.dimensions = 1;
  std::vector<double> level;
  for (int i = 0; i < 10; ++i) level.push_back(0.0);
  for (int i = 1; i <= 8; ++i) level.push_back(0.6 * i / 8.0);
  for (int i = 0; i < 4; ++i) level.push_back(0.6);
  for (int i = 7; i >= 0; --i) level.push_back(0.6 * i / 8.0);
  for (int i = 0; i < 10; ++i) level.push_back(0.0);
  for (std::size_t i = 0; i < level.size(); ++i) {
    mg::Pose p = mg::Pose::Zero(8, 1);
    p(0, 0) = p(1, 0) = level[i];
    t.frames.push_back(p);
    t.times.push_back(static_cast<double>(i) / 30.0);
    t.confidence.push_back(1.0);
    t.success.push_back(1);
  }
  // m = RMS of the top quarter (2 of 8 channels) = the level; smoothed by 3 frames. The first frame
  // above weight_low (0.03) is frame 10 (0.075), so the segment starts at frame 9; the level is 0.6
  // on frames 17–21 and the 3-frame mean first reaches 0.6 at frame 18 (the apex).
  const auto seg = mg::find_segments(t);
  ASSERT_EQ(seg.size(), 1u);
  EXPECT_EQ(seg[0].first, 9u);
  EXPECT_EQ(seg[0].peak, 18u);
  // capture_database keeps the channel count and never stabilises weights.
  mg::LabelTable labels;
  labels.entries[{"take", "0"}] = mg::Label::Happiness;
  const mg::Database db = mg::capture_database({t}, {}, &labels);
  EXPECT_EQ(db.dimensions, 1);
  EXPECT_EQ(db.landmark_count, 8u);
  ASSERT_EQ(db.sequences.size(), 1u);
  EXPECT_EQ(db.sequences[0].frames.back()(0, 0), 0.6);
  // Takes of different channel counts are refused.
  mg::TrackedFrames other = t;
  other.id = "other";
  for (auto& p : other.frames) p = mg::Pose::Zero(7, 1);
  EXPECT_THROW(mg::capture_database({t, other}, {}, &labels), emoface::InvalidInput);
  // Frames of mixed channel counts within a take are refused.
  mg::TrackedFrames broken = t;
  broken.frames[5] = mg::Pose::Zero(7, 1);
  EXPECT_THROW(broken.validate(), emoface::InvalidInput);
}
