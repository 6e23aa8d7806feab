#pragma once
// A ParleE agent living in a domain (thesis Fig. 5.3): planner + models of other agents →
// appraisal → emotion impulse vector → emotion state with decay, personality, motivational states,
// liking and learning. Used by `parlee run` (Obie, chapter 7) and the bread example (§5.9).
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "emoface/core/rng.hpp"
#include "emoface/parlee/appraisal.hpp"
#include "emoface/parlee/domain.hpp"
#include "emoface/parlee/emotion.hpp"
#include "emoface/parlee/planner.hpp"

namespace emoface::parlee {

/// What the agent does with an event its model of the world does not allow (the action is not
/// applicable in the believed state, ambiguous, or has no such outcome).
enum class DisallowedEvent : std::uint8_t {
  Skip,  ///< report it in StepRecord::skipped and go on (the step still passes: own turn, decay)
  Stop,  ///< throw InvalidInput
};
std::string_view to_string(DisallowedEvent d);
DisallowedEvent disallowed_event_from_string(std::string_view s);  ///< throws InvalidInput

/// How much the emotions decay between two events (§5.6.3, issue 17 item 3).
enum class DecayClock : std::uint8_t {
  Time,  ///< by the time between the events: (Event::time − previous)·time_unit_seconds seconds
  Step,  ///< one step of EmotionParams::step_seconds per event, whatever the times (before issue
         ///< 17)
};
std::string_view to_string(DecayClock c);
DecayClock decay_clock_from_string(std::string_view s);  ///< throws InvalidInput

/// §5.5.4: a high motivational state generates a replenishment goal ("the agent wants to reduce
/// these values"). The named goal of the agent (declared in the domain, e.g. `feed-self`) exists
/// for the agent only while `need` ≥ `threshold`: below it the goal is dormant (not planned for,
/// not appraised); when the need rises past the threshold the goal appears (unconfirmed, with
/// fresh hope/fear); when the need falls (the agent ate, drank, rested) it disappears again.
struct ReplenishmentGoal {
  std::string goal;  ///< name of one of the agent's goals in the domain
  Need need = Need::Hunger;
  double threshold = 0.5;  ///< the goal exists while level(need) ≥ threshold, (0,1]
};

struct AgentConfig {
  std::string name = "agent";        ///< label of this configuration ("neutral", "pessimistic", …)
  std::string self;                  ///< the domain agent this is; empty = the first agent
  Personality personality;
  EmotionParams emotions = EmotionParams::defaults();
  MotivationalState motivation;
  MotivationOptions motivation_options;
  AppraisalOptions appraisal;
  PlanOptions planning;
  bool learn_outcomes = false;       ///< §5.8 count-based outcome learning on observed events
  double learning_prior = 10.0;      ///< presumed observations n0 (scaled by learningFocus + 0.5), ≥ 0
  double liking_rate = 0.1;          ///< §5.6.1 liking update rate, [0,1]
  std::map<std::string, double> liking;             ///< initial LikingLevel per other agent, [−1,1]
  std::map<std::string, double> praiseworthiness;   ///< standards: value per operator name, [−1,1]
  /// §5.5.4: operator name → what it does to the body: eat/drink/rest when the agent performs it,
  /// hit when anyone performs it (the agent is hit). Every own action also counts as `action`.
  std::map<std::string, BodyEvent> body_events;
  std::vector<ReplenishmentGoal> replenishment;  ///< §5.5.4 goals created by motivational states
  std::uint64_t seed = 1;            ///< own action choices and unspecified outcomes
  DisallowedEvent on_disallowed = DisallowedEvent::Skip;  ///< events the model does not allow
  DecayClock decay_clock = DecayClock::Time;
  /// Seconds per unit of Event::time, (0, 1e9]: 60 = event times are match minutes (§7.4).
  /// With the defaults an event one minute after the previous one decays by one thesis step.
  double time_unit_seconds = 60.0;
  void validate() const;
};

/// One scripted or interactive event: an action of the agent on turn.
struct Event {
  double time = 0.0;         ///< event clock (e.g. match minute); must not decrease
  std::string action;        ///< "(shot oteam)", a prefix of the arguments is enough; "" = pass
  std::string outcome;       ///< outcome label, "case-N" or 1-based number; "" = sample (seeded)
  std::optional<double> feedback;  ///< feedback in [−1,1] on the agent's own last action (§5.8)
  std::string note;          ///< free text carried into the timeline
};

struct AppliedAction {
  std::string actor;
  std::string action;        ///< "(shot oteam)" or "pass"
  std::string outcome;       ///< label
  double p_event = 1.0;      ///< P(event) as appraised (§5.6.1)
  std::string effects;       ///< "+(score one) -(score zero)"
};

struct StepRecord {
  std::size_t step = 0;
  double time = 0.0;
  std::string note;
  std::vector<AppliedAction> actions;
  std::vector<std::string> goal_names;
  std::vector<double> goal_probability;   ///< after the step (planner, horizon H)
  std::vector<GoalStatus> goal_status;
  std::vector<bool> goal_active;          ///< false: a dormant replenishment goal (§5.5.4)
  EmotionVector impulse{};                ///< summed impulses of the step
  EmotionVector emotions{};               ///< emotion state after decay + update
  std::array<double, 6> basic{};          ///< basic_emotions(): sadness … surprise (felt)
  std::array<double, 6> shown{};          ///< revealed_emotions(basic): what the display shows
  std::map<std::string, double> liking;
  std::string state;                      ///< facts after the step
  std::string skipped;                    ///< why the event was skipped (DisallowedEvent::Skip)
};

class Agent {
 public:
  /// Copies `domain` (the agent's beliefs; learning changes the copy). Throws InvalidInput if the
  /// config is invalid or names an unknown agent.
  /// `make_planner` builds the agent's planner (default: the DP `Planner` of §5.7).
  Agent(const Domain& domain, AgentConfig config, const PlannerFactory& make_planner = {});
  Agent(const Agent&) = delete;
  Agent& operator=(const Agent&) = delete;

  /// Applies one event (the agent acts first if it is its turn, then the event, then the agent
  /// responds if the turn came back), appraises each action, decays and updates the emotions.
  /// Decay (DecayClock::Time): over the time since the previous event (or since 0), so two events
  /// at the same time decay once and events half a minute apart by half a minute.
  /// An event the agent's model does not allow (action not applicable or ambiguous, unknown
  /// outcome) is skipped and reported in StepRecord::skipped (message lists what is applicable);
  /// with DisallowedEvent::Stop it throws InvalidInput instead, and the agent may by then have
  /// taken its own turn, so treat the agent as spent after that exception. A time earlier than the
  /// previous event's or bad feedback always throws.
  StepRecord step(const Event& event);
  /// The record of the initial state (step 0): goal probabilities and the resting emotions.
  StepRecord initial_record();

  const Domain& domain() const noexcept { return *domain_; }
  const State& state() const noexcept { return state_; }
  const AgentConfig& config() const noexcept { return config_; }
  const MotivationalState& motivation() const noexcept { return config_.motivation; }
  const EmotionVector& emotions() const noexcept { return emotions_; }
  int self() const noexcept { return self_; }
  /// Actions the agent on turn may take now ("(unload-food bread car1)").
  std::vector<std::string> applicable() const;
  GoalPlanner& planner() noexcept { return *planner_; }

 private:
  void act(const std::optional<std::size_t>& forced, const std::string& outcome, StepRecord& rec,
           EmotionVector& impulse);
  void self_act(StepRecord& rec, EmotionVector& impulse);
  void pass_unreported(const Event& event, StepRecord& rec);
  std::string outcome_problem(std::size_t action, const std::string& outcome) const;  ///< "" if ok
  std::vector<double> own_goal_probabilities(const State& s);
  GoalStatus confirm(std::size_t k, const State& s) const;
  void update_replenishment();
  int own_primary_goal(const State& s) const;
  void fill(StepRecord& rec);
  double event_probability(const State& s, std::size_t action, const State& after);

  std::unique_ptr<Domain> domain_;
  AgentConfig config_;
  std::unique_ptr<GoalPlanner> planner_;
  int self_ = 0;
  State state_;
  double time_ = 0.0;
  std::size_t steps_ = 0;
  core::Rng rng_;
  EmotionVector emotions_{};
  std::vector<std::size_t> own_goals_;
  std::vector<double> p_goal_;
  std::vector<GoalStatus> status_;
  std::vector<bool> active_;                                          ///< per own goal
  std::vector<std::pair<std::size_t, ReplenishmentGoal>> replenish_;  ///< own goal index k, rule
  std::vector<double> prev_hope_, prev_fear_;
  std::map<std::string, double> liking_;
  std::map<std::string, RunningMean> feedback_;
  std::map<std::size_t, OutcomeLearner> learners_;
  std::optional<std::size_t> last_own_op_;
};

}  // namespace emoface::parlee
