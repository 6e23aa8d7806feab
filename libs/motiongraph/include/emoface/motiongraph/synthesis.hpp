#pragma once
// Motion synthesis from region graphs (paper §5), variation (§5.1), idle movements (§5) and
// mood-decay hints (§6.1: synthesis from only the initial path nodes).
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "emoface/motiongraph/database.hpp"
#include "emoface/motiongraph/graph.hpp"

namespace emoface::motiongraph {

/// Shortest path (Dijkstra, edge weights = similarity) from `source` to the cheapest node with
/// is_target[node] != 0. Returns the node sequence (source first), empty if none is reachable.
/// `cost` receives the path cost when not null.
std::vector<std::size_t> shortest_path(
    const std::vector<std::vector<std::pair<std::size_t, double>>>& adjacency, std::size_t source,
    const std::vector<char>& is_target, double* cost = nullptr);

struct SmoothingOptions {
  int savgol_window = 5;       ///< Savitzky–Golay window (frames, odd >= 3; 0 disables)
  int savgol_order = 2;        ///< polynomial order, < window
  bool sigmoid = true;         ///< then replace each landmark by its sigmoid fit (§5 step 4)...
  double sigmoid_max_rms = 1.5;  ///< ...when the fit's RMS residual is below this (units), so
                                 ///< non-monotone motion (peak → neutral → peak) is kept
  double sigmoid_min_range = 0.5;  ///< landmarks moving less than this (units, >= 0) are not fitted
  /// A fit stops when an iteration changes its RMS residual by less than this (units, >= 0; 0 = only
  /// the relative cost test). 0.01 px is 1/40 of the synthetic database's tracking noise and far
  /// below a rendered pixel, and halves the fitting time (docs/motiongraph.md, performance).
  double sigmoid_tolerance = 0.01;
  void validate() const;
};

struct SynthesisOptions {
  /// §5.1 variation: sample the duration from the peak node's N(mean, std) ...
  bool vary_duration = false;
  /// ... and replace each inner path node by a random neighbour with this probability, [0, 1].
  double replace_probability = 0.0;
  /// Target one of the label's peak nodes (per region, uniformly at random) instead of the cheapest
  /// one, so the same label need not end in the same apex pose (issue 19: a graph holds one peak per
  /// training sample, and Dijkstra from the neutral pose always finds the same one). Not in the paper.
  bool vary_peak = false;
  /// §6.1 mood-decay hint: use only this leading fraction of each path, (0, 1].
  double path_fraction = 1.0;
  /// Search reversed edges when the requested peak is unreachable along directed edges.
  bool allow_reverse_edges = true;
  SmoothingOptions smoothing;
  std::uint64_t seed = 1;  ///< variation randomness; each region draws from its own stream
  void validate() const;
};

/// Where each region graph currently is; the sink of one synthesis is the source of the next (§5).
struct SynthesisState {
  std::vector<std::size_t> nodes;  ///< per region
  /// Per region, the last synthesized displacement (1 by k·d); empty before the first synthesis.
  /// The next animation starts exactly there and fades the difference to its node out.
  std::vector<Eigen::RowVectorXd> last;
  std::uint64_t calls = 0;         ///< number of syntheses so far (advances the random streams)
};

/// All regions at their neutral node.
SynthesisState initial_state(const MotionGraph& graph);

struct SynthesisReport {
  std::vector<std::vector<std::size_t>> paths;  ///< per region, as used (after variation)
  std::vector<double> path_costs;
  std::vector<std::size_t> region_lengths;  ///< frames per region before step 3
  bool used_reverse_edges = false;
};

/// Synthesizes the transition from `state` to a peak of `label` (steps 1–4 of §5) and advances
/// `state` to the reached peak nodes. Frames are poses of graph.landmark_ids() (neutral + displacement).
/// The first frame is the current pose. `Label::Neutral` returns to rest: its target in every region
/// is the graph source (`neutral_node`, the averaged neutral pose, §4.1) and any node that is a peak
/// of a neutral sample; the length follows step 2 (a peak-to-neutral path takes the source peak's
/// neutral-to-peak length; varied as that peak's N(mean, std) with `vary_duration`).
/// Throws InvalidInput if no region has a peak of `label` (never for Neutral).
std::vector<Pose> synthesize(const MotionGraph& graph, SynthesisState& state, Label label,
                             const SynthesisOptions& options = {},
                             SynthesisReport* report = nullptr);

/// Lower-level step 1–2 of §5 for one region: poses of a given node path, stretched to `length`
/// frames (0 = no stretching). Rows = frames, columns = k·d displacements.
Eigen::MatrixXd recover_path(const RegionGraph& region, const std::vector<std::size_t>& path,
                             std::size_t length);

/// Neutral-to-peak or peak-to-peak length of §5 step 2 for a path (frames, >= 2).
double path_length(const RegionGraph& region, const std::vector<std::size_t>& path);

/// Step 3 + 4: brings per-region sequences to the longest length (linear interpolation), smooths,
/// and assembles poses (neutral + displacement) of all regions.
std::vector<Pose> assemble(const MotionGraph& graph, std::vector<Eigen::MatrixXd> region_frames,
                           const SmoothingOptions& smoothing);

struct IdleOptions {
  double duration = 4.0;      ///< seconds of idle motion, (0, 3600]
  double hop_interval = 1.0;  ///< seconds between the starts of two hops, > 0
  double dwell = 0.4;         ///< seconds spent at each hop target, [0, hop_interval)
  SmoothingOptions smoothing{5, 2, false, 1.5, 0.5};
  std::uint64_t seed = 1;
  /// Idle at rest (`Label::Neutral`): a neighbour counts as "at rest" when its displacement norm is at
  /// most this fraction of the mean displacement norm of the region's peak nodes, (0, 1]. Onsets start
  /// slowly (CK+, φ+), so their first nodes are small motions around the neutral pose: what a face at
  /// rest does. 0.1 keeps rest motion at a tenth of an average expression.
  double rest_fraction = 0.1;
  void validate() const;
};

/// Idle movements (§5): random hops among neighbours that share `label` (falling back to staying
/// put when none does), linear moves then dwell. Advances `state` to the last hop target.
/// For `Label::Neutral` (a face at rest, e.g. before its first stimulus) the candidates are the
/// neighbours labelled neutral or within `rest_fraction` of an expression from the neutral pose (databases without neutral
/// samples label no node neutral, and the paper's rule would leave the face frozen).
std::vector<Pose> idle(const MotionGraph& graph, SynthesisState& state, Label label,
                       const IdleOptions& options = {});

}  // namespace emoface::motiongraph
