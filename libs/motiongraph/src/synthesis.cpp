#include "emoface/motiongraph/synthesis.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>

#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"
#include "emoface/motiongraph/curves.hpp"
#include "flat.hpp"

namespace emoface::motiongraph {

namespace {
constexpr double kMaxFrames = 1e5;  // longest synthesized transition (frames): a guard against bad graphs
}  // namespace

void SmoothingOptions::validate() const {
  if (savgol_window != 0 && (savgol_window < 3 || savgol_window % 2 == 0))
    throw InvalidInput("smoothing: savgol_window must be 0 or odd and >= 3");
  if (savgol_window != 0 && (savgol_order < 0 || savgol_order >= savgol_window))
    throw InvalidInput("smoothing: need 0 <= savgol_order < savgol_window");
  if (!(sigmoid_max_rms >= 0.0) || !std::isfinite(sigmoid_max_rms))
    throw InvalidInput("smoothing: sigmoid_max_rms must be >= 0");
  if (!(sigmoid_min_range >= 0.0) || !std::isfinite(sigmoid_min_range))
    throw InvalidInput("smoothing: sigmoid_min_range must be >= 0");
  if (!(sigmoid_tolerance >= 0.0) || !std::isfinite(sigmoid_tolerance))
    throw InvalidInput("smoothing: sigmoid_tolerance must be >= 0");
}

void SynthesisOptions::validate() const {
  if (!(replace_probability >= 0.0 && replace_probability <= 1.0))
    throw InvalidInput("synthesis: replace_probability must be in [0, 1]");
  if (!(path_fraction > 0.0 && path_fraction <= 1.0))
    throw InvalidInput("synthesis: path_fraction must be in (0, 1]");
  smoothing.validate();
}

void IdleOptions::validate() const {
  if (!(duration > 0.0 && duration <= 3600.0)) throw InvalidInput("idle: duration must be in (0, 3600] s");
  if (!(hop_interval > 0.0) || !std::isfinite(hop_interval))
    throw InvalidInput("idle: hop_interval must be > 0");
  if (!(dwell >= 0.0 && dwell < hop_interval))
    throw InvalidInput("idle: dwell must be in [0, hop_interval)");
  if (!(rest_fraction > 0.0 && rest_fraction <= 1.0)) throw InvalidInput("idle: rest_fraction must be in (0, 1]");
  smoothing.validate();
}

// Dijkstra (1959) minimising the summed similarity along the path (§5).
std::vector<std::size_t> shortest_path(
    const std::vector<std::vector<std::pair<std::size_t, double>>>& adjacency, std::size_t source,
    const std::vector<char>& is_target, double* cost) {
  const std::size_t n = adjacency.size();
  if (source >= n || is_target.size() != n) throw InvalidInput("shortest_path: bad source or target mask");
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(n, inf);
  std::vector<std::size_t> prev(n, n);
  using Item = std::pair<double, std::size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  dist[source] = 0.0;
  queue.push({0.0, source});
  std::size_t found = n;
  while (!queue.empty()) {
    const auto [d, u] = queue.top();
    queue.pop();
    if (d > dist[u]) continue;
    if (is_target[u]) {
      found = u;
      break;
    }
    for (const auto& [v, w] : adjacency[u]) {
      if (d + w < dist[v]) {
        dist[v] = d + w;
        prev[v] = u;
        queue.push({dist[v], v});
      }
    }
  }
  if (found == n) return {};
  std::vector<std::size_t> path;
  for (std::size_t v = found; v != n; v = prev[v]) path.push_back(v);
  std::reverse(path.begin(), path.end());
  if (cost) *cost = dist[found];
  return path;
}

SynthesisState initial_state(const MotionGraph& graph) {
  SynthesisState s;
  for (const RegionGraph& r : graph.regions) s.nodes.push_back(r.neutral_node);
  return s;
}

// §5 step 1: each node yields round(mean_run) poses spread evenly around its displacement along its
// mean velocity, oriented towards the next node.
Eigen::MatrixXd recover_path(const RegionGraph& region, const std::vector<std::size_t>& path,
                             std::size_t length) {
  if (path.empty()) throw InvalidInput("recover_path: empty path");
  for (std::size_t i : path)
    if (i >= region.nodes.size()) throw InvalidInput("recover_path: node index out of range");
  std::vector<Eigen::RowVectorXd> poses;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Node& node = region.nodes[path[i]];
    const long count = std::max(1L, std::lround(node.mean_run));
    if (count == 1) {
      poses.push_back(node.displacement);
      continue;
    }
    Eigen::RowVectorXd v = node.velocity;
    const Eigen::RowVectorXd& next = region.nodes[path[std::min(i + 1, path.size() - 1)]].displacement;
    const Eigen::RowVectorXd& prev = region.nodes[path[i == 0 ? 0 : i - 1]].displacement;
    if (v.dot(next - prev) < 0.0) v = -v;
    for (long j = 0; j < count; ++j)
      poses.push_back(node.displacement + (static_cast<double>(j) - 0.5 * static_cast<double>(count - 1)) * v);
  }
  Eigen::MatrixXd out(static_cast<Eigen::Index>(poses.size()), poses[0].size());
  for (std::size_t i = 0; i < poses.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = poses[i];
  // §5 step 2: stretch or shrink to the expected length by linear interpolation.
  if (length > 0) out = resample_linear(out, static_cast<Eigen::Index>(length));
  return out;
}

namespace {

double node_length(const Node& n) { return n.is_peak() ? n.peak_length_mean : n.frames_from_neutral; }

// §5 step 2. Neutral-to-peak: the target peak's mean length. Peak-to-peak: the neutral-to-source and
// neutral-to-target lengths, weighted by how close to neutral the path gets (its node nearest the
// neutral pose): a path through neutral takes Ls + Lt, one that stays at the source takes 0 + …
double path_length_impl(const RegionGraph& region, const std::vector<std::size_t>& path,
                        double target_length) {
  if (path.size() == 1) return 1.0;
  const Node& src = region.nodes[path.front()];
  const Node& tgt = region.nodes[path.back()];
  if (path.front() == region.neutral_node || src.frames_from_neutral <= 1.5)
    return std::max(2.0, target_length);
  double closest = std::numeric_limits<double>::infinity();
  for (std::size_t i : path) closest = std::min(closest, region.nodes[i].displacement.norm());
  auto fraction = [&](const Node& n) {
    const double d = n.displacement.norm();
    return d > 0.0 ? std::clamp(1.0 - closest / d, 0.0, 1.0) : 0.0;
  };
  return std::max(2.0, node_length(src) * fraction(src) + target_length * fraction(tgt));
}

}  // namespace

double path_length(const RegionGraph& region, const std::vector<std::size_t>& path) {
  if (path.empty()) throw InvalidInput("path_length: empty path");
  return path_length_impl(region, path, node_length(region.nodes[path.back()]));
}

// §5 steps 3 and 4.
std::vector<Pose> assemble(const MotionGraph& graph, std::vector<Eigen::MatrixXd> region_frames,
                           const SmoothingOptions& smoothing) {
  smoothing.validate();
  if (region_frames.size() != graph.regions.size())
    throw InvalidInput("assemble: one frame matrix per region expected");
  for (std::size_t r = 0; r < region_frames.size(); ++r)
    if (region_frames[r].rows() < 1 || region_frames[r].cols() != graph.regions[r].neutral.size() ||
        !region_frames[r].allFinite())
      throw InvalidInput("assemble: region \"" + graph.regions[r].name +
                         "\" needs >= 1 finite frame of the region's width");
  Eigen::Index longest = 1;
  for (const auto& m : region_frames) longest = std::max(longest, m.rows());
  const int d = graph.dimensions;
  Eigen::VectorXd times(longest);
  for (Eigen::Index t = 0; t < longest; ++t) times[t] = static_cast<double>(t);
  for (std::size_t r = 0; r < region_frames.size(); ++r) {
    Eigen::MatrixXd& m = region_frames[r];
    if (m.rows() != longest) m = resample_linear(m, longest);  // step 3
    if (smoothing.savgol_window > 0 && longest >= 3) {          // step 4
      const Eigen::RowVectorXd first = m.row(0);
      m = savitzky_golay(m, smoothing.savgol_window, smoothing.savgol_order);
      m.row(0) = first;  // keep continuity with the previous animation
    }
    if (smoothing.sigmoid && longest >= 4) {
      SigmoidFitOptions fit;
      fit.solver = SigmoidSolver::VariableProjection;
      fit.max_iterations = 12;
      fit.rms_tolerance = smoothing.sigmoid_tolerance;
      for (Eigen::Index l = 0; l < m.cols() / d; ++l) {
        SigmoidFitReport rep;
        const Eigen::MatrixXd y = m.middleCols(l * d, d);
        // A landmark that (almost) does not move has nothing visible to smooth.
        if ((y.colwise().maxCoeff() - y.colwise().minCoeff()).maxCoeff() < smoothing.sigmoid_min_range) continue;
        const SigmoidCurve c = fit_sigmoid(y, fit, &rep);
        if (rep.rms < smoothing.sigmoid_max_rms) {
          Eigen::MatrixXd fitted = c.evaluate(times);
          // Pin the end points so consecutive animations stay continuous.
          const Eigen::RowVectorXd e0 = y.row(0) - fitted.row(0), e1 = y.row(longest - 1) - fitted.row(longest - 1);
          for (Eigen::Index t = 0; t < longest; ++t) {
            const double a = static_cast<double>(t) / static_cast<double>(longest - 1);
            fitted.row(t) += (1.0 - a) * e0 + a * e1;
          }
          m.middleCols(l * d, d) = fitted;
        }
      }
    }
  }
  std::vector<Pose> frames;
  Eigen::Index total = 0;
  for (const RegionGraph& rg : graph.regions) total += static_cast<Eigen::Index>(rg.landmarks.size());
  for (Eigen::Index t = 0; t < longest; ++t) {
    Pose pose(total, d);
    Eigen::Index row = 0;
    for (std::size_t r = 0; r < graph.regions.size(); ++r) {
      const Eigen::RowVectorXd flat = graph.regions[r].neutral + region_frames[r].row(t);
      for (Eigen::Index l = 0; l < flat.size() / d; ++l, ++row)
        for (int j = 0; j < d; ++j) pose(row, j) = flat[l * d + j];
    }
    frames.push_back(std::move(pose));
  }
  return frames;
}

namespace {
// Continuity between consecutive animations: start at the state's last pose and fade the offset
// to the path's own first pose out linearly over the sequence.
void continue_from(const SynthesisState& state, std::vector<Eigen::MatrixXd>& region_frames) {
  if (state.last.size() != region_frames.size()) return;
  for (std::size_t r = 0; r < region_frames.size(); ++r) {
    Eigen::MatrixXd& m = region_frames[r];
    if (state.last[r].size() != m.cols()) continue;
    const Eigen::RowVectorXd e = state.last[r] - m.row(0);
    const Eigen::Index n = m.rows();
    for (Eigen::Index t = 0; t < n; ++t)
      m.row(t) += e * (n == 1 ? 1.0 : 1.0 - static_cast<double>(t) / static_cast<double>(n - 1));
  }
}

void remember_last(const MotionGraph& graph, const Pose& last, SynthesisState& state) {
  state.last.assign(graph.regions.size(), {});
  const Eigen::RowVectorXd flat = detail::flatten(last);
  Eigen::Index col = 0;
  for (std::size_t r = 0; r < graph.regions.size(); ++r) {
    const Eigen::Index w = graph.regions[r].neutral.size();
    state.last[r] = flat.segment(col, w) - graph.regions[r].neutral;
    col += w;
  }
}

void check_state(const MotionGraph& graph, const SynthesisState& state) {
  if (graph.regions.empty()) throw InvalidInput("synthesis: empty motion graph");
  if (state.nodes.size() != graph.regions.size())
    throw InvalidInput("synthesis: state has " + std::to_string(state.nodes.size()) +
                       " regions, the graph " + std::to_string(graph.regions.size()));
  for (std::size_t r = 0; r < graph.regions.size(); ++r)
    if (state.nodes[r] >= graph.regions[r].nodes.size())
      throw InvalidInput("synthesis: state node out of range in region \"" + graph.regions[r].name + "\"");
}
}  // namespace

std::vector<Pose> synthesize(const MotionGraph& graph, SynthesisState& state, Label label,
                             const SynthesisOptions& options, SynthesisReport* report) {
  options.validate();
  check_state(graph, state);
  bool any = label == Label::Neutral;  // the source node is every region's neutral target
  for (const RegionGraph& rg : graph.regions)
    for (const Node& n : rg.nodes) any = any || n.has_peak_label(label);
  if (!any) throw InvalidInput("synthesis: the graph has no peak labelled \"" + to_string(label) + "\"");

  SynthesisReport rep;
  std::vector<Eigen::MatrixXd> region_frames;
  for (std::size_t r = 0; r < graph.regions.size(); ++r) {
    const RegionGraph& rg = graph.regions[r];
    // Independent regions (§5.1): each draws from its own stream.
    core::Rng rng(options.seed, state.calls * 1024 + r);
    std::vector<char> target(rg.nodes.size(), 0);
    for (std::size_t i = 0; i < rg.nodes.size(); ++i) target[i] = rg.nodes[i].has_peak_label(label);
    if (label == Label::Neutral) target[rg.neutral_node] = 1;  // back to rest through the source (§4.1)
    // Variation of the apex (issue 19): one of the label's peaks at random instead of the cheapest.
    if (options.vary_peak && label != Label::Neutral) {
      std::vector<std::size_t> peaks;
      for (std::size_t i = 0; i < target.size(); ++i)
        if (target[i]) peaks.push_back(i);
      if (peaks.size() > 1) {
        const std::size_t pick = peaks[rng.uniform_int(peaks.size())];
        std::fill(target.begin(), target.end(), 0);
        target[pick] = 1;
      }
    }
    double cost = 0.0;
    std::vector<std::size_t> path = shortest_path(rg.adjacency(false), state.nodes[r], target, &cost);
    if (path.empty() && options.allow_reverse_edges) {
      path = shortest_path(rg.adjacency(true), state.nodes[r], target, &cost);
      rep.used_reverse_edges = rep.used_reverse_edges || !path.empty();
    }
    if (path.empty()) path = {state.nodes[r]};
    // §5.1: replace inner path nodes by random neighbours.
    const auto adj = options.replace_probability > 0.0 ? rg.adjacency(true)
                                                       : decltype(rg.adjacency(true)){};
    if (options.replace_probability > 0.0 && path.size() > 2) {
      for (std::size_t i = 1; i + 1 < path.size(); ++i) {
        if (rng.uniform() >= options.replace_probability || adj[path[i]].empty()) continue;
        path[i] = adj[path[i]][rng.uniform_int(adj[path[i]].size())].first;
      }
    }
    const Node& tgt = rg.nodes[path.back()];
    double target_length = node_length(tgt);
    // §5.1: duration sampled from the peak node's normal distribution.
    if (options.vary_duration && tgt.is_peak())
      target_length = std::clamp(rng.normal(tgt.peak_length_mean, tgt.peak_length_std), 2.0, kMaxFrames);
    double length = path_length_impl(rg, path, target_length);
    // Back to rest: step 2 gives the source peak's own neutral-to-peak length; vary it alike (§5.1).
    const Node& src = rg.nodes[path.front()];
    if (label == Label::Neutral && options.vary_duration && path.size() > 1 && src.is_peak() &&
        src.peak_length_mean > 0.0)
      length *= std::clamp(rng.normal(src.peak_length_mean, src.peak_length_std), 2.0, kMaxFrames) /
                src.peak_length_mean;
    // §6.1: mood-decay hints use only the initial path nodes.
    if (options.path_fraction < 1.0 && path.size() > 1) {
      const std::size_t keep = std::max<std::size_t>(
          2, static_cast<std::size_t>(std::ceil(options.path_fraction * static_cast<double>(path.size()))));
      if (keep < path.size()) {
        length = std::max(2.0, length * static_cast<double>(keep) / static_cast<double>(path.size()));
        path.resize(keep);
      }
    }
    region_frames.push_back(recover_path(rg, path, static_cast<std::size_t>(std::lround(std::min(length, kMaxFrames)))));
    rep.region_lengths.push_back(static_cast<std::size_t>(region_frames.back().rows()));
    rep.paths.push_back(path);
    rep.path_costs.push_back(cost);
    state.nodes[r] = path.back();
  }
  ++state.calls;
  if (report) *report = std::move(rep);
  continue_from(state, region_frames);
  std::vector<Pose> frames = assemble(graph, std::move(region_frames), options.smoothing);
  remember_last(graph, frames.back(), state);
  return frames;
}

std::vector<Pose> idle(const MotionGraph& graph, SynthesisState& state, Label label,
                       const IdleOptions& options) {
  options.validate();
  check_state(graph, state);
  const double fps = graph.frame_rate;
  const std::size_t total = std::max<std::size_t>(2, static_cast<std::size_t>(std::lround(options.duration * fps)));
  const std::size_t move = std::max<long>(1, std::lround((options.hop_interval - options.dwell) * fps));
  const std::size_t dwell = static_cast<std::size_t>(std::lround(options.dwell * fps));
  std::vector<Eigen::MatrixXd> region_frames;
  for (std::size_t r = 0; r < graph.regions.size(); ++r) {
    const RegionGraph& rg = graph.regions[r];
    core::Rng rng(options.seed, state.calls * 1024 + r);
    const std::size_t home = state.nodes[r];
    // Hop candidates (§5): the current node and its neighbours sharing the label.
    std::vector<std::size_t> candidates{home};
    const auto adjacency = rg.adjacency(true);
    // At rest: nodes near the neutral pose count as neutral (issue 19; see the header).
    double peak_norm = 0.0, peaks = 0.0;
    for (const Node& n : rg.nodes)
      if (n.is_peak()) peak_norm += n.displacement.norm(), peaks += 1.0;
    const double rest_norm = peaks > 0.0 ? options.rest_fraction * peak_norm / peaks : 0.0;
    auto fits = [&](const Node& n) {
      return n.has_label(label) || (label == Label::Neutral && n.displacement.norm() <= rest_norm);
    };
    for (const auto& [v, w] : adjacency[home])
      if (fits(rg.nodes[v]) &&
          std::find(candidates.begin(), candidates.end(), v) == candidates.end())
        candidates.push_back(v);
    std::vector<Eigen::RowVectorXd> frames;
    std::size_t current = home;
    // Regions start their first hop at independent random offsets.
    const std::size_t offset = static_cast<std::size_t>(rng.uniform_int(move + dwell + 1));
    for (std::size_t i = 0; i <= offset && frames.size() < total; ++i) frames.push_back(rg.nodes[current].displacement);
    while (frames.size() < total) {
      std::size_t next = current;
      if (candidates.size() > 1) {
        do next = candidates[rng.uniform_int(candidates.size())]; while (next == current);
      }
      const Eigen::RowVectorXd a = rg.nodes[current].displacement, b = rg.nodes[next].displacement;
      for (std::size_t i = 1; i <= move && frames.size() < total; ++i)
        frames.push_back(a + (b - a) * (static_cast<double>(i) / static_cast<double>(move)));
      for (std::size_t i = 0; i < dwell && frames.size() < total; ++i) frames.push_back(b);
      current = next;
    }
    Eigen::MatrixXd m(static_cast<Eigen::Index>(frames.size()), frames[0].size());
    for (std::size_t i = 0; i < frames.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = frames[i];
    region_frames.push_back(std::move(m));
    state.nodes[r] = current;
  }
  ++state.calls;
  continue_from(state, region_frames);
  std::vector<Pose> out = assemble(graph, std::move(region_frames), options.smoothing);
  remember_last(graph, out.back(), state);
  return out;
}

}  // namespace emoface::motiongraph
