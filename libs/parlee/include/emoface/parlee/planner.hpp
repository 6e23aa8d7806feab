#pragma once
// The ParleE planner (thesis §5.7.2–5.7.4): finite-horizon top-down dynamic programming with
// memoisation (Fig. 5.6), extended to agents taking turns with d-level models of each other.
//
//   P^d_goal(a|s) = [goal holds in s]                                  if d = 0
//                 = max_i  Σ_s' P(s'|i,s) · P^{d-1}_goal(a|s')         if it is a's turn (Fig. 5.6)
//                 = Σ_i P^{L}(b,i|s) · Σ_s' P(s'|i,s) · P^{d-1}_goal(a|s')   if it is b's turn, b ≠ a
//   P^L(b,i|s)    = r_i / Σ_j r_j   with r_i = Σ_s' P(s'|i,s) · P^{L-1}_goal(b|s'),
//                   1/n if Σ_j r_j = 0 or L = 0 (a 0-level agent does not look ahead)  (§5.7.4)
// with L = min(D, d−1): the other agent is modelled as an L-level agent, which in turn models the
// others as (L−1)-level agents (§5.7.3). By default D = d−1, which is the thesis' recursion.
// An agent without goals is modelled as choosing uniformly. The goal of an agent used for its
// action choice is its highest-priority goal (that does not hold yet, under Within semantics).
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "emoface/parlee/domain.hpp"

namespace emoface::parlee {

/// When a goal counts as achieved inside the search window.
enum class GoalSemantics {
  Within,     ///< as soon as it holds at any step ≤ H (absorbing; "achieve within H steps")
  AtHorizon,  ///< only if it holds after the last step (Fig. 5.6 step 1 as printed)
};
std::string to_string(GoalSemantics s);
GoalSemantics goal_semantics_from_string(const std::string& s);  ///< throws InvalidInput

struct PlanOptions {
  int horizon = 3;           ///< search depth H in turns (one action per turn), [0, 64]
  int model_depth = -1;      ///< level D of the models of other agents; -1 = H−1 (thesis), [−1, 64]
  GoalSemantics semantics = GoalSemantics::Within;
  std::size_t max_memo_entries = 4000000;  ///< memo is cleared when it grows past this, ≥ 1
  void validate() const;
};

struct PlanStep {
  std::size_t action = 0;   ///< index into Domain::actions()
  int agent = 0;            ///< who acts
  double choice = 1.0;      ///< P(action chosen): 1 for the planning agent's optimal choice
  double value = 0.0;       ///< P(goal) after taking the action (expected over outcomes)
  std::size_t outcome = 0;  ///< most likely outcome, followed to build the rest of the plan
};

struct PlanResult {
  double probability = 0.0;      ///< P^H_goal from the start state
  std::vector<PlanStep> steps;   ///< the optimal (own turns) / most likely (others) line of play
  std::size_t states_evaluated = 0;
};

/// What ParleE needs from a planner (thesis §5.5: "any planner that can produce the same output
/// would fit into ParleE"): the probability of achieving a goal, the value of each applicable
/// action, and the models of other agents (their action distributions). `Planner` (the DP of
/// §5.7) is one implementation; `Agent` takes a `PlannerFactory` to use another.
class GoalPlanner {
 public:
  virtual ~GoalPlanner() = default;
  virtual const PlanOptions& options() const noexcept = 0;
  /// P^H_goal(agent of `goal` | s), in [0,1]; horizon −1 = options().horizon.
  virtual double goal_probability(std::size_t goal, const State& s, int horizon) = 0;
  /// Σ_s' P(s'|i,s)·P^{H−1}_goal(·|s') for each action of applicable_actions(s), in that order.
  virtual std::vector<double> action_values(std::size_t goal, const State& s, int horizon) = 0;
  /// P^level(b,i|s) for the agent b on turn, over applicable_actions(s) (sums to 1; empty if none).
  virtual std::vector<double> action_distribution(const State& s, int level) = 0;
  /// Highest-priority goal of `agent` that drives its choices in `s`; −1 if none.
  virtual int primary_goal(int agent, const State& s) const = 0;
  /// Forget cached values (called after the domain's outcome probabilities changed).
  virtual void clear() = 0;
};

/// Makes a planner for an agent's (copied) domain; the domain outlives the planner.
using PlannerFactory =
    std::function<std::unique_ptr<GoalPlanner>(const Domain&, const PlanOptions&)>;

class Planner final : public GoalPlanner {
 public:
  /// Keeps a reference to `domain`: it must outlive the planner. Call clear() after changing the
  /// domain's outcome probabilities.
  explicit Planner(const Domain& domain, PlanOptions options = {});

  const PlanOptions& options() const noexcept override { return options_; }

  /// P^H_goal(agent of `goal` | s); horizon −1 = options().horizon.
  double goal_probability(std::size_t goal, const State& s, int horizon = -1) override;
  /// Σ_s' P(s'|i,s)·P^{H−1}_goal(·|s') for each action of applicable_actions(s), in that order.
  std::vector<double> action_values(std::size_t goal, const State& s, int horizon = -1) override;
  /// P^level(b,i|s) for the agent b on turn, over applicable_actions(s) (sums to 1; empty if none).
  std::vector<double> action_distribution(const State& s, int level) override;
  /// Optimal plan for `goal` from `s`.
  PlanResult plan(std::size_t goal, const State& s, int horizon = -1);
  /// Highest-priority goal of `agent` (under Within semantics: not holding in `s` yet; ties:
  /// declaration order); −1 if none.
  int primary_goal(int agent, const State& s) const override;

  void clear() override;
  std::size_t memo_size() const noexcept { return value_memo_.size() + choice_memo_.size(); }
  std::size_t states_evaluated() const noexcept { return evaluated_; }

 private:
  struct Key {
    std::uint32_t goal;
    std::int32_t h;
    std::int32_t level;
    State s;
    bool operator==(const Key& o) const noexcept {
      return goal == o.goal && h == o.h && level == o.level && s == o.s;
    }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const noexcept;
  };
  double value(std::size_t goal, const State& s, int h, int level);
  const std::vector<double>& choice(const State& s, int level);
  std::vector<double> q_values(std::size_t goal, const State& s, const std::vector<std::size_t>& acts, int h,
                               int level);
  void bound_memo();

  const Domain& domain_;
  PlanOptions options_;
  std::unordered_map<Key, double, KeyHash> value_memo_;
  std::unordered_map<Key, std::vector<double>, KeyHash> choice_memo_;
  std::size_t evaluated_ = 0;
};

}  // namespace emoface::parlee
