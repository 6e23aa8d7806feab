#pragma once
// ParleE emotion state (thesis §5.5.2–5.6.5): the 21 emotion types, per-emotion thresholds α
// (activation) and ω (saturation), decay (§5.6.3), update with the effect matrix M (§5.6.4),
// the 16-dimensional personality of Table 5.1 and its effects (§5.6.5, read as powers per
// seeds/README), motivational states shifting α (§5.5.4), and the mapping to the six basic
// emotions fuzzyexpr takes.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace emoface::parlee {

/// The OCC emotions of Tables 5.2/5.3 plus Surprise (Roseman). Names (snake_case) are the file form.
enum class Emotion : std::uint8_t {
  Joy, Distress, HappyFor, SorryFor, Resentment, Gloating, Hope, Fear, Satisfaction, FearsConfirmed,
  Relief, Disappointment, Pride, Shame, Appreciation, Reproach, Anger, Gratitude, Gratification,
  Remorse, Surprise
};
inline constexpr std::size_t kEmotionCount = 21;
/// One value per Emotion, indexed by static_cast<size_t>(Emotion). Intensities are ≥ 0.
using EmotionVector = std::array<double, kEmotionCount>;

std::string_view to_string(Emotion e);
Emotion emotion_from_string(std::string_view name);  ///< throws InvalidInput
inline std::size_t index(Emotion e) { return static_cast<std::size_t>(e); }

enum class Valence : std::uint8_t { Positive, Negative, Neutral };
/// Positive: joy, happy_for, gloating, hope, satisfaction, relief, pride, appreciation, gratitude,
/// gratification; Neutral: surprise; the rest Negative.
Valence valence(Emotion e);

// ---------------------------------------------------------------- personality (Table 5.1)
/// The 16 dimensions in the thesis order (§5.5.3: component 1 = perceiving level, 2 = perceiving
/// focus, …). Each value is in [0,1]; 0.5 is neutral.
enum class Trait : std::uint8_t {
  PerceivingLevel, PerceivingFocus, ReasoningLevel, ReasoningFocus, LearningLevel, LearningFocus,
  DecidingLevel, DecidingFocus, ActingLevel, ActingFocus, InteractingLevel, InteractingFocus,
  RevealingLevel, RevealingFocus, FeelingLevel, FeelingFocus
};
inline constexpr std::size_t kTraitCount = 16;
std::string_view to_string(Trait t);          ///< "perceiving_level", …, "feeling_focus"
Trait trait_from_string(std::string_view name);  ///< throws InvalidInput

struct Personality {
  std::array<double, kTraitCount> values{0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5,
                                         0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5};
  double operator[](Trait t) const { return values[static_cast<std::size_t>(t)]; }
  double& operator[](Trait t) { return values[static_cast<std::size_t>(t)]; }
  void validate() const;  ///< every value finite and in [0,1]
};

/// §5.6.5: P' = P^(perceivingFocus + 0.5), for P(goal) and P(event) in [0,1].
double perceive_probability(const Personality& p, double probability);
/// §5.6.5: impact' = −(−impact)^(reasoningFocus + 0.5) if impact < 0, impact^(1.5 − reasoningFocus)
/// otherwise; impact in [−1,1].
double reason_impact(const Personality& p, double impact);
/// §5.6.5: impulse' = impulse^(1.5 − feelingLevel), impulse ≥ 0.
double feel_impulse(const Personality& p, double impulse);
/// §5.6.5: Desire-other impulse' = impulse · feelingFocus.
double desire_other_factor(const Personality& p);

// ---------------------------------------------------------------- thresholds, decay, update
enum class DecayModel : std::uint8_t {
  Power,    ///< Φ = decay^(1.5 − feelingLevel): neutral (0.5) keeps `decay` (default; see docs)
  Product,  ///< Φ = min(1, decay · feelingLevel) as printed in §5.6.3
};
std::string_view to_string(DecayModel m);
DecayModel decay_model_from_string(std::string_view s);

/// The length of one ParleE step in the thesis' application, in seconds: thesis §7.4, "The match
/// lasts for ninety minutes. Each minute there is an event happening" — one step = one match
/// minute. The per-step decay constants (EmotionParams::decay, §5.6.3) are given for this step.
inline constexpr double kThesisStepSeconds = 60.0;

/// An agent's emotional characteristics (§5.5.2) and the effect matrix M of §5.6.4.
struct EmotionParams {
  EmotionVector alpha;  ///< activation thresholds, 0 ≤ α ≤ ω (intensity units)
  EmotionVector omega;  ///< saturation thresholds, ω > 0
  EmotionVector decay;  ///< decayFactor per step of `step_seconds` (a saturated emotion), [0,1]
  /// effect[j][i] = M_{j,i}: how much an active emotion j damps impulses to emotion i. Entries in
  /// [0,1]; every column sum Σ_j M_{j,i} must lie in [0,1] (§5.6.4).
  std::array<EmotionVector, kEmotionCount> effect{};
  DecayModel decay_model = DecayModel::Power;
  /// Seconds one step of `decay` lasts, (0, 1e9]: decay is per second, Φ^(Δt/step_seconds) over
  /// Δt seconds (decayed()). Default the thesis' step, one match minute (kThesisStepSeconds).
  double step_seconds = kThesisStepSeconds;
  /// §5.6.3 "emotions decay slower when their intensity levels are lower … moods persist much
  /// longer than high intensity emotions": the decay rate at intensity E is k·(r + (1 − r)·E/ω),
  /// k = −ln Φ / step_seconds the rate of a saturated emotion, r this value, [0,1]. 1 = every
  /// intensity decays alike (Φ per step exactly, the per-step behaviour before issue 17); 0.5
  /// (default) = a faint mood decays at half the rate of a saturated emotion. See decayed().
  double low_intensity_rate = 0.5;

  /// α = 0.1, ω = 1, decay 0.9 (hope/fear 0.85, surprise 0.3, distress 0.97), and a
  /// small Cathexis-style M: joy ⟷ distress 0.3, fear → joy/hope 0.2, hope → fear 0.2.
  static EmotionParams defaults();
  void validate() const;  ///< throws InvalidInput naming the emotion or the offending M column
};

/// Φ(E_i, personality) of §5.6.3 for every emotion.
EmotionVector decay_multipliers(const EmotionParams& params, const Personality& p);

/// Per-second decay rates k_i = −ln Φ_i / params.step_seconds of a saturated emotion (Φ_i =
/// decay_multiplier[i]); +inf where Φ_i = 0, 0 where Φ_i = 1.
EmotionVector decay_rates(const EmotionParams& params, const EmotionVector& decay_multiplier);

/// Ψ of §5.6.3 over `dt_seconds` ≥ 0 of time, per emotion: the exact solution of
///   dE/dt = −k·(r + (1 − r)·E/ω)·E,  k = decay_rates(), r = params.low_intensity_rate,
/// i.e. with a = r·k, b = (1 − r)·k/ω:  E(Δt) = E·e^(−aΔt) / (1 + b·E·(1 − e^(−aΔt))/a)
/// (E / (1 + b·E·Δt) when a = 0). A flow: decaying Δt₁ then Δt₂ equals decaying Δt₁ + Δt₂;
/// with r = 1, E·Φ^(Δt/step_seconds), so one step of step_seconds multiplies by Φ exactly.
/// Throws InvalidInput for a negative or non-finite dt.
EmotionVector decayed(const EmotionVector& e, const EmotionParams& params,
                      const EmotionVector& decay_multiplier, double dt_seconds);

/// §5.6.4 with the decayed state given: E_{i,t+1} = min(ω_i, Ψ_i + I_i·(1 − Σ_j
/// S_{j,t}/ω_j·M_{j,i})) with S from `e` (the state before decay, E_t). `decayed` = Ψ(E_t), e.g.
/// from decayed().
void update_decayed_emotions(EmotionVector& e, const EmotionVector& decayed,
                             const EmotionVector& impulse, const EmotionParams& params,
                             const EmotionVector& alpha);

/// §5.6.4: E_{i,t+1} = min(ω_i, Φ_i·E_{i,t} + I_i·(1 − Σ_j S_{j,t}/ω_j · M_{j,i})),
/// S_{j,t} = E_{j,t} if E_{j,t} ≥ α_j else 0. `alpha` is the effective α (after motivational
/// shifts); impulses must be ≥ 0. Keeps 0 ≤ E ≤ ω when 0 ≤ E_t ≤ ω on entry.
void update_emotions(EmotionVector& e, const EmotionVector& impulse, const EmotionParams& params,
                     const EmotionVector& alpha, const EmotionVector& decay_multiplier);

/// True where E_i ≥ α_i (an emotion rather than a mood, §5.5.2).
std::array<bool, kEmotionCount> active(const EmotionVector& e, const EmotionVector& alpha);

// ---------------------------------------------------------------- motivational states (§5.5.4)
struct MotivationalState {
  double hunger = 0.0, fatigue = 0.0, thirst = 0.0, pain = 0.0;  ///< each in [0,1]
  void validate() const;
};

struct MotivationOptions {
  double fatigue_gain = 0.5;  ///< fatigue lowers α of negative, raises α of positive emotions, [0,1]
  double pain_gain = 0.5;     ///< pain lowers α of fear, [0,1]
  double hunger_gain = 0.25;  ///< hunger raises every α, [0,4]
  double thirst_gain = 0.25;  ///< thirst raises every α, [0,4]
  double action_cost = 0.01;  ///< hunger/fatigue/thirst added per action performed, [0,1]
  double hit_pain = 0.2;      ///< pain added when hit, [0,1]
  void validate() const;
};

/// α_i · f_i clamped to [0, ω_i] with f_i = 1 + hunger_gain·hunger + thirst_gain·thirst
/// ± fatigue_gain·fatigue (− for negative, + for positive emotions) − pain_gain·pain (fear only).
EmotionVector motivated_alpha(const EmotionParams& params, const MotivationalState& m,
                              const MotivationOptions& options = {});

/// One of the four motivational variables (§5.5.4).
enum class Need : std::uint8_t { Hunger, Fatigue, Thirst, Pain };
std::string_view to_string(Need n);                ///< "hunger", "fatigue", "thirst", "pain"
Need need_from_string(std::string_view s);         ///< throws InvalidInput
double level(const MotivationalState& m, Need n);  ///< the variable's value, [0,1]

enum class BodyEvent : std::uint8_t { Action, Eat, Drink, Rest, Hit };
std::string_view to_string(BodyEvent e);                ///< "action", "eat", "drink", "rest", "hit"
BodyEvent body_event_from_string(std::string_view s);  ///< throws InvalidInput
/// §5.5.4: hunger, fatigue, thirst grow with every action; pain when hit; eating, drinking and
/// resting reset hunger, thirst, and fatigue + pain. Values stay in [0,1].
void update_motivation(MotivationalState& m, BodyEvent event, const MotivationOptions& options = {});

// ---------------------------------------------------------------- basic emotions for fuzzyexpr
/// Order of fuzzyexpr's ESV.
inline constexpr std::array<std::string_view, 6> kBasicEmotionNames{"sadness", "happiness", "anger",
                                                                     "fear",    "disgust",   "surprise"};
/// Each basic intensity = max_k w_k · clamp((E_k − α_k)/(ω_k − α_k), 0, 1) over its contributing
/// emotions: only the active part of an emotion shows, moods below α do not (§5.5.2). Weights in
/// docs/parlee.md, "Mapping to the six basic emotions". Result in [0,1]^6, order above.
std::array<double, 6> basic_emotions(const EmotionVector& e, const EmotionParams& params);

/// §5.6.5 "The value of revealingLevel is used in the emotion displaying component": how much of
/// the felt basic emotions shows, read as a power like the other §5.6.5 modifiers:
/// shown_i = felt_i^(1.5 − revealingLevel). Neutral (0.5) shows what is felt, open (1) shows more
/// (felt^0.5), secretive (0) less (felt^1.5); 0 and 1 stay fixed, the order of the six is kept.
std::array<double, 6> revealed_emotions(const std::array<double, 6>& felt, const Personality& p);

}  // namespace emoface::parlee
