#include "emoface/motiongraph/synthetic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "emoface/core/errors.hpp"
#include "emoface/motiongraph/io.hpp"

namespace emoface::motiongraph {
namespace {

TEST(OnsetCurve, ThesisFormula) {
  EXPECT_DOUBLE_EQ(onset_curve(0.0, 10.0), 0.0);
  EXPECT_NEAR(onset_curve(10.0, 10.0), 1.0, 1e-15);
  EXPECT_NEAR(onset_curve(5.0, 10.0), std::sqrt(2.0) - 1.0, 1e-15);  // exp(ln2/2) − 1
  EXPECT_THROW(onset_curve(1.0, 0.0), InvalidInput);
}

TEST(ParametricModel, NeutralAndExpressions) {
  ParametricLandmarkModel m;
  const Identity id;
  const Eigen::MatrixXd n = m.landmarks(Label::Neutral, 1.0, id);
  ASSERT_EQ(n.rows(), 68);
  // Face inside a 640×490 image, eyes above the nose tip above the mouth, chin lowest.
  EXPECT_GT(n.col(0).minCoeff(), 100.0);
  EXPECT_LT(n.col(0).maxCoeff(), 540.0);
  EXPECT_LT(n(37, 1), n(33, 1));
  EXPECT_LT(n(33, 1), n(51, 1));
  EXPECT_DOUBLE_EQ(n.col(1).maxCoeff(), n(8, 1));
  // Left/right symmetry of the template about x = 320.
  EXPECT_NEAR(n(36, 0) + n(45, 0), 640.0, 1e-9);
  EXPECT_NEAR(n(48, 0) + n(54, 0), 640.0, 1e-9);
  // Expressions: happiness lifts the mouth corners, surprise raises brows and drops the jaw,
  // contempt is one-sided, every emotion moves something.
  const Eigen::MatrixXd h = m.landmarks(Label::Happiness, 1.0, id);
  EXPECT_LT(h(48, 1), n(48, 1) - 5.0);
  const Eigen::MatrixXd s = m.landmarks(Label::Surprise, 1.0, id);
  EXPECT_LT(s(19, 1), n(19, 1) - 5.0);
  EXPECT_GT(s(8, 1), n(8, 1) + 20.0);
  const Eigen::MatrixXd c = m.landmarks(Label::Contempt, 1.0, id);
  EXPECT_GT((c.row(54) - n.row(54)).norm(), 2.0 * (c.row(48) - n.row(48)).norm());
  for (Label l : all_labels())
    if (l != Label::Neutral) {
      EXPECT_GT(m.field(l).norm(), 0.05) << to_string(l);
    }
  // Intensity scales the displacement linearly.
  const Eigen::MatrixXd half = m.landmarks(Label::Anger, 0.5, id), full = m.landmarks(Label::Anger, 1.0, id);
  EXPECT_NEAR(((half - n) * 2.0 - (full - n)).norm(), 0.0, 1e-9);
  EXPECT_THROW(m.landmarks(Label::Anger, 1.5, id), InvalidInput);
}

TEST(SyntheticDatabase, DefaultIsPaperSized) {
  const Database db = generate_synthetic_database(ParametricLandmarkModel());
  EXPECT_NO_THROW(validate(db));
  EXPECT_EQ(db.sequences.size(), 70u);
  std::map<Label, int> per_label;
  std::map<std::string, int> subjects;
  for (const Sequence& s : db.sequences) {
    ++per_label[s.label];
    ++subjects[s.subject];
    EXPECT_GE(s.frames.size(), 10u);
    EXPECT_LE(s.frames.size(), 30u);
    // neutral-to-peak: frame 0 vs 1 differ only by noise, the last frame is far from the first
    EXPECT_LT((s.frames[1] - s.frames[0]).cwiseAbs().maxCoeff(), 5.0);
    EXPECT_GT((s.frames.back() - s.frames.front()).cwiseAbs().maxCoeff(), 5.0) << s.id;
  }
  EXPECT_EQ(per_label.size(), 7u);
  for (const auto& [l, n] : per_label) EXPECT_EQ(n, 10);
  EXPECT_EQ(subjects.size(), 20u);
}

TEST(SyntheticDatabase, SeededAndBadOptions) {
  SyntheticOptions o;
  o.sequences_per_label = 1;
  const ParametricLandmarkModel m;
  EXPECT_EQ(database_to_json(generate_synthetic_database(m, o)), database_to_json(generate_synthetic_database(m, o)));
  SyntheticOptions p = o;
  p.seed = 2;
  EXPECT_NE(database_to_json(generate_synthetic_database(m, o)), database_to_json(generate_synthetic_database(m, p)));
  p = o;
  p.min_frames = 1;
  EXPECT_THROW(generate_synthetic_database(m, p), InvalidInput);
  p = o;
  p.max_intensity = 2.0;
  EXPECT_THROW(generate_synthetic_database(m, p), InvalidInput);
  p = o;
  p.labels.clear();
  EXPECT_THROW(generate_synthetic_database(m, p), InvalidInput);
  p = o;
  p.noise_std = -1;
  EXPECT_THROW(generate_synthetic_database(m, p), InvalidInput);
}

}  // namespace
}  // namespace emoface::motiongraph

namespace emoface::motiongraph {
namespace {
// The same sequence, bit for bit.
void expect_same_sequence(const Sequence& s, const Sequence& w) {
  EXPECT_EQ(s.id, w.id);
  EXPECT_EQ(s.label, w.label);
  ASSERT_EQ(s.frames.size(), w.frames.size());
  for (std::size_t f = 0; f < s.frames.size(); ++f) EXPECT_TRUE(s.frames[f] == w.frames[f]) << s.id;
}
// 7 labels × 2 sequences of 3 subjects, at most 12 frames.
SyntheticOptions small_options() {
  SyntheticOptions o;
  o.sequences_per_label = 2;
  o.subjects = 3;
  o.max_frames = 12;
  return o;
}
}  // namespace

TEST(Synthetic, SingleSequencesMatchTheDatabase) {
  const SyntheticOptions o = small_options();
  const ParametricLandmarkModel model;
  const Database db = generate_synthetic_database(model, o);
  ASSERT_EQ(synthetic_sequence_count(o), db.sequences.size());
  for (std::size_t i : {std::size_t{0}, std::size_t{5}, db.sequences.size() - 1})
    expect_same_sequence(synthetic_sequence(model, o, i), db.sequences[i]);
  EXPECT_EQ(db.sequences[4].id, "S002_002");  // 5th sequence: subject 2's second recording
  EXPECT_THROW(synthetic_sequence(model, o, db.sequences.size()), InvalidInput);
}

// A shard's block is what the whole database holds at those indices, bit for bit.
TEST(Synthetic, BlocksMatchTheDatabase) {
  const SyntheticOptions o = small_options();
  const ParametricLandmarkModel model;
  const Database whole = generate_synthetic_database(model, o);
  const std::size_t n = whole.sequences.size();
  std::size_t next = 0;
  for (const auto& block :
       std::vector<std::pair<std::size_t, std::size_t>>{{0, 5}, {5, 5}, {5, n}}) {
    const Database part = generate_synthetic_database(model, o, block);
    EXPECT_EQ(part.landmark_count, whole.landmark_count);
    EXPECT_EQ(part.frame_rate, whole.frame_rate);
    ASSERT_EQ(part.sequences.size(), block.second - block.first);
    for (const Sequence& s : part.sequences) expect_same_sequence(s, whole.sequences[next++]);
  }
  EXPECT_EQ(next, n);
  EXPECT_THROW(generate_synthetic_database(model, o, {0, n + 1}), InvalidInput);
  EXPECT_THROW(generate_synthetic_database(model, o, {3, 2}), InvalidInput);
}
}  // namespace emoface::motiongraph
