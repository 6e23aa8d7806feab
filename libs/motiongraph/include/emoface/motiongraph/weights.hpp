#pragma once
// Motion graphs in weight space (issue 19 item 2): the same building (§4.1), eq. (1), synthesis
// (§5), variation (§5.1) and idle motion on sequences of blend-shape / action-unit weights instead
// of landmarks. A weight database is a Database with dimensions 1: row i of a pose is the weight of
// channel i (e.g. the 52 ARKit shapes in faceweights::arkit_names() order), in [0, 1].
//
// What changes against landmarks (docs/motiongraph.md "Weight space"):
//   * preprocessing neither translates nor aligns (weights have no head pose); the neutral is the
//   mean
//     of the first frames; cleaning, reversed copies and the neutral-start check are unchanged;
//   * eq. (1) per channel with d = 1: dist = |Δw|, and vinfl = 1 − |V̂a·V̂b| is 0 when both channels
//     move (either direction) and 1 when exactly one is still — the velocity term only tells a
//     moving channel from a still one;
//   * every length-valued option is in weight units: the presets below replace the pixel defaults.
#include "emoface/motiongraph/evaluate.hpp"
#include "emoface/motiongraph/graph.hpp"
#include "emoface/motiongraph/preprocess.hpp"
#include "emoface/motiongraph/synthesis.hpp"

namespace emoface::motiongraph {

/// True for a weight-space database or graph (dimensions 1).
inline bool is_weight_space(int dimensions) { return dimensions == 1; }

/// Preprocessing for weights: the pixel slacks of the neutral-start check scaled to weight units
/// (neutral_start_slack 0.03, neutral_mean_slack 0.01; landmark defaults 1 px and 0.25 px on faces
/// whose expressions move landmarks 10–37 px, while they move weights 0.3–1).
PreprocessOptions weight_preprocess_options();
/// Graph building for weights: sample = merge threshold 0.012 per channel (measured: 84.5 % compression
/// on the default generated ARKit database; 0.0089 gives 78 %, `mgraph eval`).
GraphOptions weight_graph_options();
/// Smoothing for weights: Savitzky–Golay as for landmarks; the sigmoid fit only for channels moving
/// more than 0.02 (sigmoid_min_range), kept when its RMS residual is below 0.05 (sigmoid_max_rms),
/// stopped at 0.0003 predicted RMS gain (sigmoid_tolerance) — the pixel values / 30.
SmoothingOptions weight_smoothing_options();
/// Synthesis options with weight_smoothing_options().
SynthesisOptions weight_synthesis_options();
/// Idle options with weight smoothing (no sigmoid, as for landmarks).
IdleOptions weight_idle_options();
/// Evaluation options with weight_graph_options() and weight_smoothing_options().
EvaluationOptions weight_evaluation_options();

/// Synthesized weight poses (graph.landmark_ids().size() by 1) → full channel vectors of
/// `channel_count` values in [0, 1] (channels outside the graph's regions 0; values clamped to
/// [0, 1], as smoothing may overshoot slightly). Throws InvalidInput for a landmark graph, a frame
/// of the wrong size, an id >= channel_count, or a non-finite value.
std::vector<std::vector<double>> weight_frames(const MotionGraph& graph,
                                               const std::vector<Pose>& frames,
                                               std::size_t channel_count);

}  // namespace emoface::motiongraph
