#pragma once
// Triggering animation (paper §6.1) for many characters: stimuli update the mood (eqs. 2–4), the top
// emotion node picks a performing action, chains follow, and while the mood decays the representative
// action of the top emotion is triggered at intervals. Stimuli may come from other characters (the
// affection towards the source enters eq. 2) or from the world (carrying their own weights); a
// character that does not know a stimulus copies it and its weights from the source (§6.1).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "emoface/core/rng.hpp"
#include "emoface/mindmap/mind_map.hpp"
#include "emoface/mindmap/mood.hpp"

namespace emoface::mindmap {

/// One stimulus at a point in time.
struct Event {
  double time = 0.0;     ///< seconds, finite, ≥ 0
  std::string target;    ///< receiving character; "*" = every character except the source
  std::string stimulus;  ///< action node name
  std::string source;    ///< acting character (must exist); empty = world stimulus
  /// World stimuli: emotion node name → stimulus edge weight in [0, 1], used by characters whose map
  /// lacks the stimulus (paper §6.1, "the particular stimulus should contain the emotional node and
  /// edge weights to be copied").
  std::vector<std::pair<std::string, double>> weights;
  std::size_t line = 0;  ///< 1-based line in the events file, for messages; 0 = unknown
  /// Runtime trait changes (paper §6: the background context is "the influence of the current
  /// location", the affection matrix "the moods towards other characters"; issue 19): an event with
  /// an empty `stimulus` and a non-empty `context` and/or `affection` replaces the target's background
  /// context (one value per emotion node in [0, 1]) and/or affection rows (by character name) at
  /// `time`. The mood is not touched: the new context enters PTraits (eq. 3) of the next mood updates
  /// (eq. 4), the new affection the perceived stimulus (eq. 2) of the next stimuli from that character.
  std::vector<double> context;
  std::vector<std::pair<std::string, std::vector<double>>> affection;
  bool changes_traits() const noexcept { return stimulus.empty() && (!context.empty() || !affection.empty()); }
};

/// Why an action was triggered.
enum class Cause {
  Stimulus,  ///< chosen after a stimulus (§6.1 steps 1–4): synthesize from all path nodes
  Chain,     ///< follows another performing action along a chain edge
  Decay,     ///< representative action during mood decay: synthesize from the initial nodes only
};
std::string_view to_string(Cause cause);
std::optional<Cause> cause_from_string(std::string_view name);

struct TriggeredAction {
  double time = 0.0;       ///< seconds
  std::string character;
  std::string action;
  std::string label;       ///< expression label for motion-graph synthesis
  std::string emotion;     ///< the top emotion node that chose the action (chains: of the first)
  double mood = 0.0;       ///< that emotion's mood value when chosen, [0, 1]
  Cause cause = Cause::Stimulus;
  std::string stimulus;    ///< the stimulus that started it; empty for Decay
  std::size_t chain_depth = 0;  ///< 0 for the chosen action, k for the k-th chained one
  /// The character the action is performed *at* (issue 19: addressees): the source of the stimulus
  /// that started it (a response is aimed back at whoever acted); empty for world stimuli and decay.
  std::string addressee;
};

/// A stimulus learnt by a character during the simulation (§6.1 copying).
struct CopiedStimulus {
  double time = 0.0;
  std::string character;
  std::string stimulus;
  std::string from;  ///< the source character, or "world"
  std::size_t edges = 0;  ///< stimulus edges copied (emotion nodes the character lacks are dropped)
};

struct SimulationOptions {
  MoodForm mood_form = MoodForm::Sum;  ///< reading of eq. 4
  /// Near-equal edges: every response edge whose |weight − mood| is within this of the closest one
  /// is a candidate, chosen uniformly with the seeded generator. [0, 1]; 0 = only exact ties.
  double tie_tolerance = 0.05;
  double chain_delay = 1.0;           ///< seconds between consecutive actions of a chain, ≥ 0
  std::size_t max_chain_length = 8;   ///< actions per chain including the first, ≥ 1
  double decay_interval = 2.0;        ///< seconds between decay-triggered actions, > 0
  double sigmoid_steepness = 10.0;    ///< k of the sigmoid decay curve, > 0
  bool copy_unknown_stimuli = true;   ///< false: an unknown stimulus is an error
  double frame_rate = 10.0;           ///< mood timeline samples per second (simulate()), > 0
  /// simulate(): length of the timeline in seconds; 0 = until the last event's decay has ended
  /// (rounded up to a whole sample).
  double duration = 0.0;
  /// simulate(): a performed action that is also a stimulus of the performer's map (receive and
  /// perform) is delivered to every other character (source = the performer, so the affection and
  /// stimulus copying apply) at the action's time, up to this many hops per original event, [0, 64];
  /// 0 = off (stimuli come only from the events).
  std::size_t propagation_depth = 0;
  /// With propagation: an action that has an addressee reaches only that character (performed *at*
  /// it); false = every other character, as before issue 19. Actions without addressee always go to
  /// every other character.
  bool propagate_to_addressee = false;
  std::uint64_t seed = 0;  ///< character c draws from core::Rng(seed, c)
  void validate() const;   ///< throws InvalidInput
};

/// Index of the largest value (the first on ties). n ≥ 1.
std::size_t top_emotion(const double* mood, std::size_t n) noexcept;

/// §6.1 step 3: among the response edges of `emotion`, the action whose edge weight is closest to
/// `mood_value`; edges within `tie_tolerance` of the closest are chosen uniformly with `rng`.
/// Returns kNone when the emotion has no response edge.
std::size_t choose_response(const MindMap& map, std::size_t emotion, double mood_value,
                            double tie_tolerance, core::Rng& rng);

/// The chain reaction started by `first`: `first`, then its chain successors depth-first in edge
/// order; every action at most once (cycles stop), at most `max_length` actions.
std::vector<std::size_t> chain_from(const MindMap& map, std::size_t first, std::size_t max_length);

/// Characters, their moods and the clock.
class World {
 public:
  /// Validates every map (InvalidInput); character names must be unique.
  explicit World(std::vector<MindMap> maps, SimulationOptions options = {});

  std::size_t size() const noexcept { return characters_.size(); }
  const MindMap& map(std::size_t c) const { return characters_.at(c).map; }
  std::optional<std::size_t> find(std::string_view character) const;
  double time() const noexcept { return time_; }
  /// Mood of character c at time(), one entry per emotion node.
  const std::vector<double>& mood(std::size_t c) const { return characters_.at(c).mood; }
  const std::vector<CopiedStimulus>& copied() const noexcept { return copied_; }
  /// Runtime trait changes (issue 19): the background context of character c (one value per emotion
  /// node in [0, 1]; empty = none) and its affection row towards `other` (empty row = remove it).
  /// They enter the next mood updates (eqs. 2–4); the current mood and its decay towards the
  /// personality are unchanged. Throw InvalidInput naming the field (nothing changes).
  void set_background_context(std::size_t c, const std::vector<double>& context);
  void set_affection(std::size_t c, const std::string& other, const std::vector<double>& row);
  /// The current traits of character c (the map's, with runtime changes applied).
  const Traits& traits(std::size_t c) const { return characters_.at(c).map.traits; }

  /// Moves the clock to t ≥ time(): moods decay towards the personality; representative actions
  /// due in (time(), t] are appended to `out` (may be null).
  void advance_to(double t, std::vector<TriggeredAction>* out);

  /// advance_to(event.time), then delivers the stimulus to its target(s): eqs. 2–4, action choice,
  /// chain. A trait-change event (Event::changes_traits) replaces the target's background context
  /// and/or affection rows instead ("*" = every character). Throws InvalidInput for unknown characters, an unknown stimulus that cannot be copied,
  /// bad weights or an event in the past (messages name the event's line); the world is then unchanged.
  void apply(const Event& event, std::vector<TriggeredAction>* out);

 private:
  struct Character {
    MindMap map;
    std::vector<double> mood, start, ptraits, scratch;
    double last_update = 0.0, next_hint = 0.0;
    bool decaying = true;
    core::Rng rng;
  };
  struct CopyPlan {
    std::vector<std::pair<std::size_t, double>> edges;  // (emotion node of the receiver, weight)
    std::string from;                                   // source character or "world"
  };
  CopyPlan plan_copy(std::size_t c, const Event& event) const;  // throws if it cannot be copied
  std::size_t learn(std::size_t c, const Event& event, const CopyPlan& plan);
  void deliver(std::size_t c, const Event& event, const CopyPlan* plan, std::vector<TriggeredAction>* out);
  void decay(Character& ch, double t, std::vector<TriggeredAction>* out);

  std::vector<Character> characters_;
  SimulationOptions options_;
  std::vector<CopiedStimulus> copied_;
  double time_ = 0.0;
};

struct SimulationResult {
  std::vector<std::string> characters;
  std::vector<double> times;  ///< sample times, k / frame_rate
  /// Per character: times.size() rows of emotion_count values, row-major.
  std::vector<std::vector<double>> mood;
  std::vector<TriggeredAction> actions;  ///< all characters, sorted by time (stable)
  std::vector<CopiedStimulus> copied;
  double duration = 0.0;
};

/// The mind map of character `c` as it stands at `time` after the events up to then (sorted by
/// time, stable; no propagation): copied stimuli learnt and background context / affection changed
/// at run time (issue 19), for drawing (mind_map_dot). Throws like World::apply.
MindMap map_at(std::vector<MindMap> maps, std::vector<Event> events, std::size_t c, double time,
               const SimulationOptions& options = {});

/// Runs the events (sorted by time, stable) through a World and samples every mood at frame_rate.
/// Events at a sample time are applied before the sample.
SimulationResult simulate(std::vector<MindMap> maps, std::vector<Event> events,
                          const SimulationOptions& options = {});

}  // namespace emoface::mindmap
