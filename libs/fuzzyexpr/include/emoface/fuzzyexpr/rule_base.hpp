#pragma once
// The rule base of the emotion → muscle system (thesis §6.6): fuzzy sets for intensities and
// contraction levels, the Single Expression Mode rules (Tables 6.1–6.6) and the Blend Expression Mode
// assignments (Table 6.7). Pure data; engine.hpp evaluates it, io.hpp reads and writes it.
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "emoface/fuzzyexpr/fuzzy_set.hpp"
#include "emoface/fuzzyexpr/names.hpp"

namespace emoface::fuzzyexpr {

/// Output-set index meaning "no rule" (a "−" cell: the muscle is not driven at that intensity).
inline constexpr int kNoRule = -1;

/// One column group of a single-emotion table: the listed muscles share one rule row.
/// levels[i] is the output set (index into RuleBase::output_sets) that input set i implies, or kNoRule:
///   "if <emotion> is input_sets[i] then <muscle> is output_sets[levels[i]]" for each muscle.
struct RuleRow {
  std::vector<Muscle> muscles;
  std::vector<int> levels;
};

/// One line of Table 6.7: in the blend of `first` and `second`, the muscles in first_muscles take their
/// level from `first`'s single rules, those in second_muscles from `second`'s; all others stay at 0.
struct BlendRule {
  Emotion first = Emotion::Surprise;
  Emotion second = Emotion::Fear;
  std::vector<Muscle> first_muscles;
  std::vector<Muscle> second_muscles;
};

struct RuleBase {
  std::vector<FuzzySet> input_sets;   ///< intensity sets on [0,1], in increasing order (VeryLow…)
  std::vector<FuzzySet> output_sets;  ///< contraction-level sets, increasing (VerySmall…)
  std::array<std::vector<RuleRow>, kEmotionCount> single;  ///< per emotion (Tables 6.1–6.6)
  std::vector<BlendRule> blend;                             ///< Table 6.7
  /// Pairs without blend rules: only the stronger emotion is expressed (thesis §6.6.3).
  std::vector<std::pair<Emotion, Emotion>> no_blend;

  /// Throws InvalidInput unless: 2–16 sets each, every set valid, set names unique, the input sets cover
  /// [0,1] (every intensity belongs to some set), rows have one level per input set and name existing
  /// output sets, a muscle appears at most once per emotion, and every one of the 15 emotion pairs is
  /// listed exactly once in `blend` or `no_blend` with disjoint, non-repeating muscle lists.
  void validate() const;

  /// The rule row that drives `muscle` for `emotion`, or nullptr if the emotion does not drive it.
  const RuleRow* row_for(Emotion emotion, Muscle muscle) const noexcept;
};

/// The built-in rule base: data/fuzzyexpr/rules.json, compiled into the library.
const RuleBase& default_rule_base();

}  // namespace emoface::fuzzyexpr
