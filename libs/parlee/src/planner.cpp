#include "emoface/parlee/planner.hpp"

#include <algorithm>

namespace emoface::parlee {

std::string to_string(GoalSemantics s) { return s == GoalSemantics::Within ? "within" : "at_horizon"; }

GoalSemantics goal_semantics_from_string(const std::string& s) {
  if (s == "within") return GoalSemantics::Within;
  if (s == "at_horizon") return GoalSemantics::AtHorizon;
  throw InvalidInput("unknown goal semantics '" + s + "' (within, at_horizon)");
}

void PlanOptions::validate() const {
  if (horizon < 0 || horizon > 64) throw InvalidInput("PlanOptions::horizon must be in [0, 64]");
  if (model_depth < -1 || model_depth > 64) throw InvalidInput("PlanOptions::model_depth must be in [-1, 64]");
  if (max_memo_entries < 1) throw InvalidInput("PlanOptions::max_memo_entries must be ≥ 1");
}

std::size_t Planner::KeyHash::operator()(const Key& k) const noexcept {
  std::size_t h = StateHash{}(k.s);
  h ^= (static_cast<std::size_t>(k.goal) * 0x9e3779b97f4a7c15ull) ^
       (static_cast<std::size_t>(static_cast<std::uint32_t>(k.h)) << 20) ^
       (static_cast<std::size_t>(static_cast<std::uint32_t>(k.level)) << 40);
  return h;
}

Planner::Planner(const Domain& domain, PlanOptions options) : domain_(domain), options_(options) {
  options_.validate();
}

void Planner::clear() {
  value_memo_.clear();
  choice_memo_.clear();
}

void Planner::bound_memo() {
  if (memo_size() > options_.max_memo_entries) clear();
}

int Planner::primary_goal(int agent, const State& s) const {
  int best = -1;
  const auto& goals = domain_.goals();
  for (std::size_t g = 0; g < goals.size(); ++g) {
    if (goals[g].agent != agent) continue;
    if (options_.semantics == GoalSemantics::Within && domain_.goal_holds(g, s)) continue;
    if (best < 0 || goals[g].priority > goals[static_cast<std::size_t>(best)].priority) best = static_cast<int>(g);
  }
  return best;
}

std::vector<double> Planner::q_values(std::size_t goal, const State& s, const std::vector<std::size_t>& acts,
                                      int h, int level) {
  std::vector<double> q(acts.size(), 0.0);
  for (std::size_t k = 0; k < acts.size(); ++k) {
    const auto& a = domain_.actions()[acts[k]];
    double v = 0.0;
    for (std::size_t o = 0; o < a.outcomes.size(); ++o) {
      if (a.outcomes[o].probability <= 0.0) continue;
      v += a.outcomes[o].probability * value(goal, domain_.apply(s, acts[k], o), h - 1, level);
    }
    q[k] = v;
  }
  return q;
}

double Planner::value(std::size_t goal, const State& s, int h, int level) {
  const bool holds = domain_.goal_holds(goal, s);
  if (h <= 0) return holds ? 1.0 : 0.0;
  if (holds && options_.semantics == GoalSemantics::Within) return 1.0;
  level = std::min(level, h - 1);
  Key key{static_cast<std::uint32_t>(goal), h, level, s};
  if (auto it = value_memo_.find(key); it != value_memo_.end()) return it->second;
  ++evaluated_;
  const auto acts = domain_.applicable_actions(s);
  double result = 0.0;
  if (acts.empty()) {
    result = value(goal, domain_.pass_turn(s), h - 1, level);
  } else {
    const int who = domain_.turn(s);
    const auto q = q_values(goal, s, acts, h, level);
    if (who == domain_.goals()[goal].agent) {
      result = *std::max_element(q.begin(), q.end());
    } else {
      const std::vector<double> w = choice(s, level);  // copy: memo may rehash during recursion
      for (std::size_t k = 0; k < q.size(); ++k) result += w[k] * q[k];
    }
  }
  bound_memo();
  value_memo_.emplace(std::move(key), result);
  return result;
}

const std::vector<double>& Planner::choice(const State& s, int level) {
  Key key{0, 0, level, s};
  if (auto it = choice_memo_.find(key); it != choice_memo_.end()) return it->second;
  const auto acts = domain_.applicable_actions(s);
  std::vector<double> w(acts.size(), acts.empty() ? 0.0 : 1.0 / static_cast<double>(acts.size()));
  const int g = level > 0 ? primary_goal(domain_.turn(s), s) : -1;
  if (g >= 0 && !acts.empty()) {
    auto r = q_values(static_cast<std::size_t>(g), s, acts, level, level - 1);
    double sum = 0.0;
    for (double v : r) sum += v;
    if (sum > 0.0) {
      for (std::size_t k = 0; k < r.size(); ++k) w[k] = r[k] / sum;
    }
  }
  bound_memo();
  return choice_memo_.emplace(std::move(key), std::move(w)).first->second;
}

double Planner::goal_probability(std::size_t goal, const State& s, int horizon) {
  if (goal >= domain_.goals().size()) throw InvalidInput("Planner: goal index out of range");
  const int h = horizon < 0 ? options_.horizon : horizon;
  const int d = options_.model_depth < 0 ? h : options_.model_depth;
  return value(goal, s, h, d);
}

std::vector<double> Planner::action_values(std::size_t goal, const State& s, int horizon) {
  if (goal >= domain_.goals().size()) throw InvalidInput("Planner: goal index out of range");
  const int h = std::max(1, horizon < 0 ? options_.horizon : horizon);
  const int d = options_.model_depth < 0 ? h : options_.model_depth;
  return q_values(goal, s, domain_.applicable_actions(s), h, std::min(d, h - 1));
}

std::vector<double> Planner::action_distribution(const State& s, int level) {
  if (level < 0) throw InvalidInput("Planner::action_distribution: level must be ≥ 0");
  return choice(s, level);
}

PlanResult Planner::plan(std::size_t goal, const State& start, int horizon) {
  PlanResult r;
  const std::size_t before = evaluated_;
  int h = horizon < 0 ? options_.horizon : horizon;
  r.probability = goal_probability(goal, start, h);
  State s = start;
  const int d = options_.model_depth < 0 ? h : options_.model_depth;
  for (; h > 0; --h) {
    if (options_.semantics == GoalSemantics::Within && domain_.goal_holds(goal, s)) break;
    const auto acts = domain_.applicable_actions(s);
    if (acts.empty()) {
      s = domain_.pass_turn(s);
      continue;
    }
    const int level = std::min(d, h - 1);
    const auto q = q_values(goal, s, acts, h, level);
    PlanStep step;
    step.agent = domain_.turn(s);
    std::size_t pick = 0;
    if (step.agent == domain_.goals()[goal].agent) {
      pick = static_cast<std::size_t>(std::max_element(q.begin(), q.end()) - q.begin());
    } else {
      const auto w = choice(s, level);
      pick = static_cast<std::size_t>(std::max_element(w.begin(), w.end()) - w.begin());
      step.choice = w[pick];
    }
    step.action = acts[pick];
    step.value = q[pick];
    const auto& outs = domain_.actions()[step.action].outcomes;
    std::size_t best = 0;
    for (std::size_t o = 1; o < outs.size(); ++o)
      if (outs[o].probability > outs[best].probability) best = o;
    step.outcome = best;
    r.steps.push_back(step);
    s = domain_.apply(s, step.action, best);
  }
  r.states_evaluated = evaluated_ - before;
  return r;
}

}  // namespace emoface::parlee
