// emo2muscle end to end: every documented flag and every bad-input case of issue 2 §3.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli_harness.hpp"
#include "emoface/core/version.hpp"

namespace {

namespace fs = std::filesystem;

using Result = emoface::test::CliResult;

class Emo2Muscle : public emoface::test::CliTest {
 protected:
  Result run(const std::string& args, const std::string& stdin_file = "") const {
    return run_tool(EMO2MUSCLE_EXE, args, stdin_file);
  }
};

const std::string kExample = std::string(EMOFACE_SOURCE_DIR) + "/data/fuzzyexpr/example_emotions.csv";
const std::string kHeader = "id,sadness,happiness,anger,fear,disgust,surprise\n";

// Output without its first line, which must be the version stamp ("# emoface x.y.z" in CSV, the stream
// header {"format": "emoface.fmcv", ...} in NDJSON).
std::string unstamped(const std::string& out) {
  const std::string first = out.substr(0, out.find('\n'));
  const bool csv_stamp = first == std::string("# ") + emoface::kGenerator;
  const bool nd_header = first.rfind("{\"format\":\"emoface.fmcv\"", 0) == 0 && first.find(emoface::kGenerator) != std::string::npos;
  EXPECT_TRUE(csv_stamp || nd_header) << first;
  return out.substr(out.find('\n') + 1);
}

TEST_F(Emo2Muscle, ConvertsTheExampleFile) {
  auto r = run(kExample + " -o " + path("m.csv") + " --summary");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string csv = unstamped(slurp(path("m.csv")));
  EXPECT_EQ(lines(csv), 14u);  // header + 13 records
  EXPECT_EQ(csv.substr(0, csv.find('\n')).find("id,zygomatic_major,"), 0u);
  EXPECT_NE(r.out.find("line 4: single happiness 0.90"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("13 record(s) converted"), std::string::npos);
}

// --weights: ARKit / FACS columns computed from the 35 side parameters (data/faceweights): checked
// against the --sides output of the same records by the documented rows (mouthSmile_L = zygomatic
// major + 0.3 zygomatic minor, clamped; AU12_L = zygomatic major).
TEST_F(Emo2Muscle, WeightsArkitAndFacs) {
  auto sides = run(kExample + " --sides");
  ASSERT_EQ(sides.code, 0) << sides.err;
  auto arkit = run(kExample + " --weights arkit");
  ASSERT_EQ(arkit.code, 0) << arkit.err;
  auto facs = run(kExample + " --weights facs");
  ASSERT_EQ(facs.code, 0) << facs.err;
  auto table = [](const std::string& csv) {
    std::vector<std::vector<std::string>> rows;
    std::string body = unstamped(csv), line;
    std::stringstream ss(body);
    while (std::getline(ss, line)) {
      std::vector<std::string> f;
      std::stringstream ls(line);
      for (std::string x; std::getline(ls, x, ',');) f.push_back(x);
      rows.push_back(f);
    }
    return rows;
  };
  const auto s = table(sides.out), a = table(arkit.out), f = table(facs.out);
  ASSERT_EQ(s.size(), a.size());
  ASSERT_EQ(a[0].size(), 53u);  // id + 52 shapes
  auto col = [](const std::vector<std::vector<std::string>>& t, const std::string& name) {
    return static_cast<std::size_t>(std::find(t[0].begin(), t[0].end(), name) - t[0].begin());
  };
  EXPECT_EQ(a[0][1], "browDown_L");
  for (std::size_t r = 1; r < s.size(); ++r) {
    const double zm = std::stod(s[r][col(s, "zygomatic_major_l")]);
    const double zn = std::stod(s[r][col(s, "zygomatic_minor_l")]);
    EXPECT_NEAR(std::stod(a[r][col(a, "mouthSmile_L")]), std::min(1.0, zm + 0.3 * zn), 2e-6) << r;
    EXPECT_NEAR(std::stod(f[r][col(f, "AU12_L")]), zm, 2e-6) << r;
  }
  EXPECT_EQ(run(kExample + " --weights arkit --sides").code, 1);
  EXPECT_EQ(run(kExample + " --weights vrm").code, 1);
}

TEST_F(Emo2Muscle, SidesNdjsonJsonAndStdinStdout) {
  auto r = run("--sides --to ndjson", kExample);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string nd_out = unstamped(r.out);
  EXPECT_EQ(lines(nd_out), 13u);
  auto first = nlohmann::json::parse(nd_out.substr(0, nd_out.find('\n')));
  EXPECT_EQ(first.size(), 36u);  // id + 35 parameters
  EXPECT_EQ(first["id"], "neutral");
  r = run(kExample + " --to json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["format"], "emoface.fmcv");
  EXPECT_EQ(doc["rows"].size(), 13u);
  // NDJSON in, CSV out by extension.
  const std::string nd = write("in.ndjson",
      "{\"id\":1,\"sadness\":0,\"happiness\":0.9,\"anger\":0,\"fear\":0,\"disgust\":0,\"surprise\":0}\n");
  r = run(nd + " -o " + path("o.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  // NDJSON members pass through to NDJSON/JSON only: a CSV header cannot hold per-line fields.
  EXPECT_NE(slurp(path("o.csv")).find("\n0.895161,0.895161,"), std::string::npos);
}

TEST_F(Emo2Muscle, ModesSeedsAndShards) {
  const std::string in = write("t.csv", kHeader + "a,0.4,0.4,0.4,0,0,0\nb,0,0.9,0,0,0,0.45\n");
  auto single = run(in + " --mode single");
  auto blend = run(in + " --mode blend");
  ASSERT_EQ(single.code, 0);
  EXPECT_NE(single.out, blend.out);
  auto r1 = run(in + " --tie-break random --seed 5"), r2 = run(in + " --tie-break random --seed 5");
  EXPECT_EQ(r1.out, r2.out);
  auto s0 = run(in + " --shard 0/2"), s1 = run(in + " --shard 1/2");
  const std::string o0 = unstamped(s0.out), o1 = unstamped(s1.out);
  EXPECT_EQ(lines(o0), 2u);
  EXPECT_EQ(lines(o1), 2u);
  EXPECT_EQ(o0.substr(o0.find('\n') + 1, 2), "a,");
  EXPECT_EQ(o1.substr(o1.find('\n') + 1, 2), "b,");
  EXPECT_EQ(run(in + " --transition smooth --missing-rule no_contraction").code, 0);
}

// Issue 18: contiguous shards (from a file and from stdin, CSV and NDJSON) merge back into the
// single-process output byte for byte; --shard auto reads the Slurm array variables.
TEST_F(Emo2Muscle, ContiguousShardsMergeBackByteForByte) {
  std::string text = kHeader;
  for (int i = 0; i < 7; ++i)
    text += "r" + std::to_string(i) + ",0." + std::to_string(i) + ",0.5,0,0.2,0,0.1\n";
  const std::string in = write("seven.csv", text);
  for (const char* to : {"csv", "ndjson"}) {
    const std::string common = " --to " + std::string(to) + " --tie-break random --seed 4";
    ASSERT_EQ(run(in + common + " -o " + path("whole.out")).code, 0);
    std::string merge_args;
    for (int i = 0; i < 3; ++i) {
      const std::string part = path("part" + std::to_string(i) + ".out");
      // shard 1 reads stdin: the records are counted from a buffered copy
      const auto r = i == 1 ? run("-" + common + " --shard 1/3 -o " + part, in)
                            : run(in + common + " --shard " + std::to_string(i) + "/3 -o " + part);
      ASSERT_EQ(r.code, 0) << r.err;
      merge_args += " " + part;
    }
    // floor(i*7/3): rows 0-1, 2-3, 4-6
    EXPECT_NE(slurp(path("part1.out")).find("r2"), std::string::npos);
    EXPECT_EQ(slurp(path("part1.out")).find("r4"), std::string::npos);
    ASSERT_EQ(run("--merge" + merge_args + " -o " + path("merged.out")).code, 0);
    EXPECT_EQ(slurp(path("merged.out")), slurp(path("whole.out"))) << to;
  }
  ::setenv("SLURM_ARRAY_TASK_ID", "2", 1);
  ::setenv("SLURM_ARRAY_TASK_COUNT", "3", 1);
  ::setenv("SLURM_ARRAY_TASK_MIN", "0", 1);
  const auto automatic = run(in + " --shard auto");
  ::unsetenv("SLURM_ARRAY_TASK_ID");
  const auto missing = run(in + " --shard auto");
  ::unsetenv("SLURM_ARRAY_TASK_COUNT");
  ::unsetenv("SLURM_ARRAY_TASK_MIN");
  EXPECT_EQ(automatic.out, run(in + " --shard 2/3").out);
  EXPECT_EQ(missing.code, 1);
  EXPECT_NE(missing.err.find("SLURM_ARRAY_TASK_ID"), std::string::npos) << missing.err;
  EXPECT_EQ(run(in + " --shard 0/2 --to json").code, 1);
}

TEST_F(Emo2Muscle, BadInputNamesLineAndColumnAndWritesNothing) {
  struct Case {
    std::string content, fragment;
  };
  const std::string big(2 << 20, '1');
  const Case cases[] = {
      {kHeader + "a,0,zero,0,0,0,0\n", "bad.csv:2:3: happiness: not a number"},
      {kHeader + "a,0,nan,0,0,0,0\n", "bad.csv:2:3: happiness: not a finite number"},
      {kHeader + "a,0,0,inf,0,0,0\n", "bad.csv:2:4"},
      {kHeader + "a,0,0,0,1.2,0,0\n", "bad.csv:2:5: fear: intensity 1.200000 is outside [0, 1]"},
      {"id,sadness,happiness\n", "bad.csv:1: header lacks emotion column(s)"},
      {"id,sadness,happiness,anger,fear,disgust,surprise,anger\n", "bad.csv:1:8: duplicated column"},
      {kHeader + "a,0,0,0,0,0,0\n\n", "bad.csv:3: empty line"},
      {kHeader + "a," + big + "\n", "bad.csv:2: line is longer than"},
      {kHeader + "\xC3\x28,0,0,0,0,0,0\n", "bad.csv:2:1: invalid UTF-8"},
      {kHeader + "a,0,0,0,0,0\n", "bad.csv:2:7: expected 7 fields, got 6"},
      {"", "bad.csv:1: empty input"},
  };
  for (const auto& c : cases) {
    const std::string in = write("bad.csv", c.content);
    fs::remove(path("out.csv"));
    auto r = run(in + " -o " + path("out.csv"));
    EXPECT_EQ(r.code, 2) << c.fragment;
    EXPECT_EQ(lines(r.err), 1u) << r.err;  // one clear line
    EXPECT_NE(r.err.find(c.fragment), std::string::npos) << "expected '" << c.fragment << "' in " << r.err;
    EXPECT_FALSE(fs::exists(path("out.csv"))) << c.fragment;
  }
  // An existing output stays untouched when a run fails.
  write("out.csv", "previous");
  write("bad.csv", kHeader + "a,0,0,0,0,0,x\n");
  EXPECT_EQ(run(path("bad.csv") + " -o " + path("out.csv")).code, 2);
  EXPECT_EQ(slurp(path("out.csv")), "previous");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), {}), 4);  // no temporary left behind
}

TEST_F(Emo2Muscle, SkipWritesGoodRowsAndCountsBadOnes) {
  const std::string in = write("t.csv", kHeader + "a,0,0,0,0,0,0\nb,0,2,0,0,0,0\nc,0,0.5,0,0,0,0\nd,x,0,0,0,0,0\n");
  auto r = run(in + " --on-error skip -o " + path("o.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(lines(unstamped(slurp(path("o.csv")))), 3u);
  EXPECT_NE(r.err.find("skipped 2 bad record(s), wrote 2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("t.csv:3:3"), std::string::npos) << r.err;
  r = run(in + " --clamp --on-error skip");
  EXPECT_NE(r.err.find("skipped 1 bad record(s), wrote 3"), std::string::npos) << r.err;
}

TEST_F(Emo2Muscle, UsageErrorsHelpVersionAndFll) {
  EXPECT_EQ(run("--mode sometimes").code, 1);
  EXPECT_EQ(run("--shard 3/2").code, 1);
  EXPECT_EQ(run("--shard x").code, 1);
  EXPECT_EQ(run("--no-such-flag").code, 1);
  auto r = run("--help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("Example:"), std::string::npos);
  r = run("--version");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("emoface "), std::string::npos);
  EXPECT_EQ(run(path("missing.csv")).code, 2);
  r = run("--export-fll " + path("e.fll"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(slurp(path("e.fll")).find("RuleBlock: single_fear"), std::string::npos);
  write("rules.json", "{\"format\":\"emoface.fuzzyrules\",\"version\":\"1.0\"}");
  r = run("--rules " + path("rules.json"), kExample);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("rules.json: missing field \"input_sets\""), std::string::npos) << r.err;
}

}  // namespace
