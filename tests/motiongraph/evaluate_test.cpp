#include "emoface/motiongraph/evaluate.hpp"

#include <gtest/gtest.h>

#include <cmath>

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

TEST(Evaluate, ShardsMergeToTheWholeEvaluation) {
  const double t = 0.6;
  const EvaluationRow whole = evaluate(test::small_prepared(), t);
  std::vector<EvaluationRow> parts;
  EvaluationOptions o;
  o.shard_count = 3;
  for (std::size_t i = 0; i < 3; ++i) {
    o.shard_index = i;
    parts.push_back(evaluate(test::small_prepared(), t, o));
  }
  const std::size_t n = test::small_prepared().samples.size();
  EXPECT_EQ(parts[0].samples + parts[1].samples + parts[2].samples, n);
  for (std::size_t i = 0; i < 3; ++i)  // contiguous blocks: ⌊(i+1)·n/3⌋ − ⌊i·n/3⌋ samples
    EXPECT_EQ(parts[i].samples, (i + 1) * n / 3 - i * n / 3) << i;
  const EvaluationRow merged = merge_rows(parts);
  EXPECT_EQ(merged.samples, whole.samples);
  EXPECT_EQ(merged.distances, whole.distances);
  EXPECT_NEAR(merged.length_mean, whole.length_mean, 1e-12);
  EXPECT_NEAR(merged.length_std, whole.length_std, 1e-9);
  EXPECT_NEAR(merged.pose_mean, whole.pose_mean, 1e-12);
  EXPECT_NEAR(merged.pose_std, whole.pose_std, 1e-9);
  EXPECT_EQ(merged.nodes, whole.nodes);
  // Hand check of the merge arithmetic: lengths {1, 3} and {2} → mean 2, population std √(2/3).
  EvaluationRow a, b;
  a.samples = 2, a.length_sum = 4, a.length_sum2 = 10;
  b.samples = 1, b.length_sum = 2, b.length_sum2 = 4;
  const EvaluationRow m = merge_rows({a, b});
  EXPECT_DOUBLE_EQ(m.length_mean, 2.0);
  EXPECT_NEAR(m.length_std, std::sqrt(2.0 / 3.0), 1e-12);
  b.threshold = 1.0;
  EXPECT_THROW(merge_rows({a, b}), InvalidInput);
  EXPECT_THROW(merge_rows({}), InvalidInput);
  o.shard_index = 3;
  EXPECT_THROW(evaluate(test::small_prepared(), t, o), InvalidInput);
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
