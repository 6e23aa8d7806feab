#include "emoface/mindmotion/behaviour.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"

namespace emoface::mindmotion {

namespace mg = motiongraph;

std::string_view to_string(SegmentKind kind) {
  switch (kind) {
    case SegmentKind::Action: return "action";
    case SegmentKind::Hint: return "hint";
    case SegmentKind::Idle: return "idle";
    case SegmentKind::Rest: return "rest";
  }
  return "idle";
}

std::optional<SegmentKind> segment_kind_from_string(std::string_view name) {
  if (name == "action") return SegmentKind::Action;
  if (name == "hint") return SegmentKind::Hint;
  if (name == "idle") return SegmentKind::Idle;
  if (name == "rest") return SegmentKind::Rest;
  return std::nullopt;
}

mg::SynthesisOptions varied_synthesis() {
  mg::SynthesisOptions o;
  o.vary_duration = true;
  o.replace_probability = 0.3;
  o.vary_peak = true;
  return o;
}

void BehaviourMotionOptions::validate() const {
  if (!(hint_path_fraction > 0.0 && hint_path_fraction <= 1.0))
    throw InvalidInput("BehaviourMotionOptions: hint_path_fraction must be in (0, 1]");
  if (!(min_idle >= 0.0 && std::isfinite(min_idle)))
    throw InvalidInput("BehaviourMotionOptions: min_idle must be finite and >= 0");
  if (!(return_after >= 0.0 && std::isfinite(return_after)))
    throw InvalidInput("BehaviourMotionOptions: return_after must be finite and >= 0");
  synthesis.validate();
  mg::IdleOptions probe = idle;
  probe.duration = 1.0;
  probe.validate();
}

std::vector<std::string> graph_labels(const mg::MotionGraph& graph) {
  std::vector<std::string> out;
  for (mg::Label l : mg::all_labels()) {
    bool found = l == mg::Label::Neutral;  // synthesize() returns to the source node
    for (const auto& r : graph.regions)
      for (const auto& n : r.nodes) found = found || n.has_peak_label(l);
    if (found) out.push_back(mg::to_string(l));
  }
  return out;
}

namespace {

class Animator {
 public:
  Animator(const mg::MotionGraph& graph, CharacterMotion& motion, const BehaviourMotionOptions& o,
           std::uint64_t seed)
      : graph_(graph), motion_(motion), options_(o), state_(mg::initial_state(graph)) {
    options_.synthesis.seed = seed;
    options_.idle.seed = seed;
  }
  double now() const { return static_cast<double>(motion_.frames.size()) / motion_.frame_rate; }

  // Fills [now, t): idle around the current label; after return_after seconds away from rest, the
  // return to neutral (when all of it fits before t) and idle at rest.
  void idle_until(double t) {
    if (label_ != mg::Label::Neutral && options_.return_after > 0.0) {
      const double rest_at = now() + options_.return_after;
      if (rest_at < t) {
        idle_plain(rest_at);
        mg::SynthesisState trial = state_;  // synthesis is cheap: try, keep it only if it fits
        std::vector<mg::Pose> back = mg::synthesize(graph_, trial, mg::Label::Neutral, options_.synthesis);
        if (now() + static_cast<double>(back.size() - 1) / motion_.frame_rate <= t + 1e-9) {
          state_ = std::move(trial);
          label_ = mg::Label::Neutral;
          append({SegmentKind::Rest, {}, "neutral", now(), now(), 0, 0}, std::move(back), true);
        }
      }
    }
    idle_plain(t);
  }

  // Fills [now, t) (rounded up to whole frames, so the next animation never starts early): idle
  // movements (§5), or the last pose held when the gap is shorter than min_idle.
  void idle_plain(double t) {
    const double fps = motion_.frame_rate;
    const double n = std::ceil((t - now()) * fps - 1e-6);
    if (n < 1.0) return;
    const Segment s{SegmentKind::Idle, {}, mg::to_string(label_), now(), now(), 0, 0};
    if (n / fps < options_.min_idle && !motion_.frames.empty()) {
      append(s, std::vector<mg::Pose>(static_cast<std::size_t>(n), motion_.frames.back()), false);
      return;
    }
    mg::IdleOptions io = options_.idle;
    io.duration = n / fps;
    if (io.hop_interval >= io.duration) io.hop_interval = io.duration, io.dwell = std::min(io.dwell, 0.5 * io.duration);
    append(s, mg::idle(graph_, state_, label_, io), false);
  }

  void perform(const mindmap::TriggeredAction& a) {
    const bool hint = a.cause == mindmap::Cause::Decay;
    if (hint && a.time + 1e-9 < now()) {
      ++motion_.dropped_hints;
      return;
    }
    idle_until(a.time);
    mg::Label label = mg::Label::Neutral;
    try {
      label = mg::label_from_string(a.label);
    } catch (const InvalidInput&) {
      throw InvalidInput("action \"" + a.action + "\" of \"" + a.character + "\": label \"" + a.label +
                         "\" is not a motion-graph label");
    }
    mg::SynthesisOptions so = options_.synthesis;
    if (hint) so.path_fraction = options_.hint_path_fraction;  // paper §6.1: initial nodes only
    label_ = label;
    append({hint ? SegmentKind::Hint : SegmentKind::Action, a.action, a.label, a.time, now(), 0, 0},
           mg::synthesize(graph_, state_, label, so), !motion_.frames.empty());
  }

 private:
  void append(Segment s, std::vector<mg::Pose> frames, bool drop_first) {
    // synthesize() starts at the current pose, which is already the last frame.
    std::size_t skip = drop_first && frames.size() > 1 ? 1 : 0;
    s.first_frame = motion_.frames.size();
    s.frame_count = frames.size() - skip;
    for (std::size_t i = skip; i < frames.size(); ++i) motion_.frames.push_back(std::move(frames[i]));
    motion_.segments.push_back(std::move(s));
  }

  const mg::MotionGraph& graph_;
  CharacterMotion& motion_;
  BehaviourMotionOptions options_;
  mg::SynthesisState state_;
  mg::Label label_ = mg::Label::Neutral;
};

}  // namespace

CharacterMotion synthesize_behaviour(const mg::MotionGraph& graph,
                                     const std::vector<mindmap::TriggeredAction>& actions,
                                     const std::string& character, std::size_t character_index,
                                     double duration, const BehaviourMotionOptions& options) {
  options.validate();
  if (!(duration >= 0.0 && duration <= 1e5)) throw InvalidInput("synthesize_behaviour: duration must be in [0, 1e5] s");
  CharacterMotion motion;
  motion.character = character;
  motion.frame_rate = graph.frame_rate;
  std::vector<const mindmap::TriggeredAction*> mine;
  for (const auto& a : actions)
    if (a.character == character && a.time <= duration) mine.push_back(&a);
  std::stable_sort(mine.begin(), mine.end(), [](auto* x, auto* y) { return x->time < y->time; });
  Animator animator(graph, motion, options, core::derive_seed(options.seed, character_index));
  for (const auto* a : mine) animator.perform(*a);
  animator.idle_until(duration);
  return motion;
}

mg::Database to_database(const mg::MotionGraph& graph, const CharacterMotion& motion) {
  mg::Database db;
  db.dimensions = graph.dimensions;
  db.frame_rate = motion.frame_rate;
  db.landmark_ids = graph.landmark_ids();
  db.landmark_count = db.landmark_ids.size();
  for (std::size_t k = 0; k < motion.segments.size(); ++k) {
    const Segment& s = motion.segments[k];
    mg::Sequence seq;
    seq.id = std::to_string(k) + "_" + std::string(to_string(s.kind)) + (s.action.empty() ? "" : "_" + s.action);
    seq.subject = motion.character;
    seq.label = mg::label_from_string(s.label);
    seq.frames.assign(motion.frames.begin() + static_cast<std::ptrdiff_t>(s.first_frame),
                      motion.frames.begin() + static_cast<std::ptrdiff_t>(s.first_frame + s.frame_count));
    db.sequences.push_back(std::move(seq));
  }
  return db;
}

std::string segments_csv(const CharacterMotion& motion) {
  std::string out = core::csv_stamp() + "kind,action,label,requested_time,start,first_frame,frame_count\n";
  char buf[96];
  for (const auto& s : motion.segments) {
    out += to_string(s.kind);
    out += ',';
    core::append_csv_field(out, s.action);
    out += ',';
    core::append_csv_field(out, s.label);
    std::snprintf(buf, sizeof buf, ",%.6f,%.6f,%zu,%zu\n", s.requested_time, s.start, s.first_frame, s.frame_count);
    out += buf;
  }
  return out;
}

}  // namespace emoface::mindmotion
