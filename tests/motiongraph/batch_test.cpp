// Batches (issue 18, item 4): the requests reader/writer pair, chained synthesis of a block of
// requests (shards concatenate to the whole run), the evaluation CSV writer/reader pair.
#include "emoface/motiongraph/batch.hpp"

#include <gtest/gtest.h>

#include "emoface/core/csv.hpp"
#include "emoface/core/shard.hpp"
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

}  // namespace
}  // namespace emoface::motiongraph
