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
  Rest,    ///< the return to the neutral pose after `return_after` seconds without an action
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

/// The §5.1 variation that mind-map pipelines use by default (issue 19): the duration drawn from the
/// peak node's N(mean, std), each inner path node replaced by a random neighbour with probability 0.3
/// (the value of the docs' `mgraph synth --vary --replace 0.3` example), and a random peak of the
/// label as the target (`vary_peak`), so the same label gives a different face per character and per
/// performance. Seeded like everything else.
motiongraph::SynthesisOptions varied_synthesis();

/// Stimulus and chained actions that arrive while the face is busy start as soon as it is free; decay
/// hints that arrive while it is busy are dropped (they only hint at the mood).
/// Before the first action the face idles at rest (Label::Neutral idle); `return_after` seconds after
/// its last animation it returns to neutral through the graph source (a Rest segment) and idles at
/// rest, provided the whole return fits before the next action.
struct BehaviourMotionOptions {
  /// Leading fraction of each path used for decay hints (§6.1 "only the initial nodes"), (0, 1].
  double hint_path_fraction = 0.35;
  /// Gaps shorter than this (seconds) hold the last pose instead of idle movements, ≥ 0.
  double min_idle = 0.25;
  /// Seconds of idle around an expression before the face returns to rest, >= 0; 0 = never return
  /// (the face holds its last expression, as before issue 19).
  double return_after = 2.0;
  /// Motion synthesis, with §5.1 variation on (varied_synthesis()); `vary_duration = false` and
  /// `replace_probability = 0` switch it off. Seed is replaced by derive_seed(seed, character).
  motiongraph::SynthesisOptions synthesis = varied_synthesis();
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

/// Expression labels `graph` can synthesize (lower-case names): `neutral` (the graph source, always)
/// and every label that is a peak of at least one region.
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
