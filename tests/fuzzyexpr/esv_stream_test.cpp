#include "emoface/fuzzyexpr/esv_stream.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/shard.hpp"

namespace emoface::fuzzyexpr {
namespace {

const char* kHeader = "id,Sadness,happiness,ANGER,fear,disgust,surprise\n";

std::vector<EsvRecord> read_all(const std::string& text, StreamFormat f = StreamFormat::Csv,
                                bool clamp = false) {
  std::istringstream in(text);
  EsvReaderOptions o;
  o.format = f;
  o.clamp = clamp;
  EsvReader r(in, "t.csv", o);
  std::vector<EsvRecord> out;
  EsvRecord rec;
  while (r.next(rec)) out.push_back(rec);
  return out;
}

// Expects the first bad record of `text` to fail at (line, column) with `fragment` in the message.
void expect_error(const std::string& text, std::size_t line, std::size_t column,
                  const std::string& fragment, StreamFormat f = StreamFormat::Csv) {
  try {
    read_all(text, f);
    FAIL() << "no error for: " << text.substr(0, 80);
  } catch (const FormatError& e) {
    EXPECT_EQ(e.where().file, "t.csv");
    EXPECT_EQ(e.where().line, line) << e.what();
    EXPECT_EQ(e.where().column, column) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(EsvReader, CsvAnyOrderCaseInsensitivePassThrough) {
  auto recs = read_all(std::string(kHeader) + "a,0.1,0.2,0.3,0.4,0.5,0.6\r\n\"b,c\",0,1,0,0,0,+0.25");
  ASSERT_EQ(recs.size(), 2u);
  EXPECT_EQ(recs[0].line, 2u);
  EXPECT_EQ(recs[0].index, 0u);
  EXPECT_EQ(recs[0].esv, (Esv{0.1, 0.2, 0.3, 0.4, 0.5, 0.6}));
  EXPECT_EQ(recs[0].extra, std::vector<std::string>{"a"});
  EXPECT_EQ(recs[1].extra, std::vector<std::string>{"b,c"});
  EXPECT_EQ(recs[1].esv[index(Emotion::Surprise)], 0.25);
  // Columns in another order.
  recs = read_all("surprise,disgust,fear,anger,happiness,sadness\n1,0,0,0,0.5,0\n");
  EXPECT_EQ(recs[0].esv, (Esv{0, 0.5, 0, 0, 0, 1}));
  // A UTF-8 BOM is skipped.
  recs = read_all("\xEF\xBB\xBFsadness,happiness,anger,fear,disgust,surprise\n0,0,0,0,0,0\n");
  EXPECT_EQ(recs.size(), 1u);
}

TEST(EsvReader, CsvBadInputNamesLineAndColumn) {
  const std::string h = kHeader;
  expect_error("", 1, 0, "empty input");
  expect_error("id,sadness,happiness\n", 1, 0, "lacks emotion column(s): anger, fear, disgust, surprise");
  expect_error("sadness,happiness,anger,fear,disgust,surprise,Sadness\n", 1, 7, "duplicated column");
  expect_error("id,id,sadness,happiness,anger,fear,disgust,surprise\n", 1, 2, "duplicated column");
  expect_error("a,,sadness\n", 1, 2, "empty column name");
  expect_error(h + "a,0.1,abc,0,0,0,0\n", 2, 3, "happiness: not a number");
  expect_error(h + "a,0.1,0.5x,0,0,0,0\n", 2, 3, "not a number");
  expect_error(h + "a,0.1,,0,0,0,0\n", 2, 3, "empty value");
  expect_error(h + "a,nan,0,0,0,0,0\n", 2, 2, "not a finite number");
  expect_error(h + "a,0,inf,0,0,0,0\n", 2, 3, "not a finite number");
  expect_error(h + "a,0,0,1e999,0,0,0\n", 2, 4, "out of range");
  expect_error(h + "a,0,0,0,1.5,0,0\n", 2, 5, "outside [0, 1]");
  expect_error(h + "a,0,0,0,0,-0.1,0\n", 2, 6, "outside [0, 1]");
  expect_error(h + "a,0,0,0,0,0\n", 2, 7, "expected 7 fields, got 6");
  expect_error(h + "a,0,0,0,0,0,0,9\n", 2, 8, "expected 7 fields, got 8");
  expect_error(h + "a,0,0,0,0,0,0\n\nb,0,0,0,0,0,0\n", 3, 0, "empty line");
  expect_error(h + "\"a,0,0,0,0,0,0\n", 2, 15, "unterminated quoted field");
  expect_error(h + "a\xFF,0,0,0,0,0,0\n", 2, 2, "invalid UTF-8");
  expect_error("\xFF\xFEs\0a\0", 1, 1, "UTF-16");
  expect_error(h + "a," + std::string(2 << 20, '0') + ",0,0,0,0,0\nb,0,0,0,0,0,0\n", 2, 0, "longer than");
}

TEST(EsvReader, ClampOption) {
  auto recs = read_all(std::string(kHeader) + "a,1.5,-2,0,0,0,0\n", StreamFormat::Csv, true);
  EXPECT_EQ(recs[0].esv[0], 1.0);
  EXPECT_EQ(recs[0].esv[1], 0.0);
  EXPECT_THROW(read_all(std::string(kHeader) + "a,nan,0,0,0,0,0\n", StreamFormat::Csv, true), FormatError);
}

TEST(EsvReader, ContinuesAfterABadRecord) {
  std::istringstream in(std::string(kHeader) + "a,0,0,0,0,0,0\nb,x,0,0,0,0,0\nc,0.5,0,0,0,0,0\n");
  EsvReader r(in, "t.csv");
  EsvRecord rec;
  ASSERT_TRUE(r.next(rec));
  EXPECT_THROW(r.next(rec), FormatError);
  ASSERT_TRUE(r.next(rec));
  EXPECT_EQ(rec.extra[0], "c");
  EXPECT_EQ(rec.index, 2u);
  EXPECT_EQ(rec.line, 4u);
  EXPECT_FALSE(r.next(rec));
}

TEST(EsvReader, Ndjson) {
  const std::string good =
      "{\"id\":7,\"sadness\":0.1,\"Happiness\":0.2,\"anger\":0,\"fear\":0,\"disgust\":0,"
      "\"surprise\":1,\"tag\":{\"a\":[1,2]}}\n";
  auto recs = read_all(good, StreamFormat::Ndjson);
  ASSERT_EQ(recs.size(), 1u);
  EXPECT_EQ(recs[0].esv, (Esv{0.1, 0.2, 0, 0, 0, 1}));
  EXPECT_EQ(recs[0].extra_json, "\"id\":7,\"tag\":{\"a\":[1,2]}");
  const auto nd = StreamFormat::Ndjson;
  expect_error("{\"sadness\":0.1\n", 1, 15, "invalid JSON", nd);
  expect_error("[1,2]\n", 1, 1, "expected a JSON object", nd);
  expect_error("{\"sadness\":0,\"happiness\":0,\"anger\":0,\"fear\":0,\"disgust\":0}\n", 1, 0,
               "missing emotion field(s): surprise", nd);
  expect_error("{\"sadness\":\"0.5\",\"happiness\":0,\"anger\":0,\"fear\":0,\"disgust\":0,\"surprise\":0}\n",
               1, 0, "expected a number", nd);
  expect_error("{\"sadness\":0,\"Sadness\":0,\"happiness\":0,\"anger\":0,\"fear\":0,\"disgust\":0,"
               "\"surprise\":0}\n", 1, 0, "duplicated field", nd);
  expect_error("{\"sadness\":2,\"happiness\":0,\"anger\":0,\"fear\":0,\"disgust\":0,\"surprise\":0}\n", 1,
               0, "outside [0, 1]", nd);
  expect_error(good + "\n" + good, 2, 0, "empty line", nd);
  expect_error("{\"sadness\":1e999,\"happiness\":0,\"anger\":0,\"fear\":0,\"disgust\":0,\"surprise\":0}\n",
               1, 0, "number overflow", nd);
}

TEST(FmcvWriter, CsvNdjsonJsonAndSides) {
  EsvRecord rec;
  rec.extra = {"x,y"};
  Fmcv f{};
  f[index(Muscle::ZygomaticMajor)] = 0.5;
  f[index(Muscle::Masseter)] = 1.0 / 3.0;
  FmcvWriterOptions o;
  FmcvWriter csv(o, {"id"});
  std::string out = csv.begin();
  csv.append(out, rec, f);
  ASSERT_EQ(out.rfind(emoface::core::csv_stamp(), 0), 0u);  // version stamp first
  out.erase(0, emoface::core::csv_stamp().size());
  EXPECT_EQ(out.substr(0, 19), "id,zygomatic_major,");
  EXPECT_NE(out.find("\n\"x,y\",0.500000,0.000000,"), std::string::npos);
  EXPECT_NE(out.find(",0.333333\n"), std::string::npos);
  o.format = StreamFormat::Json;
  o.sides = true;
  o.precision = 3;
  FmcvWriter json(o, {"id"});
  out = json.begin();
  json.append(out, rec, f);
  json.append(out, rec, f);
  out += json.end();
  auto doc = nlohmann::json::parse(out);
  EXPECT_EQ(doc["format"], "emoface.fmcv");
  EXPECT_EQ(doc["parameters"].size(), 35u);
  EXPECT_EQ(doc["rows"].size(), 2u);
  EXPECT_EQ(doc["rows"][0]["id"], "x,y");
  EXPECT_EQ(doc["rows"][1]["zygomatic_major_r"], 0.5);
  EXPECT_EQ(doc["rows"][1]["masseter"], 0.333);
  o.format = StreamFormat::Ndjson;
  FmcvWriter nd(o, {});
  EsvRecord r2;
  r2.extra_json = "\"id\":7";
  out.clear();
  nd.append(out, r2, f);
  EXPECT_EQ(out.substr(0, 28), "{\"id\":7,\"zygomatic_major_l\":");
  EXPECT_EQ(nlohmann::json::parse(out)["masseter"], 0.333);
  EXPECT_THROW(FmcvWriter(o, {"masseter"}), InvalidInput);  // clash with an output column
  o.precision = 0;
  EXPECT_THROW(FmcvWriter(o, {}), InvalidInput);
}

TEST(FmcvWriter, NdjsonStartsWithAStreamHeader) {
  FmcvWriterOptions o;
  o.format = StreamFormat::Ndjson;
  const FmcvWriter nd(o, {});
  const std::string head = nd.begin();
  EXPECT_EQ(head, emoface::core::ndjson_header("fmcv", {1, 0}));
  EXPECT_TRUE(emoface::core::is_stream_header(nlohmann::json::parse(head)));
}

TEST(EsvReader, SkipsVersionStampsAndStreamHeaders) {
  std::istringstream csv(emoface::core::csv_stamp() + "# another comment\n" + std::string(kHeader) + "a,1,0,0,0,0,0\n");
  EsvReader r(csv, "stamped.csv");
  EsvRecord rec;
  ASSERT_TRUE(r.next(rec));
  EXPECT_EQ(rec.line, 4u);  // line numbers still count the stamp lines
  EXPECT_FALSE(r.next(rec));
  const std::string row = R"({"sadness":0,"happiness":1,"anger":0,"fear":0,"disgust":0,"surprise":0})";
  std::istringstream nd(emoface::core::ndjson_header("esv", {1, 0}) + row + "\n" +
                        emoface::core::ndjson_header("esv", {1, 0}) + row + "\n");  // two concatenated shards
  EsvReaderOptions ro;
  ro.format = StreamFormat::Ndjson;
  EsvReader rn(nd, "stamped.ndjson", ro);
  ASSERT_TRUE(rn.next(rec));
  EXPECT_EQ(rec.line, 2u);
  ASSERT_TRUE(rn.next(rec));
  EXPECT_EQ(rec.line, 4u);
  EXPECT_EQ(rec.esv[index(Emotion::Happiness)], 1.0);
  EXPECT_FALSE(rn.next(rec));
  std::istringstream only_stamp(emoface::core::csv_stamp());
  EXPECT_THROW(EsvReader(only_stamp, "x.csv"), FormatError);
}

TEST(ConvertStream, ContiguousShardsMergeBackToOneRunByteForByte) {
  std::string text = kHeader;
  for (int i = 0; i < 50; ++i)
    text += "r" + std::to_string(i) + ",0.4,0.4,0.4," + std::to_string(i / 50.0) + ",0,0\n";
  ExpressionOptions eo;
  eo.tie_break = TieBreak::Random;
  eo.seed = 3;
  Engine engine(default_rule_base(), eo);
  auto run = [&](std::size_t i, std::size_t n, std::size_t* written = nullptr) {
    std::istringstream counting(text);
    EsvReader c(counting, "t.csv");
    std::istringstream in(text);
    EsvReader r(in, "t.csv");
    FmcvWriter w({}, r.extra_columns());
    BatchOptions b;
    b.shard_index = i;
    b.shard_count = n;
    b.total_records = count_records(c);
    std::string out;
    auto rep = convert_stream(r, w, engine, b, [&](std::string_view s) { out += s; });
    EXPECT_EQ(rep.records_read, 50u);
    if (written) *written = rep.records_written;
    return out;
  };
  const std::string whole = run(0, 1);
  std::vector<std::string> parts;
  std::size_t sizes[3];
  for (std::size_t i = 0; i < 3; ++i) parts.push_back(run(i, 3, &sizes[i]));
  // Blocks of floor(i·50/3): 16, 17, 17 rows, in order; r16 opens shard 1.
  EXPECT_EQ(sizes[0], 16u);
  EXPECT_EQ(sizes[1], 17u);
  EXPECT_EQ(sizes[2], 17u);
  EXPECT_NE(parts[1].find("\nr16,"), std::string::npos);
  EXPECT_EQ(emoface::core::merge_shard_outputs(parts), whole);
  EXPECT_EQ(whole, run(0, 1));  // deterministic
  BatchOptions unknown;
  unknown.shard_count = 2;
  EXPECT_THROW(unknown.validate(), InvalidInput);
}

TEST(ConvertStream, SkipCountsBadRecordsStopRethrows) {
  const std::string text = std::string(kHeader) + "a,0,0,0,0,0,0\nb,2,0,0,0,0,0\nc,0,0,0,0,0,x\nd,0,1,0,0,0,0\n";
  Engine engine;
  auto run = [&](OnError on_error) {
    std::istringstream in(text);
    EsvReader r(in, "t.csv");
    FmcvWriter w({}, r.extra_columns());
    BatchOptions b;
    b.on_error = on_error;
    std::string out;
    return std::pair{convert_stream(r, w, engine, b, [&](std::string_view s) { out += s; }), out};
  };
  auto [rep, out] = run(OnError::Skip);
  EXPECT_EQ(rep.records_read, 4u);
  EXPECT_EQ(rep.records_written, 2u);
  EXPECT_EQ(rep.records_skipped, 2u);
  ASSERT_EQ(rep.errors.size(), 2u);
  EXPECT_NE(rep.errors[0].find("t.csv:3:2"), std::string::npos) << rep.errors[0];
  EXPECT_NE(rep.errors[1].find("t.csv:4:7"), std::string::npos) << rep.errors[1];
  EXPECT_THROW(run(OnError::Stop), FormatError);
}

TEST(Describe, ReadableLine) {
  Engine engine;
  Esv esv{0, 0.7, 0, 0, 0, 0.6};
  auto s = engine.select(esv);
  auto line = describe(esv, s, engine.convert(esv));
  EXPECT_EQ(line.substr(0, 33), "blend happiness 0.70 + surprise 0");
  EXPECT_NE(line.find("zygomatic_major"), std::string::npos);
  EXPECT_EQ(describe(Esv{}, engine.select(Esv{}), Fmcv{}), "neutral | no muscle contracted");
}

}  // namespace
}  // namespace emoface::fuzzyexpr
