#include "emoface/motiongraph/weights.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "emoface/core/errors.hpp"

namespace emoface::motiongraph {

PreprocessOptions weight_preprocess_options() {
  PreprocessOptions o;
  o.neutral_start_slack = 0.03;
  o.neutral_mean_slack = 0.01;
  return o;
}

GraphOptions weight_graph_options() {
  GraphOptions o;
  o.sample_threshold = o.merge_threshold = 0.012;
  return o;
}

SmoothingOptions weight_smoothing_options() {
  SmoothingOptions o;
  o.sigmoid_max_rms = 0.05;
  o.sigmoid_min_range = 0.02;
  o.sigmoid_tolerance = 0.0003;
  return o;
}

SynthesisOptions weight_synthesis_options() {
  SynthesisOptions o;
  o.smoothing = weight_smoothing_options();
  return o;
}

IdleOptions weight_idle_options() {
  IdleOptions o;
  o.smoothing.sigmoid_max_rms = 0.05;
  o.smoothing.sigmoid_min_range = 0.02;
  o.smoothing.sigmoid_tolerance = 0.0003;
  return o;
}

EvaluationOptions weight_evaluation_options() {
  EvaluationOptions o;
  o.graph = weight_graph_options();
  o.smoothing = weight_smoothing_options();
  return o;
}

std::vector<std::vector<double>> weight_frames(const MotionGraph& graph,
                                               const std::vector<Pose>& frames,
                                               std::size_t channel_count) {
  if (!is_weight_space(graph.dimensions))
    throw InvalidInput("weight frames: the graph is a landmark graph (dimensions " +
                       std::to_string(graph.dimensions) + ")");
  const std::vector<int> ids = graph.landmark_ids();
  for (int id : ids)
    if (id < 0 || static_cast<std::size_t>(id) >= channel_count)
      throw InvalidInput("weight frames: channel id " + std::to_string(id) + " outside 0.." +
                         std::to_string(channel_count) + " - 1");
  std::vector<std::vector<double>> out;
  out.reserve(frames.size());
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const Pose& p = frames[f];
    if (p.rows() != static_cast<Eigen::Index>(ids.size()) || p.cols() != 1)
      throw InvalidInput("weight frames: frame " + std::to_string(f) + " is " +
                         std::to_string(p.rows()) + "x" + std::to_string(p.cols()) + ", expected " +
                         std::to_string(ids.size()) + "x1");
    if (!p.allFinite())
      throw InvalidInput("weight frames: frame " + std::to_string(f) +
                         " has a NaN or infinite value");
    std::vector<double> w(channel_count, 0.0);
    for (std::size_t i = 0; i < ids.size(); ++i)
      w[static_cast<std::size_t>(ids[i])] =
          std::clamp(p(static_cast<Eigen::Index>(i), 0), 0.0, 1.0);
    out.push_back(std::move(w));
  }
  return out;
}

}  // namespace emoface::motiongraph
