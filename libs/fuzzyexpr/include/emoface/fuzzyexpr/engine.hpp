#pragma once
// The emotion → facial-expression system of thesis chapter 6: Expression Mode Selection, the Single and
// Blend Expression Mode fuzzy rule-based systems (Mamdani: min implication, max aggregation) and exact
// centre-of-area defuzzification. ESV (6 intensities in [0,1]) → FMCV (19 contraction levels in [0,1]).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>

#include "emoface/fuzzyexpr/names.hpp"
#include "emoface/fuzzyexpr/rule_base.hpp"

namespace emoface::fuzzyexpr {

/// Which rule base expresses an ESV.
enum class ExpressionMode : std::uint8_t {
  Auto,    ///< thesis §6.5: single if the top intensity beats the second by more than single_margin,
           ///< or if it is the only non-zero emotion
  Single,  ///< always the strongest emotion alone
  Blend,   ///< always the two strongest (the stronger alone when the pair has no blend rules)
};
/// How equal intensities are ranked.
enum class TieBreak : std::uint8_t {
  Fixed,   ///< by ExpressionOptions::tie_order (deterministic, the default)
  Random,  ///< thesis §6.5: tied emotions are chosen at random (seeded by seed and the row number)
};
/// How the output changes across the single/blend switch and across changes of the selected emotions.
enum class Transition : std::uint8_t {
  Crisp,   ///< as in the thesis: a hard switch (the output may jump there)
  Smooth,  ///< beyond the thesis: interpretations are cross-faded over transition_width, so the FMCV
           ///< is a continuous function of the ESV everywhere (see docs/fuzzyexpr.md)
};
/// How a "−" cell inside a rule row is read.
enum class MissingRule : std::uint8_t {
  NoRule,         ///< no rule fires (a row like "− − − m b" jumps from 0 to m)
  NoContraction,  ///< "− : no contraction" (Table 6.1 caption, the default): a rule to the lowest
                  ///< output set, so such a row rises continuously from 0
};

std::string_view to_string(ExpressionMode v) noexcept;
std::string_view to_string(TieBreak v) noexcept;
std::string_view to_string(Transition v) noexcept;
std::string_view to_string(MissingRule v) noexcept;
std::optional<ExpressionMode> expression_mode_from_string(std::string_view s) noexcept;
std::optional<TieBreak> tie_break_from_string(std::string_view s) noexcept;
std::optional<Transition> transition_from_string(std::string_view s) noexcept;
std::optional<MissingRule> missing_rule_from_string(std::string_view s) noexcept;

struct ExpressionOptions {
  ExpressionMode mode = ExpressionMode::Auto;
  /// Auto mode: single when e1 − e2 > single_margin (thesis §6.5: 0.5) or e2 = 0. Range [0, 1].
  double single_margin = 0.5;
  TieBreak tie_break = TieBreak::Fixed;
  /// Fixed tie-break order: an emotion listed earlier wins a tie. Must be a permutation.
  std::array<Emotion, kEmotionCount> tie_order = {Emotion::Sadness, Emotion::Happiness,
                                                  Emotion::Anger,   Emotion::Fear,
                                                  Emotion::Disgust, Emotion::Surprise};
  /// Seed of the random tie-break; row r of a batch uses the stream (seed, r).
  std::uint64_t seed = 0;
  Transition transition = Transition::Crisp;
  /// Smooth transition: width of the cross-fade bands in intensity units. Range (0, 1].
  double transition_width = 0.1;
  /// Table 6.1's caption reads "−: no contraction": the default (docs/fuzzyexpr.md, sadness → m3).
  MissingRule missing_rule = MissingRule::NoContraction;

  /// Throws InvalidInput naming the bad field.
  void validate() const;
};

/// What the mode selection decided for one ESV (crisp modes).
struct Selection {
  ExpressionMode mode = ExpressionMode::Single;  ///< Single or Blend
  Emotion first = Emotion::Sadness;   ///< strongest emotion (the one expressed in single mode)
  Emotion second = Emotion::Sadness;  ///< second strongest (blend mode)
  bool pair_has_rules = true;         ///< false: blend of a no-blend pair → `first` alone
};

/// A compiled rule base. Construction validates and precomputes; convert() is const, allocation-free
/// and safe to call from several threads at once.
class Engine {
 public:
  /// Validates `rules` and `options` (InvalidInput) and compiles them. Copies share the compiled data.
  explicit Engine(RuleBase rules = default_rule_base(), ExpressionOptions options = {});

  const RuleBase& rules() const noexcept;
  const ExpressionOptions& options() const noexcept;

  /// Expression Mode Selection (thesis §6.5) for an ESV; `row` feeds the random tie-break stream.
  Selection select(const Esv& esv, std::uint64_t row = 0) const;

  /// ESV → FMCV. Throws InvalidInput if an intensity is NaN or outside [0, 1].
  Fmcv convert(const Esv& esv, std::uint64_t row = 0) const;

  /// Single Expression Mode FRBS alone: the FMCV of one emotion at `intensity` (Tables 6.1–6.6).
  Fmcv single(Emotion emotion, double intensity) const;

  /// Blend Expression Mode FRBS alone (Table 6.7): muscles of each emotion take that emotion's single
  /// level. For a no-blend pair, the stronger emotion alone (ties: tie_order).
  Fmcv blend(Emotion a, double intensity_a, Emotion b, double intensity_b) const;

  /// The level one single-rule row gives at `intensity` (0 when no rule fires).
  double row_level(const RuleRow& row, double intensity) const noexcept;

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;
};

/// The emotion → face mapping of thesis §6.5 as one function: ESV → FMCV (an Engine compiled once
/// from `rules`) → the 35 side parameters (expand_to_sides). Copies share the engine; thread-safe
/// to call. channels::side_parameter_mapper() turns it into a channel EmotionMapper.
std::function<SideParameters(const Esv&)> side_parameter_function(
    RuleBase rules = default_rule_base());

}  // namespace emoface::fuzzyexpr
