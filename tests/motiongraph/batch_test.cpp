// Batches (issue 18, item 4): the requests reader/writer pair, chained synthesis of a block of
// requests (shards concatenate to the whole run), the evaluation CSV writer/reader pair.
#include "emoface/motiongraph/batch.hpp"

#include <gtest/gtest.h>

#include "emoface/core/csv.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/shard.hpp"
#include "emoface/motiongraph/layout.hpp"
#include "emoface/motiongraph/render.hpp"
#include "fixtures.hpp"

namespace emoface::motiongraph {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_requests_csv(text, "r.csv");
  } catch (const FormatError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Requests, RoundTripAndStampSkipped) {
  const std::vector<SynthesisRequest> reqs{
      {"a", {"fear", "surprise"}}, {"b,quoted \"id\"", {"happiness"}}, {"c", {"neutral"}}};
  const std::string text = requests_to_csv(reqs);
  EXPECT_EQ(text.rfind(core::csv_stamp(), 0), 0u);  // stamped like every CSV emoface writes
  const std::vector<RequestRecord> back = parse_requests_csv(text, "r.csv");
  ASSERT_EQ(back.size(), 3u);
  std::vector<SynthesisRequest> again;
  for (const RequestRecord& r : back) {
    EXPECT_FALSE(r.error) << r.error->what();
    again.push_back(r.request);
  }
  EXPECT_EQ(back[0].line, 3u);  // stamp, header, first request
  EXPECT_EQ(back[1].request.id, "b,quoted \"id\"");
  EXPECT_EQ(back[0].request.labels, (std::vector<std::string>{"fear", "surprise"}));
  EXPECT_EQ(requests_to_csv(again), text);
  // CRLF, blank lines, a BOM and the header of a concatenated second file.
  const auto crlf =
      parse_requests_csv("\xEF\xBB\xBFid,labels\r\n\r\na,fear\r\nid,labels\nb,anger\n", "r.csv");
  ASSERT_EQ(crlf.size(), 2u);
  EXPECT_EQ(crlf[1].request.id, "b");
  EXPECT_EQ(crlf[1].line, 5u);
  EXPECT_THROW(requests_to_csv({{"", {"fear"}}}), InvalidInput);
  EXPECT_THROW(requests_to_csv({{"a", {}}}), InvalidInput);
  EXPECT_THROW(requests_to_csv({{"a", {"fe;ar"}}}), InvalidInput);
}

TEST(Requests, BadInput) {
  EXPECT_EQ(error_of(""), "r.csv:1:1: empty requests file (no header)");
  EXPECT_EQ(error_of("# emoface 0.1.0\n"), "r.csv:1:1: empty requests file (no header)");
  EXPECT_EQ(error_of("name,labels\n"), "r.csv:1:1: header must be \"id,labels\"");
  EXPECT_EQ(error_of("id,labels,x\n"), "r.csv:1:1: header must be \"id,labels\"");
  EXPECT_EQ(error_of("id,labels\n\xff,fear\n"), "r.csv:2: not valid UTF-8");
  // Record errors stay in their record (a bad record is still an item of the batch).
  const auto recs = parse_requests_csv(
      "id,labels\na,fear;joy\n,fear\nb,fear,x\nc,\"open\nd,\ne,fear;;anger\nf,happiness\n",
      "r.csv");
  ASSERT_EQ(recs.size(), 7u);
  auto msg = [&](std::size_t i) { return recs[i].error ? std::string(recs[i].error->what()) : ""; };
  EXPECT_EQ(msg(0).rfind("r.csv:2:2: unknown expression label \"joy\"", 0), 0u) << msg(0);
  EXPECT_EQ(msg(1), "r.csv:3:1: empty request id");
  EXPECT_EQ(msg(2), "r.csv:4:1: expected 2 fields (id,labels), got 3");
  EXPECT_EQ(msg(3).rfind("r.csv:5:", 0), 0u) << msg(3);  // unterminated quote
  EXPECT_EQ(msg(4).rfind("r.csv:6:2: unknown expression label \"\"", 0), 0u) << msg(4);
  EXPECT_EQ(msg(5).rfind("r.csv:7:2: unknown expression label \"\"", 0), 0u) << msg(5);
  EXPECT_FALSE(recs[6].error);
  // Huge: a million-label request is read (and rejected at its first unknown label) without fuss.
  std::string huge = "id,labels\nh,";
  for (int i = 0; i < 200000; ++i) huge += "fear;";
  huge += "x\n";
  const auto big = parse_requests_csv(huge, "r.csv");
  ASSERT_EQ(big.size(), 1u);
  ASSERT_TRUE(big[0].error);
  EXPECT_NE(std::string(big[0].error->what()).find("\"x\""), std::string::npos);
}

TEST(Requests, ShardsOfABatchConcatenateToTheWholeRun) {
  const MotionGraph g = build_graph(test::small_prepared(), {});
  const auto recs = parse_requests_csv(
      "id,labels\na,surprise;happiness\nb,boredom\nc,happiness\nd,surprise\ne,happiness\n",
      "r.csv");
  ChainOptions o = chain_options_for(g);
  o.synthesis.vary_duration = true;  // random choices: seeded per request
  o.idle_after = 0.5;
  EXPECT_THROW(synthesize_requests(g, recs, {0, recs.size()}, 9, o), FormatError);
  ReadReport report;
  const std::vector<Sequence> whole =
      synthesize_requests(g, recs, {0, recs.size()}, 9, o, OnError::Skip, &report);
  ASSERT_EQ(report.skipped.size(), 1u);
  EXPECT_EQ(report.skipped[0].rfind("r.csv:3:2: unknown expression label \"boredom\"", 0), 0u);
  ASSERT_EQ(whole.size(), 10u);  // a: 2 transitions + 2 idles; c, d, e: 1 + 1
  EXPECT_EQ(whole[0].id, "a/synth_0_surprise");
  EXPECT_EQ(whole[1].id, "a/idle_1_surprise");
  EXPECT_EQ(whole[4].id, "c/synth_0_happiness");
  for (std::size_t n : {2u, 3u, 5u}) {
    std::vector<Sequence> joined;
    for (std::size_t i = 0; i < n; ++i) {
      const auto part =
          synthesize_requests(g, recs, core::Shard{i, n}.block(recs.size()), 9, o, OnError::Skip);
      joined.insert(joined.end(), part.begin(), part.end());
    }
    ASSERT_EQ(joined.size(), whole.size()) << n;
    for (std::size_t s = 0; s < whole.size(); ++s) {
      EXPECT_EQ(joined[s].id, whole[s].id);
      ASSERT_EQ(joined[s].frames.size(), whole[s].frames.size());
      for (std::size_t f = 0; f < whole[s].frames.size(); ++f)
        EXPECT_TRUE(joined[s].frames[f] == whole[s].frames[f]);  // bit-exact
    }
  }
  // A block past the records; a chain without labels.
  EXPECT_THROW(synthesize_requests(g, recs, {0, 7}, 9, o), InvalidInput);
  EXPECT_THROW(synthesize_chain(g, {}, 1, "", o), InvalidInput);
}

TEST(EvaluationCsv, RoundTripByteForByteAndMergeOfConcatenatedShards) {
  const PreparedDatabase& data = test::small_prepared();
  EvaluationOptions o;
  std::vector<EvaluationRow> whole{evaluate(data, 0.6, o), evaluate(data, 1.2, o)};
  const std::string text = evaluation_csv(whole);
  const std::vector<EvaluationRow> back = parse_evaluation_csv(text, "e.csv");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(evaluation_csv(back), text);
  EXPECT_EQ(back[0].samples, whole[0].samples);
  EXPECT_EQ(back[0].pose_sum, whole[0].pose_sum);  // sums are exact (17 digits)
  EXPECT_EQ(back[1].length_sum2, whole[1].length_sum2);
  // Three shard tables, concatenated, read as one list; merged per threshold = the whole table.
  std::string cat;
  o.shard_count = 3;
  for (std::size_t i = 0; i < 3; ++i) {
    o.shard_index = i;
    cat += evaluation_csv({evaluate(data, 0.6, o)});
  }
  const auto rows = parse_evaluation_csv(cat, "cat.csv");
  ASSERT_EQ(rows.size(), 3u);
  const EvaluationRow m = merge_rows(rows);
  EXPECT_EQ(m.samples, whole[0].samples);
  EXPECT_NEAR(m.pose_mean, whole[0].pose_mean, 1e-12);
  EXPECT_NEAR(m.length_std, whole[0].length_std, 1e-9);
  // Raw columns: written and read when the rows have them.
  EvaluationRow r = whole[0];
  r.has_raw = true;
  r.raw_pose_mean = 1.5, r.raw_pose_std = 0.25, r.raw_pose_sum = 3, r.raw_pose_sum2 = 4.625;
  const auto raw = parse_evaluation_csv(evaluation_csv({r}), "r.csv");
  ASSERT_TRUE(raw[0].has_raw);
  EXPECT_EQ(raw[0].raw_pose_sum2, 4.625);
  EXPECT_THROW(evaluation_csv({r, whole[1]}), InvalidInput);
}

TEST(EvaluationCsv, BadInput) {
  const std::string good = evaluation_csv({evaluate(test::small_prepared(), 0.6)});
  const std::size_t row = good.find('\n', core::csv_stamp().size()) + 1;  // start of the data row
  auto err = [](const std::string& text) {
    try {
      parse_evaluation_csv(text, "e.csv");
    } catch (const FormatError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  auto field = [&](int k, const std::string& value) {  // replace field k of the data row
    std::string s = good;
    std::size_t b = row;
    for (int i = 0; i < k; ++i) b = s.find(',', b) + 1;
    const std::size_t e = std::min(s.find(',', b), s.find('\n', b));
    return s.replace(b, e - b, value);
  };
  EXPECT_NE(err("").find("no header"), std::string::npos);
  EXPECT_NE(err(good.substr(0, row) + "0.5,1\n").find("e.csv:3: expected 13 fields"),
            std::string::npos);                                           // truncated row
  EXPECT_NE(err(field(0, "nan")).find("e.csv:3:1:"), std::string::npos);  // NaN
  EXPECT_NE(err(field(5, "inf")).find("e.csv:3:6:"), std::string::npos);
  EXPECT_NE(err(field(11, "1e999")).find("e.csv:3:12:"), std::string::npos);  // overflow
  EXPECT_NE(err(field(1, "100.5")).find("above 100"), std::string::npos);     // out of range
  EXPECT_NE(err(field(3, "-1")).find("is below 0"), std::string::npos);
  EXPECT_NE(err(field(2, "2.5")).find("e.csv:3:3: column \"nodes\": expected a non-negative"),
            std::string::npos);
  EXPECT_NE(err(field(7, "-3")).find("e.csv:3:8:"), std::string::npos);
  EXPECT_NE(err("threshold,nodes\n1,2\n").find("missing column \"compression_percent\""),
            std::string::npos);
  std::string extra = good;
  extra.insert(good.find('\n', core::csv_stamp().size()), ",note");
  extra.insert(good.find('\n', row) + 5, ",x");
  EXPECT_NE(err(extra).find("unexpected columns"), std::string::npos);
  EXPECT_EQ(err(good), "no error");
}

// The table mgraph eval prints; the expected text written out by hand (the printf widths).
TEST(EvaluationTable, HeaderRowsAndThePaperLine) {
  EvaluationRow r;
  r.threshold = 0.5;
  r.compression = 0.5753;
  r.nodes = 12;
  r.length_mean = 1.25;
  r.length_std = 0.5;
  r.pose_mean = 2.125;
  r.pose_std = 0.25;
  const std::string paper =
      "paper (CK+, 70 sequences): 90% -> 0.98 +- 1.84 frames, 2.86 +- 2.3 px; 78% -> 0.071 +- "
      "0.39, 2.12 +- 1.81; 57.53% -> 0 +- 0, 1.52 +- 1.51\n";
  EXPECT_EQ(evaluation_table({r}, "px"),
            " threshold  compression %   nodes   length diff (frames)         pose diff (px)\n"
            "    0.5000          57.53      12      1.250 +- 0.500        2.1250 +- 0.2500  \n" +
                paper);
  EvaluationRow w;
  w.threshold = 0.012;
  w.compression = 0.9;
  w.nodes = 3;
  w.pose_mean = 0.0125;
  w.pose_std = 0.001;
  w.has_raw = true;
  w.raw_pose_mean = 0.02;
  w.raw_pose_std = 0.5;
  EXPECT_EQ(evaluation_table({w}, "weight"),
            " threshold  compression %   nodes   length diff (frames)     pose diff (weight)"
            "   vs raw samples (weight)\n"
            "    0.0120          90.00       3      0.000 +- 0.000        0.0125 +- 0.0010   "
            "    0.0200 +- 0.5000  \n" +
                paper);
}

TEST(DatabaseBlock, SlicesTheSequences) {
  const Database whole = test::small_synthetic();
  const std::size_t n = whole.sequences.size();
  const Database mid = database_block(whole, {3, 5});
  ASSERT_EQ(mid.sequences.size(), 2u);
  EXPECT_EQ(mid.sequences[0].id, whole.sequences[3].id);
  EXPECT_EQ(mid.sequences[1].id, whole.sequences[4].id);
  EXPECT_EQ(mid.landmark_count, whole.landmark_count);
  EXPECT_EQ(mid.frame_rate, whole.frame_rate);
  EXPECT_TRUE(database_block(whole, {n, n}).sequences.empty());
  EXPECT_THROW(database_block(whole, {0, n + 1}), InvalidInput);
  EXPECT_THROW(database_block(whole, {2, 1}), InvalidInput);
}

TEST(LabelPeaks, NeutralThenTheFirstPeakOfEachLabel) {
  Database db;
  db.landmark_count = 4;
  db.sequences = {test::line_sequence("a", Label::Fear, 3, 4, 1.0),
                  test::line_sequence("b", Label::Happiness, 4, 4, 2.0),
                  test::line_sequence("c", Label::Fear, 5, 4, 3.0)};
  const std::vector<Pose> peaks = label_peaks(db);
  ASSERT_EQ(peaks.size(), 3u);
  EXPECT_TRUE(peaks[0] == db.sequences[0].frames.front());
  EXPECT_TRUE(peaks[1] == db.sequences[0].frames.back());  // fear: a's peak (c comes later)
  EXPECT_TRUE(peaks[2] == db.sequences[1].frames.back());
  EXPECT_TRUE(label_peaks(Database{}).empty());
}

TEST(PeaksSheet, OnlyForIbugDatabases) {
  const std::string dir = ::testing::TempDir() + "/peaks_sheet";
  core::OutputBundle bundle;
  Database small;
  small.landmark_count = 4;
  small.sequences = {test::line_sequence("a", Label::Fear, 3, 4, 1.0)};
  EXPECT_THROW(stage_peaks_sheet(bundle, dir + "/a.png", small, 4, 100), InvalidInput);
  Database weights = test::small_synthetic();
  weights.dimensions = 1;
  EXPECT_THROW(stage_peaks_sheet(bundle, dir + "/b.png", weights, 4, 100), InvalidInput);
  Database empty = test::small_synthetic();
  empty.sequences.clear();
  EXPECT_THROW(stage_peaks_sheet(bundle, dir + "/c.png", empty, 4, 100), InvalidInput);
  // The sheet is the contact sheet of the peaks, iBUG regions coloured (as mgraph generate drew
  // it).
  const Database db = test::small_synthetic();
  stage_peaks_sheet(bundle, dir + "/d.png", db, 4, 100);
  bundle.commit();
  const std::string png = core::read_file(dir + "/d.png");
  std::vector<int> ids(68);
  for (int i = 0; i < 68; ++i) ids[static_cast<std::size_t>(i)] = i;
  const std::vector<int> layout_groups = [] {
    std::vector<int> g(68, 8);
    const LandmarkLayout l = default_layout();
    for (std::size_t r = 0; r < l.regions.size(); ++r)
      for (int i : l.regions[r].landmarks) g[static_cast<std::size_t>(i)] = static_cast<int>(r);
    return g;
  }();
  EXPECT_EQ(layout_groups[40], 0);  // the layout's first region holds the eyes
  EXPECT_EQ(png, encode_png(
                     contact_sheet(label_peaks(db), layout_groups, 4, 100, 87, contours_for(ids))));
  EXPECT_EQ(label_peaks(db).size(), 1u + 7u);  // neutral + the 7 labels of small_synthetic
}

}  // namespace
}  // namespace emoface::motiongraph
