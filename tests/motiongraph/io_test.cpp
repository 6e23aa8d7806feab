#include "emoface/motiongraph/io.hpp"

#include <gtest/gtest.h>

#include "emoface/core/csv.hpp"

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "fixtures.hpp"

namespace emoface::motiongraph {
namespace {

// A CSV database we wrote, after checking and dropping its "# emoface x.y.z" stamp line (so line numbers in
// the expectations below count from the header, as in a hand-written file).
std::string unstamped(const std::string& csv) {
  EXPECT_EQ(csv.rfind(core::csv_stamp(), 0), 0u) << csv.substr(0, 40);
  return csv.rfind(core::csv_stamp(), 0) == 0 ? csv.substr(core::csv_stamp().size()) : csv;
}

namespace fs = std::filesystem;

Database tiny(int dims = 2) {
  Database db;
  db.dimensions = dims;
  db.landmark_count = 2;
  db.frame_rate = 25.0;
  for (int s = 0; s < 2; ++s) {
    Sequence seq;
    seq.id = "S00" + std::to_string(s) + "_001";
    seq.subject = s ? "S, \"quoted\"" : "S000";
    seq.label = s ? Label::Contempt : Label::Surprise;
    for (int f = 0; f < 3; ++f) {
      Pose p(2, dims);
      for (int i = 0; i < p.size(); ++i) p.data()[i] = 0.1 * i + f * 1.0 / 3.0 + s * 1e-13;
      seq.frames.push_back(p);
    }
    db.sequences.push_back(seq);
  }
  return db;
}

void expect_equal(const Database& a, const Database& b) {
  EXPECT_EQ(a.dimensions, b.dimensions);
  EXPECT_EQ(a.landmark_count, b.landmark_count);
  EXPECT_EQ(a.frame_rate, b.frame_rate);
  EXPECT_EQ(a.landmark_ids, b.landmark_ids);
  ASSERT_EQ(a.sequences.size(), b.sequences.size());
  for (std::size_t s = 0; s < a.sequences.size(); ++s) {
    EXPECT_EQ(a.sequences[s].id, b.sequences[s].id);
    EXPECT_EQ(a.sequences[s].subject, b.sequences[s].subject);
    EXPECT_EQ(a.sequences[s].label, b.sequences[s].label);
    ASSERT_EQ(a.sequences[s].frames.size(), b.sequences[s].frames.size());
    for (std::size_t f = 0; f < a.sequences[s].frames.size(); ++f)
      EXPECT_TRUE(a.sequences[s].frames[f] == b.sequences[s].frames[f]);  // bit-exact
  }
}

TEST(DatabaseJson, RoundTrip) {
  for (int dims : {2, 3}) {
    Database db = tiny(dims);
    db.landmark_ids = {31, 4};
    const std::string text = database_to_json(db);
    expect_equal(parse_database_json(text), db);
    EXPECT_EQ(database_to_json(parse_database_json(text)), text);
  }
}

TEST(DatabaseCsv, RoundTrip) {
  for (int dims : {2, 3}) {
    const Database db = tiny(dims);
    const std::string text = unstamped(database_to_csv(db));
    EXPECT_EQ(text.substr(0, 40), dims == 2 ? "sequence,subject,label,frame,x0,y0,x1,y1"
                                            : "sequence,subject,label,frame,x0,y0,z0,x1");
    expect_equal(parse_database_csv(text, "t.csv", 25.0), db);
    expect_equal(parse_database_csv(database_to_csv(db), "t.csv", 25.0), db);  // with the stamp
  }
}

void expect_format_error(const std::string& text, const std::string& needle, bool csv = false) {
  try {
    csv ? parse_database_csv(text, "db") : parse_database_json(text, "db");
    ADD_FAILURE() << "no error for: " << text.substr(0, 200);
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(DatabaseJson, BadInput) {
  const std::string good = database_to_json(tiny());
  expect_format_error(good.substr(0, good.size() / 2), "db:");  // truncated
  expect_format_error("[1,2]", "object");
  expect_format_error("{}", "/format");
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const auto pos = s.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    return s.replace(pos, from.size(), to);
  };
  expect_format_error(replaced("\"version\":\"1.0\"", "\"version\":\"2.0\""), "newer");
  expect_format_error(replaced("\"emoface.landmark_database\"", "\"emoface.rig\""), "/format");
  expect_format_error(replaced("\"surprise\"", "\"joy\""), "/sequences/0/label");
  expect_format_error(replaced("\"label\":\"surprise\",", ""),
                      "/sequences/0: missing field \"label\"");
  expect_format_error(replaced("\"landmark_count\":2", "\"landmark_count\":3"), "/sequences/0/frames/0");
  expect_format_error(replaced("\"landmark_count\":2", "\"landmark_count\":-1"), "/landmark_count");
  expect_format_error(replaced("\"landmark_count\":2", "\"landmark_count\":1e12"), "/landmark_count");
  expect_format_error(replaced("\"dimensions\":2", "\"dimensions\":4"), "/dimensions");
  expect_format_error(replaced("\"frame_rate\":25.0", "\"frame_rate\":0"), "/frame_rate");
  expect_format_error(replaced("[0.0,0.2,0.1", "[1e999,0.2,0.1"), "db:");
  expect_format_error(replaced("[0.0,0.2,0.1", "[NaN,0.2,0.1"), "db:");
  expect_format_error(replaced("[0.0,0.2,0.1", "[\"0\",0.2,0.1"), "/sequences/0/frames/0/0");
  expect_format_error(replaced("\"S001_001\"", "\"S000_001\""), "duplicate");
  std::string one_frame = tiny().sequences.empty() ? "" : good;
  Database empty = tiny();
  empty.sequences[0].frames.resize(1);
  EXPECT_NO_THROW(parse_database_json(database_to_json(empty)));  // one frame is a valid file
  std::string no_frames = replaced("\"frames\":[[", "\"frames\":[],\"x\":[[");
  expect_format_error(no_frames, "frame");
}

TEST(DatabaseCsv, BadInput) {
  const std::string good = unstamped(database_to_csv(tiny()));
  expect_format_error("", "empty", true);
  expect_format_error("a,b,c\n", "header", true);
  expect_format_error("sequence,subject,label,frame,x0,y0,x2,y1\n", "x1", true);
  auto line = [&](int n) {
    std::size_t pos = 0;
    for (int i = 0; i < n; ++i) pos = good.find('\n', pos) + 1;
    return pos;
  };
  std::string s = good;
  s.insert(line(2) - 1, ",1.0");
  expect_format_error(s, "db:2:", true);  // wrong field count, names the line
  s = good;
  s.replace(good.find("surprise"), 8, "joy");
  expect_format_error(s, "db:2:3", true);
  s = good;
  s.replace(good.find(",0,0,0.2"), 8, ",0,nan,0.2");
  expect_format_error(s, "finite", true);
  s = good;
  s.replace(good.find(",0,0,0.2"), 8, ",0,1e999,0.2");
  expect_format_error(s, "finite", true);
  s = good;
  s.replace(good.find(",1,0.33"), 3, ",2,");
  expect_format_error(s, "expected frame 1", true);
  s = good.substr(0, line(2)) + good.substr(line(4), line(5) - line(4)) + good.substr(line(2));
  expect_format_error(s, "contiguous", true);
  s = good;
  s.insert(line(2), "S000_001,S000,surprise,0,\"unterminated\n");
  expect_format_error(s, "db:3:", true);
  EXPECT_THROW(parse_database_csv(good, "db", -1.0), InvalidInput);
}

// The unknown-field rule of docs/formats.md, per format: a 1.0 document (the reader's version)
// rejects a field the reader does not know, naming it; a 1.1 document may add fields (ignored).
template <class Parse>
void expect_unknown_field_rule(const std::string& good, const std::string& anchor,
                               const std::string& pointer, Parse parse) {
  std::string extra = good;
  const auto pos = extra.find(anchor);
  ASSERT_NE(pos, std::string::npos) << anchor;
  extra.insert(pos + anchor.size(), "\"note\":1,");
  try {
    parse(extra);
    ADD_FAILURE() << "1.0 accepted an unknown field";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("at " + pointer + "/note: unknown field \"note\""),
              std::string::npos)
        << e.what();
  }
  std::string newer = extra;
  const std::string v10 = newer.find("\"version\":\"1.0\"") != std::string::npos
                              ? "\"version\":\"1.0\""
                              : "\"version\": \"1.0\"";
  const auto vpos = newer.find(v10);
  ASSERT_NE(vpos, std::string::npos);
  newer.replace(vpos, v10.size(), "\"version\":\"1.1\"");
  EXPECT_NO_THROW(parse(newer));
}

TEST(UnknownFields, DatabaseLayoutAndGraph) {
  const std::string db = database_to_json(tiny());
  auto parse_db = [](const std::string& t) { parse_database_json(t, "d.json"); };
  expect_unknown_field_rule(db, "{", "", parse_db);
  expect_unknown_field_rule(db, "\"sequences\":[{", "/sequences/0", parse_db);
  const std::string layout = layout_to_json(default_layout());
  auto parse_l = [](const std::string& t) { parse_layout_json(t, "l.json"); };
  expect_unknown_field_rule(layout, "\"regions\": [\n    {", "/regions/0", parse_l);
  const std::string graph = graph_to_json(build_graph(test::small_prepared(), {}));
  auto parse_g = [](const std::string& t) { parse_graph_json(t, "g.json"); };
  expect_unknown_field_rule(graph, "{", "", parse_g);
  expect_unknown_field_rule(graph, "\"regions\":[{", "/regions/0", parse_g);
  expect_unknown_field_rule(graph, "\"nodes\":[{", "/regions/0/nodes/0", parse_g);
}

TEST(DatabaseFile, WriteReadByExtension) {
  const fs::path dir = fs::temp_directory_path() / "emoface_mg_io_test";
  fs::create_directories(dir);
  const Database db = tiny();
  for (const char* name : {"db.json", "db.csv"}) {
    const std::string path = (dir / name).string();
    write_database(path, db);
    expect_equal(read_database(path, 25.0), db);
  }
  EXPECT_THROW(read_database((dir / "missing.json").string()), IoError);
  fs::remove_all(dir);
}

TEST(Layout, RoundTripAndDataFileMatchesBuiltIn) {
  const LandmarkLayout l = default_layout();
  const LandmarkLayout back = parse_layout_json(layout_to_json(l));
  ASSERT_EQ(back.regions.size(), l.regions.size());
  for (std::size_t i = 0; i < l.regions.size(); ++i) {
    EXPECT_EQ(back.regions[i].name, l.regions[i].name);
    EXPECT_EQ(back.regions[i].landmarks, l.regions[i].landmarks);
    EXPECT_EQ(back.regions[i].alignment, l.regions[i].alignment);
  }
  const LandmarkLayout file = read_layout(EMOFACE_SOURCE_DIR "/data/motiongraph/layout_ibug68.json");
  EXPECT_EQ(layout_to_json(file), layout_to_json(l));
}

TEST(Layout, BadInput) {
  std::string good = layout_to_json(default_layout());
  auto bad = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    s.replace(s.find(from), from.size(), to);
    EXPECT_THROW(parse_layout_json(s, "layout"), FormatError) << to;
  };
  bad("36,\n        37", "36,\n        99");   // out of range
  bad("36,\n        37", "36,\n        36");   // duplicate landmark
  bad("\"eyebrows\"", "\"eyes\"");             // duplicate region
  bad("\"source_landmark_count\": 68", "\"source_landmark_count\": \"68\"");
  LandmarkLayout l;
  EXPECT_THROW(l.validate(), InvalidInput);
}

TEST(GraphJson, RoundTripAndBadInput) {
  const MotionGraph g = build_graph(test::small_prepared(), {});
  const std::string text = graph_to_json(g);
  const MotionGraph back = parse_graph_json(text);
  EXPECT_EQ(graph_to_json(back), text);
  ASSERT_EQ(back.regions.size(), g.regions.size());
  EXPECT_EQ(back.regions[3].nodes.size(), g.regions[3].nodes.size());
  EXPECT_EQ(back.regions[3].edges.size(), g.regions[3].edges.size());
  EXPECT_DOUBLE_EQ(back.compression_ratio(), g.compression_ratio());
  auto bad = [&](const std::string& from, const std::string& to, const std::string& needle) {
    std::string s = text;
    const auto pos = s.find(from);
    ASSERT_NE(pos, std::string::npos) << from;
    s.replace(pos, from.size(), to);
    try {
      parse_graph_json(s, "g");
      ADD_FAILURE() << "accepted " << to;
    } catch (const FormatError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  bad("\"edges\":[[", "\"edges\":[[99999,0,1.0],[", "/edges/0/0");
  bad("\"neutral_node\":", "\"neutral_node\":1000000,\"x\":", "/neutral_node");
  bad("\"mean_run\":", "\"mean_run\":0.5,\"x\":", "/mean_run");
  bad("\"labels\":[\"", "\"labels\":[\"joy\",\"", "/labels/0");
  bad("\"dimensions\":2", "\"dimensions\":7", "/dimensions");
  bad("\"regions\":[", "\"regions\":[],\"x\":[", "/regions");
  EXPECT_THROW(parse_graph_json(text.substr(0, text.size() - 10), "g"), FormatError);
}

// A CK+ tree fabricated on disk: Landmarks/<S>/<seq>/<S>_<seq>_<frame>_landmarks.txt and
// Emotion/<S>/<seq>/<S>_<seq>_<last>_emotion.txt (code in scientific notation, as in CK+).
class CkPlus : public ::testing::Test {
 protected:
  void SetUp() override {
    // One tree per test: ctest runs the tests of this fixture in parallel processes.
    root_ = fs::temp_directory_path() /
            (std::string("emoface_mg_ckplus_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    write_sequence("S005", "001", 3, 4, "   3.0000000e+00");  // disgust
    write_sequence("S010", "002", 2, 4, "   7.0000000e+00");  // surprise
    write_sequence("S010", "003", 2, 4, "");                  // unlabelled
  }
  void TearDown() override { fs::remove_all(root_); }
  void write_sequence(const std::string& s, const std::string& q, int frames, int landmarks,
                      const std::string& emotion) {
    const fs::path d = root_ / "Landmarks" / s / q;
    fs::create_directories(d);
    for (int f = 1; f <= frames; ++f) {
      char name[64];
      std::snprintf(name, sizeof name, "%s_%s_%08d_landmarks.txt", s.c_str(), q.c_str(), f);
      std::ofstream out(d / name);
      for (int i = 0; i < landmarks; ++i) out << "   " << 100.5 + i << "   " << 2.0e+02 + f << "\n";
    }
    if (emotion.empty()) return;
    const fs::path e = root_ / "Emotion" / s / q;
    fs::create_directories(e);
    std::ofstream(e / (s + "_" + q + "_0000000" + std::to_string(frames) + "_emotion.txt")) << emotion << "\n";
  }
  fs::path root_;
};

TEST_F(CkPlus, ReadsLabelledSequences) {
  const Database db = read_ck_plus(root_.string());
  ASSERT_EQ(db.sequences.size(), 2u);
  EXPECT_EQ(db.landmark_count, 4u);
  EXPECT_EQ(db.sequences[0].id, "S005_001");
  EXPECT_EQ(db.sequences[0].subject, "S005");
  EXPECT_EQ(db.sequences[0].label, Label::Disgust);
  EXPECT_EQ(db.sequences[1].label, Label::Surprise);
  ASSERT_EQ(db.sequences[0].frames.size(), 3u);
  EXPECT_DOUBLE_EQ(db.sequences[0].frames[2](3, 0), 103.5);
  EXPECT_DOUBLE_EQ(db.sequences[0].frames[2](3, 1), 203.0);
  CkPlusOptions keep;
  keep.keep_unlabelled = true;
  const Database all = read_ck_plus(root_.string(), keep);
  ASSERT_EQ(all.sequences.size(), 3u);
  EXPECT_EQ(all.sequences[2].label, Label::Neutral);
}

TEST_F(CkPlus, BadInput) {
  EXPECT_THROW(read_ck_plus((root_ / "nope").string()), IoError);
  write_sequence("S011", "001", 2, 5, "   1.0000000e+00");  // inconsistent landmark count
  EXPECT_THROW(read_ck_plus(root_.string()), FormatError);
  fs::remove_all(root_ / "Landmarks" / "S011");
  write_sequence("S012", "001", 2, 4, "   9.0000000e+00");  // unknown code
  EXPECT_THROW(read_ck_plus(root_.string()), FormatError);
  fs::remove_all(root_ / "Landmarks" / "S012");
  write_sequence("S013", "001", 2, 4, "   1.0000000e+00");
  std::ofstream(root_ / "Landmarks/S013/001/S013_001_00000001_landmarks.txt", std::ios::app) << "1.0 nan\n";
  EXPECT_THROW(read_ck_plus(root_.string()), FormatError);
}

TEST_F(CkPlus, SkipReportsBadSequencesAndKeepsTheRest) {
  write_sequence("S011", "001", 2, 5, "   1.0000000e+00");  // inconsistent landmark count
  write_sequence("S012", "001", 2, 4, "   9.0000000e+00");  // unknown code
  write_sequence("S013", "001", 2, 4, "   1.0000000e+00");
  std::ofstream(root_ / "Landmarks/S013/001/S013_001_00000002_landmarks.txt", std::ios::app) << "1.0 inf\n";
  CkPlusOptions o;
  o.on_error = OnError::Skip;
  ReadReport report;
  const Database db = read_ck_plus(root_.string(), o, &report);
  ASSERT_EQ(db.sequences.size(), 2u);
  EXPECT_EQ(db.sequences[1].id, "S010_002");
  ASSERT_EQ(report.skipped.size(), 3u);
  EXPECT_NE(report.skipped[0].find("S011_001_00000001_landmarks.txt:5:1: has 5 landmarks, expected 4"),
            std::string::npos) << report.skipped[0];
  EXPECT_NE(report.skipped[1].find("S012_001_00000002_emotion.txt:1:1: emotion code must be 0..7"),
            std::string::npos) << report.skipped[1];
  EXPECT_NE(report.skipped[2].find("S013_001_00000002_landmarks.txt:5:2"), std::string::npos) << report.skipped[2];
}

TEST(CkPlusParsers, GoodAndBadFiles) {
  const Pose p = parse_ck_landmarks("  1.5e+02   2\n\n 3 4 \r\n", "f.txt");
  ASSERT_EQ(p.rows(), 2);
  EXPECT_DOUBLE_EQ(p(0, 0), 150.0);
  EXPECT_DOUBLE_EQ(p(1, 1), 4.0);
  EXPECT_EQ(parse_ck_emotion("   5.0000000e+00\n", "e.txt"), Label::Happiness);
  EXPECT_EQ(parse_ck_emotion("2", "e.txt"), Label::Contempt);
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const FormatError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message([] { parse_ck_landmarks("", "f.txt"); }), "f.txt:1:1: no landmarks");
  EXPECT_EQ(message([] { parse_ck_landmarks("1 2\n3\n", "f.txt"); }), "f.txt:2:1: expected 2 number(s), got 1");
  EXPECT_EQ(message([] { parse_ck_landmarks("1 2 3\n", "f.txt"); }), "f.txt:1:1: expected 2 number(s), got more");
  EXPECT_EQ(message([] { parse_ck_landmarks("1 nan\n", "f.txt"); }), "f.txt:1:2: expected a finite number, got \"nan\"");
  EXPECT_EQ(message([] { parse_ck_landmarks("1 1e999\n", "f.txt"); }), "f.txt:1:2: expected a finite number, got \"1e999\"");
  EXPECT_EQ(message([] { parse_ck_landmarks("1 2x\n", "f.txt"); }), "f.txt:1:2: expected a finite number, got \"2x\"");
  EXPECT_EQ(message([] { parse_ck_landmarks("1 2\n", "f.txt", 3); }), "f.txt:1:1: has 1 landmarks, expected 3");
  EXPECT_EQ(message([] { parse_ck_emotion("", "e.txt"); }), "e.txt:1:1: expected one emotion code");
  EXPECT_EQ(message([] { parse_ck_emotion("1\n2\n", "e.txt"); }), "e.txt:1:1: expected one emotion code");
  EXPECT_EQ(message([] { parse_ck_emotion("2.5", "e.txt"); }), "e.txt:1:1: emotion code must be 0..7");
  EXPECT_EQ(message([] { parse_ck_emotion("-1", "e.txt"); }), "e.txt:1:1: emotion code must be 0..7");
  // Huge: a line with a million numbers stops at the third.
  std::string huge;
  for (int i = 0; i < 500000; ++i) huge += "1 ";
  EXPECT_EQ(message([&] { parse_ck_landmarks(huge, "f.txt"); }), "f.txt:1:1: expected 2 number(s), got more");
  EXPECT_EQ(message([] { parse_ck_landmarks("1 " + std::string(400, '9') + "\n", "f.txt"); }).substr(0, 45),
            "f.txt:1:2: expected a finite number, got \"999");
}

TEST(DatabaseJson, SkipBadSequences) {
  const std::string good = database_to_json(tiny());
  // Break sequence 0 (a NaN-like string coordinate) and give sequence 1's duplicate id to a third.
  nlohmann::json doc = nlohmann::json::parse(good);
  doc["sequences"][0]["frames"][1][2] = "x";
  doc["sequences"].push_back(doc["sequences"][1]);
  doc["sequences"][2]["frames"] = nlohmann::json::array();
  const std::string text = doc.dump();
  EXPECT_THROW(parse_database_json(text, "d.json"), FormatError);
  ReadReport report;
  const Database db = parse_database_json(text, "d.json", OnError::Skip, &report);
  ASSERT_EQ(db.sequences.size(), 1u);
  EXPECT_EQ(db.sequences[0].id, "S001_001");
  ASSERT_EQ(report.skipped.size(), 2u);
  EXPECT_EQ(report.skipped[0],
            "d.json: at /sequences/0/frames/1/2: expected a number, got a string");
  EXPECT_EQ(report.skipped[1], "d.json: at /sequences/2/id: duplicate sequence id \"S001_001\"");
  EXPECT_EQ(on_error_from_string(to_string(OnError::Skip)), OnError::Skip);  // core::OnError
  EXPECT_FALSE(on_error_from_string("ignore").has_value());
}

TEST(DatabaseCsv, SkipBadSequences) {
  const std::string csv = unstamped(database_to_csv(tiny()));
  // Row 2 (frame 1 of the first sequence) gets a bad number; the second sequence survives whole.
  std::vector<std::string> lines;
  std::size_t pos = 0;
  while (pos < csv.size()) {
    const std::size_t e = csv.find('\n', pos);
    lines.push_back(csv.substr(pos, e - pos));
    pos = e + 1;
  }
  lines[2].replace(lines[2].rfind(','), std::string::npos, ",inf");
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  text += "S009_001,S009,fear,0,1,2,3\n";  // too few fields: its own sequence is skipped
  EXPECT_THROW(parse_database_csv(text, "d.csv"), FormatError);
  ReadReport report;
  const Database db = parse_database_csv(text, "d.csv", 30.0, OnError::Skip, &report);
  ASSERT_EQ(db.sequences.size(), 1u);
  EXPECT_EQ(db.sequences[0].id, "S001_001");
  EXPECT_EQ(db.sequences[0].frames.size(), 3u);
  ASSERT_EQ(report.skipped.size(), 2u);
  EXPECT_EQ(report.skipped[0].rfind("d.csv:3:", 0), 0u) << report.skipped[0];
  EXPECT_EQ(report.skipped[1].rfind("d.csv:8:", 0), 0u) << report.skipped[1];
}

}  // namespace
}  // namespace emoface::motiongraph

namespace emoface::motiongraph {
namespace {

// Golden files (also the fuzz seeds): reading and writing reproduces them byte for byte.
TEST(GoldenFiles, RoundTripByteForByte) {
  const std::string dir = EMOFACE_TEST_DATA_DIR "/motiongraph/";
  const std::string db_json = core::read_file(dir + "tiny_database.json");
  EXPECT_EQ(database_to_json(parse_database_json(db_json)), db_json);
  const std::string db_csv = core::read_file(dir + "tiny_database.csv");
  EXPECT_EQ(database_to_csv(parse_database_csv(db_csv, "csv", 25.0)), db_csv);
  const std::string graph = core::read_file(dir + "tiny_graph.json");
  EXPECT_EQ(graph_to_json(parse_graph_json(graph)), graph);
}

}  // namespace
}  // namespace emoface::motiongraph
