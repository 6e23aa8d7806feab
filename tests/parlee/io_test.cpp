#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/parlee/io.hpp"

using namespace emoface::parlee;
using emoface::FormatError;

namespace {
const std::string kData = std::string(EMOFACE_SOURCE_DIR) + "/data/parlee/";

std::string pointer_of(const std::string& text) {
  try {
    parse_agent(text, "a.json");
  } catch (const FormatError& e) {
    return e.where().json_pointer.empty() ? "<none>" : e.where().json_pointer;
  }
  return "";
}
}  // namespace

TEST(AgentFile, RoundTrip) {
  AgentConfig c;
  c.name = "odd";
  c.self = "agent";
  c.seed = 99;
  c.personality[Trait::ReasoningFocus] = 0.125;
  c.personality[Trait::FeelingLevel] = 0.875;
  c.emotions.alpha[3] = 0.3;
  c.emotions.decay[7] = 0.5;
  c.emotions.decay_model = DecayModel::Product;
  c.emotions.effect[2][5] = 0.25;
  c.motivation.pain = 0.5;
  c.planning.horizon = 4;
  c.planning.model_depth = 2;
  c.planning.semantics = GoalSemantics::AtHorizon;
  c.learn_outcomes = true;
  c.learning_prior = 3.5;
  c.liking["user"] = -0.25;
  c.praiseworthiness["eat"] = 0.5;
  c.body_events["eat"] = BodyEvent::Eat;
  c.appraisal.prospect = ProspectMode::PerGoal;
  c.appraisal.surprise_threshold = 0.25;
  c.appraisal.compound = CompoundRule::Standards;
  c.on_disallowed = DisallowedEvent::Stop;
  c.replenishment = {{"feed-self", Need::Thirst, 0.75}};
  c.decay_clock = DecayClock::Step;
  c.time_unit_seconds = 1.5;
  c.emotions.step_seconds = 2.0;
  c.emotions.low_intensity_rate = 0.125;
  const std::string text = write_agent(c);
  const AgentConfig d = parse_agent(text, "x.json");
  EXPECT_EQ(write_agent(d), text);
  EXPECT_EQ(d.personality.values, c.personality.values);
  EXPECT_EQ(d.emotions.effect, c.emotions.effect);
  EXPECT_EQ(d.planning.semantics, GoalSemantics::AtHorizon);
  EXPECT_EQ(d.liking.at("user"), -0.25);
  EXPECT_EQ(d.appraisal.prospect, ProspectMode::PerGoal);
  EXPECT_EQ(d.appraisal.surprise_threshold, 0.25);
  EXPECT_EQ(d.appraisal.compound, CompoundRule::Standards);
  EXPECT_EQ(d.on_disallowed, DisallowedEvent::Stop);
  ASSERT_EQ(d.replenishment.size(), 1u);
  EXPECT_EQ(d.replenishment[0].need, Need::Thirst);
  EXPECT_EQ(d.replenishment[0].threshold, 0.75);
  EXPECT_EQ(d.decay_clock, DecayClock::Step);
  EXPECT_EQ(d.time_unit_seconds, 1.5);
  EXPECT_EQ(d.emotions.step_seconds, 2.0);
  EXPECT_EQ(d.emotions.low_intensity_rate, 0.125);
}

TEST(AgentFile, ShippedFilesParse) {
  for (const char* f : {"neutral", "pessimistic", "realistic", "sensitive", "fan_for",
                        "fan_against", "bread_neutral", "bread_optimistic", "bread_sensitive"}) {
    const AgentConfig c = read_agent_file(kData + "agents/" + f + ".json");
    EXPECT_EQ(c.name, f);
    EXPECT_NO_THROW(c.validate());
  }
  EXPECT_EQ(read_agent_file(kData + "agents/pessimistic.json").personality[Trait::ReasoningFocus], 0.1);
}

TEST(AgentFile, BadInputNamesThePointer) {
  const std::string head = R"({"format":"emoface.parlee_agent","version":"1.0",)";
  EXPECT_EQ(pointer_of(head + R"("personality":{"reasoning_focus":1.5}})"), "/personality/reasoning_focus");
  EXPECT_EQ(pointer_of(head + R"("personality":{"courage":0.5}})"), "/personality/courage");
  EXPECT_EQ(pointer_of(head + R"("personality":{"feeling_level":"high"}})"), "/personality/feeling_level");
  EXPECT_EQ(pointer_of(head + R"("emotions":{"alpha":{"glee":0.1}}})"), "/emotions/alpha/glee");
  EXPECT_EQ(pointer_of(head + R"("emotions":{"effect":[{"from":"joy","to":"fear","value":0.7},{"from":"hope","to":"fear","value":0.7}]}})"),
            "/emotions");  // column sum 1.4 > 1
  EXPECT_EQ(pointer_of(head + R"("emotions":{"effect":[{"from":"joy","value":0.7}]}})"), "/emotions/effect/0");
  EXPECT_EQ(pointer_of(head + R"("planning":{"horizon":1000}})"), "/planning/horizon");
  EXPECT_EQ(pointer_of(head + R"("planning":{"horizon":2.5}})"), "/planning/horizon");
  EXPECT_EQ(pointer_of(head + R"("liking":{"user":-3}})"), "/liking/user");
  EXPECT_EQ(pointer_of(head + R"("seed":-1})"), "/seed");
  EXPECT_EQ(pointer_of(head + R"("bogus":1})"), "/bogus");
  EXPECT_EQ(pointer_of(head + R"("body_events":{"eat":"nap"}})"), "/body_events/eat");
  EXPECT_EQ(pointer_of(head + R"("appraisal":{"prospect":"clamp"}})"), "/appraisal/prospect");
  EXPECT_EQ(pointer_of(head + R"("appraisal":{"prospect":3}})"), "/appraisal/prospect");
  EXPECT_EQ(pointer_of(head + R"("appraisal":{"surprise_threshold":0}})"),
            "/appraisal/surprise_threshold");
  EXPECT_EQ(pointer_of(head + R"("appraisal":{"surprise_threshold":1.5}})"),
            "/appraisal/surprise_threshold");
  EXPECT_EQ(pointer_of(head + R"("appraisal":{"pivot":0.5}})"), "/appraisal/pivot");
  EXPECT_EQ(pointer_of(head + R"("on_disallowed":"ignore"})"), "/on_disallowed");
  EXPECT_EQ(pointer_of(head + R"("appraisal":{"compound":"occ"}})"), "/appraisal/compound");
  EXPECT_EQ(pointer_of(head + R"("on_disallowed":true})"), "/on_disallowed");
  EXPECT_EQ(pointer_of(head + R"("replenishment":{}})"), "/replenishment");
  EXPECT_EQ(pointer_of(head + R"("replenishment":[{"need":"hunger"}]})"), "/replenishment/0");
  EXPECT_EQ(pointer_of(head + R"("replenishment":[{"goal":"g","need":"boredom"}]})"),
            "/replenishment/0/need");
  EXPECT_EQ(pointer_of(head + R"("replenishment":[{"goal":"g","threshold":0}]})"),
            "/replenishment/0/threshold");
  EXPECT_EQ(pointer_of(head + R"("replenishment":[{"goal":"g","x":1}]})"), "/replenishment/0/x");
  // issue 17 item 3: decay per second
  EXPECT_EQ(pointer_of(head + R"("decay_clock":"minutes"})"), "/decay_clock");
  EXPECT_EQ(pointer_of(head + R"("decay_clock":1})"), "/decay_clock");
  EXPECT_EQ(pointer_of(head + R"("time_unit_seconds":0})"), "/time_unit_seconds");
  EXPECT_EQ(pointer_of(head + R"("time_unit_seconds":-60})"), "/time_unit_seconds");
  EXPECT_EQ(pointer_of(head + R"("time_unit_seconds":"60"})"), "/time_unit_seconds");
  EXPECT_EQ(pointer_of(head + R"("emotions":{"step_seconds":0}})"), "/emotions/step_seconds");
  EXPECT_EQ(pointer_of(head + R"("emotions":{"step_seconds":1e300}})"), "/emotions/step_seconds");
  EXPECT_EQ(pointer_of(head + R"("emotions":{"low_intensity_rate":1.5}})"),
            "/emotions/low_intensity_rate");
  EXPECT_EQ(pointer_of(head + R"("emotions":{"low_intensity_rate":null}})"),
            "/emotions/low_intensity_rate");
  EXPECT_NE(pointer_of(R"({"format":"emoface.parlee_agent","version":"2.0"})"), "");
  EXPECT_NE(pointer_of(R"({"format":"emoface.rig","version":"1.0"})"), "");
  EXPECT_NE(pointer_of(head + R"("name":"x")"), "");  // truncated
  EXPECT_NE(pointer_of("[1,2]"), "");
  EXPECT_NE(pointer_of(head + R"("motivation":{"pain":1e400}})"), "");
}

TEST(Events, ParseWriteRoundTripAndErrors) {
  const std::string text =
      "{\"time\":1,\"action\":\"(shot team)\",\"outcome\":\"goal\",\"note\":\"x\"}\n\n"
      "{\"time\":2.5,\"action\":\"\",\"feedback\":-0.5}\n";
  const auto ev = parse_events(text, "e.ndjson");
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].outcome, "goal");
  EXPECT_EQ(*ev[1].feedback, -0.5);
  const std::string w = write_events(ev);
  EXPECT_EQ(write_events(parse_events(w, "w")), w);
  auto line_of = [](const std::string& t) -> std::size_t {
    try {
      parse_events(t, "e");
    } catch (const FormatError& e) {
      return e.where().line;
    }
    return 0;
  };
  EXPECT_EQ(line_of("{\"time\":1}\n{\"time\":0}\n"), 2u);  // time decreases
  EXPECT_EQ(line_of("{\"time\":1}\n\n{\"time\":2,\"x\":1}\n"), 3u);
  EXPECT_EQ(line_of("{\"time\":1,\"action\":\"(a\"\n"), 1u);  // truncated
  EXPECT_EQ(line_of("{\"time\":-1}\n"), 1u);
  EXPECT_EQ(line_of("{\"time\":1e300}\n"), 1u);
  EXPECT_EQ(line_of("{\"time\":1,\"feedback\":3}\n"), 1u);
  EXPECT_EQ(line_of("[1]\n"), 1u);
  EXPECT_EQ(line_of("{\"time\":1,\"action\":5}\n"), 1u);
  const auto match = read_events_file(kData + "match.ndjson");
  EXPECT_EQ(match.size(), 91u);
}

TEST(Timeline, LineNamesEveryEmotionAndTheEsv) {
  StepRecord r;
  r.step = 3;
  r.time = 12;
  r.goal_names = {"win"};
  r.goal_probability = {0.25};
  r.goal_status = {GoalStatus::Unconfirmed};
  r.emotions[index(Emotion::Fear)] = 0.5;
  r.basic[3] = 0.4;
  r.actions.push_back({"team", "(shot oteam)", "goal", 0.06, "+(score minus-one)"});
  const std::string line = timeline_line(r);
  ASSERT_EQ(line.back(), '\n');
  const auto j = nlohmann::json::parse(line);
  EXPECT_EQ(j["emotions"].size(), kEmotionCount);
  EXPECT_EQ(j["emotions"]["fear"], 0.5);
  EXPECT_EQ(j["esv"].size(), 6u);
  EXPECT_EQ(j["esv"]["fear"], 0.4);
  EXPECT_EQ(j["goals"]["win"]["status"], "unconfirmed");
  EXPECT_EQ(j["events"][0]["outcome"], "goal");
}

// The unknown-field rule of docs/formats.md (core::JsonReader): the agent reader is 1.1; a 1.0 or
// 1.1 file rejects a field it does not know (at the root or nested), a 1.2 file may add fields.
TEST(AgentFile, UnknownFieldRule) {
  for (const char* version : {"1.0", "1.1"}) {
    const std::string head =
        std::string(R"({"format":"emoface.parlee_agent","version":")") + version + R"(",)";
    EXPECT_EQ(pointer_of(head + R"("mood":1})"), "/mood") << version;
    EXPECT_EQ(pointer_of(head + R"("planning":{"horizon":2,"beam":3}})"), "/planning/beam");
    EXPECT_EQ(
        pointer_of(head +
                   R"("emotions":{"effect":[{"from":"joy","to":"fear","value":0.1,"w":1}]}})"),
        "/emotions/effect/0/w");
    try {
      parse_agent(head + R"("mood":1})", "a.json");
    } catch (const FormatError& e) {
      EXPECT_STREQ(e.what(), "a.json: at /mood: unknown field \"mood\"");
    }
  }
  const std::string newer = R"({"format":"emoface.parlee_agent","version":"1.2",)";
  EXPECT_EQ(pointer_of(newer + R"("mood":1,"planning":{"horizon":2,"beam":3},"name":"n"})"), "");
  EXPECT_EQ(parse_agent(newer + R"("mood":1,"planning":{"horizon":2,"beam":3}})", "a.json")
                .planning.horizon,
            2);
  // Known fields are still checked in a newer minor.
  EXPECT_EQ(pointer_of(newer + R"("planning":{"horizon":2.5}})"), "/planning/horizon");
}

TEST(Events, UnknownFieldsAreErrors) {
  // Events carry no version: every field must be known.
  try {
    parse_events("{\"time\":1,\"action\":\"a\"}\n{\"time\":2,\"action\":\"b\",\"x\":1}\n", "e");
    ADD_FAILURE();
  } catch (const FormatError& e) {
    EXPECT_STREQ(e.what(), "e:2: unknown field \"x\"");
  }
}
