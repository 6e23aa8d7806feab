#include "emoface/motiongraph/evaluate.hpp"

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "fixtures.hpp"

namespace emoface::motiongraph {
namespace {

TEST(Evaluate, NoCompressionReproducesLengths) {
  const EvaluationRow row = evaluate(test::small_prepared(), 0.0);
  // Only identical poses merge: the first frames (one source node) and the reversed copies.
  std::size_t frames = 0;
  for (const auto& s : test::small_prepared().samples) frames += s.peak_frame + 1;
  const double samples = static_cast<double>(test::small_prepared().samples.size());
  EXPECT_NEAR(row.compression, (samples - 1.0) / static_cast<double>(frames), 1e-12);
  EXPECT_DOUBLE_EQ(row.length_mean, 0.0);  // each peak node holds one sample: its own length
  EXPECT_DOUBLE_EQ(row.length_std, 0.0);
  EXPECT_LT(row.pose_mean, 1.0);  // only smoothing changes the poses
}

TEST(Evaluate, ErrorGrowsWithCompression) {
  const EvaluationRow low = evaluate(test::small_prepared(), 0.3);
  const EvaluationRow high = evaluate(test::small_prepared(), 3.0);
  EXPECT_LT(low.compression, high.compression);
  EXPECT_LE(low.pose_mean, high.pose_mean);
  EXPECT_GE(high.pose_std, 0.0);
}

TEST(Evaluate, ThresholdForCompression) {
  const double t = threshold_for_compression(test::small_prepared(), 0.78);
  GraphOptions o;
  o.sample_threshold = o.merge_threshold = t;
  EXPECT_NEAR(build_graph(test::small_prepared(), o).compression_ratio(), 0.78, 0.03);
  EXPECT_THROW(threshold_for_compression(test::small_prepared(), 1.0), InvalidInput);
}

}  // namespace
}  // namespace emoface::motiongraph
