// `parlee` CLI end to end: plan / run / interact, outputs, exit codes, atomic outputs.
#include <gtest/gtest.h>

#include "emoface/core/io.hpp"
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli_harness.hpp"

namespace {

namespace fs = std::filesystem;
const std::string kData = std::string(EMOFACE_SOURCE_DIR) + "/data/parlee/";

using Result = emoface::test::CliResult;

class ParleeApp : public emoface::test::CliTest {
 protected:
  Result run(const std::string& args, const std::string& stdin_file = "") const {
    return run_tool(PARLEE_EXE, args, stdin_file);
  }
};

}  // namespace

TEST_F(ParleeApp, PlanTextAndJson) {
  auto r = run("plan --domain " + kData + "rocket.domain --horizon 5");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("= 0.52488"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(MOVE r1 london paris)"), std::string::npos);
  r = run("plan --domain " + kData + "rocket2.domain --horizon 3 --depth 0 --semantics at_horizon --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["goal"], "deliver");
  EXPECT_EQ(j["model_depth"], 0);
  EXPECT_EQ(j["plan"].size(), 3u);
  EXPECT_EQ(run("--help").code, 0);
}

TEST_F(ParleeApp, PlanErrors) {
  const std::string bad = write("bad.domain", "(predicates (p 1))\n(objects a)\n(initial (q a))\n");
  auto r = run("plan --domain " + bad + " --horizon 2");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("bad.domain:3:10: unknown predicate 'q'"), std::string::npos) << r.err;
  EXPECT_EQ(run("plan --domain " + kData + "rocket.domain --horizon 99").code, 1);
  EXPECT_EQ(run("plan --horizon 3").code, 1);
  EXPECT_EQ(run("plan --domain " + path("missing") + " --horizon 3").code, 2);
  EXPECT_EQ(run("plan --domain " + kData + "rocket.domain --horizon 3 --goal nope").code, 2);
}

// Issue 18: the timeline and the charts are written together or not at all (core::OutputBundle).
TEST_F(ParleeApp, RunWritesNothingWhenAChartCannotBeWritten) {
  std::filesystem::create_directories(path("charts/fear.png"));  // a directory where a chart goes
  const auto r = run("run --domain " + kData + "football.domain --agent " + kData +
                     "agents/neutral.json --events " + kData + "match.ndjson --out " +
                     path("t.ndjson") + " --plot " + path("charts"));
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("fear.png"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("t.ndjson")));
  EXPECT_FALSE(std::filesystem::exists(path("charts/neutral.png")));
}

TEST_F(ParleeApp, RunWritesTimelineAndCharts) {
  const auto r = run("run --domain " + kData + "football.domain --agent " + kData + "agents/neutral.json --events " +
                     kData + "match.ndjson --out " + path("t.ndjson") + " --plot " + path("charts"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream lines(slurp(path("t.ndjson")));
  std::string line;
  std::size_t n = 0;
  ASSERT_TRUE(std::getline(lines, line));
  EXPECT_EQ(nlohmann::json::parse(line),
            nlohmann::json::parse(emoface::core::ndjson_header("parlee.timeline", {1, 1})));
  while (std::getline(lines, line)) {
    const auto j = nlohmann::json::parse(line);
    EXPECT_EQ(j["agent"], "neutral");
    EXPECT_EQ(j["emotions"].size(), 21u);
    EXPECT_EQ(j["esv"].size(), 6u);
    ++n;
  }
  EXPECT_EQ(n, 92u);  // initial state + 91 events
  for (const char* png : {"neutral.png", "fear.png", "happiness.png", "surprise.png", "sadness.png"}) {
    const std::string bytes = slurp(path(std::string("charts/") + png));
    ASSERT_GT(bytes.size(), 8u) << png;
    EXPECT_EQ(bytes.substr(1, 3), "PNG") << png;
  }
}

TEST_F(ParleeApp, RunSkipsOrRejectsEventsTheModelDoesNotAllow) {
  // default (on_disallowed "skip"): reported on stderr with file:line, skipped, the run goes on
  auto r = run("run --domain " + kData + "football.domain --agent " + kData +
               "agents/neutral.json --events " + kData + "bread_events.ndjson --out " +
               path("t.ndjson"));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: " + kData + "bread_events.ndjson:5: agent neutral: skipped: "),
            std::string::npos)
      << r.err;
  ASSERT_TRUE(fs::exists(path("t.ndjson")));
  EXPECT_NE(slurp(path("t.ndjson")).find("\"skipped\":"), std::string::npos);
  // "stop": a located error and nothing written
  const std::string strict =
      write("strict.json", R"({"format":"emoface.parlee_agent","version":"1.1",)"
                           R"("self":"agent","on_disallowed":"stop"})");
  r = run("run --domain " + kData + "football.domain --agent " + strict + " --events " + kData +
          "bread_events.ndjson --out " + path("u.ndjson"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("bread_events.ndjson:5"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("u.ndjson")));
  const std::string agent = write("a.json", R"({"format":"emoface.parlee_agent","version":"1.0","personality":{"x":1}})");
  EXPECT_EQ(run("run --domain " + kData + "football.domain --agent " + agent + " --events " + kData +
                "match.ndjson --out " + path("t.ndjson"))
                .code,
            2);
}

// The §7.4 timeline is byte-identical across processes for the same agent seeds (the four Obies
// and the two supporters; the per-second decay of the runtime branch does not change this).
TEST_F(ParleeApp, MatchTimelineIsByteIdenticalAcrossRuns) {
  const std::string args = "run --domain " + kData + "football.domain --problem " + kData +
                           "rivals.problem" + " --agent " + kData + "agents/neutral.json --agent " +
                           kData + "agents/sensitive.json" + " --agent " + kData +
                           "agents/fan_against.json --events " + kData + "match.ndjson --out ";
  ASSERT_EQ(run(args + path("a.ndjson")).code, 0);
  ASSERT_EQ(run(args + path("b.ndjson")).code, 0);
  const std::string a = slurp(path("a.ndjson"));
  EXPECT_EQ(a, slurp(path("b.ndjson")));
  EXPECT_GT(a.size(), 100000u);
}

TEST_F(ParleeApp, InteractListsActionsAndTheAgentResponds) {
  const std::string in = write("in.txt", "0\n7\nx\n-1\n");
  const auto r = run("interact --domain " + kData + "bread.domain --agent " + kData + "agents/bread_neutral.json", in);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("FACT: (acting user) (at-home car1) (in-shop bread)"), std::string::npos);
  EXPECT_NE(r.out.find("0: No Action\n1: (go-shopping car1 user)\n2: (go-working car1)"), std::string::npos);
  EXPECT_NE(r.out.find("Agent did: (go-shopping car1 agent)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("no such action"), std::string::npos);
  EXPECT_NE(r.out.find("please type a number"), std::string::npos);
}
