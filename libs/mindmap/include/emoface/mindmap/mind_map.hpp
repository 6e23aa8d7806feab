#pragma once
// Mind maps as behaviour controllers (paper §6): a character node, a layer of emotion nodes (any
// names: emotions, states such as "bored"), and a layer of action nodes that can be received
// (stimuli) and/or performed. Weighted edges: stimulus → emotion (the stimulus' influence on the mood)
// and emotion → performing action (the emotional threshold of the action); unweighted edges
// performing action → performing action make chain reactions. Each emotion node may flag one
// representative performing action, triggered while the mood decays (§6.1). Each performing action
// carries the expression label that drives motion-graph synthesis.
//
// Nodes are referred to by index in memory and by name in files (emoface/mindmap/io.hpp).
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace emoface::mindmap {

/// "No node" in index fields (e.g. an emotion without a representative action).
inline constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

/// Shape of the mood decay towards the personality (§6: "linear, quadratic or sigmoid").
enum class DecayCurve { Linear, Quadratic, Sigmoid };
std::string_view to_string(DecayCurve curve);
/// Inverse of to_string ("linear", "quadratic", "sigmoid"); nullopt for anything else.
std::optional<DecayCurve> decay_curve_from_string(std::string_view name);

struct ActionNode {
  std::string name;          ///< unique among actions and emotions, non-empty
  bool receivable = false;   ///< can be received as a stimulus
  bool performable = false;  ///< can be performed (then `label` is mandatory)
  std::string label;         ///< expression label for motion-graph synthesis (e.g. "happiness")
};

/// stimulus → emotion: the stimulus' influence on that emotion node, in [0, 1] (ActionEmot, eq. 2).
struct StimulusEdge {
  std::size_t action = kNone;
  std::size_t emotion = kNone;
  double weight = 0.0;
};

/// emotion → performing action: the mood value at which the action fits best, in [0, 1] (§6.1).
struct ResponseEdge {
  std::size_t emotion = kNone;
  std::size_t action = kNone;
  double weight = 0.0;
};

/// performing action → performing action (chain reaction, e.g. surprised then happy). Chains from
/// one action run in the order the edges are listed.
struct ChainEdge {
  std::size_t from = kNone;
  std::size_t to = kNone;
};

/// Personality traits (§6). Arrays have one entry per emotion node, values in [0, 1].
struct Traits {
  std::vector<double> starting_mood;  ///< mandatory
  std::vector<double> personality;    ///< mandatory; the mood decays towards it
  std::vector<double> background_context;  ///< optional (empty = absent): influence of the location
  /// Optional affection matrix: one row per other character (by name), the mood towards it.
  std::vector<std::pair<std::string, std::vector<double>>> affection;
  double lambda = 0.0;  ///< eq. 2: weight of the affection towards the source, [0, 1]
  double alpha = 0.5;   ///< eq. 4: importance of the stimulus over the personality traits, [0, 1]
  double beta = 0.5;    ///< eq. 4: how much a stimulus changes the current mood, [0, 1]
  double decay_duration = 5.0;  ///< seconds from an update until the mood equals the personality, > 0
  DecayCurve decay_curve = DecayCurve::Linear;

  /// The affection row towards `character`, or nullptr when there is none.
  const std::vector<double>* affection_towards(std::string_view character) const;
};

struct MindMap {
  std::string character;              ///< the central node: the character's name, non-empty
  std::vector<std::string> emotions;  ///< emotion nodes (≥ 1), unique names
  std::vector<ActionNode> actions;
  std::vector<StimulusEdge> stimulus_edges;
  std::vector<ResponseEdge> response_edges;
  std::vector<ChainEdge> chain_edges;
  /// Per emotion node, the index of its representative performing action or kNone; empty = none.
  std::vector<std::size_t> representative;
  Traits traits;

  std::size_t emotion_count() const { return emotions.size(); }
  std::optional<std::size_t> find_emotion(std::string_view name) const;
  std::optional<std::size_t> find_action(std::string_view name) const;
  /// Representative action of emotion `e`, or kNone.
  std::size_t representative_of(std::size_t e) const {
    return e < representative.size() ? representative[e] : kNone;
  }
};

/// Checks every invariant stated above (names, indices, edge kinds, duplicate edges, weights and
/// trait values finite in [0, 1], array sizes equal to the number of emotion nodes, λ α β in [0, 1],
/// decay duration > 0). Throws InvalidInput naming the offending node or field.
void validate(const MindMap& map);

/// One line for `mindmap check`: "<character>: <n> emotion nodes, <n> actions, <n> edges" (edges:
/// stimulus, response and chain edges together), no newline.
std::string summary(const MindMap& map);

/// Checks that every performing action's label is one of `known` (e.g. the labels of a motion graph).
/// Throws InvalidInput naming the action and the label.
void validate_labels(const MindMap& map, const std::vector<std::string>& known);

}  // namespace emoface::mindmap
