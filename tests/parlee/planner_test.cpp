// Planner probabilities against values computed independently: a hand-coded model of the rocket
// domain explored by exhaustive enumeration of every action and outcome sequence, hand-computed
// values for the two-agent variant, and a memo-free recursion of the §5.7.4 formulas for d = 0,1,2.
#include "emoface/parlee/planner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>

#include "emoface/parlee/domain.hpp"
#include "naive_planner.hpp"

using namespace emoface::parlee;
using emoface::parlee::test::Naive;

namespace {

Domain load(const std::string& name) {
  return Domain(read_domain_files({std::string(EMOFACE_SOURCE_DIR) + "/data/parlee/" + name}));
}

// ---- independent rocket model: cargo location 0 = london, 1 = paris, 2 = in rocket
struct R {
  int c[2];
  int rocket;  // 0 london, 1 paris
  bool fuel;
};

double enumerate(const R& s, int h, bool within) {
  const bool goal = s.c[0] == 1 && s.c[1] == 1;
  if (goal && within) return 1.0;
  if (h == 0) return goal ? 1.0 : 0.0;
  double best = -1.0;
  auto consider = [&](double p_ok, const R& ok, const R& fail) {
    best = std::max(best, p_ok * enumerate(ok, h - 1, within) + (1 - p_ok) * enumerate(fail, h - 1, within));
  };
  for (int k = 0; k < 2; ++k) {
    if (s.c[k] == s.rocket) {  // LOAD 0.9
      R t = s;
      t.c[k] = 2;
      consider(0.9, t, s);
    }
    if (s.c[k] == 2) {  // UNLOAD 0.9
      R t = s;
      t.c[k] = s.rocket;
      consider(0.9, t, s);
    }
  }
  if (s.fuel) {  // MOVE 0.8, consumes fuel
    R t = s;
    t.rocket = 1 - s.rocket;
    t.fuel = false;
    consider(0.8, t, s);
  }
  if (best < 0) return goal ? 1.0 : 0.0;  // no action: nothing changes
  return best;
}

}  // namespace

TEST(Planner, RocketMatchesExhaustiveEnumeration) {
  const Domain d = load("rocket.domain");
  for (auto sem : {GoalSemantics::Within, GoalSemantics::AtHorizon}) {
    PlanOptions o;
    o.semantics = sem;
    Planner planner(d, o);
    for (int h = 0; h <= 9; ++h) {
      const double expect = enumerate(R{{0, 0}, 0, true}, h, sem == GoalSemantics::Within);
      EXPECT_NEAR(planner.goal_probability(0, d.initial_state(), h), expect, 1e-12) << "h=" << h;
    }
  }
}

TEST(Planner, RocketHandValues) {
  const Domain d = load("rocket.domain");
  Planner planner(d);
  EXPECT_EQ(planner.goal_probability(0, d.initial_state(), 4), 0.0);
  // load, load, move, unload, unload: 0.9^4 · 0.8
  EXPECT_NEAR(planner.goal_probability(0, d.initial_state(), 5), 0.9 * 0.9 * 0.9 * 0.9 * 0.8, 1e-12);
  const auto plan = planner.plan(0, d.initial_state(), 5);
  ASSERT_EQ(plan.steps.size(), 5u);
  EXPECT_EQ(d.action_text(plan.steps[0].action).substr(0, 6), "(LOAD ");
  EXPECT_EQ(d.action_text(plan.steps[2].action), "(MOVE r1 london paris)");
  EXPECT_EQ(d.action_text(plan.steps[4].action).substr(0, 8), "(UNLOAD ");
  // monotone in the horizon under Within semantics
  double prev = 0.0;
  for (int h = 0; h < 12; ++h) {
    const double p = planner.goal_probability(0, d.initial_state(), h);
    EXPECT_GE(p, prev - 1e-15);
    prev = p;
  }
}

namespace {

State rocket2_state(const Domain& d, std::initializer_list<const char*> facts) {
  State s = d.empty_state();
  for (const char* f : facts) {
    const long id = d.fact_id(f);
    EXPECT_GE(id, 0) << f;
    if (id >= 0) s.set(static_cast<std::size_t>(id));
  }
  return s;
}

}  // namespace

TEST(Planner, TwoAgentHandComputed) {
  const Domain d = load("rocket2.domain");
  const State s = rocket2_state(d, {"(at r1 paris)", "(in c1 r1)", "(is-acting pilot)"});
  PlanOptions o;
  o.semantics = GoalSemantics::AtHorizon;
  o.model_depth = 0;  // the thief chooses uniformly (0-level agent)
  Planner p0(d, o);
  EXPECT_NEAR(p0.goal_probability(0, s, 1), 0.9, 1e-12);
  EXPECT_NEAR(p0.goal_probability(0, s, 2), 0.54, 1e-12);
  EXPECT_NEAR(p0.goal_probability(0, s, 3), 0.954, 1e-12);
  o.model_depth = -1;  // thesis: the thief is a (d−1)-level agent
  Planner p1(d, o);
  EXPECT_NEAR(p1.goal_probability(0, s, 2), 0.54, 1e-12);
  EXPECT_NEAR(p1.goal_probability(0, s, 3), 0.9 * 0.91 + 0.1 * 0.999 / 1.1, 1e-12);
}

TEST(Planner, TwoAgentLevelsMatchNaiveRecursion) {
  const Domain d = load("rocket2.domain");
  for (bool within : {false, true}) {
    const Naive naive{d, within};
    for (int D : {0, 1, 2}) {
      PlanOptions o;
      o.semantics = within ? GoalSemantics::Within : GoalSemantics::AtHorizon;
      o.model_depth = D;
      Planner planner(d, o);
      for (int h = 0; h <= 7; ++h) {
        for (std::size_t g = 0; g < 2; ++g) {
          EXPECT_NEAR(planner.goal_probability(g, d.initial_state(), h), naive.p_goal(g, d.initial_state(), h, D),
                      1e-12)
              << "within=" << within << " D=" << D << " h=" << h << " goal=" << g;
        }
      }
      const auto w = planner.action_distribution(d.initial_state(), D);
      const auto wn = naive.choice(d.initial_state(), D);
      ASSERT_EQ(w.size(), wn.size());
      double sum = 0.0;
      for (std::size_t k = 0; k < w.size(); ++k) {
        EXPECT_NEAR(w[k], wn[k], 1e-12);
        sum += w[k];
      }
      EXPECT_NEAR(sum, 1.0, 1e-12);
    }
  }
}

TEST(Planner, DepthLevelsDiffer) {
  // The thief's model level changes the pilot's estimate: d = 0, 1, 2 give different values.
  const Domain d = load("rocket2.domain");
  const State s = rocket2_state(d, {"(at r1 paris)", "(in c1 r1)", "(is-acting pilot)"});
  std::vector<double> v;
  for (int D : {0, 1, 2}) {
    PlanOptions o;
    o.semantics = GoalSemantics::AtHorizon;
    o.model_depth = D;
    Planner planner(d, o);
    v.push_back(planner.goal_probability(0, s, 5));
  }
  EXPECT_NE(v[0], v[1]);
  EXPECT_NE(v[1], v[2]);
}

TEST(Planner, OptionsValidate) {
  PlanOptions o;
  o.horizon = -1;
  EXPECT_THROW(o.validate(), emoface::InvalidInput);
  o.horizon = 3;
  o.model_depth = -2;
  EXPECT_THROW(o.validate(), emoface::InvalidInput);
  EXPECT_EQ(goal_semantics_from_string(to_string(GoalSemantics::AtHorizon)), GoalSemantics::AtHorizon);
  EXPECT_THROW(goal_semantics_from_string("soon"), emoface::InvalidInput);
}

TEST(Planner, Fig54AsPrintedHasNoPlan) {
  // Thesis Fig. 5.4 verbatim (plus declarations): LOAD needs the agent at the place, MOVE and
  // UNLOAD need it in the rocket, nothing boards it — so the goal is unreachable at any horizon.
  const char* text = R"(
(types CARGO ROCKET PLACE AGENT)
(predicates (at 2) (in 2) (has-fuel 1) (is-acting 1))
(objects (c1 CARGO) (r1 ROCKET) (rocket ROCKET) (london PLACE) (paris PLACE) (pilot AGENT))
(agents pilot)
(operator LOAD
(params (<object> CARGO) (<rocket> ROCKET) (<place> PLACE) (<agent> AGENT))
(preconds (at <rocket> <place>) (at <object> <place>)
(at <agent> <place>) (is-acting <agent>))
(effects (0.9 (in <object> <rocket>) (del at <object> <place>))
(0.1) ))
(operator UNLOAD
(params (<object> CARGO) (<rocket> ROCKET) (<place> PLACE) (<agent> AGENT))
(preconds (at <rocket> <place>) (in <object> <rocket>)
(in <agent> <rocket>) (is-acting <agent>))
(effects (0.9 (at <object> <place>) (del in <object> <rocket>))
(0.1) ))
(operator MOVE
(params (<rocket> ROCKET) (<from> PLACE) (<to> PLACE) (<agent> AGENT))
(preconds (has-fuel <rocket>) (at <rocket> <from>)
(in <agent> rocket) (is-acting <agent>))
(effects (0.8 (at <rocket> <to>) (del has-fuel <rocket>) (del at <rocket> <from>))
(0.2) ))
(initial (at r1 london) (has-fuel r1) (at c1 london) (at pilot london) (is-acting pilot))
(goal deliver (agent pilot) (facts (at c1 paris)))
)";
  DomainSpec spec;
  parse_domain_text(text, "fig54", spec);
  const Domain d(spec);
  Planner planner(d);
  for (int h = 0; h <= 8; ++h) EXPECT_EQ(planner.goal_probability(0, d.initial_state(), h), 0.0) << h;
  // LOAD is possible, MOVE never is
  bool can_load = false;
  for (auto a : d.applicable_actions(d.initial_state())) can_load |= d.action_text(a).rfind("(LOAD", 0) == 0;
  EXPECT_TRUE(can_load);
}
