#include <gtest/gtest.h>

#include <cmath>

#include "emoface/core/errors.hpp"
#include "emoface/parlee/appraisal.hpp"

using namespace emoface::parlee;
using emoface::InvalidInput;

namespace {
double I(const AppraisalResult& r, Emotion e) { return r.impulse[index(e)]; }
GoalAppraisal goal(double before, double after, double importance = 1.0) {
  GoalAppraisal g;
  g.p_before = before;
  g.p_after = after;
  g.importance = importance;
  return g;
}
}  // namespace

TEST(Appraisal, DesirableEventByOther) {
  AppraisalInput in;
  in.goals = {goal(0.2, 0.6, 2.0)};
  in.p_event = 0.36;
  in.actor = Actor::Other;
  const auto r = appraise(in, Personality{});
  EXPECT_NEAR(I(r, Emotion::Joy), 0.4 * 2.0 * std::sqrt(0.64), 1e-12);        // 0.64
  EXPECT_NEAR(I(r, Emotion::Gratitude), 0.64, 1e-12);
  EXPECT_NEAR(I(r, Emotion::Hope), 2.0 * 0.1, 1e-12);                          // Import·(P − 0.5)
  EXPECT_EQ(I(r, Emotion::Fear), 0.0);
  EXPECT_NEAR(I(r, Emotion::Surprise), 0.5 - 0.36, 1e-12);
  EXPECT_EQ(I(r, Emotion::Distress), 0.0);
  EXPECT_EQ(I(r, Emotion::Gratification), 0.0);
  ASSERT_EQ(r.hope.size(), 1u);
  EXPECT_NEAR(r.hope[0], 0.2, 1e-12);
}

TEST(Appraisal, UndesirableEventByOtherAndSelf) {
  AppraisalInput in;
  in.goals = {goal(0.6, 0.2)};
  in.p_event = 0.5;
  in.actor = Actor::Other;
  auto r = appraise(in, Personality{});
  EXPECT_NEAR(I(r, Emotion::Distress), 0.4 * 0.25, 1e-12);  // unexpectedness squared
  EXPECT_NEAR(I(r, Emotion::Anger), 0.4 * std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(I(r, Emotion::Fear), 0.3, 1e-12);
  EXPECT_EQ(I(r, Emotion::Surprise), 0.0);  // P(event) = 0.5 is not < 0.5
  in.actor = Actor::Self;
  r = appraise(in, Personality{});
  EXPECT_NEAR(I(r, Emotion::Remorse), 0.4 * std::sqrt(0.5), 1e-12);
  EXPECT_EQ(I(r, Emotion::Anger), 0.0);
  in.goals = {goal(0.6, 0.9)};
  r = appraise(in, Personality{});
  EXPECT_NEAR(I(r, Emotion::Gratification), 0.3 * std::sqrt(0.5), 1e-12);
}

TEST(Appraisal, ConfirmationEmotionsUsePreviousProspect) {
  AppraisalInput in;
  GoalAppraisal g = goal(0.7, 1.0);
  g.status = GoalStatus::Success;
  g.status_changed = true;
  g.previous_hope = 0.2;
  g.previous_fear = 0.0;
  in.goals = {g};
  auto r = appraise(in, Personality{});
  EXPECT_NEAR(I(r, Emotion::Satisfaction), 0.2, 1e-12);
  EXPECT_EQ(I(r, Emotion::Relief), 0.0);
  EXPECT_EQ(I(r, Emotion::Hope), 0.0);  // confirmed goals give no prospect emotions
  in.goals[0].previous_hope = 0.0;
  in.goals[0].previous_fear = 0.35;
  r = appraise(in, Personality{});
  EXPECT_NEAR(I(r, Emotion::Relief), 0.35, 1e-12);
  in.goals[0].status = GoalStatus::Fail;
  in.goals[0].p_after = 0.0;
  r = appraise(in, Personality{});
  EXPECT_NEAR(I(r, Emotion::FearsConfirmed), 0.35, 1e-12);
  in.goals[0].previous_hope = 0.25;
  in.goals[0].previous_fear = 0.0;
  r = appraise(in, Personality{});
  EXPECT_NEAR(I(r, Emotion::Disappointment), 0.25, 1e-12);
  in.goals[0].status_changed = false;  // already confirmed earlier: nothing new
  r = appraise(in, Personality{});
  EXPECT_EQ(I(r, Emotion::Disappointment), 0.0);
}

TEST(Appraisal, StandardsAndDesireOther) {
  AppraisalInput in;
  in.has_praiseworthiness = true;
  in.praiseworthiness = 0.6;
  in.actor = Actor::Self;
  EXPECT_NEAR(I(appraise(in, Personality{}), Emotion::Pride), 0.6, 1e-12);
  in.praiseworthiness = -0.6;
  EXPECT_NEAR(I(appraise(in, Personality{}), Emotion::Shame), 0.6, 1e-12);
  in.actor = Actor::Other;
  EXPECT_NEAR(I(appraise(in, Personality{}), Emotion::Reproach), 0.6, 1e-12);
  in.praiseworthiness = 0.3;
  EXPECT_NEAR(I(appraise(in, Personality{}), Emotion::Appreciation), 0.3, 1e-12);

  AppraisalInput d;
  d.p_event = 0.75;
  d.others = {OtherAppraisal{0.6, {1.0}, {0.5}}};
  // other's joy = 0.5·1·(0.25)^0.5 = 0.25; Happy-for = LL·joy·feelingFocus = 0.6·0.25·0.5
  EXPECT_NEAR(I(appraise(d, Personality{}), Emotion::HappyFor), 0.075, 1e-12);
  d.others[0].liking = -0.6;
  EXPECT_NEAR(I(appraise(d, Personality{}), Emotion::Resentment), 0.075, 1e-12);
  d.others[0].impact = {-0.5};  // other's distress = 0.5·0.25² = 0.03125
  EXPECT_NEAR(I(appraise(d, Personality{}), Emotion::Gloating), 0.6 * 0.5 * 0.03125, 1e-12);
  d.others[0].liking = 0.6;
  EXPECT_NEAR(I(appraise(d, Personality{}), Emotion::SorryFor), 0.6 * 0.5 * 0.03125, 1e-12);
  Personality unselfish;
  unselfish[Trait::FeelingFocus] = 1.0;
  EXPECT_NEAR(I(appraise(d, unselfish), Emotion::SorryFor), 0.6 * 0.03125, 1e-12);
  d.others[0].liking = 0.0;
  EXPECT_EQ(I(appraise(d, Personality{}), Emotion::SorryFor), 0.0);
}

TEST(Appraisal, PersonalityDirectionAndMagnitude) {
  AppraisalInput bad;
  bad.goals = {goal(0.6, 0.3)};
  bad.p_event = 0.2;
  AppraisalInput good;
  good.goals = {goal(0.3, 0.6)};
  good.p_event = 0.2;
  Personality neutral, pessimist, optimist, sensitive, realist;
  pessimist[Trait::ReasoningFocus] = 0.0;
  optimist[Trait::ReasoningFocus] = 1.0;
  sensitive[Trait::FeelingLevel] = 1.0;
  realist[Trait::PerceivingFocus] = 1.0;
  const double d0 = I(appraise(bad, neutral), Emotion::Distress);
  const double j0 = I(appraise(good, neutral), Emotion::Joy);
  // pessimistic: |impact|^0.5 on bad news, impact^1.5 on good news
  EXPECT_NEAR(I(appraise(bad, pessimist), Emotion::Distress), std::sqrt(0.3) * 0.64, 1e-12);
  EXPECT_NEAR(I(appraise(good, pessimist), Emotion::Joy), std::pow(0.3, 1.5) * std::sqrt(0.8), 1e-12);
  EXPECT_GT(I(appraise(bad, pessimist), Emotion::Distress), d0);
  EXPECT_LT(I(appraise(good, pessimist), Emotion::Joy), j0);
  EXPECT_LT(I(appraise(bad, optimist), Emotion::Distress), d0);
  EXPECT_GT(I(appraise(good, optimist), Emotion::Joy), j0);
  // sensitive: every impulse^0.5
  EXPECT_NEAR(I(appraise(bad, sensitive), Emotion::Distress), std::sqrt(d0), 1e-12);
  EXPECT_NEAR(I(appraise(bad, sensitive), Emotion::Surprise), std::sqrt(0.3), 1e-12);
  // realistic: P(event)^1.5 = 0.0894… → more surprise
  EXPECT_NEAR(I(appraise(bad, realist), Emotion::Surprise), 0.5 - std::pow(0.2, 1.5), 1e-12);
}

TEST(Appraisal, RejectsBadInput) {
  AppraisalInput in;
  in.p_event = 1.5;
  EXPECT_THROW(appraise(in, Personality{}), InvalidInput);
  in.p_event = std::nan("");
  EXPECT_THROW(appraise(in, Personality{}), InvalidInput);
  in.p_event = 0.5;
  in.goals = {goal(0.2, 1.2)};
  EXPECT_THROW(appraise(in, Personality{}), InvalidInput);
  in.goals = {goal(0.2, 0.3, -1.0)};
  EXPECT_THROW(appraise(in, Personality{}), InvalidInput);
  in.goals = {};
  in.others = {OtherAppraisal{2.0, {}, {}}};
  EXPECT_THROW(appraise(in, Personality{}), InvalidInput);
  in.others = {OtherAppraisal{0.5, {1.0}, {}}};
  EXPECT_THROW(appraise(in, Personality{}), InvalidInput);
  AppraisalOptions o;
  o.surprise_threshold = 0.0;
  EXPECT_THROW(o.validate(), InvalidInput);
}

TEST(Liking, UpdateAndClamp) {
  EXPECT_NEAR(update_liking(0.0, 0.5), 0.05, 1e-15);
  EXPECT_NEAR(update_liking(0.2, -1.0), 0.1, 1e-15);
  EXPECT_EQ(update_liking(0.95, 1.0), 1.0);
  EXPECT_EQ(update_liking(-0.95, -1.0), -1.0);
  EXPECT_EQ(update_liking(0.5, 100.0), 1.0);
  EXPECT_NEAR(desirability({1.0, 0.5}, {0.4, -0.2}), 0.3, 1e-15);
  EXPECT_THROW(desirability({1.0}, {}), InvalidInput);
  EXPECT_THROW(update_liking(0.0, std::nan("")), InvalidInput);
}

TEST(Learning, CountBasedOutcomeUpdate) {
  OutcomeLearner l{{0.9, 0.1}, 10.0};
  l.observe(1);
  EXPECT_NEAR(l.p[0], 9.0 / 11.0, 1e-15);
  EXPECT_NEAR(l.p[1], 2.0 / 11.0, 1e-15);
  EXPECT_EQ(l.n, 11.0);
  for (int k = 0; k < 1000; ++k) l.observe(1);
  EXPECT_NEAR(l.p[0] + l.p[1], 1.0, 1e-12);
  EXPECT_GT(l.p[1], 0.98);
  EXPECT_THROW(l.observe(2), InvalidInput);
  RunningMean m;
  m.add(1.0);
  m.add(-0.5);
  EXPECT_NEAR(m.mean, 0.25, 1e-15);
  EXPECT_EQ(m.count, 2u);
  EXPECT_THROW(m.add(2.0), InvalidInput);
  EXPECT_THROW(m.add(std::nan("")), InvalidInput);
}

TEST(Appraisal, EnumStrings) {
  for (auto s : {GoalStatus::Unconfirmed, GoalStatus::Success, GoalStatus::Fail})
    EXPECT_EQ(goal_status_from_string(to_string(s)), s);
  for (auto a : {Actor::Self, Actor::Other, Actor::Nobody}) EXPECT_EQ(actor_from_string(to_string(a)), a);
  EXPECT_THROW(goal_status_from_string("maybe"), InvalidInput);
  EXPECT_THROW(actor_from_string("god"), InvalidInput);
}

// §5.6.2 as printed: one signed sum over the goals; its positive part is Hope, its negative part
// Fear. Two goals pulling opposite ways: 1·(0.9 − 0.5) + 2·(0.3 − 0.5) = 0.4 − 0.4 = 0 → neither.
TEST(Appraisal, HopeAndFearAreTheSignedSumByDefault) {
  AppraisalInput in;
  in.goals = {goal(0.9, 0.9, 1.0), goal(0.3, 0.3, 2.0)};
  EXPECT_EQ(AppraisalOptions{}.prospect, ProspectMode::SignedSum);
  auto r = appraise(in, Personality{});
  EXPECT_NEAR(I(r, Emotion::Hope), 0.0, 1e-12);
  EXPECT_NEAR(I(r, Emotion::Fear), 0.0, 1e-12);
  // 1·(0.9 − 0.5) + 1·(0.3 − 0.5) = 0.2 → Hope 0.2, all of it the first goal's share
  in.goals[1].importance = 1.0;
  r = appraise(in, Personality{});
  EXPECT_NEAR(I(r, Emotion::Hope), 0.2, 1e-12);
  EXPECT_EQ(I(r, Emotion::Fear), 0.0);
  ASSERT_EQ(r.hope.size(), 2u);
  EXPECT_NEAR(r.hope[0], 0.2, 1e-12);
  EXPECT_EQ(r.hope[1], 0.0);
  EXPECT_EQ(r.fear[0] + r.fear[1], 0.0);
  // the per-goal clamp (the option): Hope 0.4 and Fear 0.2 at once
  AppraisalOptions o;
  o.prospect = ProspectMode::PerGoal;
  r = appraise(in, Personality{}, o);
  EXPECT_NEAR(I(r, Emotion::Hope), 0.4, 1e-12);
  EXPECT_NEAR(I(r, Emotion::Fear), 0.2, 1e-12);
  EXPECT_NEAR(r.fear[1], 0.2, 1e-12);
  // a confirmed goal takes no part: only the unconfirmed 0.3 goal remains → Fear 0.2
  in.goals[0].status = GoalStatus::Success;
  r = appraise(in, Personality{});
  EXPECT_EQ(I(r, Emotion::Hope), 0.0);
  EXPECT_NEAR(I(r, Emotion::Fear), 0.2, 1e-12);
  EXPECT_EQ(prospect_mode_from_string(to_string(ProspectMode::PerGoal)), ProspectMode::PerGoal);
  EXPECT_EQ(prospect_mode_from_string(to_string(ProspectMode::SignedSum)), ProspectMode::SignedSum);
  EXPECT_THROW(prospect_mode_from_string("clamp"), InvalidInput);
}

// Table 5.2: Anger = Distress + Reproach etc. Under CompoundRule::Standards the compound emotions
// need a praiseworthiness of the right sign; their intensity stays the §5.6.2 formula.
TEST(Appraisal, CompoundEmotionsUnderTheStandardsRule) {
  AppraisalInput in;
  in.goals = {goal(0.6, 0.2, 1.0)};  // Impact −0.4
  in.p_event = 0.36;                 // (1 − 0.36)^0.5 = 0.8
  in.actor = Actor::Other;
  AppraisalOptions o;
  EXPECT_EQ(o.compound, CompoundRule::Impact);
  EXPECT_NEAR(I(appraise(in, Personality{}, o), Emotion::Anger), 0.4 * 0.8, 1e-12);
  o.compound = CompoundRule::Standards;
  auto r = appraise(in, Personality{}, o);
  EXPECT_EQ(I(r, Emotion::Anger), 0.0);  // no standard known: distress only
  EXPECT_NEAR(I(r, Emotion::Distress), 0.4 * 0.64 * 0.64, 1e-12);
  in.has_praiseworthiness = true;
  in.praiseworthiness = 0.5;  // praiseworthy: appreciation, still no anger
  r = appraise(in, Personality{}, o);
  EXPECT_EQ(I(r, Emotion::Anger), 0.0);
  EXPECT_NEAR(I(r, Emotion::Appreciation), 0.5, 1e-12);
  in.praiseworthiness = -0.5;  // blameworthy: reproach and anger
  r = appraise(in, Personality{}, o);
  EXPECT_NEAR(I(r, Emotion::Anger), 0.32, 1e-12);
  EXPECT_NEAR(I(r, Emotion::Reproach), 0.5, 1e-12);
  in.goals = {goal(0.2, 0.6, 1.0)};  // desirable; own action, praiseworthy: gratification
  in.actor = Actor::Self;
  in.praiseworthiness = 0.25;
  r = appraise(in, Personality{}, o);
  EXPECT_NEAR(I(r, Emotion::Gratification), 0.32, 1e-12);
  in.praiseworthiness = -0.25;
  EXPECT_EQ(I(appraise(in, Personality{}, o), Emotion::Gratification), 0.0);
  EXPECT_EQ(compound_rule_from_string(to_string(CompoundRule::Standards)), CompoundRule::Standards);
  EXPECT_THROW(compound_rule_from_string("occ"), InvalidInput);
}
