// The Obie scenario (thesis §7.4) and the bread illustration (§5.9) end to end.
#include "emoface/parlee/agent.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "emoface/core/errors.hpp"
#include "emoface/parlee/io.hpp"
#include "naive_planner.hpp"

using namespace emoface::parlee;

namespace {

const std::string kData = std::string(EMOFACE_SOURCE_DIR) + "/data/parlee/";

std::vector<StepRecord> run(const std::string& domain, const std::string& agent, const std::string& events) {
  const Domain d(read_domain_files({kData + domain}));
  Agent a(d, read_agent_file(kData + "agents/" + agent + ".json"));
  std::vector<StepRecord> out{a.initial_record()};
  for (const auto& e : read_events_file(kData + events)) out.push_back(a.step(e));
  return out;
}

// ESV channel at the last record with time ≤ t.
double at(const std::vector<StepRecord>& run, double t, std::size_t basic) {
  double v = 0.0;
  for (const auto& r : run)
    if (r.time <= t) v = r.basic[basic];
  return v;
}
constexpr std::size_t kSad = 0, kHappy = 1, kAnger = 2, kFear = 3, kSurprise = 5;

class Obie : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    for (const char* p : {"neutral", "pessimistic", "realistic", "sensitive"})
      runs_[p] = run("football.domain", p, "match.ndjson");
  }
  static std::map<std::string, std::vector<StepRecord>> runs_;
};
std::map<std::string, std::vector<StepRecord>> Obie::runs_;

}  // namespace

TEST_F(Obie, NeutralFollowsTheStory) {
  const auto& r = runs_["neutral"];
  ASSERT_EQ(r.size(), 92u);
  // fear until 40' and again after 80'
  for (double t : {10.0, 20.0, 35.0, 39.0}) EXPECT_GT(at(r, t, kFear), 0.5) << t;
  EXPECT_LT(at(r, 60, kFear), 0.05);
  EXPECT_GT(at(r, 85, kFear), 0.5);
  // happiness after the goals, decaying afterwards
  EXPECT_LT(at(r, 29, kHappy), 0.05);
  EXPECT_GT(at(r, 30, kHappy), 0.2);
  EXPECT_GT(at(r, 40.5, kHappy), 0.5);
  EXPECT_LT(at(r, 60, kHappy), 0.5 * at(r, 40.5, kHappy));
  // the biggest surprise is the long free-kick and the goal at 40'
  double best_t = 0, best = -1;
  for (const auto& s : r)
    if (s.basic[kSurprise] > best) best = s.basic[kSurprise], best_t = s.time;
  EXPECT_GE(best_t, 40.0);
  EXPECT_LE(best_t, 41.0);
  EXPECT_LT(at(r, 43, kSurprise), 0.05);  // and it decays very fast
  // sadness after 80' decaying slowly
  EXPECT_GT(at(r, 80, kSad), 0.8);
  EXPECT_GT(at(r, 89, kSad), 0.6 * at(r, 80, kSad));
  EXPECT_LT(at(r, 89, kSad), at(r, 81, kSad));
  // the final whistle confirms both goals: a draw
  EXPECT_EQ(r.back().goal_status[0], GoalStatus::Fail);
  EXPECT_EQ(r.back().goal_status[1], GoalStatus::Success);
}

TEST_F(Obie, PersonalitiesDiffer) {
  const auto& n = runs_["neutral"];
  const auto& p = runs_["pessimistic"];
  const auto& s = runs_["sensitive"];
  const auto& re = runs_["realistic"];
  for (double t : {12.0, 20.0, 80.0, 85.0}) EXPECT_GE(at(p, t, kSad), at(n, t, kSad)) << t;
  for (double t : {30.0, 40.5, 50.0}) EXPECT_LE(at(p, t, kHappy), at(n, t, kHappy)) << t;
  for (double t : {12.0, 30.0, 40.5, 60.0, 85.0}) {
    EXPECT_GE(at(s, t, kSad), at(n, t, kSad)) << t;
    EXPECT_GE(at(s, t, kHappy), at(n, t, kHappy)) << t;
  }
  bool differs = false;
  for (std::size_t k = 0; k < n.size(); ++k) differs |= n[k].basic != re[k].basic;
  EXPECT_TRUE(differs);
}

TEST_F(Obie, IntensitiesStayWithinThresholds) {
  const EmotionParams p = EmotionParams::defaults();
  for (const auto& [name, r] : runs_)
    for (const auto& s : r)
      for (std::size_t i = 0; i < kEmotionCount; ++i) {
        ASSERT_GE(s.emotions[i], 0.0);
        ASSERT_LE(s.emotions[i], p.omega[i]);
      }
}

TEST(Agent, DeterministicForASeed) {
  const auto a = run("football.domain", "neutral", "match.ndjson");
  const auto b = run("football.domain", "neutral", "match.ndjson");
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(timeline_line(a[k]), timeline_line(b[k]));
}

TEST(Agent, BreadUserEatsTheBread) {
  const auto n = run("bread.domain", "bread_neutral", "bread_events.ndjson");
  const auto o = run("bread.domain", "bread_optimistic", "bread_events.ndjson");
  const auto s = run("bread.domain", "bread_sensitive", "bread_events.ndjson");
  // §5.9: the neutral agent gets angry after the user eats his bread, the optimistic one less
  // (and stays a bit happy), the sensitive one very angry.
  EXPECT_LT(at(n, 4, kAnger), 0.01);
  EXPECT_GT(at(n, 5, kAnger), 0.3);
  EXPECT_LT(at(o, 5, kAnger), at(n, 5, kAnger));
  EXPECT_GT(at(o, 5, kHappy), at(n, 5, kHappy));
  EXPECT_GT(at(s, 5, kAnger), at(n, 5, kAnger));
  EXPECT_EQ(n[5].actions[0].action, "(eat bread user)");
}

TEST(Agent, RejectsInapplicableEventsAndUnknownAgents) {
  const Domain d(read_domain_files({kData + "football.domain"}));
  AgentConfig c;
  c.self = "agent";
  c.on_disallowed = DisallowedEvent::Stop;
  Agent a(d, c);
  Event e;
  e.time = 1;
  e.action = "(shot team)";
  try {
    a.step(e);
    FAIL();
  } catch (const emoface::InvalidInput& err) {
    EXPECT_NE(std::string(err.what()).find("(re-kickoff team)"), std::string::npos);  // lists what is
  }
  e.action = "(re-kickoff team)";
  e.outcome = "exploded";
  EXPECT_THROW(a.step(e), emoface::InvalidInput);
  e.outcome = "";
  e.time = -1;
  EXPECT_THROW(a.step(e), emoface::InvalidInput);
  c.self = "referee";
  EXPECT_THROW(Agent(d, c), emoface::InvalidInput);
  EXPECT_EQ(disallowed_event_from_string(to_string(DisallowedEvent::Skip)), DisallowedEvent::Skip);
  EXPECT_EQ(disallowed_event_from_string(to_string(DisallowedEvent::Stop)), DisallowedEvent::Stop);
  EXPECT_THROW(disallowed_event_from_string("ignore"), emoface::InvalidInput);
}

// §5.5 (the default): an event the agent's model does not allow is reported and skipped; the
// rest of the match goes on exactly as without it.
TEST(Agent, DisallowedEventsAreReportedAndSkipped) {
  const Domain d(read_domain_files({kData + "football.domain"}));
  const AgentConfig c = read_agent_file(kData + "agents/neutral.json");
  ASSERT_EQ(c.on_disallowed, DisallowedEvent::Skip);
  auto events = read_events_file(kData + "match.ndjson");
  Agent clean(d, c), noisy(d, c);
  std::vector<std::string> a, b;
  for (const auto& e : events) a.push_back(timeline_line(clean.step(e)));
  for (std::size_t k = 0; k < events.size(); ++k) {
    if (k == 20) {  // 21': the for team holds the ball in its half; an against shot is impossible
      Event bad = events[k - 1];
      bad.action = "(shot oteam)";
      const StepRecord r = noisy.step(bad);
      EXPECT_NE(r.skipped.find("'(shot oteam)' is not applicable; applicable:"), std::string::npos)
          << r.skipped;
      EXPECT_NE(timeline_line(r).find("\"skipped\""), std::string::npos);
      Event outcome = events[k];  // applicable, but no such outcome
      outcome.time = events[k - 1].time;
      outcome.outcome = "exploded";
      EXPECT_NE(noisy.step(outcome).skipped.find("has no outcome 'exploded'"), std::string::npos);
    }
    b.push_back(timeline_line(noisy.step(events[k])));
  }
  // the skipped steps decay the emotions (time passes) but change no fact: from 21' on the state
  // and the goal probabilities are those of the clean run
  for (std::size_t k = 0; k < events.size(); ++k) {
    const auto ja = nlohmann::json::parse(a[k]), jb = nlohmann::json::parse(b[k]);
    EXPECT_EQ(ja["state"], jb["state"]) << k;
    EXPECT_EQ(ja["goals"], jb["goals"]) << k;
  }
  EXPECT_EQ(a.back().find("skipped"), std::string::npos);
}

TEST(Agent, LearnsOutcomeProbabilities) {
  const Domain d(read_domain_files({kData + "rocket.domain"}));
  AgentConfig c;
  c.learn_outcomes = true;
  c.learning_prior = 9.0;  // × (learningFocus + 0.5) = 9 presumed observations
  Agent a(d, c);
  Event e;
  e.action = "(LOAD c1)";
  e.outcome = "failed";
  a.step(e);
  const auto& outs = a.domain().actions()[static_cast<std::size_t>(
      a.domain().find_action("(LOAD c2)", a.domain().applicable_actions(a.state())))].outcomes;
  EXPECT_NEAR(outs[0].probability, 0.9 * 9 / 10, 1e-12);  // 0.81
  EXPECT_NEAR(outs[1].probability, (0.1 * 9 + 1) / 10, 1e-12);  // 0.19
  // the original domain is untouched
  EXPECT_EQ(d.actions()[0].outcomes[0].probability, 0.9);
}

TEST(Agent, MotivationalStatesFollowActions) {
  const Domain d(read_domain_files({kData + "bread.domain"}));
  AgentConfig c = read_agent_file(kData + "agents/bread_neutral.json");
  c.motivation.hunger = 0.5;
  c.body_events["eat"] = BodyEvent::Eat;
  c.body_events["go-working"] = BodyEvent::Hit;  // pretend the user's leaving hurts
  Agent a(d, c);
  Event e;
  e.time = 1;
  e.action = "(go-working car1)";  // the user drives off (a "hit"), then the agent acts once
  const StepRecord r = a.step(e);
  ASSERT_EQ(r.actions.size(), 2u);
  EXPECT_EQ(r.actions[1].actor, "agent");
  EXPECT_NEAR(a.motivation().pain, 0.2, 1e-12);
  EXPECT_NEAR(a.motivation().hunger, 0.51, 1e-12);  // +0.01 per own action
  EXPECT_NEAR(a.motivation().fatigue, 0.01, 1e-12);
  EXPECT_EQ(to_string(BodyEvent::Rest), "rest");
  EXPECT_EQ(body_event_from_string("hit"), BodyEvent::Hit);
  EXPECT_THROW(body_event_from_string("nap"), emoface::InvalidInput);
}

TEST(Agent, FeedbackBecomesPraiseworthiness) {
  const Domain d(read_domain_files({kData + "rocket.domain"}));
  AgentConfig c;
  Agent a(d, c);
  Event e;
  e.action = "(LOAD c1)";
  e.outcome = "loaded";
  a.step(e);
  e.time = 1;
  e.action = "(LOAD c2)";
  e.feedback = 0.8;  // on the previous LOAD
  const StepRecord r = a.step(e);
  EXPECT_NEAR(r.impulse[index(Emotion::Pride)], 0.8, 1e-12);
}

// Obie's 0-0 state at the kick-off, by hand. With H = 3 the turns are: against team (only the for
// team's kick-off is applicable: every other team action needs (not (kickoff))), Obie, against
// team (the for team holds the ball in its own half: a pass, a tackle or a block, none scores).
// So P(win within 3) = 0 and P(not-lose within 3) = 1 (the 0-0 already holds). §5.6.2:
//   signed sum  S = 1·(0 − 0.5) + 0.5·(1 − 0.5) = −0.25  → Fear 0.25, Hope 0
//   per goal    Fear = 1·0.5 = 0.5, Hope = 0.5·0.5 = 0.25
TEST(Agent, ObieHopeAndFearAtZeroZeroByHand) {
  const Domain d(read_domain_files({kData + "football.domain"}));
  Planner planner(d, PlanOptions{3});
  auto goal_index = [&](const std::string& name) {
    for (std::size_t g = 0; g < d.goals().size(); ++g)
      if (d.goals()[g].name == name) return static_cast<int>(g);
    return -1;
  };
  const int win = goal_index("win"), not_lose = goal_index("not-lose");
  ASSERT_GE(win, 0);
  ASSERT_GE(not_lose, 0);
  const double p_win = planner.goal_probability(static_cast<std::size_t>(win), d.initial_state());
  const double p_nl =
      planner.goal_probability(static_cast<std::size_t>(not_lose), d.initial_state());
  EXPECT_EQ(p_win, 0.0);
  EXPECT_EQ(p_nl, 1.0);
  AppraisalInput in;
  for (auto [p, imp] : {std::pair{p_win, 1.0}, std::pair{p_nl, 0.5}}) {
    GoalAppraisal g;
    g.p_before = g.p_after = p;
    g.importance = imp;
    in.goals.push_back(g);
  }
  auto r = appraise(in, Personality{});
  EXPECT_NEAR(r.impulse[index(Emotion::Fear)], 0.25, 1e-12);
  EXPECT_EQ(r.impulse[index(Emotion::Hope)], 0.0);
  AppraisalOptions per_goal;
  per_goal.prospect = ProspectMode::PerGoal;
  r = appraise(in, Personality{}, per_goal);
  EXPECT_NEAR(r.impulse[index(Emotion::Fear)], 0.5, 1e-12);
  EXPECT_NEAR(r.impulse[index(Emotion::Hope)], 0.25, 1e-12);
}

// §7.3: the against team is an agent with a goal (the against team winning); Obie predicts its
// choices with the d-level model (§5.7.4) instead of uniformly.
TEST(Agent, AgainstTeamIsPredictedByItsGoal) {
  const Domain d(read_domain_files({kData + "football.domain"}));
  Agent obie(d, read_agent_file(kData + "agents/neutral.json"));
  const auto events = read_events_file(kData + "match.ndjson");
  std::size_t k = 0;
  for (; events[k].time < 12.0; ++k) obie.step(events[k]);
  // 11': the against team holds the ball in the for team's penalty area, on turn
  const State s = obie.state();
  ASSERT_EQ(d.spec().agents[static_cast<std::size_t>(d.turn(s))], "oteam");
  const auto acts = d.applicable_actions(s);
  const auto uniform = obie.planner().action_distribution(s, 0);
  const auto model = obie.planner().action_distribution(s, 1);
  std::size_t shot = acts.size();
  for (std::size_t i = 0; i < acts.size(); ++i)
    if (d.action_text(acts[i]).rfind("(shot oteam", 0) == 0) shot = i;
  ASSERT_LT(shot, acts.size());
  EXPECT_NEAR(uniform[shot], 1.0 / static_cast<double>(acts.size()), 1e-12);
  // a 1-level against team looks one action ahead: only the shot can make it lead → P = 1
  EXPECT_NEAR(model[shot], 1.0, 1e-12);
  // Obie's own model is (H − 1 = 6)-level: P(event) of the goal = P(shot)·0.25 (the shot's goal
  // outcome; no other action reaches that state), above the uniform 0.25/n
  const auto deep = obie.planner().action_distribution(s, 6);
  const StepRecord r = obie.step(events[k]);
  EXPECT_NEAR(r.actions.front().p_event, deep[shot] * 0.25, 1e-12);
  EXPECT_GT(r.actions.front().p_event, 0.25 / static_cast<double>(acts.size()));
}

TEST_F(Obie, HappinessRisesWithTheAttackAndNotAtTheDrawWhistle) {
  const auto& r = runs_["neutral"];
  // the long free-kick reaching the penalty area raises P(win) (0.01 → 0.16 at H = 7): joy before
  // the goal (Fig. 7.5)
  EXPECT_GT(at(r, 40, kHappy), at(r, 39, kHappy) + 0.05);
  // the draw at 90': `win` fails (fears confirmed), `not-lose` succeeds but with the signed sum
  // there was no hope to satisfy (Fear = 1·0.5 − 0.5·0.5 > 0): no happiness
  const StepRecord& last = r.back();
  EXPECT_EQ(last.impulse[index(Emotion::Satisfaction)], 0.0);
  EXPECT_EQ(last.impulse[index(Emotion::Relief)], 0.0);
  EXPECT_GT(last.impulse[index(Emotion::FearsConfirmed)], 0.2);
  EXPECT_EQ(last.basic[kHappy], 0.0);
}

TEST_F(Obie, RealisticDiffersFromNeutral) {
  // §5.6.5 P' = P^(perceivingFocus + 0.5) = P^1.4: events look less likely, so more unexpected
  const auto& n = runs_["neutral"];
  const auto& re = runs_["realistic"];
  EXPECT_GT(at(re, 12, kSad), at(n, 12, kSad) + 0.02);
  // at 80' both saturate at ω = 1 (the sadness mood left from 12' persists, §5.6.3): compare
  // what the goal itself brings, the distress impulse (0.96 vs 0.88)
  auto impulse_at = [](const std::vector<StepRecord>& run, double t) {
    for (const auto& r : run)
      if (r.time == t) return r.impulse[index(Emotion::Distress)];
    return -1.0;
  };
  EXPECT_GT(impulse_at(re, 80), impulse_at(n, 80) + 0.02);
  EXPECT_GE(at(re, 80, kSad), at(n, 80, kSad));
  EXPECT_GT(at(re, 12, kSurprise), at(n, 12, kSurprise) + 0.1);
  EXPECT_GT(at(re, 30, kHappy), at(n, 30, kHappy));
}

// §5.5: "any planner that can produce the same output would fit into ParleE". A second planner
// (memo-free transcription of §5.7.4) plugged through the GoalPlanner interface gives the same
// timeline of the §7.4 match as the memoised DP, line for line (H = 5, d = H − 1).
TEST(Agent, PluggedPlannerGivesTheSameTimeline) {
  const Domain d(read_domain_files({kData + "football.domain"}));
  AgentConfig c = read_agent_file(kData + "agents/neutral.json");
  c.planning.horizon = 5;
  const PlannerFactory naive = [](const Domain& dom, const PlanOptions& o) {
    return std::unique_ptr<GoalPlanner>(std::make_unique<test::NaivePlanner>(dom, o));
  };
  Agent dp(d, c), other(d, c, naive);
  EXPECT_NE(dynamic_cast<test::NaivePlanner*>(&other.planner()), nullptr);
  EXPECT_EQ(timeline_line(dp.initial_record()), timeline_line(other.initial_record()));
  std::size_t n = 0;
  for (const auto& e : read_events_file(kData + "match.ndjson")) {
    const std::string a = timeline_line(dp.step(e)), b = timeline_line(other.step(e));
    ASSERT_EQ(a, b) << "event " << n;
    ++n;
  }
  EXPECT_EQ(n, 91u);
  const PlannerFactory none = [](const Domain&, const PlanOptions&) { return nullptr; };
  EXPECT_THROW(Agent(d, c, none), emoface::InvalidInput);
}

// §5.5.4: "high values [of the motivational states] will generate a goal for the agent, viz. the
// agent wants to reduce these values" (replenishment goals). The bread agent's goal feed-self is
// its replenishment goal for hunger: dormant while hunger < 0.495, it appears when one more action
// (+0.01) takes hunger from 0.49 to 0.50, and disappears when the agent has eaten.
TEST(Agent, ReplenishmentGoalAppearsWithHungerAndGoesWhenFed) {
  const Domain d(read_domain_files({kData + "bread.domain"}));
  AgentConfig c = read_agent_file(kData + "agents/bread_neutral.json");
  c.motivation.hunger = 0.49;
  c.replenishment = {{"feed-self", Need::Hunger, 0.495}};
  c.body_events["eat"] = BodyEvent::Eat;
  Agent a(d, c);
  const StepRecord r0 = a.initial_record();
  ASSERT_EQ(r0.goal_active.size(), 1u);
  EXPECT_FALSE(r0.goal_active[0]);
  EXPECT_NE(timeline_line(r0).find(R"("active":false)"), std::string::npos);
  Event pass;  // the user passes; the agent acts
  pass.time = 1;
  const StepRecord r1 = a.step(pass);  // the agent's first action: hunger 0.49 → 0.50
  EXPECT_NEAR(a.motivation().hunger, 0.50, 1e-12);
  EXPECT_TRUE(r1.goal_active[0]);
  EXPECT_GT(r1.impulse[index(Emotion::Hope)] + r1.impulse[index(Emotion::Fear)], 0.0);
  bool fed = false;
  for (int t = 2; t <= 12 && !fed; ++t) {
    pass.time = t;
    const StepRecord r = a.step(pass);
    if (a.motivation().hunger == 0.0) {  // the agent ate (BodyEvent::Eat resets hunger)
      fed = true;
      EXPECT_FALSE(r.goal_active[0]);
      EXPECT_EQ(r.goal_status[0], GoalStatus::Success);
      EXPECT_GT(r.impulse[index(Emotion::Satisfaction)] + r.impulse[index(Emotion::Relief)], 0.0);
    } else {
      EXPECT_TRUE(r.goal_active[0]) << t;
    }
  }
  EXPECT_TRUE(fed);
  // without the rule the same agent would have had the goal (and fear about it) from the start
  AgentConfig plain = c;
  plain.replenishment.clear();
  Agent b(d, plain);
  EXPECT_TRUE(b.initial_record().goal_active[0]);
  c.replenishment = {{"fly", Need::Hunger, 0.5}};
  EXPECT_THROW(Agent(d, c), emoface::InvalidInput);
  c.replenishment = {{"feed-self", Need::Hunger, 0.0}};
  EXPECT_THROW(Agent(d, c), emoface::InvalidInput);
  EXPECT_EQ(need_from_string(to_string(Need::Pain)), Need::Pain);
  EXPECT_THROW(need_from_string("boredom"), emoface::InvalidInput);
}

// §5.6.2 Desire-other emotions in a shipped scenario: two supporters of opposite teams watch the
// §7.4 match (data/parlee/rivals.problem). The for-team supporter dislikes the other (liking −0.8):
// resentment when the against team scores (12'), gloating when it concedes (30'); the against-team
// supporter likes the first (+0.8): sorry-for at 12' and 80', happy-for at the lead (40.5').
TEST(Agent, TwoSupportersFeelForEachOther) {
  const Domain d(read_domain_files({kData + "football.domain", kData + "rivals.problem"}));
  auto run_fan = [&](const std::string& name) {
    Agent a(d, read_agent_file(kData + "agents/" + name + ".json"));
    std::map<double, StepRecord> at;
    for (const auto& e : read_events_file(kData + "match.ndjson")) {
      StepRecord r = a.step(e);
      EXPECT_TRUE(r.skipped.empty()) << name << " " << e.time << ": " << r.skipped;
      at[e.time] = std::move(r);
    }
    return at;
  };
  const auto fan_for = run_fan("fan_for"), fan_against = run_fan("fan_against");
  auto E = [](const StepRecord& r, Emotion e) { return r.emotions[index(e)]; };
  auto I = [](const StepRecord& r, Emotion e) { return r.impulse[index(e)]; };
  // the for-team supporter
  EXPECT_GT(I(fan_for.at(12), Emotion::Resentment), 0.2);  // the rival's joy at the against goal
  EXPECT_LT(I(fan_for.at(12), Emotion::Gloating), 1e-3);
  EXPECT_GT(I(fan_for.at(30), Emotion::Gloating), 0.2);  // the rival's distress at the equaliser
  // (tiny amounts come from the liking toward the against team itself, which §5.6.1 updates)
  EXPECT_LT(E(fan_for.at(30), Emotion::HappyFor) + E(fan_for.at(30), Emotion::SorryFor), 1e-3);
  // the against-team supporter
  EXPECT_GT(I(fan_against.at(12), Emotion::SorryFor), 0.1);
  EXPECT_GT(I(fan_against.at(40.5), Emotion::HappyFor), 0.2);
  EXPECT_GT(I(fan_against.at(80), Emotion::SorryFor), 0.2);
  EXPECT_LT(E(fan_against.at(80), Emotion::Resentment) + E(fan_against.at(80), Emotion::Gloating),
            1e-3);
  // and each feels its own team's goals the other way round
  EXPECT_GT(fan_for.at(40.5).basic[kHappy], 0.5);
  EXPECT_GT(fan_against.at(40.5).basic[kSad], 0.5);
  EXPECT_GT(fan_against.at(12).basic[kHappy], 0.5);
}

// Issue 17 item 3: the agent decays by the time between events (§5.6.3 per second, one thesis step
// = one match minute, §7.4). The long free-kick at 40' and the goal at 40.5' are half a minute
// apart: surprise (Φ = 0.3 per minute, no M column, ω = 1, r = 1/2) decays by
//   ψ = E·0.3^(1/4) / (1 + E·(1 − 0.3^(1/4)))   (e^(−aΔt) = Φ^(r·Δt/step) = 0.3^(1/4), b/a = 1)
// before the goal's impulse adds, not by a whole step. With DecayClock::Step and r = 1 the old
// per-step law E·Φ + I comes back.
TEST(Agent, DecaysByEventTimeNotBySteps) {
  const Domain d(read_domain_files({kData + "football.domain"}));
  const auto events = read_events_file(kData + "match.ndjson");
  auto run_with = [&](DecayClock clock, double r) {
    AgentConfig c = read_agent_file(kData + "agents/neutral.json");
    c.decay_clock = clock;
    c.emotions.low_intensity_rate = r;
    Agent a(d, c);
    std::vector<StepRecord> out;
    for (const auto& e : events) out.push_back(a.step(e));
    return out;
  };
  auto record = [](const std::vector<StepRecord>& run, double t) {
    for (const auto& r : run)
      if (r.time == t) return r;
    ADD_FAILURE() << "no record at " << t;
    return StepRecord{};
  };
  const std::size_t s = index(Emotion::Surprise);
  const auto by_time = run_with(DecayClock::Time, 0.5);
  const double e40 = record(by_time, 40).emotions[s];
  const StepRecord goal = record(by_time, 40.5);
  ASSERT_GT(e40, 0.3);
  ASSERT_LT(goal.emotions[s], 1.0);  // not saturated: the decay shows
  const double q = std::pow(0.3, 0.25);
  EXPECT_NEAR(goal.emotions[s], std::min(1.0, e40 * q / (1 + e40 * (1 - q)) + goal.impulse[s]),
              1e-12);
  // per step (one minute per event, whatever the times): more surprise lost between 40' and 40.5'
  const auto by_step = run_with(DecayClock::Step, 0.5);
  const double s40 = record(by_step, 40).emotions[s];
  const StepRecord sgoal = record(by_step, 40.5);
  const double h = std::sqrt(0.3);
  EXPECT_NEAR(sgoal.emotions[s], std::min(1.0, s40 * h / (1 + s40 * (1 - h)) + sgoal.impulse[s]),
              1e-12);
  EXPECT_GT(goal.emotions[s] - goal.impulse[s], sgoal.emotions[s] - sgoal.impulse[s] + 0.05);
  // the per-step law of before (Step clock, r = 1): E' = Φ·E + I exactly
  const auto old = run_with(DecayClock::Step, 1.0);
  for (double t : {40.5, 41.0, 12.0}) {
    const double before = record(old, t == 12.0 ? 11.0 : (t == 41.0 ? 40.5 : 40.0)).emotions[s];
    const StepRecord now = record(old, t);
    EXPECT_DOUBLE_EQ(now.emotions[s], std::min(1.0, 0.3 * before + now.impulse[s])) << t;
  }
  // Time clock with r = 1 and events one minute apart is the per-step law too: 41' → 42'
  const auto time1 = run_with(DecayClock::Time, 1.0);
  const std::size_t j = index(Emotion::Distress);
  const StepRecord m42 = record(time1, 42);
  EXPECT_NEAR(record(time1, 42).emotions[j],
              std::min(1.0, 0.97 * record(time1, 41).emotions[j] +
                                m42.impulse[j] *
                                    (1 - record(time1, 41).emotions[index(Emotion::Joy)] * 0.3)),
              1e-12);
}

TEST(Agent, DecayClockConfigIsValidated) {
  AgentConfig c;
  c.time_unit_seconds = 0.0;
  EXPECT_THROW(c.validate(), emoface::InvalidInput);
  c.time_unit_seconds = std::nan("");
  EXPECT_THROW(c.validate(), emoface::InvalidInput);
  EXPECT_EQ(decay_clock_from_string(to_string(DecayClock::Step)), DecayClock::Step);
  EXPECT_EQ(decay_clock_from_string("time"), DecayClock::Time);
  EXPECT_THROW(decay_clock_from_string("minutes"), emoface::InvalidInput);
}
