#include <algorithm>
// mgraph end to end: face/parametric generation, shards, --on-error, batch requests, GIF/MP4
// output.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_harness.hpp"
#include "emoface/core/csv.hpp"
#include "emoface/core/shard.hpp"
#include "emoface/core/version.hpp"
#include "emoface/core/video.hpp"

namespace {

namespace fs = std::filesystem;
using Result = emoface::test::CliResult;

// Lines of a CSV file we wrote, after checking and dropping its "# emoface x.y.z" stamp line.
std::vector<std::string> csv_lines(const std::string& s) {
  EXPECT_EQ(s.rfind(emoface::core::csv_stamp(), 0), 0u) << s.substr(0, 40);
  std::vector<std::string> out;
  std::istringstream in(s.substr(s.rfind(emoface::core::csv_stamp(), 0) == 0 ? emoface::core::csv_stamp().size() : 0));
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

class Mgraph : public emoface::test::CliTest {
 protected:
  Result run(const std::string& args) const { return run_tool(MGRAPH_EXE, args); }

  // A small face-driven database and its graph, made once for the suite.
  static void SetUpTestSuite() {
    // One directory per process: ctest runs the tests of this suite in parallel processes.
    shared_ =
        fs::temp_directory_path() / ("emoface_cli_mgraph_shared_" + std::to_string(::getpid()));
    fs::remove_all(shared_);
    fs::create_directories(shared_);
    const std::string exe = MGRAPH_EXE;
    const std::string db = (shared_ / "db.json").string(),
                      graph = (shared_ / "graph.json").string();
    ASSERT_EQ(
        std::system(
            (exe + " generate --per-label 2 --subjects 4 --out " + db + " 2>/dev/null").c_str()),
        0);
    ASSERT_EQ(std::system((exe + " build --db " + db + " --out " + graph + " 2>/dev/null").c_str()),
              0);
  }
  static void TearDownTestSuite() { fs::remove_all(shared_); }
  static std::string shared(const std::string& name) { return (shared_ / name).string(); }
  static fs::path shared_;
};
fs::path Mgraph::shared_;

TEST_F(Mgraph, GeneratesFaceDrivenAndParametricDatabases) {
  auto r = run("generate --per-label 1 --subjects 3 --out " + path("face.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto face = nlohmann::json::parse(slurp(path("face.json")));
  EXPECT_EQ(face["format"], "emoface.landmark_database");
  EXPECT_EQ(face["landmark_count"], 68);
  ASSERT_EQ(face["sequences"].size(), 7u);
  r = run("generate --model parametric --per-label 1 --subjects 3 --out " + path("par.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto par = nlohmann::json::parse(slurp(path("par.json")));
  ASSERT_EQ(par["sequences"].size(), 7u);
  // Same sequence ids, labels and lengths (same seed), different faces.
  EXPECT_EQ(face["sequences"][3]["id"], par["sequences"][3]["id"]);
  EXPECT_EQ(face["sequences"][3]["frames"].size(), par["sequences"][3]["frames"].size());
  EXPECT_NE(face["sequences"][3]["frames"][0], par["sequences"][3]["frames"][0]);
  // Orthographic differs from the default perspective; same seed → same file.
  r = run("generate --per-label 1 --subjects 3 --projection orthographic --out " +
          path("ortho.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(slurp(path("ortho.json")), slurp(path("face.json")));
  r = run("generate --per-label 1 --subjects 3 --out " + path("face2.json"));
  EXPECT_EQ(slurp(path("face2.json")), slurp(path("face.json")));
  // Bad option values: usage errors, nothing written.
  r = run("generate --model blendshape --out " + path("x.json"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--model"), std::string::npos) << r.err;
  r = run("generate --projection fisheye --out " + path("x.json"));
  EXPECT_EQ(r.code, 1);
  r = run("generate --camera-distance 0 --out " + path("x.json"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("camera_distance"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("x.json")));
}

TEST_F(Mgraph, GenerateShardsConcatenateToTheWholeRun) {
  // Contiguous blocks (issue 18, item 6): the shard outputs, merged in shard order (stamp and
  // repeated header dropped: core::merge_shard_outputs), are the single run byte for byte.
  const std::string common = "generate --model parametric --per-label 2 --subjects 5 ";
  ASSERT_EQ(run(common + "--out " + path("all.csv")).code, 0);
  for (int n : {2, 3}) {
    std::vector<std::string> parts;
    for (int i = 0; i < n; ++i) {
      const std::string out = path("s" + std::to_string(i) + ".csv");
      ASSERT_EQ(
          run(common + "--shard " + std::to_string(i) + "/" + std::to_string(n) + " --out " + out)
              .code,
          0);
      parts.push_back(slurp(out));
      EXPECT_GT(csv_lines(parts.back()).size(), 1u);
    }
    EXPECT_EQ(emoface::core::merge_shard_outputs(parts), slurp(path("all.csv"))) << n;
  }
  // --shard auto: the Slurm array variables.
  const std::string slurm = "SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_COUNT=3 ";
  ASSERT_EQ(run_tool(slurm + MGRAPH_EXE, common + "--shard auto --out " + path("auto.csv")).code,
            0);
  EXPECT_EQ(slurp(path("auto.csv")), slurp(path("s1.csv")));
  auto r = run(common + "--shard 2/2 --out " + path("bad.csv"));
  EXPECT_EQ(r.code, 1);
  r = run(common + "--shard 1of2 --out " + path("bad.csv"));
  EXPECT_EQ(r.code, 1);
  r = run_tool("env -u SLURM_ARRAY_TASK_COUNT " MGRAPH_EXE,
               common + "--shard auto --out " + path("bad.csv"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("SLURM_ARRAY_TASK_COUNT"), std::string::npos) << r.err;
}

TEST_F(Mgraph, SynthRequestShardsConcatenateToTheWholeRun) {
  // The requests file may carry the "# emoface" stamp (requests_to_csv writes it); bad requests
  // count as items of the batch.
  const std::string req =
      write("req.csv", emoface::core::csv_stamp() +
                           "id,labels\na,fear;surprise\nb,boredom\nc,happiness\n"
                           "d,surprise\ne,anger;happiness\n");
  const std::string common = "synth --graph " + shared("graph.json") + " --requests " + req +
                             " --vary --idle 0.3 --seed 5 --on-error skip ";
  auto r = run(common + "--out " + path("all.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::vector<std::string> parts;
  for (int i = 0; i < 2; ++i) {
    const std::string out = path("p" + std::to_string(i) + ".csv");
    r = run(common + "--shard " + std::to_string(i) + "/2 --out " + out);
    ASSERT_EQ(r.code, 0) << r.err;
    parts.push_back(slurp(out));
  }
  EXPECT_NE(parts[0], parts[1]);
  EXPECT_EQ(emoface::core::merge_shard_outputs(parts), slurp(path("all.csv")));
}

TEST_F(Mgraph, AnimationOutputsAreAllOrNothing) {
  // The sheet cannot be written (its directory is a file): neither the database nor the plot
  // appears, and no temporary file is left.
  write("file", "x");
  auto r = run("synth --graph " + shared("graph.json") + " --labels surprise --out " +
               path("anim.json") + " --plot " + path("plot.png") + " --sheet " +
               path("file/sheet.png") + " --frames-dir " + path("frames"));
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_FALSE(fs::exists(path("anim.json")));
  EXPECT_FALSE(fs::exists(path("plot.png")));
  EXPECT_FALSE(fs::exists(path("frames")));
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".bundle"), std::string::npos) << e.path();
  r = run("synth --graph " + shared("graph.json") + " --labels surprise --out " +
          path("anim.json") + " --plot " + path("plot.png") + " --frames-dir " + path("frames"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("anim.json")));
  EXPECT_TRUE(fs::exists(path("plot.png")));
  EXPECT_TRUE(fs::exists(path("frames/frame_00000.png")));
}

TEST_F(Mgraph, OnErrorSkipReportsBadSequences) {
  auto doc = nlohmann::json::parse(slurp(shared("db.json")));
  doc["sequences"][2]["frames"][1][5] = nullptr;  // not a number
  doc["sequences"][4]["label"] = "boredom";       // unknown label
  const std::string bad = write("bad.json", doc.dump());
  auto r = run("build --db " + bad + " --out " + path("g.json"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("bad.json: at /sequences/2/frames/1/5: expected a number, got null"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(path("g.json")));
  r = run("build --db " + bad + " --on-error skip --out " + path("g.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("skipped: " + bad + ": at /sequences/2/frames/1/5"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("/sequences/4/label"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("2 record(s) skipped"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(path("g.json")));
  r = run("build --db " + bad + " --on-error ignore --out " + path("g2.json"));
  EXPECT_EQ(r.code, 1);
  // A sequence that does not start neutral (issue 19): stop by default, skipped and reported with skip.
  auto reversed = nlohmann::json::parse(slurp(shared("db.json")));
  auto& frames = reversed["sequences"][1]["frames"];
  std::reverse(frames.begin(), frames.end());
  const std::string rev = write("rev.json", reversed.dump());
  r = run("build --db " + rev + " --no-clean --out " + path("g3.json"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("does not start neutral"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("g3.json")));
  r = run("build --db " + rev + " --no-clean --on-error skip --out " + path("g3.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("skipped: preprocess: sequence \"" + reversed["sequences"][1]["id"].get<std::string>() +
                       "\" does not start neutral"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::exists(path("g3.json")));
}

TEST_F(Mgraph, EvalShardsMergeToTheWholeTable) {
  auto r = run("eval --db " + shared("db.json") + " --thresholds 0.5 --csv " + path("all.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("paper (CK+"), std::string::npos);
  double length_sum = 0, pose_sum = 0, samples = 0, distances = 0;
  for (int i = 0; i < 3; ++i) {
    const std::string csv = path("s" + std::to_string(i) + ".csv");
    r = run("eval --db " + shared("db.json") + " --thresholds 0.5 --shard " + std::to_string(i) +
            "/3 --csv " + csv);
    ASSERT_EQ(r.code, 0) << r.err;
    const auto lines = csv_lines(slurp(csv));
    ASSERT_EQ(lines.size(), 2u);
    std::vector<std::string> f;
    std::stringstream ss(lines[1]);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    ASSERT_EQ(f.size(), 13u);
    samples += std::stod(f[7]);
    distances += std::stod(f[8]);
    length_sum += std::stod(f[9]);
    pose_sum += std::stod(f[11]);
  }
  const auto whole = csv_lines(slurp(path("all.csv")));
  std::vector<std::string> w;
  std::stringstream ss(whole[1]);
  for (std::string x; std::getline(ss, x, ',');) w.push_back(x);
  EXPECT_EQ(samples, std::stod(w[7]));
  EXPECT_EQ(samples, 14.0);
  EXPECT_EQ(distances, std::stod(w[8]));
  EXPECT_NEAR(length_sum / samples, std::stod(w[3]), 1e-5);
  EXPECT_NEAR(pose_sum / distances, std::stod(w[5]), 1e-5);
}

TEST_F(Mgraph, SynthBatchRequestsWithShardsAndSkip) {
  const std::string req = write("req.csv", "id,labels\na,fear;surprise\nb,boredom\nc,happiness\n");
  auto r = run("synth --graph " + shared("graph.json") + " --requests " + req + " --out " +
               path("o.json"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("req.csv:3:2:"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("o.json")));
  r = run("synth --graph " + shared("graph.json") + " --requests " + req +
          " --on-error skip --out " + path("o.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("1 request(s) skipped"), std::string::npos) << r.err;
  const auto doc = nlohmann::json::parse(slurp(path("o.json")));
  ASSERT_EQ(doc["sequences"].size(), 3u);  // a: 2 transitions, c: 1
  EXPECT_EQ(doc["sequences"][0]["id"], "a/synth_0_fear");
  EXPECT_EQ(doc["sequences"][2]["id"], "c/synth_0_happiness");
  // Shard 2/3 holds request c only, and it is the same animation as in the whole run.
  r = run("synth --graph " + shared("graph.json") + " --requests " + req + " --shard 2/3 --out " +
          path("c.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto c = nlohmann::json::parse(slurp(path("c.json")));
  ASSERT_EQ(c["sequences"].size(), 1u);
  EXPECT_EQ(c["sequences"][0], doc["sequences"][2]);
  // Malformed files.
  r = run("synth --graph " + shared("graph.json") + " --requests " +
          write("h.csv", "name,labels\n") + " --out -");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("header"), std::string::npos);
  r = run("synth --graph " + shared("graph.json") + " --requests " + write("e.csv", "") +
          " --out -");
  EXPECT_EQ(r.code, 2);
  r = run("synth --graph " + shared("graph.json") + " --out -");
  EXPECT_EQ(r.code, 1);
  r = run("synth --graph " + shared("graph.json") + " --labels fear --requests " + req +
          " --out -");
  EXPECT_EQ(r.code, 1);
}

TEST_F(Mgraph, WritesGifAndMp4) {
  if (!emoface::core::ffmpeg_available()) GTEST_SKIP() << "ffmpeg not installed";
  auto r =
      run("synth --graph " + shared("graph.json") + " --labels surprise --out " + path("s.json") +
          " --video " + path("s.gif") + " --video-width 160 --video-height 120");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(path("s.gif")).substr(0, 6), "GIF89a");
  r = run("idle --graph " + shared("graph.json") + " --label happiness --duration 1 --out " +
          path("i.csv") + " --video " + path("i.mp4") +
          " --video-width 160 --video-height 120 --fps 25");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string mp4 = slurp(path("i.mp4"));
  ASSERT_GT(mp4.size(), 12u);
  EXPECT_EQ(mp4.substr(4, 4), "ftyp");
  EXPECT_NE(mp4.find(emoface::kGenerator), std::string::npos);  // version stamp in the comment metadata
  // Same seed → the same GIF, byte for byte.
  r = run("synth --graph " + shared("graph.json") + " --labels surprise --out " + path("s2.json") +
          " --video " + path("s2.gif") + " --video-width 160 --video-height 120");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(path("s2.gif")), slurp(path("s.gif")));
  // Unsupported extension: nothing written.
  r = run("synth --graph " + shared("graph.json") + " --labels surprise --out " + path("s3.json") +
          " --video " + path("s.avi"));
  EXPECT_EQ(r.code, 2);
  EXPECT_FALSE(fs::exists(path("s.avi")));
  EXPECT_FALSE(fs::exists(path("s3.json")));
}

// Issue 19: the committed capture examples are what `mgraph capture-example` writes (data/capture/README.md),
// and `mgraph capture` turns them into labelled sequences; bad files stop with a located error.
TEST_F(Mgraph, CaptureExamplesAreReproducibleAndReadBack) {
  const std::string data = std::string(EMOFACE_SOURCE_DIR) + "/data/capture/";
  auto r = run("capture-example --format openface --out " + path("of") +
               " --subjects 7 --per-label 1 --max-takes 2 --min-frames 8 --max-frames 12 --rest 6 --hold 3");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"take_S001.csv", "take_S002.csv", "labels.csv"})
    EXPECT_EQ(slurp(path("of/") + f), slurp(data + "openface/" + f)) << f;
  r = run("capture-example --format mediapipe --out " + path("mp") +
          " --subjects 7 --per-label 1 --max-takes 1 --min-frames 5 --max-frames 5 --rest 3 --hold 1");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"take_S001.ndjson", "labels.csv"})
    EXPECT_EQ(slurp(path("mp/") + f), slurp(data + "mediapipe/" + f)) << f;
  // Read back: labels from the column and from the side file give the same database.
  r = run("capture --openface " + data + "openface/take_S001.csv " + data + "openface/take_S002.csv" +
          " --label-column label --out " + path("a.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("2 take(s) → 2 labelled neutral-to-peak sequence(s)"), std::string::npos) << r.err;
  r = run("capture --openface " + data + "openface/take_S001.csv " + data + "openface/take_S002.csv" +
          " --labels " + data + "openface/labels.csv --out " + path("b.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(path("a.json")), slurp(path("b.json")));
  const auto db = nlohmann::json::parse(slurp(path("a.json")));
  EXPECT_EQ(db["sequences"][0]["label"], "happiness");
  EXPECT_EQ(db["sequences"][1]["label"], "sadness");
  r = run("capture --mediapipe " + data + "mediapipe/take_S001.ndjson --out " + path("m.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  // Without labels a segment is an error (exit 2, nothing written), or skipped and reported.
  r = run("capture --openface " + data + "openface/take_S001.csv --out " + path("none.json"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("has no label"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("none.json")));
  // A broken file names its line and field.
  std::string text = slurp(data + "openface/take_S001.csv");
  const std::size_t line3 = text.find('\n', text.find('\n') + 1) + 1;
  text.replace(text.find(", ", line3 + 2) + 2, 1, "x");  // the timestamp of the second frame
  const std::string bad = write("bad.csv", text);
  r = run("capture --openface " + bad + " --label-column label --out " + path("bad.json"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("bad.csv:3:3: expected a finite number"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("bad.json")));
  EXPECT_EQ(run("capture --out " + path("x.json")).code, 1);  // no input
  EXPECT_EQ(run("capture-example --format xml --out " + path("x")).code, 1);
}

// Issue 19, item 4: region graphs as Graphviz pictures.
TEST_F(Mgraph, DotDrawsARegionGraph) {
  auto r = run("dot --graph " + shared("graph.json") + " --region mouth --depth 1 --weights --out " + path("m.dot"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string dot = slurp(path("m.dot"));
  EXPECT_EQ(dot.rfind("digraph \"motion graph mouth\"", 0), 0u);
  EXPECT_NE(dot.find("source"), std::string::npos);
  r = run("dot --graph " + shared("graph.json") + " --region lips --out " + path("x.dot"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("eyes, eyebrows, nose, mouth, cheeks_jaw"), std::string::npos) << r.err;
  if (std::system("dot -V > /dev/null 2>&1") == 0) {
    ASSERT_EQ(run("dot --graph " + shared("graph.json") + " --region eyes --depth 1 --out " + path("e.svg")).code, 0);
    EXPECT_NE(slurp(path("e.svg")).find("<svg"), std::string::npos);
  }
}

}  // namespace

// Issue 19, item 2: motion graphs in weight space (ARKit-52), Live Link Face takes.
TEST_F(Mgraph, WeightSpaceFromLiveLinkAndTheFaceModel) {
  const std::string data = std::string(EMOFACE_SOURCE_DIR) + "/data/capture/livelink/";
  auto r = run("capture-example --format livelink --out " + path("ll") +
               " --subjects 7 --per-label 1 --max-takes 2 --min-frames 8 --max-frames 12 --rest 6 --hold 3");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"take_S001.csv", "take_S002.csv", "labels.csv"})
    EXPECT_EQ(slurp(path("ll/") + f), slurp(data + f)) << f;
  const std::string takes = data + "take_S001.csv " + data + "take_S002.csv";
  r = run("capture --livelink " + takes + " --labels " + data + "labels.csv --timecode-fps 30 --out " + path("w.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("2 take(s) → 2 labelled neutral-to-peak sequence(s)"), std::string::npos) << r.err;
  const auto db = nlohmann::json::parse(slurp(path("w.json")));
  EXPECT_EQ(db["dimensions"], 1);
  EXPECT_EQ(db["landmark_count"], 52);
  EXPECT_EQ(db["sequences"][0]["label"], "happiness");
  EXPECT_EQ(db["sequences"][1]["label"], "sadness");
  // Face model → ARKit weights → graph → synthesis → Live Link CSV and face parameters.
  r = run("generate --space arkit --per-label 1 --subjects 7 --out " + path("wdb.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(slurp(path("wdb.csv")).find(",frame,w0,w1,"), std::string::npos);
  r = run("build --db " + path("wdb.csv") + " --out " + path("wg.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("threshold 0.012"), std::string::npos) << r.err;  // the weight default
  r = run("synth --graph " + path("wg.json") + " --labels surprise,neutral --idle 0.5 --out " + path("s.json") +
          " --livelink " + path("s_ll.csv") + " --params " + path("s_params.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(path("s_ll.csv")).rfind("Timecode,BlendShapeCount,EyeBlinkLeft,", 0), 0u);
  const auto params = csv_lines(slurp(path("s_params.csv")));
  ASSERT_GT(params.size(), 10u);
  EXPECT_EQ(params[0].rfind("time,zygomatic_major_l,", 0), 0u) << params[0];
  r = run("eval --db " + path("wdb.csv") + " --thresholds 0.01 --raw --csv " + path("e.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("vs raw samples (weight)"), std::string::npos) << r.out;
  const auto rows = csv_lines(slurp(path("e.csv")));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_NE(rows[0].find(",raw_pose_diff_mean,raw_pose_diff_std,raw_pose_sum,raw_pose_sum2"), std::string::npos);
  // Usage errors (exit 1) and bad files (exit 2, nothing written, file:line named).
  EXPECT_EQ(run("generate --space voxels --out " + path("x.json")).code, 1);
  EXPECT_EQ(run("generate --space arkit --model parametric --out " + path("x.json")).code, 1);
  EXPECT_EQ(run("generate --space arkit --sheet " + path("x.png") + " --out " + path("x.json")).code, 1);
  EXPECT_EQ(run("generate --space arkit --weight-noise -1 --out " + path("x.json")).code, 1);
  EXPECT_EQ(run("synth --graph " + path("wg.json") + " --labels fear --sheet " + path("x.png") + " --out " +
                path("x.json")).code, 1);
  EXPECT_EQ(run("synth --graph " + shared("graph.json") + " --labels fear --livelink " + path("x.csv") +
                " --out " + path("x.json")).code, 1);
  EXPECT_EQ(run("capture --livelink " + takes + " --openface " + takes + " --out " + path("x.json")).code, 1);
  EXPECT_EQ(run("capture --livelink " + takes + " --label-column label --out " + path("x.json")).code, 1);
  EXPECT_EQ(run("capture --livelink " + takes + " --timecode-fps 0 --out " + path("x.json")).code, 1);
  EXPECT_FALSE(fs::exists(path("x.json")));
  r = run("capture --livelink " + takes + " --timecode-fps 30 --out " + path("none.json"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("has no label"), std::string::npos) << r.err;
  std::string text = slurp(data + "take_S001.csv");
  const std::size_t line3 = text.find('\n', text.find('\n') + 1) + 1;
  const std::size_t field = text.find(',', text.find(',', line3) + 1) + 1;  // EyeBlinkLeft of frame 2
  text.replace(field, text.find(',', field) - field, "nan");
  r = run("capture --livelink " + write("bad.csv", text) + " --labels " + data + "labels.csv --timecode-fps 30 --out " +
          path("bad.json"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("bad.csv:3:"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("bad.json")));
  text = slurp(data + "take_S001.csv");
  r = run("capture --livelink " + write("short.csv", text.substr(0, line3 + 40)) + " --timecode-fps 30 --out " +
          path("short.json"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("short.csv:3"), std::string::npos) << r.err;
}
