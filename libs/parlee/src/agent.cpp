#include "emoface/parlee/agent.hpp"

#include <algorithm>
#include <cmath>

namespace emoface::parlee {
namespace {

bool unit(double v) { return v >= 0.0 && v <= 1.0; }

std::string effects_text(const Domain& d, const GroundOutcome& o) {
  std::string s;
  for (auto f : o.add) s += (s.empty() ? "+" : " +") + d.facts()[f];
  for (auto f : o.del) s += (s.empty() ? "-" : " -") + d.facts()[f];
  return s;
}

}  // namespace

std::string_view to_string(DisallowedEvent d) {
  return d == DisallowedEvent::Skip ? "skip" : "stop";
}

DisallowedEvent disallowed_event_from_string(std::string_view s) {
  if (s == "skip") return DisallowedEvent::Skip;
  if (s == "stop") return DisallowedEvent::Stop;
  throw InvalidInput("unknown on_disallowed '" + std::string(s) + "' (skip, stop)");
}

std::string_view to_string(DecayClock c) { return c == DecayClock::Time ? "time" : "step"; }

DecayClock decay_clock_from_string(std::string_view s) {
  if (s == "time") return DecayClock::Time;
  if (s == "step") return DecayClock::Step;
  throw InvalidInput("unknown decay_clock '" + std::string(s) + "' (time, step)");
}

void AgentConfig::validate() const {
  if (!(time_unit_seconds > 0.0 && time_unit_seconds <= 1e9))
    throw InvalidInput("time_unit_seconds must be in (0, 1e9]");
  personality.validate();
  emotions.validate();
  motivation.validate();
  motivation_options.validate();
  appraisal.validate();
  planning.validate();
  if (!(learning_prior >= 0.0 && learning_prior <= 1e9)) throw InvalidInput("learning_prior must be in [0, 1e9]");
  if (!unit(liking_rate)) throw InvalidInput("liking_rate must be in [0,1]");
  for (const auto& [k, v] : liking)
    if (!(v >= -1.0 && v <= 1.0)) throw InvalidInput("liking of '" + k + "' must be in [-1,1]");
  for (const auto& [k, v] : praiseworthiness)
    if (!(v >= -1.0 && v <= 1.0)) throw InvalidInput("praiseworthiness of '" + k + "' must be in [-1,1]");
  for (const auto& r : replenishment)
    if (!(r.threshold > 0.0 && r.threshold <= 1.0))
      throw InvalidInput("replenishment threshold of '" + r.goal + "' must be in (0,1]");
}

Agent::Agent(const Domain& domain, AgentConfig config, const PlannerFactory& make_planner)
    : domain_(std::make_unique<Domain>(domain)), config_(std::move(config)), rng_(config_.seed, 0) {
  config_.validate();
  if (make_planner) {
    planner_ = make_planner(*domain_, config_.planning);
    if (!planner_) throw InvalidInput("Agent: the planner factory returned no planner");
  } else {
    planner_ = std::make_unique<Planner>(*domain_, config_.planning);
  }
  if (!config_.self.empty()) {
    self_ = domain_->agent_index(config_.self);
    if (self_ < 0) throw InvalidInput("agent '" + config_.self + "' is not an agent of the domain");
  }
  for (std::size_t g = 0; g < domain_->goals().size(); ++g)
    if (domain_->goals()[g].agent == self_) own_goals_.push_back(g);
  for (const auto& name : domain_->spec().agents) {
    if (name == domain_->spec().agents[static_cast<std::size_t>(self_)]) continue;
    auto it = config_.liking.find(name);
    liking_[name] = it == config_.liking.end() ? 0.0 : it->second;
  }
  for (const auto& [op, v] : config_.praiseworthiness) {
    RunningMean m;
    m.add(v);
    feedback_[op] = m;
  }
  for (const auto& r : config_.replenishment) {
    std::size_t k = 0;
    while (k < own_goals_.size() && domain_->goals()[own_goals_[k]].name != r.goal) ++k;
    if (k == own_goals_.size())
      throw InvalidInput("replenishment goal '" + r.goal + "' is not a goal of agent '" +
                         domain_->spec().agents[static_cast<std::size_t>(self_)] + "'");
    replenish_.emplace_back(k, r);
  }
  state_ = domain_->initial_state();
  p_goal_ = own_goal_probabilities(state_);
  status_.assign(own_goals_.size(), GoalStatus::Unconfirmed);
  active_.assign(own_goals_.size(), true);
  for (const auto& [k, r] : replenish_)
    active_[k] = level(config_.motivation, r.need) >= r.threshold;
  prev_hope_.assign(own_goals_.size(), 0.0);
  prev_fear_.assign(own_goals_.size(), 0.0);
}

// A goal is confirmed once: success as soon as it holds (no deadline) or at its deadline; failure
// when the deadline passes without it.
GoalStatus Agent::confirm(std::size_t k, const State& s) const {
  if (status_[k] != GoalStatus::Unconfirmed) return status_[k];
  const auto& g = domain_->goals()[own_goals_[k]];
  const bool holds = domain_->goal_holds(own_goals_[k], s);
  if (g.deadline > 0 && time_ >= g.deadline) return holds ? GoalStatus::Success : GoalStatus::Fail;
  if (g.deadline == 0 && holds) return GoalStatus::Success;
  return GoalStatus::Unconfirmed;
}

std::vector<double> Agent::own_goal_probabilities(const State& s) {
  std::vector<double> p;
  for (auto g : own_goals_) p.push_back(planner_->goal_probability(g, s, -1));
  return p;
}

std::vector<std::string> Agent::applicable() const {
  std::vector<std::string> out;
  for (auto a : domain_->applicable_actions(state_)) out.push_back(domain_->action_text(a));
  return out;
}

// thesis §5.6.1: P(event) = P(other's action at s) · P(outcome); outcomes of different actions that
// lead to the same observed state are indistinguishable and add up.
double Agent::event_probability(const State& s, std::size_t action, const State& after) {
  const int who = domain_->turn(s);
  auto outcome_mass = [&](std::size_t a) {
    double m = 0.0;
    const auto& outs = domain_->actions()[a].outcomes;
    for (std::size_t o = 0; o < outs.size(); ++o)
      if (domain_->apply(s, a, o) == after) m += outs[o].probability;
    return m;
  };
  if (who == self_) return outcome_mass(action);
  const int h = config_.planning.horizon;
  const int d = config_.planning.model_depth < 0 ? h - 1 : config_.planning.model_depth;
  const int level = std::max(0, std::min(d, h - 1));
  const auto acts = domain_->applicable_actions(s);
  const auto w = planner_->action_distribution(s, level);
  double p = 0.0;
  for (std::size_t k = 0; k < acts.size(); ++k) p += w[k] * outcome_mass(acts[k]);
  return std::clamp(p, 0.0, 1.0);
}

void Agent::act(const std::optional<std::size_t>& forced, const std::string& outcome_spec, StepRecord& rec,
                EmotionVector& impulse) {
  const State s = state_;
  const int who = domain_->turn(s);
  const std::string& who_name = domain_->spec().agents[static_cast<std::size_t>(who)];
  const auto acts = domain_->applicable_actions(s);
  if (acts.empty() && !forced) {
    state_ = domain_->pass_turn(s);
    rec.actions.push_back({who_name, "pass", "", 1.0, ""});
    return;
  }
  std::size_t a = 0;
  if (forced) {
    a = *forced;
  } else {
    // thesis §5.7.4: action i chosen with probability P_goal(a|s,i)/Σ_j P_goal(a|s,j), 1/n if Σ = 0
    std::vector<double> w(acts.size(), 1.0);
    const int g = who == self_ ? own_primary_goal(s) : planner_->primary_goal(who, s);
    if (g >= 0) {
      auto q = planner_->action_values(static_cast<std::size_t>(g), s, -1);
      double sum = 0.0;
      for (double v : q) sum += v;
      if (sum > 0.0) w = q;
    }
    double total = 0.0;
    for (double v : w) total += v;
    double x = rng_.uniform() * total;
    a = acts.back();
    for (std::size_t k = 0; k < acts.size(); ++k) {
      if (x < w[k]) { a = acts[k]; break; }
      x -= w[k];
    }
  }
  const GroundAction& ga = domain_->actions()[a];
  std::size_t o = 0;
  if (outcome_spec.empty()) {
    double x = rng_.uniform();
    o = ga.outcomes.size() - 1;
    for (std::size_t k = 0; k < ga.outcomes.size(); ++k) {
      if (x < ga.outcomes[k].probability) { o = k; break; }
      x -= ga.outcomes[k].probability;
    }
  } else {
    if (auto bad = outcome_problem(a, outcome_spec); !bad.empty()) throw InvalidInput(bad);
    for (std::size_t k = 0; k < ga.outcomes.size(); ++k) {
      if (ga.outcomes[k].label == outcome_spec || std::to_string(k + 1) == outcome_spec) {
        o = k;
        break;
      }
    }
  }
  const State after = domain_->apply(s, a, o);
  const double p_event = event_probability(s, a, after);
  const auto p_after = own_goal_probabilities(after);

  AppraisalInput in;
  in.p_event = p_event;
  in.actor = who == self_ ? Actor::Self : Actor::Other;
  std::vector<double> importance, impact;
  for (std::size_t k = 0; k < own_goals_.size(); ++k) {
    if (!active_[k]) continue;  // a dormant replenishment goal (§5.5.4)
    const auto& g = domain_->goals()[own_goals_[k]];
    GoalAppraisal ga_k;
    ga_k.importance = g.importance;
    ga_k.p_before = p_goal_[k];
    ga_k.p_after = p_after[k];
    const GoalStatus st = confirm(k, after);
    ga_k.status = st;
    ga_k.status_changed = st != status_[k];
    ga_k.previous_hope = prev_hope_[k];
    ga_k.previous_fear = prev_fear_[k];
    status_[k] = st;
    in.goals.push_back(ga_k);
    importance.push_back(g.importance);
    impact.push_back(p_after[k] - p_goal_[k]);
  }
  const std::string& op_name = domain_->spec().operators[ga.op].name;
  if (who == self_) {
    if (auto it = feedback_.find(op_name); it != feedback_.end()) {
      in.has_praiseworthiness = true;
      in.praiseworthiness = it->second.mean;
    }
  } else if (auto it = config_.praiseworthiness.find(op_name); it != config_.praiseworthiness.end()) {
    in.has_praiseworthiness = true;
    in.praiseworthiness = it->second;
  }
  for (std::size_t b = 0; b < domain_->agent_count(); ++b) {
    if (static_cast<int>(b) == self_) continue;
    OtherAppraisal other;
    other.liking = liking_[domain_->spec().agents[b]];
    for (std::size_t g = 0; g < domain_->goals().size(); ++g) {
      if (domain_->goals()[g].agent != static_cast<int>(b)) continue;
      other.importance.push_back(domain_->goals()[g].importance);
      other.impact.push_back(planner_->goal_probability(g, after, -1) -
                             planner_->goal_probability(g, s, -1));
    }
    if (!other.impact.empty()) in.others.push_back(std::move(other));
  }
  AppraisalResult res = appraise(in, config_.personality, config_.appraisal);
  // Prospect emotions are appraised once per step on the resulting state (Agent::step).
  res.impulse[index(Emotion::Hope)] = 0.0;
  res.impulse[index(Emotion::Fear)] = 0.0;
  for (std::size_t i = 0; i < kEmotionCount; ++i) impulse[i] += res.impulse[i];
  if (who != self_) {  // thesis §5.6.1 liking update for events caused by another agent
    double& ll = liking_[who_name];
    ll = update_liking(ll, desirability(importance, impact), config_.liking_rate);
  } else {
    update_motivation(config_.motivation, BodyEvent::Action, config_.motivation_options);
    last_own_op_ = ga.op;
  }
  if (auto it = config_.body_events.find(op_name); it != config_.body_events.end()) {  // §5.5.4
    const bool own = who == self_;
    if ((own && it->second != BodyEvent::Hit && it->second != BodyEvent::Action) || it->second == BodyEvent::Hit)
      update_motivation(config_.motivation, it->second, config_.motivation_options);
  }
  if (config_.learn_outcomes) {  // thesis §5.8
    auto it = learners_.find(ga.op);
    if (it == learners_.end()) {
      OutcomeLearner l;
      for (const auto& oc : ga.outcomes) l.p.push_back(oc.probability);
      l.n = config_.learning_prior * (config_.personality[Trait::LearningFocus] + 0.5);
      it = learners_.emplace(ga.op, std::move(l)).first;
    }
    it->second.observe(o);
    domain_->set_outcome_probabilities(ga.op, it->second.p);
    planner_->clear();
  }
  rec.actions.push_back({who_name, domain_->action_text(a), ga.outcomes[o].label, p_event,
                         effects_text(*domain_, ga.outcomes[o])});
  state_ = after;
  p_goal_ = config_.learn_outcomes ? own_goal_probabilities(after) : p_after;
}

std::string Agent::outcome_problem(std::size_t a, const std::string& spec) const {
  if (spec.empty()) return {};
  const GroundAction& ga = domain_->actions()[a];
  for (std::size_t k = 0; k < ga.outcomes.size(); ++k)
    if (ga.outcomes[k].label == spec || std::to_string(k + 1) == spec) return {};
  std::string labels;
  for (const auto& oc : ga.outcomes) labels += " " + oc.label;
  return "action " + domain_->action_text(a) + " has no outcome '" + spec +
         "' (outcomes:" + labels + ")";
}

// The script reports only what matters: other agents on turn that the event does not name (a
// second supporter, whose watching changes nothing) pass unobserved, and so does the agent itself
// if it has nothing to do, provided the event then fits. Otherwise nothing changes (the event is
// then skipped or rejected by the caller).
void Agent::pass_unreported(const Event& event, StepRecord& rec) {
  State s = state_;
  std::vector<int> passed;
  auto fits = [&](const State& at) {
    return domain_->find_action(event.action, domain_->applicable_actions(at)) >= 0;
  };
  while (passed.size() < domain_->agent_count() && !fits(s)) {
    const int who = domain_->turn(s);
    if (who == self_ && !domain_->applicable_actions(s).empty()) return;  // the agent acts itself
    passed.push_back(who);
    s = domain_->pass_turn(s);
  }
  if (!fits(s)) return;
  state_ = s;
  for (int who : passed)
    rec.actions.push_back(
        {domain_->spec().agents[static_cast<std::size_t>(who)], "pass", "", 1.0, ""});
}

void Agent::self_act(StepRecord& rec, EmotionVector& impulse) { act(std::nullopt, "", rec, impulse); }

StepRecord Agent::step(const Event& event) {
  if (!std::isfinite(event.time) || event.time < time_)
    throw InvalidInput("event time " + std::to_string(event.time) + " is before the current time");
  if (event.feedback) {
    if (!(*event.feedback >= -1.0 && *event.feedback <= 1.0)) throw InvalidInput("feedback must be in [-1,1]");
    if (last_own_op_) feedback_[domain_->spec().operators[*last_own_op_].name].add(*event.feedback);
  }
  // §5.6.3 per second: the time this event's decay covers (issue 17 item 3)
  const double dt_seconds = config_.decay_clock == DecayClock::Time
                                ? (event.time - time_) * config_.time_unit_seconds
                                : config_.emotions.step_seconds;
  if (!std::isfinite(dt_seconds))
    throw InvalidInput("event time " + std::to_string(event.time) + " is too far ahead");
  time_ = event.time;
  StepRecord rec;
  rec.step = ++steps_;
  rec.time = time_;
  rec.note = event.note;
  EmotionVector impulse{};
  const bool is_pass = event.action.empty() || event.action == "pass";
  auto find = [&]() -> long {
    return is_pass ? -1 : domain_->find_action(event.action, domain_->applicable_actions(state_));
  };
  if (domain_->turn(state_) == self_ && domain_->agent_count() > 1 && find() < 0) self_act(rec, impulse);
  if (!is_pass && find() < 0) pass_unreported(event, rec);
  const int actor = domain_->turn(state_);
  if (is_pass) {
    state_ = domain_->pass_turn(state_);
    rec.actions.push_back({domain_->spec().agents[static_cast<std::size_t>(actor)], "pass", "", 1.0, ""});
  } else {
    const long a = find();
    std::string why;
    if (a < 0) {
      std::string list;
      for (const auto& t : applicable()) list += " " + t;
      why = "event at time " + std::to_string(event.time) + ": '" + event.action + "' is " +
            (a == -2 ? "ambiguous" : "not applicable") +
            "; applicable:" + (list.empty() ? " none" : list);
    } else if (auto bad = outcome_problem(static_cast<std::size_t>(a), event.outcome);
               !bad.empty()) {
      why = "event at time " + std::to_string(event.time) + ": " + bad;
    }
    if (!why.empty() && config_.on_disallowed == DisallowedEvent::Stop) throw InvalidInput(why);
    if (why.empty()) act(static_cast<std::size_t>(a), event.outcome, rec, impulse);
    rec.skipped = why;
  }
  if (actor != self_ && domain_->turn(state_) == self_ && domain_->agent_count() > 1) self_act(rec, impulse);

  update_replenishment();  // §5.5.4: motivational states changed by the actions of this step
  // Prospect emotions (§5.6.2 Hope/Fear) and deadline-driven goal confirmation on the final state.
  AppraisalInput in;
  std::vector<std::size_t> appraised;
  for (std::size_t k = 0; k < own_goals_.size(); ++k) {
    if (!active_[k]) continue;
    appraised.push_back(k);
    const auto& g = domain_->goals()[own_goals_[k]];
    GoalAppraisal ga;
    ga.importance = g.importance;
    ga.p_before = ga.p_after = p_goal_[k];
    const GoalStatus st = confirm(k, state_);
    ga.status = st;
    ga.status_changed = st != status_[k];
    ga.previous_hope = prev_hope_[k];
    ga.previous_fear = prev_fear_[k];
    status_[k] = st;
    in.goals.push_back(ga);
  }
  const AppraisalResult pr = appraise(in, config_.personality, config_.appraisal);
  for (std::size_t i = 0; i < kEmotionCount; ++i) impulse[i] += pr.impulse[i];
  prev_hope_.assign(own_goals_.size(), 0.0);
  prev_fear_.assign(own_goals_.size(), 0.0);
  for (std::size_t j = 0; j < appraised.size(); ++j) {
    prev_hope_[appraised[j]] = pr.hope[j];
    prev_fear_[appraised[j]] = pr.fear[j];
  }

  const EmotionVector alpha = motivated_alpha(config_.emotions, config_.motivation, config_.motivation_options);
  const EmotionVector psi =
      decayed(emotions_, config_.emotions, decay_multipliers(config_.emotions, config_.personality),
              dt_seconds);
  update_decayed_emotions(emotions_, psi, impulse, config_.emotions, alpha);
  rec.impulse = impulse;
  fill(rec);
  return rec;
}

void Agent::update_replenishment() {
  for (const auto& [k, r] : replenish_) {
    const bool now = level(config_.motivation, r.need) >= r.threshold;
    if (now && !active_[k]) {  // the goal appears: unconfirmed, judged afresh from here
      status_[k] = GoalStatus::Unconfirmed;
      p_goal_[k] = planner_->goal_probability(own_goals_[k], state_, -1);
      prev_hope_[k] = prev_fear_[k] = 0.0;
    }
    active_[k] = now;
  }
}

// The agent's own choices follow its highest-priority active goal that does not hold yet (Within).
int Agent::own_primary_goal(const State& s) const {
  int best = -1;
  const bool within = config_.planning.semantics == GoalSemantics::Within;
  for (std::size_t k = 0; k < own_goals_.size(); ++k) {
    if (!active_[k] || (within && domain_->goal_holds(own_goals_[k], s))) continue;
    const auto& g = domain_->goals()[own_goals_[k]];
    if (best < 0 || g.priority > domain_->goals()[static_cast<std::size_t>(best)].priority)
      best = static_cast<int>(own_goals_[k]);
  }
  return best;
}

StepRecord Agent::initial_record() {
  StepRecord rec;
  rec.time = time_;
  fill(rec);
  return rec;
}

void Agent::fill(StepRecord& rec) {
  for (std::size_t k = 0; k < own_goals_.size(); ++k) rec.goal_names.push_back(domain_->goals()[own_goals_[k]].name);
  rec.goal_probability = p_goal_;
  rec.goal_status = status_;
  rec.goal_active = active_;
  rec.emotions = emotions_;
  rec.basic = basic_emotions(emotions_, config_.emotions);
  rec.shown = revealed_emotions(rec.basic, config_.personality);
  rec.liking = liking_;
  rec.state = domain_->state_text(state_);
}

}  // namespace emoface::parlee
