#pragma once
// From mind-map behaviour to landmark motion (paper §6.1 step 4): the expression label of every
// triggered action drives motion-graph synthesis (motiongraph, paper §5); actions triggered by the
// mood decay only hint at the mood (synthesis from the initial path nodes); idle movements fill the
// gaps. Kept apart from `mindmap`, which depends on core only.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/mindmap/simulation.hpp"
#include "emoface/motiongraph/database.hpp"
#include "emoface/motiongraph/graph.hpp"
#include "emoface/motiongraph/synthesis.hpp"

namespace emoface::mindmotion {

enum class SegmentKind {
  Action,  ///< a stimulus or chained action: synthesis from all path nodes
  Hint,    ///< a mood-decay action: synthesis from the leading path fraction only
  Idle,    ///< idle movements between animations
};
std::string_view to_string(SegmentKind kind);
std::optional<SegmentKind> segment_kind_from_string(std::string_view name);

/// One piece of a character's animation.
struct Segment {
  SegmentKind kind = SegmentKind::Idle;
  std::string action;          ///< empty for Idle
  std::string label;           ///< expression label synthesized (Idle: the label idled around)
  double requested_time = 0.0; ///< seconds: when the action was triggered (Idle: = start)
  double start = 0.0;          ///< seconds: when its first frame plays (later if the face was busy)
  std::size_t first_frame = 0; ///< index into CharacterMotion::frames
  std::size_t frame_count = 0;
};

/// Stimulus and chained actions that arrive while the face is busy start as soon as it is free; decay
/// hints that arrive while it is busy are dropped (they only hint at the mood).
struct BehaviourMotionOptions {
  /// Leading fraction of each path used for decay hints (§6.1 "only the initial nodes"), (0, 1].
  double hint_path_fraction = 0.35;
  /// Gaps shorter than this (seconds) hold the last pose instead of idle movements, ≥ 0.
  double min_idle = 0.25;
  motiongraph::SynthesisOptions synthesis;  ///< seed is replaced by derive_seed(seed, character)
  motiongraph::IdleOptions idle;            ///< duration is set per gap; seed as above
  std::uint64_t seed = 0;
  void validate() const;  ///< throws InvalidInput
};

struct CharacterMotion {
  std::string character;
  double frame_rate = 30.0;                 ///< the graph's, frames per second
  std::vector<motiongraph::Pose> frames;    ///< landmark poses of graph.landmark_ids(), frame k at k/fps s
  std::vector<Segment> segments;            ///< in time order, covering all frames
  std::size_t dropped_hints = 0;
};

/// Expression labels that are a peak of at least one region of `graph` (lower-case names).
std::vector<std::string> graph_labels(const motiongraph::MotionGraph& graph);

/// Animates `character` (index `character_index` in the world, used for the seed) from the actions
/// of a simulation over [0, duration] seconds (other characters' actions and actions after `duration`
/// are ignored; the last animation may run past `duration`).
/// Throws InvalidInput for a label the graph cannot synthesize.
CharacterMotion synthesize_behaviour(const motiongraph::MotionGraph& graph,
                                     const std::vector<mindmap::TriggeredAction>& actions,
                                     const std::string& character, std::size_t character_index,
                                     double duration, const BehaviourMotionOptions& options = {});

/// The motion as a landmark database (one sequence per segment, id "<k>_<kind>_<action>"), ready for
/// motiongraph::write_database.
motiongraph::Database to_database(const motiongraph::MotionGraph& graph, const CharacterMotion& motion);

/// CSV "kind,action,label,requested_time,start,first_frame,frame_count" with a header row.
std::string segments_csv(const CharacterMotion& motion);

}  // namespace emoface::mindmotion
