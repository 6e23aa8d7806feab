#pragma once
// Live use of a motion graph (issue 19 item 5): a frame-by-frame player whose next transition is
// prepared while the current one plays, and which can be interrupted at any frame — the new
// transition starts exactly at the pose on screen (no jump) and blends the difference out.
//
//   mg::MotionPlayer player(graph);                 // at rest, idling (Label::Neutral)
//   player.queue(mg::Label::Happiness);             // synthesized now, played after the current
//   part for (;;) { const mg::Pose& p = player.next_frame(); ... }   // one pose per graph frame
//   player.interrupt(mg::Label::Surprise);          // from the current frame, drops the queue
//
// Works on landmark and weight graphs (weights.hpp) alike. Not thread-safe; deterministic for the
// options' seeds and the sequence of calls.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "emoface/motiongraph/graph.hpp"
#include "emoface/motiongraph/synthesis.hpp"

namespace emoface::motiongraph {

struct PlayerOptions {
  SynthesisOptions synthesis;  ///< transitions (seed: the player's random stream)
  IdleOptions idle;            ///< idle stretches when nothing is queued (duration = one chunk)
  /// After a transition, idle under its label (§5 idle movements; neutral = at rest); otherwise
  /// hold the last pose.
  bool idle_when_done = true;
  void validate() const;
};

/// PlayerOptions for a weight graph (weight_synthesis_options, weight_idle_options).
PlayerOptions weight_player_options();

class MotionPlayer {
 public:
  /// Starts at the graph's neutral pose under Label::Neutral. Throws InvalidInput for an empty
  /// graph or invalid options. The graph must outlive the player.
  explicit MotionPlayer(const MotionGraph& graph, PlayerOptions options = {});

  /// Appends a transition to a peak of `label` after the last queued one (or after the part playing
  /// now); it is synthesized immediately (prepared ahead). Idle stretches prepared ahead are
  /// dropped: the transition follows the current part. Throws InvalidInput if the graph has no peak
  /// of `label` (nothing changes then).
  /// `path_fraction` in (0, 1] overrides SynthesisOptions::path_fraction for this transition (§6.1
  /// mood-decay hints: only the leading path nodes).
  void queue(Label label, double path_fraction = 1.0);
  /// Replaces what plays and the queue by a transition to `label` that starts at the current frame
  /// (the pose last returned by next_frame(), or the start pose): each region continues from the
  /// node nearest to its current displacement, and the offset to it fades out over the transition
  /// (synthesize's continuation), so the first new frame is one step from the current one. Throws
  /// InvalidInput like queue() (nothing changes then).
  void interrupt(Label label, double path_fraction = 1.0);
  /// True while a transition plays or is queued (false while idling or holding).
  bool busy() const noexcept;
  /// The next frame (graph.landmark_ids() poses, graph units); never runs dry: idles (or holds)
  /// when nothing is queued, preparing the next idle stretch when the current one starts.
  const Pose& next_frame();

  const Pose& current() const noexcept { return current_; }
  /// Label of the part playing now (a transition's target, or the idle label).
  Label label() const noexcept { return playing_label_; }
  /// Frames prepared beyond the current one (the rest of the current part plus everything queued).
  std::size_t prepared_frames() const noexcept;
  /// Parts prepared after the current one (queued transitions and an idle stretch ahead).
  std::size_t prepared_parts() const noexcept { return parts_.size(); }
  std::uint64_t frames_played() const noexcept { return played_; }

 private:
  struct Part {
    std::vector<Pose> frames;
    Label label = Label::Neutral;
    bool idle = false;
    SynthesisState end;  // the graph state after this part
  };
  Part make_transition(const SynthesisState& from, Label label, double path_fraction);
  Part make_idle(const SynthesisState& from, Label label);
  void check_label(Label label) const;
  const SynthesisState& tail_state() const;
  void advance_part();

  const MotionGraph& graph_;
  PlayerOptions options_;
  Part playing_;
  std::size_t index_ = 0;  // next frame of playing_ to return
  std::deque<Part> parts_;
  Pose current_;
  Label playing_label_ = Label::Neutral;
  std::uint64_t played_ = 0;
  std::uint64_t calls_ = 0;  // random stream counter of the player's syntheses
};

}  // namespace emoface::motiongraph
