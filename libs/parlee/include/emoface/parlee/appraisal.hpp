#pragma once
// Emotion appraisal (thesis §5.5.1, Tables 5.2–5.3) and the Emotion Impulse Vector (§5.6.2),
// with the personality modifiers of §5.6.5; liking (§5.6.1) and learning (§5.8).
#include <cstddef>
#include <string>
#include <vector>

#include "emoface/parlee/emotion.hpp"

namespace emoface::parlee {

enum class GoalStatus : std::uint8_t { Unconfirmed, Success, Fail };
std::string_view to_string(GoalStatus s);
GoalStatus goal_status_from_string(std::string_view s);

/// Who caused the event (Table 5.3, "actor").
enum class Actor : std::uint8_t { Self, Other, Nobody };
std::string_view to_string(Actor a);
Actor actor_from_string(std::string_view s);

/// One of the appraising agent's goals, before and after the event.
struct GoalAppraisal {
  double importance = 1.0;   ///< Import(goal) ≥ 0
  double p_before = 0.0;     ///< P(goal) before the event, [0,1]
  double p_after = 0.0;      ///< P(goal) after the event, [0,1]
  GoalStatus status = GoalStatus::Unconfirmed;  ///< after the event
  bool status_changed = false;  ///< the status became Success/Fail with this event
  double previous_hope = 0.0;   ///< this goal's hope impulse at the previous appraisal
  double previous_fear = 0.0;   ///< this goal's fear impulse at the previous appraisal
};

/// Another agent, as seen through the appraising agent's model of it (Desire-other emotions).
struct OtherAppraisal {
  double liking = 0.0;  ///< LikingLevel toward it, [−1,1]
  std::vector<double> importance;  ///< its goals' importance
  std::vector<double> impact;      ///< I2: impact of the event on each of its goals, [−1,1]
};

struct AppraisalInput {
  std::vector<GoalAppraisal> goals;
  double p_event = 1.0;             ///< P(event), [0,1]
  Actor actor = Actor::Nobody;
  bool has_praiseworthiness = false;
  double praiseworthiness = 0.0;    ///< Praiseworthiness(action), [−1,1]
  std::vector<OtherAppraisal> others;
};

/// How Hope and Fear combine over goals (thesis §5.6.2).
enum class ProspectMode : std::uint8_t {
  SignedSum,  ///< as printed: S = Σ Import·(P − pivot); Hope = max(0, S), Fear = max(0, −S)
  PerGoal,    ///< each goal clamped first: Hope = Σ max(0, Import·(P − pivot)), Fear likewise
};
std::string_view to_string(ProspectMode m);
ProspectMode prospect_mode_from_string(std::string_view s);  ///< throws InvalidInput

/// When the compound emotions Anger, Gratitude, Gratification and Remorse arise.
enum class CompoundRule : std::uint8_t {
  Impact,     ///< §5.6.2: any (un)desirable action of another agent / of oneself
  Standards,  ///< Table 5.2 (OCC): Anger = Distress + Reproach, Gratitude = Joy + Appreciation,
              ///< Gratification = Joy + Pride, Remorse = Distress + Self-reproach: only when the
              ///< action's praiseworthiness is known and of the right sign; intensity as §5.6.2
};
std::string_view to_string(CompoundRule r);
CompoundRule compound_rule_from_string(std::string_view s);  ///< throws InvalidInput

struct AppraisalOptions {
  CompoundRule compound = CompoundRule::Impact;     ///< Table 5.2 vs §5.6.2 for Anger & co.
  ProspectMode prospect = ProspectMode::SignedSum;  ///< §5.6.2 combination of Hope/Fear over goals
  double prospect_pivot = 0.5;      ///< Hope if P(goal) > pivot, Fear if below (§5.6.2), (0,1)
  double surprise_threshold = 0.5;  ///< Surprise = threshold − P(event) if P(event) < threshold, (0,1]
  double joy_exponent = 0.5;        ///< unexpectedness exponent for happiness-type emotions, > 0
  double distress_exponent = 2.0;   ///< unexpectedness exponent for sadness, > 0
  void validate() const;
};

struct AppraisalResult {
  EmotionVector impulse{};          ///< after personality (§5.6.5), ≥ 0
  /// Per goal, before personality: feed back as previous_hope / previous_fear. Under SignedSum
  /// each goal holds its share of the net Hope (Fear) in proportion to its positive (negative)
  /// term, so that the shares add up to the impulse; under PerGoal its own clamped term.
  std::vector<double> hope;
  std::vector<double> fear;
};

/// The EIV of §5.6.2:
///   Impact   = P'after − P'before (P' = perceive_probability), then reason_impact
///   Joy      = Σ Impact·Import·(1−P'(event))^0.5 (Impact > 0); Distress with |Impact| and ^2
///   Hope     = max(0, S), Fear = max(0, −S), S = Σ_unconfirmed Import·(P'(goal) − 0.5)
///              (ProspectMode::SignedSum, as printed; PerGoal clamps each goal's term first)
///   Gratitude/Anger (actor other), Gratification/Remorse (actor self): like Joy with |Impact|,
///   ^0.5 Satisfaction/Relief on success = previous Hope/Fear; Disappointment/FearsConfirmed on
///   failure Pride/Shame (self), Appreciation/Reproach (other) = ±Praiseworthiness
///   HappyFor/SorryFor (liking > 0), Resentment/Gloating (liking < 0) = |LL|·other's joy/distress,
///   times feelingFocus
///   Surprise = 0.5 − P'(event) if P'(event) < 0.5
/// and finally every impulse^(1.5 − feelingLevel). Throws InvalidInput for out-of-range inputs.
AppraisalResult appraise(const AppraisalInput& input, const Personality& personality,
                         const AppraisalOptions& options = {});

/// §5.6.1: Desirability = Σ_goal Import·Impact.
double desirability(const std::vector<double>& importance, const std::vector<double>& impact);
/// §5.6.1: LikingLevel_{t+1} = max(−1, min(1, LikingLevel_t + rate·Desirability)), rate 0.1.
double update_liking(double liking, double desirability, double rate = 0.1);

/// §5.8: count-based outcome learning. P_j ← (P_j·n + [j = observed])/(n + 1), n ← n + 1.
struct OutcomeLearner {
  std::vector<double> p;  ///< outcome probabilities, sum 1
  double n = 10.0;        ///< presumed number of previous observations (learning rate), ≥ 0
  void observe(std::size_t outcome);  ///< throws InvalidInput if out of range
};

/// §5.8: praiseworthiness of an action = mean of the feedback points received, each in [−1,1].
struct RunningMean {
  double mean = 0.0;
  std::size_t count = 0;
  void add(double feedback);  ///< throws InvalidInput outside [−1,1] or non-finite
};

}  // namespace emoface::parlee
