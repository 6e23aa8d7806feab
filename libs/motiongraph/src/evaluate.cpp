#include "emoface/motiongraph/evaluate.hpp"

#include <cmath>

#include "emoface/core/errors.hpp"
#include "emoface/core/shard.hpp"
#include "emoface/motiongraph/curves.hpp"
#include "flat.hpp"

namespace emoface::motiongraph {

void EvaluationOptions::validate() const {
  graph.validate();
  smoothing.validate();
  if (shard_count < 1 || shard_index >= shard_count)
    throw InvalidInput("evaluation: need shard_index < shard_count");
}

namespace {
struct Stats {
  double sum = 0.0, sum2 = 0.0;
  double n = 0.0;
  void add(double x) {
    sum += x;
    sum2 += x * x;
    n += 1.0;
  }
  double mean() const { return n > 0 ? sum / n : 0.0; }
  double std() const { return n > 0 ? std::sqrt(std::max(0.0, sum2 / n - mean() * mean())) : 0.0; }
};
}  // namespace

// §7: "We have compared the training samples against the synthesized equivalent".
EvaluationRow evaluate(const PreparedDatabase& data, double threshold, const EvaluationOptions& options,
                       const PreparedDatabase* raw) {
  options.validate();
  if (raw) {
    bool same = raw->samples.size() == data.samples.size() &&
                raw->layout.regions.size() == data.layout.regions.size() &&
                raw->dimensions == data.dimensions;
    for (std::size_t s = 0; same && s < data.samples.size(); ++s) {
      const PreparedSample& a = data.samples[s];
      const PreparedSample& b = raw->samples[s];
      same = a.id == b.id && a.peak_frame == b.peak_frame &&
             a.displacement.size() == b.displacement.size();
      for (std::size_t r = 0; same && r < a.displacement.size(); ++r)
        same = a.displacement[r].rows() == b.displacement[r].rows() &&
               a.displacement[r].cols() == b.displacement[r].cols();
    }
    if (!same)
      throw InvalidInput("evaluation: the raw database does not match the cleaned one (samples, "
                         "frames or regions differ)");
  }
  GraphOptions go = options.graph;
  go.sample_threshold = go.merge_threshold = threshold;
  GraphBuildReport built;
  const MotionGraph graph = build_graph(data, go, &built);
  EvaluationRow row;
  row.threshold = threshold;
  row.compression = graph.compression_ratio();
  row.nodes = graph.node_count();
  Stats length, pose, raw_pose;
  const int d = data.dimensions;
  // Contiguous blocks of samples, like every --shard of emoface (core::Shard, docs/scale-out.md).
  const auto [first, last] =
      core::Shard{options.shard_index, options.shard_count}.block(data.samples.size());
  for (std::size_t s = first; s < last; ++s) {
    const PreparedSample& ps = data.samples[s];
    std::vector<Eigen::MatrixXd> region_frames;
    for (std::size_t r = 0; r < graph.regions.size(); ++r) {
      const RegionGraph& rg = graph.regions[r];
      const auto& nodes = built.frame_nodes[r][s];
      std::vector<char> target(rg.nodes.size(), 0);
      target[nodes[ps.peak_frame]] = 1;
      std::vector<std::size_t> path = shortest_path(rg.adjacency(false), nodes[0], target);
      if (path.empty()) path = shortest_path(rg.adjacency(true), nodes[0], target);
      const double len = path_length(rg, path);
      region_frames.push_back(recover_path(rg, path, static_cast<std::size_t>(std::lround(len))));
    }
    const std::vector<Pose> synth = assemble(graph, std::move(region_frames), options.smoothing);
    const std::size_t original = ps.peak_frame + 1;
    length.add(std::abs(static_cast<double>(synth.size()) - static_cast<double>(original)));
    // Compare at corresponding times: the synthesized sequence resampled to the original length.
    Eigen::MatrixXd flat(static_cast<Eigen::Index>(synth.size()), synth[0].size());
    for (std::size_t t = 0; t < synth.size(); ++t) flat.row(static_cast<Eigen::Index>(t)) = detail::flatten(synth[t]);
    const Eigen::MatrixXd resampled = resample_linear(flat, static_cast<Eigen::Index>(original));
    for (std::size_t t = 0; t < original; ++t) {
      Eigen::Index col = 0;
      for (std::size_t r = 0; r < graph.regions.size(); ++r) {
        const Eigen::RowVectorXd truth =
            graph.regions[r].neutral + ps.displacement[r].row(static_cast<Eigen::Index>(t));
        const Eigen::RowVectorXd truth_raw =
            raw ? (graph.regions[r].neutral +
                   raw->samples[s].displacement[r].row(static_cast<Eigen::Index>(t)))
                      .eval()
                : truth;
        for (Eigen::Index l = 0; l < truth.size() / d; ++l, ++col) {
          double d2 = 0.0, r2 = 0.0;
          for (int j = 0; j < d; ++j) {
            const double v = resampled(static_cast<Eigen::Index>(t), col * d + j);
            const double e = v - truth[l * d + j], er = v - truth_raw[l * d + j];
            d2 += e * e;
            r2 += er * er;
          }
          pose.add(std::sqrt(d2));
          if (raw) raw_pose.add(std::sqrt(r2));
        }
      }
    }
  }
  row.length_mean = length.mean();
  row.length_std = length.std();
  row.pose_mean = pose.mean();
  row.pose_std = pose.std();
  row.samples = static_cast<std::size_t>(length.n);
  row.distances = static_cast<std::size_t>(pose.n);
  row.length_sum = length.sum, row.length_sum2 = length.sum2;
  row.pose_sum = pose.sum, row.pose_sum2 = pose.sum2;
  if (raw) {
    row.has_raw = true;
    row.raw_pose_mean = raw_pose.mean(), row.raw_pose_std = raw_pose.std();
    row.raw_pose_sum = raw_pose.sum, row.raw_pose_sum2 = raw_pose.sum2;
  }
  return row;
}

EvaluationRow merge_rows(const std::vector<EvaluationRow>& rows) {
  if (rows.empty()) throw InvalidInput("merge_rows: no rows");
  EvaluationRow out = rows.front();
  Stats length, pose, raw_pose;
  for (const EvaluationRow& r : rows) {
    if (r.threshold != out.threshold) throw InvalidInput("merge_rows: rows of different thresholds");
    if (r.has_raw != out.has_raw)
      throw InvalidInput("merge_rows: rows with and without the raw comparison");
    length.sum += r.length_sum, length.sum2 += r.length_sum2, length.n += static_cast<double>(r.samples);
    pose.sum += r.pose_sum, pose.sum2 += r.pose_sum2, pose.n += static_cast<double>(r.distances);
    raw_pose.sum += r.raw_pose_sum, raw_pose.sum2 += r.raw_pose_sum2;
    raw_pose.n += static_cast<double>(r.distances);
  }
  if (out.has_raw) {
    out.raw_pose_sum = raw_pose.sum, out.raw_pose_sum2 = raw_pose.sum2;
    out.raw_pose_mean = raw_pose.mean(), out.raw_pose_std = raw_pose.std();
  }
  out.samples = static_cast<std::size_t>(length.n);
  out.distances = static_cast<std::size_t>(pose.n);
  out.length_sum = length.sum, out.length_sum2 = length.sum2;
  out.pose_sum = pose.sum, out.pose_sum2 = pose.sum2;
  out.length_mean = length.mean(), out.length_std = length.std();
  out.pose_mean = pose.mean(), out.pose_std = pose.std();
  return out;
}

double threshold_for_compression(const PreparedDatabase& data, double target, const GraphOptions& options) {
  if (!(target >= 0.0 && target < 1.0)) throw InvalidInput("threshold_for_compression: target must be in [0, 1)");
  GraphOptions go = options;
  auto compression = [&](double t) {
    go.sample_threshold = go.merge_threshold = t;
    return build_graph(data, go).compression_ratio();
  };
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 40 && compression(hi) < target; ++i) hi *= 2.0;
  double best = hi, best_err = std::abs(compression(hi) - target);
  for (int i = 0; i < 20; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double c = compression(mid);
    if (std::abs(c - target) < best_err) {
      best_err = std::abs(c - target);
      best = mid;
    }
    (c < target ? lo : hi) = mid;
  }
  return best;
}

}  // namespace emoface::motiongraph
