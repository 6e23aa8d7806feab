#include <gtest/gtest.h>

#include <string>

#include "emoface/core/io.hpp"
#include "emoface/parlee/domain.hpp"

using namespace emoface::parlee;
using emoface::FormatError;

namespace {

const char* kTiny = R"(
(types THING PLACE)
(predicates (at 2) (clean 1))
(objects (box THING) (home PLACE) (work PLACE))
(agents me)
(operator carry (params (<t> THING) (<from> PLACE) (<to> PLACE))
  (preconds (at <t> <from>) (not (at <t> <to>)))
  (effects (0.7 moved (at <t> <to>) (del at <t> <from>)) (0.2 (del at <t> <from>))))
(initial (at box home))
(goal deliver (agent me) (priority 2) (importance 0.5) (deadline 10) (facts (at box work)))
)";

DomainSpec parse(const std::string& text) {
  DomainSpec s;
  parse_domain_text(text, "t.domain", s);
  return s;
}

// Parses and grounds; returns the FormatError's location (line, column) or {0,0} if none thrown.
std::pair<std::size_t, std::size_t> error_at(const std::string& text, std::string* msg = nullptr) {
  try {
    Domain d(parse(text));
  } catch (const FormatError& e) {
    if (msg) *msg = e.message();
    return {e.where().line, e.where().column};
  }
  return {0, 0};
}

}  // namespace

TEST(Domain, ParsesAndGrounds) {
  const Domain d(parse(kTiny));
  // carry box home→work, work→home (from == to pruned by the negative precondition at run time)
  EXPECT_EQ(d.actions().size(), 4u);
  const auto acts = d.applicable_actions(d.initial_state());
  ASSERT_EQ(acts.size(), 1u);
  EXPECT_EQ(d.action_text(acts[0]), "(carry box home work)");
  const auto& outs = d.actions()[acts[0]].outcomes;
  ASSERT_EQ(outs.size(), 3u);  // two explicit + implicit "nothing" with 0.1
  EXPECT_EQ(outs[0].label, "moved");
  EXPECT_EQ(outs[1].label, "case-2");
  EXPECT_EQ(outs[2].label, "nothing");
  EXPECT_NEAR(outs[2].probability, 0.1, 1e-15);
  const State s = d.apply(d.initial_state(), acts[0], 0);
  EXPECT_EQ(d.state_text(s), "(at box work)");
  EXPECT_TRUE(d.goal_holds(0, s));
  EXPECT_FALSE(d.goal_holds(0, d.initial_state()));
  EXPECT_EQ(d.goals()[0].priority, 2);
  EXPECT_EQ(d.goals()[0].deadline, 10);
  EXPECT_EQ(d.find_action("(carry box)", acts), static_cast<long>(acts[0]));
  EXPECT_EQ(d.find_action("(carry crate)", acts), -1);
}

TEST(Domain, WriteParseRoundTrip) {
  const DomainSpec a = parse(kTiny);
  const std::string text = write_domain_text(a);
  const DomainSpec b = parse(text);
  EXPECT_EQ(write_domain_text(b), text);
  const Domain da(a), db(b);
  EXPECT_EQ(da.facts(), db.facts());
  EXPECT_EQ(da.actions().size(), db.actions().size());
  for (const char* f : {"rocket.domain", "rocket2.domain", "football.domain", "bread.domain"}) {
    const std::string path = std::string(EMOFACE_SOURCE_DIR) + "/data/parlee/" + f;
    const DomainSpec s = read_domain_files({path});
    const std::string t = write_domain_text(s);
    EXPECT_EQ(write_domain_text(parse(t)), t) << f;
    EXPECT_EQ(Domain(parse(t)).actions().size(), Domain(s).actions().size()) << f;
  }
  // the two-supporter problem adds an agent and its goals to the football domain
  const std::string dir = std::string(EMOFACE_SOURCE_DIR) + "/data/parlee/";
  const DomainSpec rivals = read_domain_files({dir + "football.domain", dir + "rivals.problem"});
  const std::string t = write_domain_text(rivals);
  EXPECT_EQ(write_domain_text(parse(t)), t);
  const Domain dr(rivals);
  EXPECT_EQ(dr.agent_count(), 3u);
  EXPECT_EQ(dr.agent_index("rival"), 2);
  EXPECT_EQ(dr.goals().size(), 5u);
}

TEST(Domain, PpddlSubset) {
  const char* text = R"(
(define (domain carry)
  (:requirements :typing :probabilistic-effects)
  (:types thing place)
  (:predicates (at ?t - thing ?p - place))
  (:action carry :parameters (?t - thing ?from ?to - place)
    :precondition (and (at ?t ?from) (not (at ?t ?to)))
    :effect (and (not (at ?t ?from)) (probabilistic 0.7 (at ?t ?to)))))
(define (problem p) (:domain carry)
  (:objects box - thing home work - place)
  (:init (at box home))
  (:goal (and (at box work))))
)";
  const Domain d(parse(text));
  const auto acts = d.applicable_actions(d.initial_state());
  ASSERT_EQ(acts.size(), 1u);
  const auto& outs = d.actions()[acts[0]].outcomes;
  ASSERT_EQ(outs.size(), 2u);
  EXPECT_NEAR(outs[0].probability, 0.7, 1e-15);
  EXPECT_NEAR(outs[1].probability, 0.3, 1e-15);
  EXPECT_EQ(outs[1].del.size(), 1u);  // the deterministic delete applies to both outcomes
  EXPECT_TRUE(d.goal_holds(0, d.apply(d.initial_state(), acts[0], 0)));
}

TEST(Domain, ErrorsHaveLineAndColumn) {
  std::string msg;
  EXPECT_EQ(error_at("(types A)\n(objects (x A)\n", &msg), (std::pair<std::size_t, std::size_t>{2, 1}));
  EXPECT_NE(msg.find("missing ')'"), std::string::npos);
  EXPECT_EQ(error_at("(types A))", &msg), (std::pair<std::size_t, std::size_t>{1, 10}));
  EXPECT_EQ(error_at("(predicates (p 1))\n(objects a)\n(initial (q a))", &msg),
            (std::pair<std::size_t, std::size_t>{3, 10}));
  EXPECT_NE(msg.find("unknown predicate 'q'"), std::string::npos);
  EXPECT_EQ(error_at("(predicates (p 1))\n(objects a)\n(initial (p b))", &msg),
            (std::pair<std::size_t, std::size_t>{3, 10}));
  EXPECT_NE(msg.find("unknown object 'b'"), std::string::npos);
  EXPECT_EQ(error_at("(predicates (p 1))\n(objects a)\n(initial (p a a))", &msg).first, 3u);
  EXPECT_NE(msg.find("takes 1 arguments"), std::string::npos);
  // probabilities summing to more than 1
  EXPECT_EQ(error_at("(predicates (p 0))\n(operator o (effects\n (0.6 (p)) (0.5)))", &msg).first, 2u);
  EXPECT_NE(msg.find("sum to 1.1"), std::string::npos);
  EXPECT_EQ(error_at("(predicates (p 0))\n(operator o (effects (1.5 (p))))", &msg).first, 2u);
  EXPECT_EQ(error_at("(predicates (p 0))\n(operator o (effects (nan (p))))", &msg).first, 2u);
  EXPECT_EQ(error_at("(predicates (p 0))\n(operator o (effects (inf (p))))", &msg).first, 2u);
  EXPECT_EQ(error_at("(predicates (p 1))\n(operator o (params (<x>)) (preconds (p <y>)))", &msg).first, 2u);
  EXPECT_NE(msg.find("unbound variable"), std::string::npos);
  EXPECT_EQ(error_at("(frobnicate)", &msg).first, 1u);
  EXPECT_EQ(error_at("stray", &msg).first, 1u);
  EXPECT_EQ(error_at("(goal g (facts))\n(goal h (importance -1) (facts))", &msg).first, 2u);
  EXPECT_EQ(error_at("(predicates (p x))", &msg).first, 1u);
  EXPECT_EQ(error_at("(predicates (p 0))\n(goal g (facts (p)))\n(goal g (facts (p)))", &msg).first, 3u);
  EXPECT_NE(msg.find("declared twice"), std::string::npos);
  EXPECT_EQ(error_at("(predicates (p 0))\n(operator o)\n(operator o)", &msg).first, 3u);
  EXPECT_THROW(Domain(parse("(predicates (p 0) (p 1))")), FormatError);
  EXPECT_THROW(Domain(parse("(objects a a)")), FormatError);
  EXPECT_EQ(error_at("(\"quoted\")", &msg).first, 1u);
  // deep nesting is refused, not a stack overflow
  EXPECT_NE(error_at(std::string(100000, '(') + std::string(100000, ')')).first, 0u);
  // truncated real file
  const std::string rocket = emoface::core::read_file(std::string(EMOFACE_SOURCE_DIR) + "/data/parlee/rocket.domain");
  for (std::size_t cut : {rocket.find("(operator UNLOAD") + 20, rocket.find("(initial") + 5, rocket.size() - 3}) {
    EXPECT_NE(error_at(rocket.substr(0, cut)).first, 0u) << cut;
  }
}

TEST(Domain, GroundingLimits) {
  CompileOptions o;
  o.max_ground_actions = 2;
  EXPECT_THROW(Domain(parse(kTiny), o), FormatError);
  o.max_ground_actions = 0;
  EXPECT_THROW(o.validate(), emoface::InvalidInput);
}

TEST(Domain, TurnsPassAutomatically) {
  const Domain d(read_domain_files({std::string(EMOFACE_SOURCE_DIR) + "/data/parlee/rocket2.domain"}));
  const State s0 = d.initial_state();
  EXPECT_EQ(d.turn(s0), 0);
  const auto acts = d.applicable_actions(s0);
  for (auto a : acts) EXPECT_NE(d.actions()[a].actor, 1);
  const State s1 = d.apply(s0, acts[0], d.actions()[acts[0]].outcomes.size() - 1);
  EXPECT_EQ(d.turn(s1), 1);
  EXPECT_EQ(d.turn(d.pass_turn(s1)), 0);
}
