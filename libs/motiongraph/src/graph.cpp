#include "emoface/motiongraph/graph.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"

namespace emoface::motiongraph {

bool Node::has_label(Label l) const { return std::find(labels.begin(), labels.end(), l) != labels.end(); }
bool Node::has_peak_label(Label l) const {
  return std::find(peak_labels.begin(), peak_labels.end(), l) != peak_labels.end();
}

std::vector<std::vector<std::pair<std::size_t, double>>> RegionGraph::adjacency(bool undirected) const {
  std::vector<std::vector<std::pair<std::size_t, double>>> adj(nodes.size());
  for (const Edge& e : edges) {
    adj[e.from].emplace_back(e.to, e.weight);
    if (undirected) adj[e.to].emplace_back(e.from, e.weight);
  }
  return adj;
}

double MotionGraph::compression_ratio() const {
  if (regions.empty() || source_frames == 0) return 0.0;
  return 1.0 - static_cast<double>(node_count()) /
                   static_cast<double>(regions.size() * source_frames);
}

std::size_t MotionGraph::node_count() const {
  std::size_t n = 0;
  for (const RegionGraph& r : regions) n += r.nodes.size();
  return n;
}

std::vector<int> MotionGraph::landmark_ids() const {
  std::vector<int> ids;
  for (const RegionGraph& r : regions) ids.insert(ids.end(), r.landmarks.begin(), r.landmarks.end());
  return ids;
}

std::vector<int> MotionGraph::landmark_regions() const {
  std::vector<int> out;
  for (std::size_t r = 0; r < regions.size(); ++r) out.insert(out.end(), regions[r].landmarks.size(), static_cast<int>(r));
  return out;
}

const RegionGraph& MotionGraph::region(std::string_view name) const {
  std::string names;
  for (const RegionGraph& r : regions) {
    if (r.name == name) return r;
    names += (names.empty() ? "" : ", ") + r.name;
  }
  throw InvalidInput("no region \"" + std::string(name) + "\" (the graph has " + names + ")");
}

void GraphOptions::validate() const {
  if (!(sample_threshold >= 0.0) || !std::isfinite(sample_threshold))
    throw InvalidInput("graph: sample_threshold must be a finite number >= 0");
  if (!(merge_threshold >= 0.0) || !std::isfinite(merge_threshold))
    throw InvalidInput("graph: merge_threshold must be a finite number >= 0");
  similarity.validate();
}

namespace {

// A node being built: running means of displacement and velocity over `weight` frames.
struct Accumulator {
  Eigen::RowVectorXd disp, vel;
  double weight = 0.0;
  void add(const Eigen::RowVectorXd& d, const Eigen::RowVectorXd& v, double w) {
    if (weight == 0.0) {
      disp = d;
      vel = v;
    } else {
      disp = (disp * weight + d * w) / (weight + w);
      vel = (vel * weight + v * w) / (weight + w);
    }
    weight += w;
  }
};

// The comparing-and-merging step shared by sample graphs and the final graph (§4.1): returns the
// index of the most similar node if its eq. (1) value is below the threshold, else appends a node.
std::size_t merge_or_append(std::vector<Accumulator>& nodes, const Eigen::RowVectorXd& d,
                            const Eigen::RowVectorXd& v, double w, double threshold, int dims,
                            const SimilarityOptions& sim) {
  const Eigen::Index k = d.size() / dims;
  double best = std::numeric_limits<double>::infinity();
  std::size_t best_i = nodes.size();
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double s = similarity(d.data(), v.data(), nodes[i].disp.data(), nodes[i].vel.data(), k, dims, sim,
                                std::min(best, threshold));
    if (s < best) {
      best = s;
      best_i = i;
    }
  }
  // §4.1 merges when the value is "lower than the threshold"; `<=` also merges identical poses at
  // threshold 0 (the reversed copies, the common first frames).
  if (best_i < nodes.size() && best <= threshold) {
    nodes[best_i].add(d, v, w);
    return best_i;
  }
  nodes.emplace_back();
  nodes.back().add(d, v, w);
  return nodes.size() - 1;
}

}  // namespace

MotionGraph build_graph(const PreparedDatabase& data, const GraphOptions& options,
                        GraphBuildReport* report) {
  options.validate();
  if (data.samples.empty()) throw InvalidInput("graph: no samples");
  const std::size_t nr = data.layout.regions.size();
  if (data.neutral.size() != nr) throw InvalidInput("graph: prepared data has inconsistent regions");
  const int dims = data.dimensions;
  const std::size_t ns = data.samples.size();
  for (const PreparedSample& s : data.samples) {
    if (s.displacement.size() != nr || s.frame_count() < 1 || s.peak_frame >= s.frame_count())
      throw InvalidInput("graph: sample \"" + s.id + "\" is inconsistent with the layout");
  }

  MotionGraph g;
  g.dimensions = dims;
  g.frame_rate = data.frame_rate;
  g.lambda = options.similarity.lambda;
  // Database poses: the original frames (reversed copies repeat them and do not count).
  for (const PreparedSample& s : data.samples) g.source_frames += s.peak_frame + 1;

  // The final graph is seeded with a random sample graph (§4.1); the rest follow in order.
  core::Rng rng(options.seed, 0);
  const std::size_t seed_sample = static_cast<std::size_t>(rng.uniform_int(ns));
  std::vector<std::size_t> order{seed_sample};
  for (std::size_t s = 0; s < ns; ++s)
    if (s != seed_sample) order.push_back(s);

  GraphBuildReport rep;
  rep.seed_sample = seed_sample;
  rep.frame_nodes.assign(nr, std::vector<std::vector<std::size_t>>(ns));

  for (std::size_t r = 0; r < nr; ++r) {
    const Region& reg = data.layout.regions[r];
    const double per = options.threshold_per_landmark ? static_cast<double>(reg.landmarks.size()) : 1.0;
    const double thr_sample = options.sample_threshold * per;
    const double thr_merge = options.merge_threshold * per;
    std::vector<Accumulator> final_nodes;
    std::size_t source = 0;
    auto& frame_nodes = rep.frame_nodes[r];
    for (std::size_t s : order) {
      const Eigen::MatrixXd& disp = data.samples[s].displacement[r];
      const Eigen::Index nf = disp.rows();
      // Sample graph (§4.1): each pose against all current sample-graph nodes.
      std::vector<Accumulator> sample_nodes;
      std::vector<std::size_t> frame_to_sample(static_cast<std::size_t>(nf));
      for (Eigen::Index f = 0; f < nf; ++f) {
        const Eigen::RowVectorXd v = f == 0 ? Eigen::RowVectorXd::Zero(disp.cols()).eval()
                                            : (disp.row(f) - disp.row(f - 1)).eval();
        frame_to_sample[f] =
            merge_or_append(sample_nodes, disp.row(f), v, 1.0, thr_sample, dims, options.similarity);
      }
      // Merge into the final graph with the second threshold.
      // Every sample starts at the common neutral pose (§4.1), so the node holding its first frame
      // joins the graph source: the node of the seed sample's first frame.
      std::vector<std::size_t> to_final(sample_nodes.size());
      for (std::size_t i = 0; i < sample_nodes.size(); ++i) {
        if (s == seed_sample) {
          final_nodes.push_back(sample_nodes[i]);
          to_final[i] = final_nodes.size() - 1;
          if (i == frame_to_sample[0]) source = to_final[i];
        } else if (i == frame_to_sample[0]) {
          final_nodes[source].add(sample_nodes[i].disp, sample_nodes[i].vel, sample_nodes[i].weight);
          to_final[i] = source;
        } else {
          to_final[i] = merge_or_append(final_nodes, sample_nodes[i].disp, sample_nodes[i].vel,
                                        sample_nodes[i].weight, thr_merge, dims, options.similarity);
        }
      }
      frame_nodes[s].resize(static_cast<std::size_t>(nf));
      for (Eigen::Index f = 0; f < nf; ++f) frame_nodes[s][f] = to_final[frame_to_sample[f]];
    }

    // Node content from the frame assignment (§4): means, labels, runs, peak statistics.
    RegionGraph rg;
    rg.name = reg.name;
    rg.landmarks = reg.landmarks;
    rg.neutral = data.neutral[r];
    const std::size_t nn = final_nodes.size();
    const Eigen::Index width = data.neutral[r].size();
    rg.nodes.resize(nn);
    std::vector<std::set<Label>> labels(nn), peak_labels(nn);
    std::vector<std::vector<double>> runs(nn), peak_lengths(nn);
    std::vector<double> from_neutral(nn, 0.0);
    std::set<std::pair<std::size_t, std::size_t>> edge_set;
    for (std::size_t i = 0; i < nn; ++i) {
      rg.nodes[i].displacement = Eigen::RowVectorXd::Zero(width);
      rg.nodes[i].velocity = Eigen::RowVectorXd::Zero(width);
    }
    for (std::size_t s = 0; s < ns; ++s) {
      const PreparedSample& ps = data.samples[s];
      const Eigen::MatrixXd& disp = ps.displacement[r];
      const auto& path = frame_nodes[s];
      std::size_t run = 0;
      for (std::size_t f = 0; f < path.size(); ++f) {
        Node& node = rg.nodes[path[f]];
        const Eigen::Index fi = static_cast<Eigen::Index>(f);
        node.displacement += disp.row(fi);
        if (f > 0) node.velocity += disp.row(fi) - disp.row(fi - 1);
        ++node.frame_count;
        labels[path[f]].insert(ps.label);
        const std::size_t from = f <= ps.peak_frame ? f : 2 * ps.peak_frame - std::min(f, 2 * ps.peak_frame);
        from_neutral[path[f]] += static_cast<double>(from + 1);
        if (f == ps.peak_frame) {
          peak_labels[path[f]].insert(ps.label);
          peak_lengths[path[f]].push_back(static_cast<double>(ps.peak_frame + 1));
        }
        ++run;
        if (f + 1 == path.size() || path[f + 1] != path[f]) {
          runs[path[f]].push_back(static_cast<double>(run));
          run = 0;
        }
        if (f > 0 && path[f - 1] != path[f]) edge_set.insert({path[f - 1], path[f]});
      }
    }
    for (std::size_t i = 0; i < nn; ++i) {
      Node& node = rg.nodes[i];
      const double c = static_cast<double>(std::max<std::size_t>(node.frame_count, 1));
      node.displacement /= c;
      node.velocity /= c;
      node.labels.assign(labels[i].begin(), labels[i].end());
      node.peak_labels.assign(peak_labels[i].begin(), peak_labels[i].end());
      double sum = 0.0;
      for (double x : runs[i]) sum += x;
      node.mean_run = runs[i].empty() ? 1.0 : sum / static_cast<double>(runs[i].size());
      node.frames_from_neutral = from_neutral[i] / c;
      if (!peak_lengths[i].empty()) {
        double m = 0.0, v = 0.0;
        for (double x : peak_lengths[i]) m += x;
        m /= static_cast<double>(peak_lengths[i].size());
        for (double x : peak_lengths[i]) v += (x - m) * (x - m);
        node.peak_length_mean = m;
        node.peak_length_std = std::sqrt(v / static_cast<double>(peak_lengths[i].size()));
      }
    }
    rg.neutral_node = source;
    const Eigen::Index k = width / dims;
    for (const auto& [a, b] : edge_set) {
      const Node& na = rg.nodes[a];
      const Node& nb = rg.nodes[b];
      rg.edges.push_back({a, b,
                          similarity(na.displacement.data(), na.velocity.data(), nb.displacement.data(),
                                     nb.velocity.data(), k, dims, options.similarity)});
    }
    g.regions.push_back(std::move(rg));
  }
  if (report) *report = std::move(rep);
  return g;
}

}  // namespace emoface::motiongraph
