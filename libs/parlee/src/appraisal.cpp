#include "emoface/parlee/appraisal.hpp"

#include <algorithm>
#include <cmath>

#include "emoface/core/errors.hpp"

namespace emoface::parlee {
namespace {

void check(bool ok, const char* what) {
  if (!ok) throw InvalidInput(what);
}
bool unit(double v) { return v >= 0.0 && v <= 1.0; }

}  // namespace

std::string_view to_string(GoalStatus s) {
  switch (s) {
    case GoalStatus::Unconfirmed: return "unconfirmed";
    case GoalStatus::Success: return "success";
    case GoalStatus::Fail: return "fail";
  }
  return "unconfirmed";
}

GoalStatus goal_status_from_string(std::string_view s) {
  if (s == "unconfirmed") return GoalStatus::Unconfirmed;
  if (s == "success") return GoalStatus::Success;
  if (s == "fail") return GoalStatus::Fail;
  throw InvalidInput("unknown goal status '" + std::string(s) + "'");
}

std::string_view to_string(Actor a) {
  switch (a) {
    case Actor::Self: return "self";
    case Actor::Other: return "other";
    case Actor::Nobody: return "nobody";
  }
  return "nobody";
}

Actor actor_from_string(std::string_view s) {
  if (s == "self") return Actor::Self;
  if (s == "other") return Actor::Other;
  if (s == "nobody") return Actor::Nobody;
  throw InvalidInput("unknown actor '" + std::string(s) + "'");
}

std::string_view to_string(CompoundRule r) {
  return r == CompoundRule::Impact ? "impact" : "standards";
}

CompoundRule compound_rule_from_string(std::string_view s) {
  if (s == "impact") return CompoundRule::Impact;
  if (s == "standards") return CompoundRule::Standards;
  throw InvalidInput("unknown compound rule '" + std::string(s) + "' (impact, standards)");
}

std::string_view to_string(ProspectMode m) {
  return m == ProspectMode::SignedSum ? "signed_sum" : "per_goal";
}

ProspectMode prospect_mode_from_string(std::string_view s) {
  if (s == "signed_sum") return ProspectMode::SignedSum;
  if (s == "per_goal") return ProspectMode::PerGoal;
  throw InvalidInput("unknown prospect mode '" + std::string(s) + "' (signed_sum, per_goal)");
}

void AppraisalOptions::validate() const {
  check(prospect_pivot > 0.0 && prospect_pivot < 1.0, "AppraisalOptions::prospect_pivot must be in (0,1)");
  check(surprise_threshold > 0.0 && surprise_threshold <= 1.0, "AppraisalOptions::surprise_threshold must be in (0,1]");
  check(joy_exponent > 0.0 && joy_exponent < 100.0, "AppraisalOptions::joy_exponent must be in (0,100)");
  check(distress_exponent > 0.0 && distress_exponent < 100.0, "AppraisalOptions::distress_exponent must be in (0,100)");
}

AppraisalResult appraise(const AppraisalInput& in, const Personality& pers, const AppraisalOptions& opt) {
  opt.validate();
  pers.validate();
  check(unit(in.p_event), "appraise: p_event must be in [0,1]");
  check(!in.has_praiseworthiness || (in.praiseworthiness >= -1.0 && in.praiseworthiness <= 1.0),
        "appraise: praiseworthiness must be in [-1,1]");
  AppraisalResult r;
  auto& I = r.impulse;
  auto add = [&](Emotion e, double v) { I[index(e)] += v; };
  // §5.6.5: perceived probability of the event; unexpectedness 1 − P(event) (§5.6.2)
  const double p_event = perceive_probability(pers, in.p_event);
  const double unexpected = 1.0 - p_event;
  const double u_joy = std::pow(unexpected, opt.joy_exponent);
  const double u_sad = std::pow(unexpected, opt.distress_exponent);
  std::vector<double> terms;
  terms.reserve(in.goals.size());
  // Table 5.2 (CompoundRule::Standards): Gratitude/Gratification need a praiseworthy action,
  // Anger/Remorse a blameworthy one; §5.6.2 (Impact): any desirable/undesirable action.
  const bool by_impact = opt.compound == CompoundRule::Impact;
  const bool praised = by_impact || (in.has_praiseworthiness && in.praiseworthiness > 0.0);
  const bool blamed = by_impact || (in.has_praiseworthiness && in.praiseworthiness < 0.0);
  for (const auto& g : in.goals) {
    check(unit(g.p_before) && unit(g.p_after), "appraise: goal probabilities must be in [0,1]");
    check(g.importance >= 0.0 && std::isfinite(g.importance), "appraise: importance must be ≥ 0");
    check(g.previous_hope >= 0.0 && g.previous_fear >= 0.0, "appraise: previous hope/fear must be ≥ 0");
    const double before = perceive_probability(pers, g.p_before);
    const double after = perceive_probability(pers, g.p_after);
    const double impact = reason_impact(pers, after - before);  // §5.6.1 Impact = Pafter − Pbefore
    const double w = g.importance;
    if (impact > 0.0) {
      add(Emotion::Joy, impact * w * u_joy);  // §5.6.2 Happiness
      if (in.actor == Actor::Other && praised) add(Emotion::Gratitude, impact * w * u_joy);
      if (in.actor == Actor::Self && praised) add(Emotion::Gratification, impact * w * u_joy);
    } else if (impact < 0.0) {
      add(Emotion::Distress, -impact * w * u_sad);  // §5.6.2 Sadness
      if (in.actor == Actor::Other && blamed)
        add(Emotion::Anger, -impact * w * u_joy);  // §5.6.2 Anger
      if (in.actor == Actor::Self && blamed) add(Emotion::Remorse, -impact * w * u_joy);
    }
    // §5.6.2 prospect term of this goal, Import·(P(goal) − 0.5), for unconfirmed goals only
    terms.push_back(g.status == GoalStatus::Unconfirmed ? w * (after - opt.prospect_pivot) : 0.0);
    if (g.status_changed && g.status == GoalStatus::Success) {  // §5.6.2 Relief = previous Fear
      add(Emotion::Satisfaction, g.previous_hope);
      add(Emotion::Relief, g.previous_fear);
    } else if (g.status_changed && g.status == GoalStatus::Fail) {
      add(Emotion::Disappointment, g.previous_hope);
      add(Emotion::FearsConfirmed, g.previous_fear);
    }
  }
  // §5.6.2 Hope = Σ Import·(P(goal) − 0.5), Fear = Σ Import·(0.5 − P(goal)) (as printed: one
  // signed sum over the goals, its positive part Hope and its negative part Fear) or per goal.
  r.hope.assign(in.goals.size(), 0.0);
  r.fear.assign(in.goals.size(), 0.0);
  double pos = 0.0, neg = 0.0;
  for (double t : terms) (t > 0.0 ? pos : neg) += std::fabs(t);
  if (opt.prospect == ProspectMode::PerGoal) {
    for (std::size_t k = 0; k < terms.size(); ++k) {
      r.hope[k] = std::max(0.0, terms[k]);
      r.fear[k] = std::max(0.0, -terms[k]);
    }
  } else {
    const double net = pos - neg;
    for (std::size_t k = 0; k < terms.size(); ++k) {  // shares of the net, summing to it
      if (net > 0.0 && terms[k] > 0.0) r.hope[k] = net * terms[k] / pos;
      if (net < 0.0 && terms[k] < 0.0) r.fear[k] = -net * -terms[k] / neg;
    }
  }
  for (std::size_t k = 0; k < terms.size(); ++k) {
    add(Emotion::Hope, r.hope[k]);
    add(Emotion::Fear, r.fear[k]);
  }
  if (in.has_praiseworthiness) {  // §5.6.2 Pride = Praiseworthiness, Shame = −Praiseworthiness
    const double pw = in.praiseworthiness;
    if (in.actor == Actor::Self) add(pw >= 0.0 ? Emotion::Pride : Emotion::Shame, std::fabs(pw));
    if (in.actor == Actor::Other) add(pw >= 0.0 ? Emotion::Appreciation : Emotion::Reproach, std::fabs(pw));
  }
  for (const auto& o : in.others) {
    check(o.liking >= -1.0 && o.liking <= 1.0, "appraise: liking must be in [-1,1]");
    check(o.importance.size() == o.impact.size(), "appraise: other agent importance/impact sizes differ");
    double joy = 0.0, distress = 0.0;  // the other's Happiness/Sadness from our model of it
    for (std::size_t k = 0; k < o.impact.size(); ++k) {
      check(o.impact[k] >= -1.0 && o.impact[k] <= 1.0, "appraise: other impact must be in [-1,1]");
      if (o.impact[k] > 0.0) joy += o.impact[k] * o.importance[k] * u_joy;
      if (o.impact[k] < 0.0) distress += -o.impact[k] * o.importance[k] * u_sad;
    }
    const double f = std::fabs(o.liking) * desire_other_factor(pers);  // §5.6.2 Happy for = LL·Happiness
    if (o.liking > 0.0) {
      add(Emotion::HappyFor, f * joy);
      add(Emotion::SorryFor, f * distress);
    } else if (o.liking < 0.0) {
      add(Emotion::Resentment, f * joy);
      add(Emotion::Gloating, f * distress);
    }
  }
  if (p_event < opt.surprise_threshold) add(Emotion::Surprise, opt.surprise_threshold - p_event);  // §5.5.1
  for (double& v : I) v = feel_impulse(pers, v);  // §5.6.5 newImpulse = impulse^(1.5−feelingLevel)
  return r;
}

double desirability(const std::vector<double>& importance, const std::vector<double>& impact) {
  if (importance.size() != impact.size()) throw InvalidInput("desirability: sizes differ");
  double d = 0.0;
  for (std::size_t k = 0; k < impact.size(); ++k) d += importance[k] * impact[k];
  return d;
}

// thesis §5.6.1
double update_liking(double liking, double d, double rate) {
  if (!std::isfinite(liking) || !std::isfinite(d) || !std::isfinite(rate))
    throw InvalidInput("update_liking: non-finite input");
  return std::max(-1.0, std::min(1.0, liking + rate * d));
}

// thesis §5.8
void OutcomeLearner::observe(std::size_t outcome) {
  if (outcome >= p.size()) throw InvalidInput("OutcomeLearner::observe: outcome out of range");
  if (!(n >= 0.0) || !std::isfinite(n)) throw InvalidInput("OutcomeLearner: n must be ≥ 0");
  for (std::size_t j = 0; j < p.size(); ++j) p[j] = (p[j] * n + (j == outcome ? 1.0 : 0.0)) / (n + 1.0);
  n += 1.0;
}

void RunningMean::add(double feedback) {
  if (!(feedback >= -1.0 && feedback <= 1.0)) throw InvalidInput("feedback must be in [-1,1]");
  ++count;
  mean += (feedback - mean) / static_cast<double>(count);
}

}  // namespace emoface::parlee
