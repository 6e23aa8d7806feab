#include "emoface/mindmap/mind_map.hpp"

#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "fixtures.hpp"

namespace mm = emoface::mindmap;
using mm::test::make_alice;

TEST(MindMap, FixtureIsValidAndLookupsWork) {
  const mm::MindMap m = make_alice();
  EXPECT_NO_THROW(mm::validate(m));
  EXPECT_EQ(m.find_emotion("sadness"), 1u);
  EXPECT_FALSE(m.find_emotion("smile"));
  EXPECT_EQ(m.find_action("wave"), 5u);
  EXPECT_EQ(m.representative_of(1), 4u);
  mm::MindMap no_reps = m;
  no_reps.representative.clear();
  EXPECT_NO_THROW(mm::validate(no_reps));
  EXPECT_EQ(no_reps.representative_of(0), mm::kNone);
  EXPECT_EQ(m.traits.affection_towards("bob"), nullptr);
}

TEST(MindMap, EveryBrokenInvariantIsRejected) {
  const std::vector<std::pair<const char*, std::function<void(mm::MindMap&)>>> cases = {
      {"empty character", [](mm::MindMap& m) { m.character.clear(); }},
      {"no emotions", [](mm::MindMap& m) { m.emotions.clear(); }},
      {"duplicate emotion", [](mm::MindMap& m) { m.emotions[1] = "happiness"; }},
      {"action named like an emotion", [](mm::MindMap& m) { m.actions[0].name = "sadness"; }},
      {"duplicate action", [](mm::MindMap& m) { m.actions[1].name = "gift"; }},
      {"empty action name", [](mm::MindMap& m) { m.actions[1].name.clear(); }},
      {"neither received nor performed", [](mm::MindMap& m) { m.actions[0].receivable = false; }},
      {"performing without label", [](mm::MindMap& m) { m.actions[2].label.clear(); }},
      {"stimulus edge from performing-only", [](mm::MindMap& m) { m.stimulus_edges[0].action = 2; }},
      {"dangling stimulus edge", [](mm::MindMap& m) { m.stimulus_edges[0].emotion = 2; }},
      {"dangling response edge", [](mm::MindMap& m) { m.response_edges[0].action = 99; }},
      {"response to a stimulus-only", [](mm::MindMap& m) { m.response_edges[0].action = 0; }},
      {"weight above 1", [](mm::MindMap& m) { m.stimulus_edges[0].weight = 1.5; }},
      {"negative weight", [](mm::MindMap& m) { m.response_edges[0].weight = -0.1; }},
      {"NaN weight", [](mm::MindMap& m) { m.response_edges[0].weight = std::nan(""); }},
      {"duplicate stimulus edge", [](mm::MindMap& m) { m.stimulus_edges.push_back({0, 0, 0.1}); }},
      {"duplicate response edge", [](mm::MindMap& m) { m.response_edges.push_back({0, 2, 0.1}); }},
      {"chain to itself", [](mm::MindMap& m) { m.chain_edges.push_back({3, 3}); }},
      {"chain from stimulus", [](mm::MindMap& m) { m.chain_edges.push_back({0, 3}); }},
      {"duplicate chain", [](mm::MindMap& m) { m.chain_edges.push_back({2, 5}); }},
      {"representatives wrong size", [](mm::MindMap& m) { m.representative.push_back(2); }},
      {"representative not performable", [](mm::MindMap& m) { m.representative[0] = 0; }},
      {"representative missing", [](mm::MindMap& m) { m.representative[0] = 42; }},
      {"starting mood missing", [](mm::MindMap& m) { m.traits.starting_mood.clear(); }},
      {"personality too long", [](mm::MindMap& m) { m.traits.personality.push_back(0.1); }},
      {"personality out of range", [](mm::MindMap& m) { m.traits.personality[1] = 1.01; }},
      {"background wrong size", [](mm::MindMap& m) { m.traits.background_context = {0.1}; }},
      {"affection wrong size", [](mm::MindMap& m) { m.traits.affection = {{"bob", {0.1}}}; }},
      {"affection duplicate", [](mm::MindMap& m) { m.traits.affection = {{"bob", {0, 0}}, {"bob", {0, 0}}}; }},
      {"affection unnamed", [](mm::MindMap& m) { m.traits.affection = {{"", {0, 0}}}; }},
      {"lambda", [](mm::MindMap& m) { m.traits.lambda = 2.0; }},
      {"alpha", [](mm::MindMap& m) { m.traits.alpha = -1.0; }},
      {"beta", [](mm::MindMap& m) { m.traits.beta = INFINITY; }},
      {"decay duration 0", [](mm::MindMap& m) { m.traits.decay_duration = 0.0; }},
      {"decay duration NaN", [](mm::MindMap& m) { m.traits.decay_duration = std::nan(""); }},
  };
  for (const auto& [what, mutate] : cases) {
    mm::MindMap m = make_alice();
    mutate(m);
    EXPECT_THROW(mm::validate(m), emoface::InvalidInput) << what;
  }
}

TEST(MindMap, MessagesNameTheCharacterAndTheProblem) {
  mm::MindMap m = make_alice();
  m.stimulus_edges[0].weight = 1.5;
  try {
    mm::validate(m);
    FAIL();
  } catch (const emoface::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("alice"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("gift -> happiness"), std::string::npos);
  }
}

TEST(MindMap, LabelsAreCheckedAgainstAKnownSet) {
  const mm::MindMap m = make_alice();
  EXPECT_NO_THROW(mm::validate_labels(m, {"happiness", "sadness", "anger"}));
  try {
    mm::validate_labels(m, {"happiness", "anger"});
    FAIL();
  } catch (const emoface::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("\"sigh\" has unknown expression label \"sadness\""), std::string::npos)
        << e.what();
  }
}

TEST(MindMap, SummaryCountsNodesActionsAndEdges) {
  // alice: 2 emotions, 6 actions, 2 stimulus + 3 response + 1 chain edges (fixtures.hpp).
  EXPECT_EQ(mm::summary(mm::test::make_alice()), "alice: 2 emotion nodes, 6 actions, 6 edges");
  EXPECT_EQ(mm::summary(mm::test::make_bob()), "bob: 2 emotion nodes, 2 actions, 3 edges");
}
