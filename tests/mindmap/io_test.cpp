#include "emoface/mindmap/io.hpp"

#include <filesystem>
#include <fstream>
#include <functional>

#include <gtest/gtest.h>

#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "fixtures.hpp"

namespace mm = emoface::mindmap;
using mm::test::make_alice;
using mm::test::make_bob;
using Json = nlohmann::ordered_json;

namespace {

bool same(const mm::MindMap& a, const mm::MindMap& b) { return mm::to_json_text(a) == mm::to_json_text(b); }

// Applies `edit` to alice's document and expects a FormatError at `pointer` whose message contains `text`.
void expect_error(const std::function<void(Json&)>& edit, const std::string& pointer, const std::string& text) {
  Json doc = Json::parse(mm::to_json_text(make_alice()));
  edit(doc);
  try {
    mm::parse_mind_map(doc.dump(), "alice.json");
    ADD_FAILURE() << "no error for " << pointer;
  } catch (const emoface::FormatError& e) {
    EXPECT_EQ(e.where().file, "alice.json");
    EXPECT_EQ(e.where().json_pointer, pointer) << e.what();
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(MindMapIo, RoundTripKeepsEverything) {
  mm::MindMap a = make_alice();
  a.traits.background_context = {0.25, 0.125};
  a.traits.affection = {{"bob", {0.1, 0.9}}, {"carol", {0.3, 0.7}}};
  a.traits.lambda = 0.1 + 0.2;  // not exactly representable in short decimal: must round-trip
  a.traits.decay_curve = mm::DecayCurve::Sigmoid;
  a.actions.push_back({"hug", true, true, "happiness"});
  const std::string text = mm::to_json_text(a);
  const mm::MindMap b = mm::parse_mind_map(text, "a.json");
  EXPECT_EQ(mm::to_json_text(b), text);
  EXPECT_EQ(b.traits.lambda, a.traits.lambda);
  EXPECT_EQ(b.traits.affection, a.traits.affection);
  EXPECT_EQ(b.representative, a.representative);
  EXPECT_EQ(b.actions[6].receivable && b.actions[6].performable, true);
  EXPECT_TRUE(same(mm::parse_mind_map(mm::to_json_text(make_bob())), make_bob()));  // no representatives
  EXPECT_TRUE(mm::parse_mind_map(mm::to_json_text(make_bob())).representative.empty());
  const Json doc = Json::parse(text);
  EXPECT_EQ(doc["format"], "emoface.mindmap");
  EXPECT_EQ(doc["version"], "1.0");
}

TEST(MindMapIo, FilesAndDirectoriesRoundTrip) {
  const auto dir = std::filesystem::temp_directory_path() / "emoface_mindmap_io_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  mm::write_mind_map(make_bob(), (dir / "b.json").string());
  mm::write_mind_map(make_alice(), (dir / "a.json").string());
  emoface::core::write_file_atomic((dir / "notes.txt").string(), "not a map");
  const auto maps = mm::read_mind_map_dir(dir.string());
  ASSERT_EQ(maps.size(), 2u);
  EXPECT_EQ(maps[0].character, "alice");  // sorted by file name
  EXPECT_TRUE(same(maps[1], make_bob()));
  EXPECT_THROW(mm::read_mind_map_dir(dir.string(), {"anger"}), emoface::FormatError);  // alice's labels
  mm::write_mind_map(make_alice(), (dir / "c.json").string());
  EXPECT_THROW(mm::read_mind_map_dir(dir.string()), emoface::InvalidInput);  // alice twice
  EXPECT_THROW(mm::read_mind_map_dir((dir / "missing").string()), emoface::IoError);
  EXPECT_THROW(mm::read_mind_map((dir / "missing.json").string()), emoface::IoError);
  std::filesystem::remove_all(dir);
}

TEST(MindMapIo, BadDocumentsNameTheField) {
  expect_error([](Json& d) { d["format"] = "emoface.rig"; }, "/format", "unknown format");
  expect_error([](Json& d) { d["version"] = "2.0"; }, "/version", "newer");
  expect_error([](Json& d) { d.erase("traits"); }, "", "\"traits\"");
  expect_error([](Json& d) { d["traits"].erase("personality"); }, "/traits", "\"personality\"");
  expect_error([](Json& d) { d["traits"].erase("starting_mood"); }, "/traits", "\"starting_mood\"");
  expect_error([](Json& d) { d["traits"]["personality"].push_back(0.5); }, "/traits/personality",
               "one per emotion node");
  expect_error([](Json& d) { d["traits"]["background_context"] = {0.5}; }, "/traits/background_context",
               "expected one per emotion node (2)");
  expect_error([](Json& d) { d["traits"]["affection"] = {{"bob", {0.1, 0.2, 0.3}}}; }, "/traits/affection/bob",
               "one per emotion node");
  expect_error([](Json& d) { d["traits"]["starting_mood"][1] = 1.5; }, "/traits/starting_mood/1", "out of range");
  expect_error([](Json& d) { d["traits"]["starting_mood"][0] = "high"; }, "/traits/starting_mood/0", "number");
  expect_error([](Json& d) { d["traits"]["beta"] = -0.5; }, "/traits/beta", "out of range");
  expect_error([](Json& d) { d["traits"]["decay"]["curve"] = "cubic"; }, "/traits/decay/curve", "unknown curve");
  expect_error([](Json& d) { d["traits"]["decay"]["duration"] = 0; }, "/traits/decay/duration", "out of range");
  expect_error([](Json& d) { d["stimulus_edges"][0]["weight"] = 1.01; }, "/stimulus_edges/0/weight", "out of range");
  expect_error([](Json& d) { d["response_edges"][1]["weight"] = -1; }, "/response_edges/1/weight", "out of range");
  expect_error([](Json& d) { d["stimulus_edges"][0]["emotion"] = "joy"; }, "/stimulus_edges/0/emotion",
               "dangling edge");
  expect_error([](Json& d) { d["response_edges"][0]["action"] = "dance"; }, "/response_edges/0/action",
               "dangling edge");
  expect_error([](Json& d) { d["response_edges"][0]["action"] = "gift"; }, "/response_edges/0/action",
               "cannot be performed");
  expect_error([](Json& d) { d["stimulus_edges"][0]["stimulus"] = "smile"; }, "/stimulus_edges/0/stimulus",
               "cannot be received");
  expect_error([](Json& d) { d["chain_edges"][0]["to"] = "nowhere"; }, "/chain_edges/0/to", "dangling edge");
  expect_error([](Json& d) { d["chain_edges"][0]["to"] = "smile"; }, "/chain_edges/0", "itself");
  expect_error([](Json& d) { d["chain_edges"].push_back(d["chain_edges"][0]); }, "/chain_edges/1", "duplicate");
  expect_error([](Json& d) { d["representatives"]["joy"] = "smile"; }, "/representatives/joy", "no emotion");
  expect_error([](Json& d) { d["representatives"]["sadness"] = "gift"; }, "/representatives/sadness",
               "cannot be performed");
  expect_error([](Json& d) { d["emotions"].push_back("happiness"); }, "/emotions/2", "duplicate");
  expect_error([](Json& d) { d["emotions"] = Json::array(); }, "/emotions", "at least one");
  expect_error([](Json& d) { d["emotions"][0] = 3; }, "/emotions/0", "string");
  expect_error([](Json& d) { d["actions"][2].erase("label"); }, "/actions/2", "label");
  expect_error([](Json& d) { d["actions"][0].erase("receive"); }, "/actions/0", "received and/or performed");
  expect_error([](Json& d) { d["actions"][1]["name"] = "gift"; }, "/actions/1/name", "duplicate");
  expect_error([](Json& d) { d["actions"][1]["name"] = "sadness"; }, "/actions/1/name", "duplicate");
  expect_error([](Json& d) { d["actions"][0]["receive"] = 1; }, "/actions/0/receive", "true or false");
  expect_error([](Json& d) { d["traits"]["mood"] = 1; }, "/traits/mood", "unknown field");
  expect_error([](Json& d) { d["character"] = ""; }, "/character", "non-empty");
  expect_error([](Json& d) { d["actions"] = Json::object(); }, "/actions", "array");
}

TEST(MindMapIo, NewerMinorVersionMayAddFields) {
  Json doc = Json::parse(mm::to_json_text(make_alice()));
  doc["version"] = "1.3";
  doc["traits"]["new_trait"] = 1;
  EXPECT_NO_THROW(mm::parse_mind_map(doc.dump()));
}

TEST(MindMapIo, UnknownLabelsAreRejectedWhenLabelsAreKnown) {
  const std::string text = mm::to_json_text(make_alice());
  EXPECT_NO_THROW(mm::parse_mind_map(text, "a.json", {"happiness", "sadness"}));
  try {
    mm::parse_mind_map(text, "a.json", {"happiness", "anger"});
    FAIL();
  } catch (const emoface::FormatError& e) {
    EXPECT_EQ(e.where().json_pointer, "/actions/4/label");
    EXPECT_NE(std::string(e.what()).find("unknown expression label \"sadness\""), std::string::npos);
  }
}

TEST(MindMapIo, MalformedTruncatedAndHugeInputs) {
  const std::string text = mm::to_json_text(make_alice());
  for (std::size_t cut : {std::size_t{0}, std::size_t{1}, text.size() / 3, text.size() / 2, text.size() - 3}) {
    EXPECT_THROW(mm::parse_mind_map(text.substr(0, cut), "t.json"), emoface::FormatError) << cut;
  }
  EXPECT_THROW(mm::parse_mind_map("{\"format\": NaN}", "t.json"), emoface::FormatError);
  std::string inf = text;
  inf.replace(inf.find("\"lambda\": 0.0") + 10, 3, "1e999");
  EXPECT_THROW(mm::parse_mind_map(inf, "t.json"), emoface::FormatError);
  EXPECT_THROW(mm::parse_mind_map(std::string(100000, '['), "t.json"), emoface::FormatError);
  EXPECT_THROW(mm::parse_mind_map("[1, 2]", "t.json"), emoface::FormatError);
  EXPECT_THROW(mm::parse_mind_map(std::string("{\"a\":\"\xff\"}"), "t.json"), emoface::FormatError);
  // Many emotion nodes are fine (no quadratic blow-up in checks that matter here).
  Json doc = Json::parse(text);
  Json emotions = Json::array(), mood = Json::array();
  for (int i = 0; i < 2000; ++i) {
    emotions.push_back("e" + std::to_string(i));
    mood.push_back(0.5);
  }
  doc["emotions"] = emotions;
  doc["traits"]["starting_mood"] = mood;
  doc["traits"]["personality"] = mood;
  doc.erase("stimulus_edges");
  doc.erase("response_edges");
  doc.erase("representatives");
  EXPECT_EQ(mm::parse_mind_map(doc.dump()).emotion_count(), 2000u);
}

TEST(EventsIo, ParsesAndRoundTrips) {
  const std::string text =
      "# a comment\n"
      "{\"time\": 1.5, \"to\": \"bob\", \"stimulus\": \"gift\", \"from\": \"alice\"}\n"
      "\n"
      "{\"time\": 3, \"to\": \"*\", \"stimulus\": \"explosion\", \"weights\": {\"fear\": 0.9, \"surprise\": 0.7}}\r\n";
  const auto events = mm::parse_events(text, "e.ndjson");
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].time, 1.5);
  EXPECT_EQ(events[0].source, "alice");
  EXPECT_EQ(events[0].line, 2u);
  EXPECT_EQ(events[1].line, 4u);
  EXPECT_EQ(events[1].weights, (std::vector<std::pair<std::string, double>>{{"fear", 0.9}, {"surprise", 0.7}}));
  const auto again = mm::parse_events(mm::events_to_ndjson(events));
  EXPECT_EQ(mm::events_to_ndjson(again), mm::events_to_ndjson(events));
}

TEST(EventsIo, BadLinesNameTheLine) {
  auto expect_line = [](const std::string& text, std::size_t line, const std::string& pointer) {
    try {
      mm::parse_events(text, "e.ndjson");
      ADD_FAILURE() << text;
    } catch (const emoface::FormatError& e) {
      EXPECT_EQ(e.where().line, line) << e.what();
      EXPECT_EQ(e.where().json_pointer, pointer) << e.what();
    }
  };
  const std::string ok = "{\"time\": 0, \"to\": \"a\", \"stimulus\": \"s\"}\n";
  expect_line(ok + "{\"time\": 1, \"to\": \"a\"", 2, "");
  expect_line(ok + ok + "{\"to\": \"a\", \"stimulus\": \"s\"}", 3, "");
  expect_line("{\"time\": -1, \"to\": \"a\", \"stimulus\": \"s\"}", 1, "/time");
  expect_line("{\"time\": 1e999, \"to\": \"a\", \"stimulus\": \"s\"}", 1, "");
  expect_line("{\"time\": \"now\", \"to\": \"a\", \"stimulus\": \"s\"}", 1, "/time");
  expect_line("{\"time\": 1, \"to\": \"\", \"stimulus\": \"s\"}", 1, "/to");
  expect_line("{\"time\": 1, \"to\": \"a\", \"stimulus\": \"s\", \"weights\": {\"fear\": 2}}", 1, "/weights/fear");
  expect_line("{\"time\": 1, \"to\": \"a\", \"stimulus\": \"s\", \"weights\": [1]}", 1, "/weights");
  expect_line("{\"time\": 1, \"to\": \"a\", \"stimulus\": \"s\", \"extra\": 1}", 1, "/extra");
  expect_line("[1]", 1, "");
}

// The unknown-field rule (docs/formats.md) for the NDJSON streams: the stream header sets the
// version; a 1.0 stream (or one without a header) rejects unknown fields, a 1.1 stream ignores
// them.
TEST(EventsIo, UnknownFieldRuleFollowsTheStreamHeader) {
  const std::string rec = "{\"time\": 1, \"to\": \"a\", \"stimulus\": \"s\", \"mood\": 1}\n";
  const std::string v10 = "{\"format\": \"emoface.mindmap_events\", \"version\": \"1.0\"}\n";
  const std::string v11 = "{\"format\": \"emoface.mindmap_events\", \"version\": \"1.1\"}\n";
  for (const std::string& text : {rec, v10 + rec}) {
    try {
      mm::parse_events(text, "e.ndjson");
      ADD_FAILURE() << text;
    } catch (const emoface::FormatError& e) {
      EXPECT_EQ(std::string(e.what()).find("e.ndjson:"), 0u) << e.what();
      EXPECT_NE(std::string(e.what()).find("at /mood: unknown field \"mood\""), std::string::npos)
          << e.what();
      EXPECT_EQ(e.where().line, text == rec ? 1u : 2u);
    }
  }
  const auto events = mm::parse_events(v11 + rec, "e.ndjson");
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].line, 2u);
  EXPECT_THROW(
      mm::parse_events("{\"format\": \"emoface.mindmap_events\", \"version\": \"2.0\"}\n" + rec,
                       "e.ndjson"),
      emoface::FormatError);  // a newer major
  // Actions: the same rule with their own header.
  const std::string act =
      "{\"time\":1,\"character\":\"a\",\"action\":\"x\",\"label\":\"fear\",\"emotion\":\"e\","
      "\"mood\":0.5,\"cause\":\"stimulus\",\"stimulus\":\"s\",\"depth\":0,\"note\":1}\n";
  EXPECT_THROW(mm::parse_actions(act, "a.ndjson"), emoface::FormatError);
  EXPECT_EQ(mm::parse_actions(
                "{\"format\":\"emoface.mindmap_actions\",\"version\":\"1.3\"}\n" + act, "a.ndjson")
                .size(),
            1u);
}

TEST(ActionsIo, NdjsonRoundTripAndCsv) {
  std::vector<mm::TriggeredAction> actions = {
      {0.5, "alice", "smile", "happiness", "happiness", 0.325, mm::Cause::Stimulus, "gift", 0},
      {1.5, "alice", "wave, big", "happiness", "happiness", 0.325, mm::Cause::Chain, "gift", 1},
      {2.0, "bob", "frown", "anger", "anger", 0.1 + 0.2, mm::Cause::Decay, "", 0}};
  const std::string nd = mm::actions_to_ndjson(actions);
  EXPECT_EQ(nd.rfind(emoface::core::ndjson_header("mindmap_actions", {1, 0}), 0), 0u);  // stream header first
  const auto back = mm::parse_actions(nd, "a.ndjson");
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back[2].mood, 0.1 + 0.2);
  EXPECT_EQ(back[1].cause, mm::Cause::Chain);
  EXPECT_EQ(mm::actions_to_ndjson(back), nd);
  EXPECT_THROW(mm::parse_actions("{\"time\": 1}\n", "a"), emoface::FormatError);
  const std::string csv = mm::actions_to_csv(actions);
  ASSERT_EQ(csv.rfind(emoface::core::csv_stamp(), 0), 0u);
  EXPECT_EQ(csv.substr(emoface::core::csv_stamp().size(), csv.find('\n', emoface::core::csv_stamp().size()) - emoface::core::csv_stamp().size()),
            "time,character,action,label,emotion,mood,cause,stimulus,depth");
  EXPECT_NE(csv.find("1.500000,alice,\"wave, big\",happiness,happiness,0.325000,chain,gift,1\n"), std::string::npos);
}

TEST(Timeline, CsvHasAHeaderAndOneRowPerSample) {
  mm::SimulationOptions o;
  o.frame_rate = 2.0;
  o.duration = 1.0;
  const auto r = mm::simulate({make_alice()}, {}, o);
  EXPECT_EQ(mm::mood_timeline_csv(r, make_alice(), 0),
            emoface::core::csv_stamp() + "time,happiness,sadness\n0.000000,0.200000,0.400000\n0.500000,0.187500,0.387500\n"
            "1.000000,0.175000,0.375000\n");
  EXPECT_THROW(mm::mood_timeline_csv(r, make_bob(), 1), emoface::InvalidInput);
}

TEST(ExampleData, TwoCharactersReactDifferentlyToTheSameStimuli) {
  const std::string dir = std::string(EMOFACE_SOURCE_DIR) + "/data/mindmap";
  const auto maps = mm::read_mind_map_dir(dir + "/characters");
  ASSERT_EQ(maps.size(), 2u);
  const auto events = mm::read_events(dir + "/events.ndjson");
  const auto r = mm::simulate(maps, events, {});
  std::vector<std::string> seq[2];
  for (const auto& a : r.actions)
    if (a.cause == mm::Cause::Stimulus) seq[a.character == maps[0].character ? 0 : 1].push_back(a.label);
  ASSERT_FALSE(seq[0].empty());
  ASSERT_FALSE(seq[1].empty());
  EXPECT_NE(seq[0], seq[1]);
}

// Golden output of the example characters, made with (the first two lines one command)
//   build/apps/mindmap/mindmap simulate --maps data/mindmap/characters
//       --events data/mindmap/events.ndjson --out /tmp/golden --seed 0 --no-charts
//   cp /tmp/golden/actions.ndjson tests/data/mindmap/example_actions_seed0.ndjson
// A difference means the behaviour changed: check it, then regenerate.
TEST(ExampleData, MatchesTheGoldenActions) {
  const std::string dir = std::string(EMOFACE_SOURCE_DIR) + "/data/mindmap";
  const auto r = mm::simulate(mm::read_mind_map_dir(dir + "/characters"), mm::read_events(dir + "/events.ndjson"), {});
  EXPECT_EQ(mm::actions_to_ndjson(r.actions),
            emoface::core::read_file(std::string(EMOFACE_TEST_DATA_DIR) + "/mindmap/example_actions_seed0.ndjson"));
}
