#pragma once
// Region motion graphs (paper §4, §4.1): per region a directed graph whose nodes hold landmark
// displacements from the averaged neutral pose and whose edges hold eq. (1) similarity values.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/motiongraph/database.hpp"
#include "emoface/motiongraph/preprocess.hpp"
#include "emoface/motiongraph/similarity.hpp"

namespace emoface::motiongraph {

struct Node {
  Eigen::RowVectorXd displacement;  ///< mean displacement from the neutral, 1 by (k·d)
  Eigen::RowVectorXd velocity;      ///< mean landmark velocity (units/frame), 1 by (k·d)
  std::vector<Label> labels;        ///< labels of every sample merged in (sorted, unique)
  std::size_t frame_count = 0;      ///< database frames merged into this node
  /// Average number of consecutive frames of one sample merged into this node (§4 "average number
  /// of consecutive merged nodes"), >= 1.
  double mean_run = 1.0;
  /// Mean number of frames from neutral to the frames of this node (1 = the neutral frame itself).
  double frames_from_neutral = 1.0;
  /// Destination (peak) node data (§4): labels of the samples whose peak is here and the mean and
  /// standard deviation of their neutral-to-peak lengths (frames, inclusive). Empty/0 otherwise.
  std::vector<Label> peak_labels;
  double peak_length_mean = 0.0;
  double peak_length_std = 0.0;
  bool is_peak() const { return !peak_labels.empty(); }
  bool has_label(Label l) const;
  bool has_peak_label(Label l) const;
};

struct Edge {
  std::size_t from = 0;
  std::size_t to = 0;
  double weight = 0.0;  ///< eq. (1) similarity of the two nodes
};

struct RegionGraph {
  std::string name;
  std::vector<int> landmarks;   ///< source landmark indices (layout order)
  Eigen::RowVectorXd neutral;   ///< averaged neutral pose, 1 by (k·d)
  std::vector<Node> nodes;
  std::vector<Edge> edges;      ///< unique (from, to), no self loops
  std::size_t neutral_node = 0; ///< graph source: holds every sample's first frame
  /// Out-neighbours (or all neighbours when `undirected`) of each node as (node, edge weight).
  std::vector<std::vector<std::pair<std::size_t, double>>> adjacency(bool undirected) const;
};

struct MotionGraph {
  int dimensions = 2;
  double frame_rate = 30.0;
  double lambda = 0.5;              ///< λ used for the edge weights
  std::size_t source_frames = 0;    ///< database poses (original frames, without reversed copies)
  std::vector<RegionGraph> regions;
  /// 1 − nodes / (regions · source_frames): memory saved against one node per pose (§7).
  double compression_ratio() const;
  std::size_t node_count() const;
  /// Source landmark ids of the synthesized poses (regions concatenated).
  std::vector<int> landmark_ids() const;
  /// Region index of each synthesized landmark (same order as landmark_ids()).
  std::vector<int> landmark_regions() const;
  /// The region called `name`; InvalidInput naming the regions the graph has otherwise.
  const RegionGraph& region(std::string_view name) const;
};

struct GraphOptions {
  /// Merge thresholds of eq. (1) for sample graphs and for merging into the final graph (§4.1), >= 0
  /// (a pose merges into the most similar node when its value is <= the threshold),
  /// in landmark units per landmark when threshold_per_landmark (multiplied by the region's landmark
  /// count, so one value suits regions of different size), else absolute eq. (1) units.
  double sample_threshold = 0.4;  ///< ≈ 78 % compression on the default synthetic database
  double merge_threshold = 0.4;
  bool threshold_per_landmark = true;
  SimilarityOptions similarity;
  std::uint64_t seed = 1;  ///< picks the random sample graph that seeds the final graph
  void validate() const;
};

/// Which node each database frame ended up in: [region][sample][frame].
struct GraphBuildReport {
  std::vector<std::vector<std::vector<std::size_t>>> frame_nodes;
  std::size_t seed_sample = 0;
};

/// Builds one graph per region (§4.1). Deterministic for a given seed.
MotionGraph build_graph(const PreparedDatabase& data, const GraphOptions& options = {},
                        GraphBuildReport* report = nullptr);

}  // namespace emoface::motiongraph
