#include "emoface/motiongraph/player.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"
#include "emoface/motiongraph/weights.hpp"
#include "flat.hpp"

namespace emoface::motiongraph {

void PlayerOptions::validate() const {
  synthesis.validate();
  idle.validate();
}

PlayerOptions weight_player_options() {
  PlayerOptions o;
  o.synthesis = weight_synthesis_options();
  o.idle = weight_idle_options();
  return o;
}

namespace {
// The pose of every region at its node (neutral + node displacement), regions concatenated.
Pose pose_at(const MotionGraph& g, const SynthesisState& s) {
  const std::size_t rows = g.landmark_ids().size();
  Pose p(static_cast<Eigen::Index>(rows), g.dimensions);
  Eigen::Index row = 0;
  for (std::size_t r = 0; r < g.regions.size(); ++r) {
    const RegionGraph& rg = g.regions[r];
    const Eigen::RowVectorXd flat = rg.neutral + rg.nodes[s.nodes[r]].displacement;
    for (std::size_t l = 0; l < rg.landmarks.size(); ++l, ++row)
      for (int j = 0; j < g.dimensions; ++j)
        p(row, j) = flat[static_cast<Eigen::Index>(l) * g.dimensions + j];
  }
  return p;
}
}  // namespace

MotionPlayer::MotionPlayer(const MotionGraph& graph, PlayerOptions options)
    : graph_(graph), options_(std::move(options)) {
  options_.validate();
  if (graph_.regions.empty()) throw InvalidInput("motion player: empty motion graph");
  for (const RegionGraph& rg : graph_.regions) {  // a malformed graph must not index out of range
    const auto width = static_cast<Eigen::Index>(rg.landmarks.size()) * graph_.dimensions;
    bool ok = graph_.dimensions >= 1 && graph_.dimensions <= 3 && rg.neutral.size() == width &&
              rg.neutral_node < rg.nodes.size();
    for (const Node& n : rg.nodes) ok = ok && n.displacement.size() == width;
    if (!ok)
      throw InvalidInput("motion player: region \"" + rg.name +
                         "\" does not match the graph's dimensions and landmarks");
  }
  playing_.end = initial_state(graph_);
  playing_.label = Label::Neutral;
  playing_.idle = true;
  current_ = pose_at(graph_, playing_.end);
  playing_.frames = {current_};
  index_ = 1;  // the start pose counts as shown
}

void MotionPlayer::check_label(Label label) const {
  if (label == Label::Neutral) return;
  for (const RegionGraph& rg : graph_.regions)
    for (const Node& n : rg.nodes)
      if (n.has_peak_label(label)) return;
  throw InvalidInput("motion player: the graph has no peak labelled \"" + to_string(label) + "\"");
}

MotionPlayer::Part MotionPlayer::make_transition(const SynthesisState& from, Label label,
                                                 double path_fraction) {
  Part p;
  p.label = label;
  p.end = from;
  SynthesisOptions o = options_.synthesis;
  if (path_fraction < 1.0) o.path_fraction = path_fraction;
  o.validate();
  o.seed = core::derive_seed(options_.synthesis.seed, calls_++);
  p.frames = synthesize(graph_, p.end, label, o);
  // The first frame repeats the pose the part starts from: drop it (no held frame).
  if (p.frames.size() > 1) p.frames.erase(p.frames.begin());
  return p;
}

MotionPlayer::Part MotionPlayer::make_idle(const SynthesisState& from, Label label) {
  Part p;
  p.label = label;
  p.idle = true;
  p.end = from;
  if (options_.idle_when_done) {
    IdleOptions o = options_.idle;
    o.seed = core::derive_seed(options_.idle.seed, calls_++);
    p.frames = idle(graph_, p.end, label, o);
    if (p.frames.size() > 1) p.frames.erase(p.frames.begin());
  } else {  // hold the pose the part starts from for one idle duration
    Pose hold = pose_at(graph_, from);
    if (from.last.size() == graph_.regions.size()) {  // the exact last pose of the previous part
      Eigen::Index row = 0;
      for (std::size_t r = 0; r < graph_.regions.size(); ++r) {
        const Eigen::RowVectorXd flat = graph_.regions[r].neutral + from.last[r];
        for (std::size_t l = 0; l < graph_.regions[r].landmarks.size(); ++l, ++row)
          for (int j = 0; j < graph_.dimensions; ++j)
            hold(row, j) = flat[static_cast<Eigen::Index>(l) * graph_.dimensions + j];
      }
    }
    const std::size_t n = std::max<std::size_t>(
        1, static_cast<std::size_t>(options_.idle.duration * graph_.frame_rate + 0.5));
    p.frames.assign(n, hold);
  }
  return p;
}

const SynthesisState& MotionPlayer::tail_state() const {
  for (auto it = parts_.rbegin(); it != parts_.rend(); ++it)
    if (!it->idle) return it->end;
  return playing_.end;
}

bool MotionPlayer::busy() const noexcept {
  if (!playing_.idle && index_ < playing_.frames.size()) return true;
  for (const Part& p : parts_)
    if (!p.idle) return true;
  return false;
}

void MotionPlayer::queue(Label label, double path_fraction) {
  check_label(label);
  if (!(path_fraction > 0.0 && path_fraction <= 1.0))
    throw InvalidInput("motion player: path_fraction must be in (0, 1]");
  // Speculative idle stretches prepared ahead give way to the transition.
  while (!parts_.empty() && parts_.back().idle) parts_.pop_back();
  Part t = make_transition(tail_state(), label, path_fraction);
  parts_.push_back(std::move(t));
}

void MotionPlayer::interrupt(Label label, double path_fraction) {
  check_label(label);
  if (!(path_fraction > 0.0 && path_fraction <= 1.0))
    throw InvalidInput("motion player: path_fraction must be in (0, 1]");
  // State at the current frame: per region the nearest node, and the exact current displacement.
  SynthesisState from = playing_.end;
  from.nodes.assign(graph_.regions.size(), 0);
  from.last.assign(graph_.regions.size(), {});
  const Eigen::RowVectorXd flat = detail::flatten(current_);
  Eigen::Index col = 0;
  for (std::size_t r = 0; r < graph_.regions.size(); ++r) {
    const RegionGraph& rg = graph_.regions[r];
    const Eigen::Index w = rg.neutral.size();
    const Eigen::RowVectorXd d = flat.segment(col, w) - rg.neutral;
    col += w;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < rg.nodes.size(); ++i) {
      const double e = (rg.nodes[i].displacement - d).squaredNorm();
      if (e < best) best = e, from.nodes[r] = i;
    }
    from.last[r] = d;
  }
  Part t = make_transition(from, label, path_fraction);
  parts_.clear();
  playing_ = std::move(t);
  playing_label_ = label;
  index_ = 0;
  parts_.push_back(make_idle(playing_.end, label));  // prepared ahead
}

void MotionPlayer::advance_part() {
  if (parts_.empty()) parts_.push_back(make_idle(playing_.end, playing_.label));
  playing_ = std::move(parts_.front());
  parts_.pop_front();
  playing_label_ = playing_.label;
  index_ = 0;
  // Prepare the next idle stretch now, while this part plays (dropped if something is queued).
  if (parts_.empty()) parts_.push_back(make_idle(playing_.end, playing_.label));
}

const Pose& MotionPlayer::next_frame() {
  if (index_ >= playing_.frames.size()) advance_part();
  current_ = playing_.frames[index_++];
  ++played_;
  return current_;
}

std::size_t MotionPlayer::prepared_frames() const noexcept {
  std::size_t n = playing_.frames.size() - std::min(index_, playing_.frames.size());
  for (const Part& p : parts_) n += p.frames.size();
  return n;
}

}  // namespace emoface::motiongraph
