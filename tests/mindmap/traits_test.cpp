// Issue 19 item 4 (mind maps): addressees, runtime changes of background context and affection
// (paper §6, eqs. 2–4), in the simulation, the files and the DOT export.
#include <gtest/gtest.h>

#include <cmath>

#include "emoface/core/errors.hpp"
#include "emoface/mindmap/dot.hpp"
#include "emoface/mindmap/io.hpp"
#include "emoface/mindmap/simulation.hpp"
#include "fixtures.hpp"

namespace mm = emoface::mindmap;
using mm::test::make_alice;
using mm::test::make_bob;

namespace {
mm::Event stim(double t, std::string to, std::string stimulus, std::string from = {}) {
  mm::Event e;
  e.time = t;
  e.target = std::move(to);
  e.stimulus = std::move(stimulus);
  e.source = std::move(from);
  return e;
}
mm::Event change(double t, std::string to, std::vector<double> context,
                 std::vector<std::pair<std::string, std::vector<double>>> affection = {}) {
  mm::Event e;
  e.time = t;
  e.target = std::move(to);
  e.context = std::move(context);
  e.affection = std::move(affection);
  return e;
}
// bob answers an insult with an insult (receivable and performable: it can propagate).
mm::MindMap insulting_bob(const std::string& name = "bob") {
  mm::MindMap m = make_bob();
  m.character = name;
  m.response_edges = {{0, 0, 0.6}};
  return m;
}
}  // namespace

TEST(Addressee, ResponsesAreAimedAtTheSource) {
  mm::World w({make_alice(), make_bob()});
  std::vector<mm::TriggeredAction> out;
  w.apply(stim(1.0, "alice", "insult", "bob"), &out);
  ASSERT_FALSE(out.empty());
  for (const auto& a : out) EXPECT_EQ(a.addressee, "bob") << a.action;
  out.clear();
  mm::Event world = stim(2.0, "alice", "gift");
  w.apply(world, &out);
  ASSERT_FALSE(out.empty());
  EXPECT_EQ(out[0].addressee, "");  // world stimulus: at nobody
  out.clear();
  w.advance_to(20.0, &out);
  for (const auto& a : out) EXPECT_EQ(a.addressee, "") << "decay";
  // The actions file keeps it ("at") and reads it back.
  std::vector<mm::TriggeredAction> a{
      {1.0, "alice", "sigh", "sadness", "sadness", 0.5, mm::Cause::Stimulus, "insult", 0, "bob"}};
  const auto back = mm::parse_actions(mm::actions_to_ndjson(a), "a.ndjson");
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].addressee, "bob");
}

TEST(Addressee, PropagationCanReachOnlyTheAddressee) {
  auto carol_acted = [](bool to_addressee) {
    mm::SimulationOptions o;
    o.propagation_depth = 1;
    o.propagate_to_addressee = to_addressee;
    const auto r = mm::simulate({make_alice(), insulting_bob(), insulting_bob("carol")},
                                {stim(1.0, "bob", "insult", "alice")}, o);
    bool carol = false, alice = false;
    for (const auto& a : r.actions) {
      carol = carol || (a.character == "carol" && a.cause == mm::Cause::Stimulus);
      alice = alice || (a.character == "alice" && a.cause == mm::Cause::Stimulus);
    }
    EXPECT_TRUE(alice);  // bob's insult at alice reaches her either way
    return carol;
  };
  EXPECT_TRUE(carol_acted(false));  // everyone hears it (the behaviour before issue 19)
  EXPECT_FALSE(carol_acted(true));  // performed at alice: only she reacts
}

TEST(RuntimeTraits, BackgroundContextEntersEq3HandComputed) {
  // alice: mood {0.2, 0.4}, personality {0.1, 0.3}, α = β = 0.5, λ = 0, gift → happiness 0.8.
  // Context {0.5, 0.1}: PTraits = {0.3, 0.2}; eq. 4 (sum form): 0.5·mood + 0.5·(0.5·S + 0.5·PT)
  //   = {0.1, 0.2} + 0.5·({0.4, 0} + {0.15, 0.1}) = {0.375, 0.25}
  // (without the context: {0.1, 0.2} + 0.5·({0.4, 0} + {0.05, 0.15}) = {0.325, 0.275}).
  mm::World w({make_alice()});
  w.apply(change(0.0, "alice", {0.5, 0.1}), nullptr);
  EXPECT_EQ(w.traits(0).background_context, (std::vector<double>{0.5, 0.1}));
  EXPECT_NEAR(w.mood(0)[0], 0.2, 1e-15);  // the mood itself is not touched
  w.apply(stim(0.0, "alice", "gift"), nullptr);
  EXPECT_NEAR(w.mood(0)[0], 0.375, 1e-12);
  EXPECT_NEAR(w.mood(0)[1], 0.25, 1e-12);
  mm::World plain({make_alice()});
  plain.apply(stim(0.0, "alice", "gift"), nullptr);
  EXPECT_NEAR(plain.mood(0)[0], 0.325, 1e-12);
  EXPECT_NEAR(plain.mood(0)[1], 0.275, 1e-12);
}

TEST(RuntimeTraits, AffectionEntersEq2HandComputed) {
  // alice with λ = 0.5; bob insults her: ActionEmot {0, 0.6}. Affection towards bob {0, 1}:
  // Stimulus = 0.5·{0, 0.6} + 0.5·{0, 1} = {0, 0.8}; PT = {0.1, 0.3};
  // mood = {0.1, 0.2} + 0.5·({0, 0.4} + {0.05, 0.15}) = {0.125, 0.475}.
  mm::MindMap alice = make_alice();
  alice.traits.lambda = 0.5;
  mm::World w({alice, make_bob()});
  w.apply(change(0.0, "alice", {}, {{"bob", {0.0, 1.0}}}), nullptr);
  ASSERT_NE(w.traits(0).affection_towards("bob"), nullptr);
  w.apply(stim(0.0, "alice", "insult", "bob"), nullptr);
  EXPECT_NEAR(w.mood(0)[0], 0.125, 1e-12);
  EXPECT_NEAR(w.mood(0)[1], 0.475, 1e-12);
  // An empty row removes it: Stimulus = ActionEmot again.
  w.set_affection(0, "bob", {});
  EXPECT_EQ(w.traits(0).affection_towards("bob"), nullptr);
}

TEST(RuntimeTraits, BadChangesAreRefusedAndChangeNothing) {
  mm::World w({make_alice(), make_bob()});
  const mm::Traits before = w.traits(0);
  EXPECT_THROW(w.apply(change(1.0, "alice", {0.5}), nullptr), emoface::InvalidInput);  // size
  EXPECT_THROW(w.apply(change(1.0, "alice", {0.5, 1.5}), nullptr), emoface::InvalidInput);
  EXPECT_THROW(w.apply(change(1.0, "alice", {0.5, std::nan("")}), nullptr), emoface::InvalidInput);
  EXPECT_THROW(w.apply(change(1.0, "nobody", {0.5, 0.5}), nullptr), emoface::InvalidInput);
  EXPECT_THROW(w.apply(change(1.0, "alice", {}, {{"alice", {0.1, 0.1}}}), nullptr),
               emoface::InvalidInput);
  EXPECT_THROW(w.apply(change(1.0, "alice", {}, {{"bob", {0.1}}}), nullptr), emoface::InvalidInput);
  // "*": bob's map has 2 emotions as well; a bad row for anyone stops the whole change.
  EXPECT_THROW(w.apply(change(1.0, "*", {0.2, -0.1}), nullptr), emoface::InvalidInput);
  EXPECT_EQ(w.traits(0).background_context, before.background_context);
  EXPECT_TRUE(w.traits(0).affection.empty());
  EXPECT_EQ(w.time(), 0.0);
  EXPECT_THROW(w.set_background_context(0, {2.0, 0.0}), emoface::InvalidInput);
  EXPECT_THROW(w.set_affection(0, "", {0.1, 0.1}), emoface::InvalidInput);
  w.apply(change(1.0, "*", {0.2, 0.3}), nullptr);
  EXPECT_EQ(w.traits(1).background_context, (std::vector<double>{0.2, 0.3}));
}

TEST(RuntimeTraits, EventFilesCarryChangesWithLocatedErrors) {
  const std::string text =
      "{\"time\": 1, \"to\": \"alice\", \"context\": [0.5, 0.1]}\n"
      "{\"time\": 2, \"to\": \"alice\", \"affection\": {\"bob\": [0, 1]}}\n"
      "{\"time\": 3, \"to\": \"alice\", \"stimulus\": \"gift\"}\n";
  const auto ev = mm::parse_events(text, "e.ndjson");
  ASSERT_EQ(ev.size(), 3u);
  EXPECT_TRUE(ev[0].changes_traits());
  EXPECT_EQ(ev[0].context, (std::vector<double>{0.5, 0.1}));
  EXPECT_EQ(ev[1].affection.at(0).first, "bob");
  EXPECT_FALSE(ev[2].changes_traits());
  const auto again = mm::parse_events(mm::events_to_ndjson(ev), "e2.ndjson");
  ASSERT_EQ(again.size(), 3u);
  EXPECT_EQ(again[0].context, ev[0].context);
  EXPECT_EQ(again[1].affection, ev[1].affection);
  EXPECT_EQ(again[2].stimulus, "gift");
  auto error_of = [](const std::string& t) -> std::string {
    try {
      mm::parse_events(t, "bad.ndjson");
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  };
  for (const auto& [line, where] : std::vector<std::pair<std::string, std::string>>{
           {R"({"time": 1, "to": "a", "stimulus": "gift", "context": [0.1]})", "/stimulus"},
           {R"({"time": 1, "to": "a", "context": 0.5})", "/context"},
           {R"({"time": 1, "to": "a", "context": [0.1, 1.5]})", "/context/1"},
           {R"({"time": 1, "to": "a", "context": []})", "/context"},
           {R"({"time": 1, "to": "a", "affection": [1]})", "/affection"},
           {R"({"time": 1, "to": "a", "affection": {"b": [0.1, "x"]}})", "/affection/b/1"},
           {R"({"time": 1, "to": "a"})", "stimulus"}}) {
    const std::string e = error_of(line + "\n");
    EXPECT_NE(e.find("bad.ndjson"), std::string::npos) << line << ": " << e;
    EXPECT_NE(e.find(where), std::string::npos) << line << ": " << e;
  }
  // simulate() applies them in time order.
  mm::SimulationOptions o;
  const auto r = mm::simulate({make_alice(), make_bob()}, ev, o);
  EXPECT_FALSE(r.actions.empty());
}

TEST(RuntimeTraits, DotShowsContextAndAffection) {
  mm::MindMap m = make_alice();
  m.traits.background_context = {0.5, 0.1};
  m.traits.affection = {{"bob", {0.0, 0.7}}};
  const std::string dot = mm::mind_map_dot(m);
  EXPECT_NE(dot.find("context 0.50"), std::string::npos) << dot;
  EXPECT_NE(dot.find("\"bob\""), std::string::npos);
  EXPECT_NE(dot.find("affection\\nsadness 0.70"), std::string::npos) << dot;
}

TEST(RuntimeTraits, ShippedExampleRuns) {
  const std::string dir = std::string(EMOFACE_SOURCE_DIR) + "/data/mindmap";
  const auto maps = mm::read_mind_map_dir(dir + "/characters");
  const auto events = mm::read_events(dir + "/events_traits.ndjson");
  const auto r = mm::simulate(maps, events, {});
  bool at_ben = false;
  for (const auto& a : r.actions) at_ben = at_ben || (a.character == "ana" && a.addressee == "ben");
  EXPECT_TRUE(at_ben);
  std::size_t ana = 0;
  while (maps[ana].character != "ana") ++ana;
  const mm::MindMap before = mm::map_at(maps, events, ana, 3.0);
  const mm::MindMap after = mm::map_at(maps, events, ana, 14.0);
  EXPECT_EQ(before.traits.background_context, maps[ana].traits.background_context);
  EXPECT_EQ(after.traits.background_context, (std::vector<double>{0.9, 0.0, 0.0, 0.2, 0.0, 0.1}));
  ASSERT_NE(after.traits.affection_towards("ben"), nullptr);
  EXPECT_EQ(*after.traits.affection_towards("ben"),
            (std::vector<double>{0.0, 0.3, 0.8, 0.0, 0.1, 0.0}));
  EXPECT_THROW(mm::map_at(maps, events, 7, 1.0), emoface::InvalidInput);
}
