#include "emoface/mindmap/simulation.hpp"

#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "emoface/mindmap/io.hpp"
#include "fixtures.hpp"

namespace mm = emoface::mindmap;
using mm::test::make_alice;
using mm::test::make_bob;

namespace {

mm::Event event(double t, std::string to, std::string stimulus, std::string from = {}) {
  mm::Event e;
  e.time = t;
  e.target = std::move(to);
  e.stimulus = std::move(stimulus);
  e.source = std::move(from);
  return e;
}

}  // namespace

TEST(Choice, TopEmotionTakesTheFirstMaximum) {
  const double m[4] = {0.2, 0.7, 0.7, 0.1};
  EXPECT_EQ(mm::top_emotion(m, 4), 1u);
  EXPECT_EQ(mm::top_emotion(m, 1), 0u);
}

TEST(Choice, ClosestEdgeWeightWins) {
  const mm::MindMap m = make_alice();  // happiness → smile 0.3, laugh 0.9
  emoface::core::Rng rng(1);
  EXPECT_EQ(mm::choose_response(m, 0, 0.55, 0.0, rng), 2u);  // |0.3−0.55| = 0.25 < 0.35
  EXPECT_EQ(mm::choose_response(m, 0, 0.65, 0.0, rng), 3u);
  EXPECT_EQ(mm::choose_response(m, 0, 0.0, 0.0, rng), 2u);
  EXPECT_EQ(mm::choose_response(m, 1, 0.9, 0.0, rng), 4u);   // only edge
  mm::MindMap none = m;
  none.response_edges.pop_back();
  EXPECT_EQ(mm::choose_response(none, 1, 0.9, 0.0, rng), mm::kNone);
}

TEST(Choice, NearTiesAreChosenBySeededFuzziness) {
  mm::MindMap m = make_alice();
  m.response_edges[0].weight = 0.50;  // smile
  m.response_edges[1].weight = 0.53;  // laugh
  std::set<std::size_t> picked_tol, picked_exact;
  for (std::uint64_t seed = 0; seed < 64; ++seed) {
    emoface::core::Rng a(seed), b(seed);
    const std::size_t x = mm::choose_response(m, 0, 0.51, 0.05, a);
    EXPECT_EQ(x, mm::choose_response(m, 0, 0.51, 0.05, b));  // same seed, same choice
    picked_tol.insert(x);
    emoface::core::Rng c(seed);
    picked_exact.insert(mm::choose_response(m, 0, 0.51, 0.0, c));
  }
  EXPECT_EQ(picked_tol, (std::set<std::size_t>{2, 3}));
  EXPECT_EQ(picked_exact, (std::set<std::size_t>{2}));  // tolerance 0: the strictly closest
}

TEST(Chain, DepthFirstInEdgeOrderWithCycleProtection) {
  mm::MindMap m = make_alice();  // smile(2) → wave(5)
  EXPECT_EQ(mm::chain_from(m, 2, 8), (std::vector<std::size_t>{2, 5}));
  EXPECT_EQ(mm::chain_from(m, 3, 8), (std::vector<std::size_t>{3}));
  m.chain_edges = {{2, 3}, {2, 4}, {3, 5}, {5, 2}, {4, 2}};  // cycles smile→laugh→wave→smile, sigh→smile
  EXPECT_EQ(mm::chain_from(m, 2, 8), (std::vector<std::size_t>{2, 3, 5, 4}));
  EXPECT_EQ(mm::chain_from(m, 2, 2), (std::vector<std::size_t>{2, 3}));
  EXPECT_EQ(mm::chain_from(m, 4, 8), (std::vector<std::size_t>{4, 2, 3, 5}));
}

TEST(World, StimulusUpdatesMoodByEqs2to4AndTriggersTheChain) {
  mm::SimulationOptions o;
  o.chain_delay = 0.5;
  mm::World w({make_alice()}, o);
  std::vector<mm::TriggeredAction> out;
  w.apply(event(0.0, "alice", "gift"), &out);
  // happiness: 0.5·0.2 + 0.5·(0.5·0.8 + 0.5·0.1) = 0.325; sadness: 0.5·0.4 + 0.5·(0 + 0.5·0.3) = 0.275
  EXPECT_NEAR(w.mood(0)[0], 0.325, 1e-15);
  EXPECT_NEAR(w.mood(0)[1], 0.275, 1e-15);
  ASSERT_EQ(out.size(), 2u);  // smile (closest to 0.325), then the chained wave
  EXPECT_EQ(out[0].action, "smile");
  EXPECT_EQ(out[0].label, "happiness");
  EXPECT_EQ(out[0].emotion, "happiness");
  EXPECT_EQ(out[0].cause, mm::Cause::Stimulus);
  EXPECT_NEAR(out[0].mood, 0.325, 1e-15);
  EXPECT_EQ(out[1].action, "wave");
  EXPECT_EQ(out[1].cause, mm::Cause::Chain);
  EXPECT_EQ(out[1].time, 0.5);
  EXPECT_EQ(out[1].chain_depth, 1u);
  EXPECT_EQ(out[1].stimulus, "gift");
}

TEST(World, MoodDecaysToPersonalityAndHintsFollowTheTopEmotion) {
  mm::SimulationOptions o;
  o.decay_interval = 1.0;
  mm::World w({make_alice()}, o);
  std::vector<mm::TriggeredAction> out;
  w.apply(event(0.0, "alice", "gift"), &out);
  out.clear();
  w.advance_to(2.0, &out);  // linear, 4 s: half way from {0.325, 0.275} to {0.1, 0.3}
  EXPECT_NEAR(w.mood(0)[0], 0.2125, 1e-15);
  EXPECT_NEAR(w.mood(0)[1], 0.2875, 1e-15);
  w.advance_to(10.0, &out);
  EXPECT_EQ(w.mood(0), (std::vector<double>{0.1, 0.3}));
  // Hints at 1, 2, 3 s (not at the end, 4 s); happiness falls below sadness at 0.8 s, so every hint
  // is sadness' representative, sigh.
  ASSERT_EQ(out.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(out[i].time, 1.0 + static_cast<double>(i));
    EXPECT_EQ(out[i].action, "sigh");
    EXPECT_EQ(out[i].cause, mm::Cause::Decay);
  }
  EXPECT_NEAR(out[0].mood, 0.275 + 0.025 * 0.25, 1e-15);
}

TEST(World, NoRepresentativeMeansNoDecayAction) {
  mm::MindMap m = make_alice();
  m.representative = {2, mm::kNone};
  mm::SimulationOptions o;
  o.decay_interval = 1.0;
  mm::World w({m}, o);
  std::vector<mm::TriggeredAction> out;
  w.apply(event(0.0, "alice", "gift"), &out);
  out.clear();
  w.advance_to(10.0, &out);
  EXPECT_TRUE(out.empty());
}

TEST(World, AffectionTowardsTheSourceEntersEq2) {
  mm::MindMap a = make_alice();
  a.traits.lambda = 0.5;
  a.traits.affection = {{"bob", {0.0, 1.0}}};
  mm::MindMap b = make_bob();
  b.actions.push_back({"gift", true, true, "happiness"});
  mm::World w({a, b});
  w.apply(event(0.0, "alice", "gift", "bob"), nullptr);
  // Stimulus = 0.5·{0.8, 0} + 0.5·{0, 1} = {0.4, 0.5};
  // happiness 0.1 + 0.5·(0.2 + 0.05) = 0.225, sadness 0.2 + 0.5·(0.25 + 0.15) = 0.4
  EXPECT_NEAR(w.mood(0)[0], 0.225, 1e-15);
  EXPECT_NEAR(w.mood(0)[1], 0.4, 1e-15);
  // A world stimulus (no source) ignores the affection.
  mm::World w2({a, b});
  w2.apply(event(0.0, "alice", "gift"), nullptr);
  EXPECT_NEAR(w2.mood(0)[0], 0.325, 1e-15);
}

TEST(World, UnknownStimulusIsCopiedFromTheSource) {
  mm::World w({make_alice(), make_bob()});
  std::vector<mm::TriggeredAction> out;
  w.apply(event(1.0, "alice", "insult", "bob"), &out);  // alice knows insult: no copy
  EXPECT_TRUE(w.copied().empty());
  mm::MindMap a = make_alice();
  a.actions.erase(a.actions.begin() + 1);  // alice without insult
  for (auto& e : a.response_edges) e.action -= 1;
  for (auto& e : a.chain_edges) e.from -= 1, e.to -= 1;
  for (auto& r : a.representative) r -= 1;
  a.stimulus_edges = {{0, 0, 0.8}};
  mm::World w3({a, make_bob()});
  w3.apply(event(1.0, "alice", "insult", "bob"), &out);
  ASSERT_EQ(w3.copied().size(), 1u);
  EXPECT_EQ(w3.copied()[0].from, "bob");
  EXPECT_EQ(w3.copied()[0].edges, 1u);  // bob's anger edge is dropped: alice has no anger node
  const mm::MindMap& learnt = w3.map(0);
  const auto ia = learnt.find_action("insult");
  ASSERT_TRUE(ia);
  EXPECT_TRUE(learnt.actions[*ia].receivable);
  ASSERT_EQ(learnt.stimulus_edges.back().action, *ia);
  EXPECT_EQ(learnt.stimulus_edges.back().emotion, 1u);
  EXPECT_EQ(learnt.stimulus_edges.back().weight, 0.3);
  EXPECT_NO_THROW(mm::validate(learnt));
  // sadness at t = 1: decayed starting mood 0.4 + (0.3 − 0.4)/4 = 0.375 → 0.5·0.375 + 0.5·(0.15 + 0.15)
  EXPECT_NEAR(w3.mood(0)[1], 0.3375, 1e-15);
}

TEST(World, WorldStimuliCarryTheirWeights) {
  mm::World w({make_alice(), make_bob()});
  mm::Event e = event(0.0, "*", "explosion");
  e.weights = {{"sadness", 0.9}, {"fear", 1.0}, {"anger", 0.2}};
  std::vector<mm::TriggeredAction> out;
  w.apply(e, &out);
  ASSERT_EQ(w.copied().size(), 2u);
  EXPECT_EQ(w.copied()[0].character, "alice");
  EXPECT_EQ(w.copied()[0].edges, 1u);  // sadness (fear unknown to alice)
  EXPECT_EQ(w.copied()[1].edges, 2u);  // bob: sadness, anger
  EXPECT_EQ(w.copied()[1].from, "world");
  // The learnt stimulus is reused, weights or not.
  w.apply(event(1.0, "bob", "explosion"), &out);
  EXPECT_EQ(w.copied().size(), 2u);
}

TEST(World, BadEventsAreRejectedWithTheirLine) {
  mm::World w({make_alice(), make_bob()});
  mm::Event e = event(0.0, "alice", "explosion");
  e.line = 7;
  try {
    w.apply(e, nullptr);
    FAIL();
  } catch (const emoface::InvalidInput& x) {
    EXPECT_NE(std::string(x.what()).find("line 7"), std::string::npos) << x.what();
  }
  EXPECT_THROW(w.apply(event(0.0, "carol", "gift"), nullptr), emoface::InvalidInput);
  EXPECT_THROW(w.apply(event(0.0, "alice", "gift", "carol"), nullptr), emoface::InvalidInput);
  EXPECT_THROW(w.apply(event(0.0, "bob", "insult", "bob"), nullptr), emoface::InvalidInput);
  EXPECT_THROW(w.apply(event(0.0, "alice", ""), nullptr), emoface::InvalidInput);
  EXPECT_THROW(w.apply(event(std::nan(""), "alice", "gift"), nullptr), emoface::InvalidInput);
  mm::Event bad_weight = event(0.0, "alice", "storm");
  bad_weight.weights = {{"sadness", 1.5}};
  EXPECT_THROW(w.apply(bad_weight, nullptr), emoface::InvalidInput);
  mm::Event emotion_name = event(0.0, "alice", "sadness");
  emotion_name.weights = {{"sadness", 0.5}};
  EXPECT_THROW(w.apply(emotion_name, nullptr), emoface::InvalidInput);
  w.apply(event(2.0, "alice", "gift"), nullptr);
  EXPECT_THROW(w.apply(event(1.0, "alice", "gift"), nullptr), emoface::InvalidInput);
  mm::SimulationOptions strict;
  strict.copy_unknown_stimuli = false;
  mm::World ws({make_alice(), make_bob()}, strict);
  mm::Event copyable = event(0.0, "bob", "gift", "alice");
  EXPECT_THROW(ws.apply(copyable, nullptr), emoface::InvalidInput);
  EXPECT_THROW(mm::World({make_alice(), make_alice()}), emoface::InvalidInput);
}

TEST(World, AFailingEventLeavesTheWorldUnchanged) {
  mm::World w({make_alice(), make_bob()});
  const std::vector<double> before = w.mood(0);
  // alice knows "gift", bob does not and nothing carries its weights: nobody is touched.
  EXPECT_THROW(w.apply(event(1.0, "*", "gift"), nullptr), emoface::InvalidInput);
  EXPECT_EQ(w.mood(0), before);
  EXPECT_EQ(w.time(), 0.0);
  EXPECT_TRUE(w.copied().empty());
  EXPECT_FALSE(w.map(1).find_action("gift"));
}

TEST(World, OptionsAreValidated) {
  auto bad = [](auto mutate) {
    mm::SimulationOptions o;
    mutate(o);
    EXPECT_THROW(o.validate(), emoface::InvalidInput);
  };
  bad([](mm::SimulationOptions& o) { o.tie_tolerance = 1.5; });
  bad([](mm::SimulationOptions& o) { o.chain_delay = -1; });
  bad([](mm::SimulationOptions& o) { o.max_chain_length = 0; });
  bad([](mm::SimulationOptions& o) { o.decay_interval = 0; });
  bad([](mm::SimulationOptions& o) { o.sigmoid_steepness = std::nan(""); });
  bad([](mm::SimulationOptions& o) { o.frame_rate = 0; });
  bad([](mm::SimulationOptions& o) { o.duration = -1; });
  EXPECT_NO_THROW(mm::SimulationOptions{}.validate());
}

TEST(Simulate, SamplesMoodAndIsDeterministic) {
  mm::MindMap a = make_alice();
  a.response_edges[0].weight = 0.32;  // smile and laugh nearly tied for ...
  a.response_edges[1].weight = 0.34;  // ... happiness 0.325
  std::vector<mm::Event> events = {event(2.0, "alice", "gift"), event(0.0, "bob", "insult", "alice"),
                                   event(2.0, "bob", "insult")};
  mm::SimulationOptions o;
  o.frame_rate = 4.0;
  o.decay_interval = 0.5;
  const auto r1 = mm::simulate({a, make_bob()}, events, o);
  EXPECT_EQ(r1.duration, 6.0);  // last event 2 s + longest decay 4 s
  ASSERT_EQ(r1.times.size(), 25u);
  EXPECT_EQ(r1.times[8], 2.0);
  // alice at 2 s: the starting mood decayed half way, {0.15, 0.35}, then the gift (eq. 4):
  // happiness 0.5·0.15 + 0.5·(0.4 + 0.05) = 0.3, sadness 0.5·0.35 + 0.5·0.15 = 0.25
  EXPECT_NEAR(r1.mood[0][8 * 2 + 0], 0.3, 1e-12);
  EXPECT_NEAR(r1.mood[0][8 * 2 + 1], 0.25, 1e-12);
  EXPECT_NEAR(r1.mood[0][4 * 2 + 0], 0.175, 1e-12);  // 1 s: a quarter of the way
  const auto r2 = mm::simulate({a, make_bob()}, events, o);
  EXPECT_EQ(mm::actions_to_ndjson(r1.actions), mm::actions_to_ndjson(r2.actions));
  EXPECT_EQ(r1.mood, r2.mood);
  for (std::size_t k = 1; k < r1.actions.size(); ++k) EXPECT_LE(r1.actions[k - 1].time, r1.actions[k].time);
  std::set<std::string> first_actions;
  for (std::uint64_t seed = 0; seed < 32; ++seed) {
    o.seed = seed;
    for (const auto& act : mm::simulate({a, make_bob()}, events, o).actions)
      if (act.character == "alice" && act.cause == mm::Cause::Stimulus) first_actions.insert(act.action);
  }
  EXPECT_EQ(first_actions, (std::set<std::string>{"smile", "laugh"}));
}

TEST(Simulate, PropertyMoodStaysInRangeForRandomWorlds) {
  emoface::core::Rng rng(11);
  for (int trial = 0; trial < 30; ++trial) {
    mm::MindMap a = make_alice(), b = make_bob();
    for (mm::MindMap* m : {&a, &b}) {
      for (auto& e : m->stimulus_edges) e.weight = rng.uniform();
      for (auto& e : m->response_edges) e.weight = rng.uniform();
      for (auto& v : m->traits.starting_mood) v = rng.uniform();
      for (auto& v : m->traits.personality) v = rng.uniform();
      m->traits.alpha = rng.uniform();
      m->traits.beta = rng.uniform();
      m->traits.decay_curve = static_cast<mm::DecayCurve>(rng.uniform_int(3));
    }
    std::vector<mm::Event> events;
    for (int i = 0; i < 20; ++i)
      events.push_back(event(rng.uniform(0, 10), rng.uniform() < 0.5 ? "alice" : "bob", "insult"));
    mm::SimulationOptions o;
    o.mood_form = trial % 2 ? mm::MoodForm::Printed : mm::MoodForm::Sum;
    o.seed = static_cast<std::uint64_t>(trial);
    const auto r = mm::simulate({a, b}, events, o);
    for (const auto& series : r.mood)
      for (double v : series) {
        ASSERT_GE(v, 0.0);
        ASSERT_LE(v, 1.0);
      }
    for (std::size_t c = 0; c < 2; ++c) {  // the end of the timeline is the personality
      const auto& p = (c == 0 ? a : b).traits.personality;
      for (std::size_t e = 0; e < 2; ++e)
        EXPECT_NEAR(r.mood[c][(r.times.size() - 1) * 2 + e], p[e], 1e-12);
    }
  }
}

TEST(Simulate, PerformedStimuliPropagateBetweenCharactersUpToTheDepth) {
  // bob answers an insult with an insult (receive + perform); alice answers one with "retort", which
  // is also a stimulus, so insults could ping-pong for ever without the depth limit.
  mm::MindMap a = make_alice(), b = make_bob();
  b.response_edges = {{0, 0, 0.7}};  // anger → insult
  a.actions.push_back({"retort", true, true, "anger"});
  a.response_edges.push_back({1, 6, 0.5});  // sadness → retort
  a.stimulus_edges.push_back({6, 1, 0.6});  // retort → sadness
  mm::SimulationOptions o;
  o.tie_tolerance = 0.0;
  o.duration = 2.0;
  const std::vector<mm::Event> events = {event(1.0, "bob", "insult", "alice")};
  auto performed = [&](std::size_t depth) {
    o.propagation_depth = depth;
    std::vector<std::string> seq;
    for (const auto& x : mm::simulate({a, b}, events, o).actions)
      if (x.cause == mm::Cause::Stimulus) seq.push_back(x.character + ":" + x.action + "<-" + x.stimulus);
    return seq;
  };
  EXPECT_EQ(performed(0), (std::vector<std::string>{"bob:insult<-insult"}));
  EXPECT_EQ(performed(1), (std::vector<std::string>{"bob:insult<-insult", "alice:sigh<-insult"}));
  // Depth 3: bob insults, alice sighs (not a stimulus): the chain stops by itself.
  EXPECT_EQ(performed(3), performed(1));
  // With alice retorting, the exchange is cut after `depth` hops; bob learns "retort" from alice.
  a.response_edges = {{1, 6, 0.5}};
  b.response_edges = {{0, 0, 0.7}, {1, 0, 0.4}};  // bob also insults when sad
  const auto r = [&] { o.propagation_depth = 3; return mm::simulate({a, b}, events, o); }();
  std::vector<std::string> seq;
  for (const auto& x : r.actions)
    if (x.cause == mm::Cause::Stimulus) seq.push_back(x.character + ":" + x.action);
  EXPECT_EQ(seq, (std::vector<std::string>{"bob:insult", "alice:retort", "bob:insult", "alice:retort"}));
  ASSERT_EQ(r.copied.size(), 1u);
  EXPECT_EQ(r.copied[0].character, "bob");
  EXPECT_EQ(r.copied[0].stimulus, "retort");
  EXPECT_EQ(r.copied[0].from, "alice");
}
