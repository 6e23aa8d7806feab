#pragma once
// The paper's §7 evaluation: re-synthesize every training sample from the graph built on the whole
// database and compare with the sample (length difference in frames, pose difference in pixels),
// against the compression ratio of the graph.
#include <cstddef>
#include <vector>

#include "emoface/motiongraph/graph.hpp"
#include "emoface/motiongraph/preprocess.hpp"
#include "emoface/motiongraph/synthesis.hpp"

namespace emoface::motiongraph {

struct EvaluationRow {
  double threshold = 0.0;    ///< sample and merge threshold used (GraphOptions units)
  double compression = 0.0;  ///< graph compression ratio in [0, 1]
  std::size_t nodes = 0;
  double length_mean = 0.0, length_std = 0.0;  ///< |synth − original| frames, over samples
  double pose_mean = 0.0, pose_std = 0.0;      ///< landmark distance (units), over all landmarks
                                               ///< of all frames of all samples
  /// Sums behind the statistics, so rows of shards can be merged exactly (merge_rows).
  std::size_t samples = 0;       ///< samples evaluated
  std::size_t distances = 0;     ///< landmark distances measured
  double length_sum = 0.0, length_sum2 = 0.0, pose_sum = 0.0, pose_sum2 = 0.0;
  /// The pose difference against the *raw* samples (issue 19: aligned but not sigmoid-cleaned, the
  /// tracker's own values), when evaluate() was given them; else 0. Same landmarks and frames.
  bool has_raw = false;
  double raw_pose_mean = 0.0, raw_pose_std = 0.0, raw_pose_sum = 0.0, raw_pose_sum2 = 0.0;
};

struct EvaluationOptions {
  GraphOptions graph;           ///< thresholds are overridden per row
  SmoothingOptions smoothing;   ///< smoothing of the re-synthesized samples
  /// Evaluate only the shard_index-th of shard_count contiguous blocks of the samples
  /// (core::Shard::block; the graph is always built from the whole database, so shards are parts
  /// of one evaluation). shard_index < shard_count.
  std::size_t shard_index = 0, shard_count = 1;
  void validate() const;
};

/// One row: builds the graph with sample = merge = `threshold`, re-synthesizes each sample from its
/// first-frame node to its peak node (Dijkstra + §5 steps 1–4, no variation) and compares it with
/// the sample's neutral-to-peak part (synthesized frames resampled to the original length).
/// With `raw` (the same database preprocessed with `clean = false` and otherwise the same options:
/// same samples, frames and alignment), the synthesized frames are also compared with the raw samples
/// (EvaluationRow::raw_pose_*). Throws InvalidInput if `raw` does not match `data`.
EvaluationRow evaluate(const PreparedDatabase& data, double threshold,
                       const EvaluationOptions& options = {},
                       const PreparedDatabase* raw = nullptr);

/// Merges rows of the same threshold computed on different shards: sums added, statistics recomputed
/// (mean and population standard deviation over all samples / distances). Throws InvalidInput for an
/// empty list or different thresholds.
EvaluationRow merge_rows(const std::vector<EvaluationRow>& rows);

/// Threshold whose graph compression is closest to `target` in [0, 1) (bisection, ~20 builds).
double threshold_for_compression(const PreparedDatabase& data, double target,
                                 const GraphOptions& options = {});

}  // namespace emoface::motiongraph
