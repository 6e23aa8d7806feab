#include "emoface/obie/match.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "emoface/core/errors.hpp"
#include "emoface/obie/bundle.hpp"
#include "test_match.hpp"

namespace emoface::obie {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_match(text, "m.json");
  } catch (const FormatError& e) {
    return e.what();
  }
  return "no error";
}

std::string minimal(const std::string& body) {
  return R"({"format": "emoface.obie.match", "version": "1.0", "domain": "d.domain", )" + body + "}";
}

// The unknown-field rule (docs/formats.md, core::JsonReader): a 1.0 match rejects a field it does
// not know, naming it; a 1.1 match may add fields (ignored); known fields are still checked.
TEST(Match, UnknownFieldRule) {
  const std::string body = R"("events": [{"minute": 3, "action": "", "colour": 2}], "venue": "x")";
  EXPECT_EQ(error_of(minimal(body)), "m.json: at /venue: unknown field \"venue\"");
  EXPECT_EQ(error_of(minimal(body.substr(0, body.find(", \"venue\"")))),
            "m.json: at /events/0/colour: unknown field \"colour\"");
  std::string newer = minimal(body);
  newer.replace(newer.find("\"1.0\""), 5, "\"1.1\"");
  EXPECT_EQ(error_of(newer), "no error");
  EXPECT_EQ(parse_match(newer, "m.json").events.size(), 1u);
  newer.replace(newer.find("\"minute\": 3"), 11, "\"minute\": -3");
  EXPECT_NE(error_of(newer).find("/events/0/minute"), std::string::npos);
}

TEST(Match, ParsesTheShortMatch) {
  const MatchScript m = parse_match(test::short_match_json(), "/some/dir/short.json");
  EXPECT_EQ(m.title, "short");
  ASSERT_EQ(m.events.size(), 13u);
  EXPECT_EQ(m.events[11].action, "(shot oteam)");
  EXPECT_EQ(m.events[11].outcome, "goal");
  EXPECT_EQ(m.events[0].note, "kick-off");
  EXPECT_DOUBLE_EQ(m.duration, 14);
  EXPECT_EQ(m.for_team.side, "team");
  EXPECT_EQ(m.against_team.name, "Against");
  ASSERT_EQ(m.key_moments.size(), 2u);
  EXPECT_EQ(m.base_dir, "/some/dir");
  EXPECT_EQ(m.domain_paths()[0], std::string(EMOFACE_SOURCE_DIR) + "/data/parlee/football.domain");
}

TEST(Match, DomainIsRelativeToTheScript) {
  const MatchScript m = parse_match(minimal(R"("events": [])"), "data/obie/x.json");
  EXPECT_EQ(m.domain_paths()[0], "data/obie/d.domain");
  const MatchScript two = parse_match(R"({"format": "emoface.obie.match", "version": "1.0",
      "domain": ["a.domain", "/abs/b.problem"], "events": []})", "x.json");
  ASSERT_EQ(two.domain_paths().size(), 2u);
  EXPECT_EQ(two.domain_paths()[0], "a.domain");
  EXPECT_EQ(two.domain_paths()[1], "/abs/b.problem");
}

TEST(Match, RoundTrips) {
  MatchScript m = parse_match(test::short_match_json(), "s.json");
  m.events[2].feedback = -0.5;
  m.events[3].minute = 3.5;
  m.commentary.push_back({12, "What a strike."});
  m.goal_outcomes = {"goal", "own-goal"};
  const std::string text = write_match(m);
  EXPECT_NE(text.find("\"generator\": \"emoface "), std::string::npos);
  const MatchScript back = parse_match(text, "s.json");
  ASSERT_EQ(back.events.size(), m.events.size());
  for (std::size_t i = 0; i < m.events.size(); ++i) {
    EXPECT_EQ(back.events[i].minute, m.events[i].minute);
    EXPECT_EQ(back.events[i].action, m.events[i].action);
    EXPECT_EQ(back.events[i].outcome, m.events[i].outcome);
    EXPECT_EQ(back.events[i].feedback, m.events[i].feedback);
    EXPECT_EQ(back.events[i].note, m.events[i].note);
  }
  EXPECT_EQ(back.title, m.title);
  EXPECT_EQ(back.domain, m.domain);
  EXPECT_EQ(back.goal_outcomes, m.goal_outcomes);
  ASSERT_EQ(back.commentary.size(), 1u);
  EXPECT_EQ(back.commentary[0].text, "What a strike.");
  EXPECT_EQ(back.key_moments[1].label, "0-1");
  EXPECT_EQ(write_match(back), text);
}

TEST(Match, ConvertsParleeEvents) {
  std::vector<parlee::Event> ev(2);
  ev[0].time = 1;
  ev[0].action = "(re-kickoff team)";
  ev[1].time = 95.5;
  ev[1].action = "(shot team)";
  ev[1].outcome = "goal";
  ev[1].feedback = 0.25;
  MatchScript m = match_from_events(ev);
  EXPECT_DOUBLE_EQ(m.duration, 96);
  ASSERT_EQ(m.events.size(), 2u);
  EXPECT_EQ(m.events[1].outcome, "goal");
  const auto back = to_parlee_events(m);
  EXPECT_DOUBLE_EQ(back[1].time, 95.5);
  EXPECT_EQ(back[1].feedback, 0.25);
  ev[0].time = std::nan("");
  EXPECT_THROW(match_from_events(ev), InvalidInput);
}

TEST(Match, BadInputsNameTheirPlace) {
  EXPECT_NE(error_of("{\"format\": ").find("m.json:1:"), std::string::npos);  // truncated: line/column
  EXPECT_NE(error_of("[1, 2]").find("m.json"), std::string::npos);
  EXPECT_NE(error_of(R"({"format": "emoface.parlee_agent", "version": "1.0"})").find("/format"), std::string::npos);
  EXPECT_NE(error_of(R"({"format": "emoface.obie.match", "version": "2.0", "domain": "d", "events": []})")
                .find("/version"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"format": "emoface.obie.match", "version": "1.0", "events": []})").find("domain"),
            std::string::npos);
  EXPECT_NE(error_of(minimal(R"("domain2": 1, "events": [])")).find("/domain2"), std::string::npos);
  EXPECT_NE(error_of(minimal(R"("duration": 90)")).find("events"), std::string::npos);
  EXPECT_NE(error_of(minimal(R"("events": [{"minute": 5, "action": ""}, {"minute": 4, "action": ""}])"))
                .find("/events/1/minute"),
            std::string::npos);
  EXPECT_NE(error_of(minimal(R"("events": [{"minute": 91, "action": ""}])")).find("/events/0/minute"),
            std::string::npos);
  EXPECT_NE(error_of(minimal(R"("events": [{"minute": -1, "action": ""}])")).find("/events/0/minute"),
            std::string::npos);
  EXPECT_NE(error_of(minimal(R"("events": [{"minute": 1e999, "action": ""}])")).find("m.json: invalid JSON: number overflow"),
            std::string::npos);
  EXPECT_NE(error_of(minimal(R"("events": [{"minute": "3", "action": ""}])")).find("/events/0/minute"),
            std::string::npos);
  EXPECT_NE(error_of(minimal(R"("events": [{"minute": 3}])")).find("/events/0"), std::string::npos);
  EXPECT_NE(error_of(minimal(R"("events": [{"minute": 3, "action": "", "feedback": 2}])")).find("/events/0/feedback"),
            std::string::npos);
  EXPECT_NE(error_of(minimal(R"("events": [{"minute": 3, "action": "", "colour": 2}])")).find("/events/0/colour"),
            std::string::npos);
  EXPECT_NE(error_of(minimal(R"("events": [3])")).find("/events/0"), std::string::npos);
  EXPECT_NE(error_of(minimal(R"("events": {})")).find("/events"), std::string::npos);
  EXPECT_NE(error_of(minimal(R"("duration": 0, "events": [])")).find("/duration"), std::string::npos);
  EXPECT_NE(error_of(minimal(R"("duration": 5000, "events": [])")).find("/duration"), std::string::npos);
  EXPECT_NE(error_of(minimal(R"("teams": {"for": {"side": "a"}, "against": {"side": "a"}}, "events": [])"))
                .find("/teams/against/side"),
            std::string::npos);
  EXPECT_NE(error_of(minimal(R"("teams": {"for": {"side": "a"}}, "events": [])")).find("/teams"), std::string::npos);
  EXPECT_NE(error_of(minimal(R"("teams": {"for": {"side": ""}, "against": {"side": "b"}}, "events": [])"))
                .find("/teams/for/side"),
            std::string::npos);
  EXPECT_NE(error_of(minimal(R"("events": [], "key_moments": [{"minute": 100}])")).find("/key_moments/0/minute"),
            std::string::npos);
  EXPECT_NE(error_of(minimal(R"("events": [], "commentary": [{"minute": 1, "text": ""}])")).find("/commentary/0/text"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"format": "emoface.obie.match", "version": "1.0", "domain": [], "events": []})")
                .find("/domain"),
            std::string::npos);
  EXPECT_NE(error_of(minimal(R"("title": ")" + std::string(5000, 'x') + R"(", "events": [])")).find("/title"),
            std::string::npos);
}

TEST(Match, HugeScriptsAreRefused) {
  std::string events;
  for (std::size_t i = 0; i <= kMaxMatchEvents; ++i) events += R"J({"minute": 1, "action": ""},)J";
  events.pop_back();
  EXPECT_NE(error_of(minimal(R"("events": [)" + events + "]")).find("/events: too many entries"), std::string::npos);
  EXPECT_NE(error_of(minimal(R"("duration": 1e308, "events": [])")).find("/duration"), std::string::npos);
}

TEST(Match, ValidateCatchesWhatTheReaderCatches) {
  MatchScript m = parse_match(test::short_match_json(), "s.json");
  m.validate();
  MatchScript bad = m;
  bad.events[3].minute = 0.5;
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = m;
  bad.against_team.side = bad.for_team.side;
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = m;
  bad.domain.clear();
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = m;
  bad.key_moments[0].minute = std::nan("");
  EXPECT_THROW(write_match(bad), InvalidInput);
}

}  // namespace
}  // namespace emoface::obie

namespace emoface::obie {
namespace {

TEST(KeyMoment, ParsesMinuteAndOptionalLabel) {
  const KeyMoment a = parse_key_moment("12:the against team scores");
  EXPECT_EQ(a.minute, 12.0);
  EXPECT_EQ(a.label, "the against team scores");
  const KeyMoment b = parse_key_moment("40.5");
  EXPECT_EQ(b.minute, 40.5);
  EXPECT_EQ(b.label, "");
  EXPECT_EQ(parse_key_moment("3:a:b").label, "a:b");
  for (const char* bad : {"", ":x", "x:y", "12x:y", "nan:x", "1e999"})
    EXPECT_THROW(parse_key_moment(bad), InvalidInput) << bad;
}

}  // namespace
}  // namespace emoface::obie
