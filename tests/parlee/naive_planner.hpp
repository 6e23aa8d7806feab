#pragma once
// A second planner for the tests: a memo-free transcription of the §5.7.4 formulas, used to
// cross-check the memoised DP (planner_test) and plugged into an Agent through the GoalPlanner
// interface (agent_test: the same timeline as the DP).
#include <algorithm>
#include <vector>

#include "emoface/parlee/planner.hpp"

namespace emoface::parlee::test {

// Memo-free transcription of the §5.7.4 formulas (for cross-checking the memoised planner).
struct Naive {
  const Domain& d;
  bool within;
  int primary(int agent, const State& s) const {  // highest priority, first declared on ties
    int best = -1;
    for (std::size_t g = 0; g < d.goals().size(); ++g) {
      if (d.goals()[g].agent != agent || (within && d.goal_holds(g, s))) continue;
      if (best < 0 || d.goals()[g].priority > d.goals()[static_cast<std::size_t>(best)].priority)
        best = static_cast<int>(g);
    }
    return best;
  }
  double p_goal(std::size_t g, const State& s, int h, int D) const {
    const bool holds = d.goal_holds(g, s);
    if (h == 0 || (within && holds)) return holds ? 1.0 : 0.0;
    const auto acts = d.applicable_actions(s);
    if (acts.empty()) return p_goal(g, d.pass_turn(s), h - 1, D);
    std::vector<double> q;
    for (auto a : acts) {
      double v = 0.0;
      for (std::size_t o = 0; o < d.actions()[a].outcomes.size(); ++o)
        v += d.actions()[a].outcomes[o].probability * p_goal(g, d.apply(s, a, o), h - 1, D);
      q.push_back(v);
    }
    if (d.turn(s) == d.goals()[g].agent) return *std::max_element(q.begin(), q.end());
    const auto w = choice(s, std::min(D, h - 1));
    double v = 0.0;
    for (std::size_t k = 0; k < q.size(); ++k) v += w[k] * q[k];
    return v;
  }
  std::vector<double> choice(const State& s, int L) const {
    const auto acts = d.applicable_actions(s);
    std::vector<double> w(acts.size(), 1.0 / static_cast<double>(acts.size()));
    const int g = L > 0 ? primary(d.turn(s), s) : -1;
    if (g < 0) return w;
    std::vector<double> r;
    double sum = 0.0;
    for (auto a : acts) {
      double v = 0.0;
      for (std::size_t o = 0; o < d.actions()[a].outcomes.size(); ++o)
        v += d.actions()[a].outcomes[o].probability *
             p_goal(static_cast<std::size_t>(g), d.apply(s, a, o), L - 1, L - 1);
      r.push_back(v);
      sum += v;
    }
    if (sum > 0)
      for (std::size_t k = 0; k < r.size(); ++k) w[k] = r[k] / sum;
    return w;
  }
};

/// `Naive` behind the GoalPlanner interface (thesis §5.5: "any planner that can produce the same
/// output would fit into ParleE").
class NaivePlanner final : public GoalPlanner {
 public:
  NaivePlanner(const Domain& d, const PlanOptions& o)
      : naive_{d, o.semantics == GoalSemantics::Within}, options_(o) {}
  const PlanOptions& options() const noexcept override { return options_; }
  double goal_probability(std::size_t goal, const State& s, int horizon) override {
    const int h = horizon < 0 ? options_.horizon : horizon;
    return naive_.p_goal(goal, s, h, depth(h));
  }
  std::vector<double> action_values(std::size_t goal, const State& s, int horizon) override {
    const int h = std::max(1, horizon < 0 ? options_.horizon : horizon);
    std::vector<double> q;
    for (auto a : naive_.d.applicable_actions(s)) {
      double v = 0.0;
      const auto& outs = naive_.d.actions()[a].outcomes;
      for (std::size_t o = 0; o < outs.size(); ++o)
        v += outs[o].probability * naive_.p_goal(goal, naive_.d.apply(s, a, o), h - 1, depth(h));
      q.push_back(v);
    }
    return q;
  }
  std::vector<double> action_distribution(const State& s, int level) override {
    return naive_.choice(s, level);
  }
  int primary_goal(int agent, const State& s) const override { return naive_.primary(agent, s); }
  void clear() override {}

 private:
  int depth(int h) const { return options_.model_depth < 0 ? h : options_.model_depth; }
  Naive naive_;
  PlanOptions options_;
};

}  // namespace emoface::parlee::test
