#include "emoface/motiongraph/preprocess.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "emoface/core/errors.hpp"
#include "fixtures.hpp"

namespace emoface::motiongraph {
namespace {

TEST(Procrustes, RecoversSimilarityTransform) {
  Eigen::MatrixXd from(5, 2);
  from << 0, 0, 1, 0, 0, 2, 3, 1, -1, 4;
  const double a = 0.3, s = 1.7;
  Eigen::Matrix2d r;
  r << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  Eigen::MatrixXd to = (from * r.transpose()) * s;
  to.rowwise() += Eigen::RowVector2d(5, -2);
  const Eigen::MatrixXd t = procrustes(from, to);
  EXPECT_NEAR((apply_transform(t, from) - to).norm(), 0.0, 1e-10);
  EXPECT_NEAR(t(0, 0), s * std::cos(a), 1e-10);
  EXPECT_NEAR(t(1, 0), s * std::sin(a), 1e-10);
  EXPECT_THROW(procrustes(from, to.topRows(4)), InvalidInput);
}

TEST(Procrustes, NoReflection) {
  Eigen::MatrixXd from(5, 2), to(5, 2);
  from << 0, 0, 1, 0, 0, 2, 3, 1, -1, 4;
  to = from;
  to.col(0) *= -1.0;  // mirror image: best proper rotation, not a reflection
  EXPECT_GT(procrustes(from, to).topLeftCorner(2, 2).determinant(), 0.0);
}

TEST(Preprocess, DisplacementsStartAtZeroAndReverseCopies) {
  PreprocessReport rep;
  const Database db = test::small_synthetic();
  const PreparedDatabase p = preprocess(db, default_layout(), {}, &rep);
  ASSERT_EQ(p.samples.size(), db.sequences.size());
  EXPECT_EQ(p.neutral.size(), 5u);
  EXPECT_GT(rep.sigmoid_fits, 0u);
  EXPECT_LT(rep.mean_fit_rms, 1.0);  // noise is 0.4 px
  for (std::size_t s = 0; s < p.samples.size(); ++s) {
    const PreparedSample& ps = p.samples[s];
    const std::size_t n = db.sequences[s].frames.size();
    EXPECT_EQ(ps.peak_frame, n - 1);
    EXPECT_EQ(ps.frame_count(), 2 * n - 1);
    for (std::size_t r = 0; r < 5; ++r) {
      EXPECT_EQ(ps.displacement[r].cols(), static_cast<Eigen::Index>(default_layout().regions[r].landmarks.size() * 2));
      EXPECT_NEAR(ps.displacement[r].row(0).norm(), 0.0, 1e-12);
      for (std::size_t f = 0; f < n; ++f)  // reversed copy mirrors the onset
        EXPECT_TRUE(ps.displacement[r].row(static_cast<Eigen::Index>(f)) ==
                    ps.displacement[r].row(static_cast<Eigen::Index>(2 * n - 2 - f)));
    }
  }
  // The mouth of a happiness sample moves, its peak displacement is several pixels.
  EXPECT_GT(p.samples[0].displacement[3].row(static_cast<Eigen::Index>(p.samples[0].peak_frame)).norm(), 10.0);
}

TEST(Preprocess, AlignmentRemovesPoseDifferences) {
  // The same expression on two head poses: after alignment the displacements agree.
  ParametricLandmarkModel model;
  Identity a, b;
  b.scale = 1.2;
  b.roll = 0.2;
  b.translation = Eigen::Vector2d(40, -30);
  Database db;
  db.landmark_count = 68;
  for (int k = 0; k < 2; ++k) {
    Sequence s;
    s.id = k ? "b" : "a";
    s.label = Label::Surprise;
    for (int f = 0; f < 5; ++f) s.frames.push_back(model.landmarks(Label::Surprise, f / 4.0, k ? b : a));
    db.sequences.push_back(s);
  }
  PreprocessOptions o;
  o.clean = false;
  const PreparedDatabase p = preprocess(db, default_layout(), o);
  for (std::size_t r = 0; r < 5; ++r)
    EXPECT_LT((p.samples[0].displacement[r] - p.samples[1].displacement[r]).cwiseAbs().maxCoeff(), 1e-6)
        << default_layout().regions[r].name;
  o.align = false;
  const PreparedDatabase raw = preprocess(db, default_layout(), o);
  EXPECT_GT((raw.samples[0].displacement[3] - raw.samples[1].displacement[3]).cwiseAbs().maxCoeff(), 1.0);
}

TEST(Preprocess, SkipBadSamplesLeavesOutSequencesThatDoNotStartNeutral) {
  Database db = test::small_synthetic(1);
  std::reverse(db.sequences[0].frames.begin(), db.sequences[0].frames.end());  // peak first
  EXPECT_THROW(preprocess(db, default_layout()), InvalidInput);
  PreprocessOptions o;
  o.skip_bad_samples = true;
  o.clean = false;
  PreprocessReport rep;
  const PreparedDatabase p = preprocess(db, default_layout(), o, &rep);
  ASSERT_EQ(rep.skipped.size(), 1u);
  EXPECT_NE(rep.skipped[0].find(db.sequences[0].id), std::string::npos) << rep.skipped[0];
  EXPECT_NE(rep.skipped[0].find("does not start neutral"), std::string::npos);
  ASSERT_EQ(p.samples.size(), db.sequences.size() - 1);
  // The same as preprocessing the database without it (mean neutral recomputed).
  Database kept = db;
  kept.sequences.erase(kept.sequences.begin());
  const PreparedDatabase q = preprocess(kept, default_layout(), o);
  for (std::size_t r = 0; r < p.neutral.size(); ++r) EXPECT_EQ(p.neutral[r], q.neutral[r]);
  for (std::size_t s = 0; s < p.samples.size(); ++s) EXPECT_EQ(p.samples[s].id, q.samples[s].id);
}

TEST(Preprocess, RejectsBadInput) {
  Database db = test::small_synthetic(1);
  EXPECT_THROW(preprocess(db, single_region_layout(10)), InvalidInput);  // layout mismatch
  Database reversed = db;
  std::reverse(reversed.sequences[0].frames.begin(), reversed.sequences[0].frames.end());
  EXPECT_THROW(preprocess(reversed, default_layout()), InvalidInput);  // does not start neutral
  PreprocessOptions lax;
  lax.check_neutral_start = false;
  EXPECT_NO_THROW(preprocess(reversed, default_layout(), lax));
  Database one = db;
  one.sequences[0].frames.resize(1);
  EXPECT_THROW(preprocess(one, default_layout()), InvalidInput);
  Database empty = db;
  empty.sequences.clear();
  EXPECT_THROW(preprocess(empty, default_layout()), InvalidInput);
  Database nan = db;
  nan.sequences[0].frames[1](3, 0) = std::nan("");
  EXPECT_THROW(preprocess(nan, default_layout()), InvalidInput);
  PreprocessOptions bad;
  bad.neutral_start_tolerance = -1;
  EXPECT_THROW(preprocess(db, default_layout(), bad), InvalidInput);
}

}  // namespace
}  // namespace emoface::motiongraph
