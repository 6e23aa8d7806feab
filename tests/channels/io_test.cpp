#include "emoface/channels/io.hpp"

#include <gtest/gtest.h>

#include "emoface/core/csv.hpp"

#include <cmath>
#include <filesystem>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"

namespace emoface::channels {
namespace {

std::string data(const char* rel) { return std::string(EMOFACE_SOURCE_DIR) + "/data/channels/" + rel; }

TEST(Io, VisemesRoundTripAndDataFileMatchesBuiltIn) {
  const VisemeSet set = default_viseme_set();
  const std::string text = format_visemes(set);
  EXPECT_EQ(format_visemes(parse_visemes(text)), text);
  // data/channels/visemes.json is written by `talkinghead --dump-visemes`
  EXPECT_EQ(core::read_file(data("visemes.json")), text);
}

TEST(Io, ConflictsRoundTripAndDataFileMatchesBuiltIn) {
  const std::string text = format_conflicts(default_conflict_table());
  const ConflictTable back = parse_conflicts(text);
  ASSERT_EQ(back.pairs.size(), default_conflict_table().pairs.size());
  EXPECT_EQ(format_conflicts(back), text);
  EXPECT_EQ(core::read_file(data("conflicts.json")), text);
}

Tracks sample_tracks() {
  Tracks t;
  t.fps = 25;
  t.names = {"masseter", "head_yaw", "odd,name"};
  for (int f = 0; f < 7; ++f)
    for (int c = 0; c < 3; ++c) t.values.push_back(std::sin(f * 0.7 + c) * 0.3 + (c == 0 ? 0.3 : 0.0));
  return t;
}

TEST(Io, TracksJsonAndCsvRoundTripExactly) {
  const Tracks t = sample_tracks();
  for (const Tracks& back : {parse_tracks_json(format_tracks_json(t)), parse_tracks_csv(format_tracks_csv(t))}) {
    EXPECT_EQ(back.fps, t.fps);
    EXPECT_EQ(back.names, t.names);
    EXPECT_EQ(back.values, t.values);
  }
  const std::string csv = format_tracks_csv(t);
  ASSERT_EQ(csv.rfind(emoface::core::csv_stamp(), 0), 0u);  // version stamp, then the header
  const std::string body = csv.substr(emoface::core::csv_stamp().size());
  EXPECT_EQ(body.substr(0, body.find('\n')), "time,masseter,head_yaw,\"odd,name\"");
  // Without the stamp (hand-written files) it reads the same; error lines count the stamp line.
  EXPECT_EQ(parse_tracks_csv(body, "x.csv").values, t.values);
  try {
    parse_tracks_csv(emoface::core::csv_stamp() + "time,a\n0,0\n0.5,0\n0.75,0\n", "bad.csv");
    FAIL() << "non-uniform time accepted";
  } catch (const emoface::FormatError& e) {
    EXPECT_EQ(e.where().line, 4u) << e.what();  // stamp, header, frame 0, frame 1
  }
}

TEST(Io, TracksFilesByExtension) {
  const auto dir = std::filesystem::temp_directory_path() / "emoface_channels_io_test";
  std::filesystem::create_directories(dir);
  const Tracks t = sample_tracks();
  for (const char* name : {"a.csv", "a.json"}) {
    const std::string p = (dir / name).string();
    write_tracks(p, t);
    EXPECT_EQ(read_tracks(p).values, t.values);
  }
  std::filesystem::remove_all(dir);
}

void expect_format_error(const std::function<void()>& f, const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no FormatError, expected " << needle;
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(Io, BadTracksJson) {
  const auto j = [](const std::string& body) {
    return "{\"format\":\"emoface.tracks\",\"version\":\"1.0\"" + body + "}";
  };
  expect_format_error([&] { parse_tracks_json(j(",\"fps\":25,\"names\":[\"a\"],\"frames\":[[1,2]]")); }, "/frames/0");
  expect_format_error([&] { parse_tracks_json(j(",\"fps\":0,\"names\":[],\"frames\":[]")); }, "/fps");
  expect_format_error([&] { parse_tracks_json(j(",\"fps\":25,\"names\":[\"a\",\"a\"],\"frames\":[]")); }, "/names/1");
  expect_format_error([&] { parse_tracks_json(j(",\"fps\":25,\"names\":[\"a\"],\"frames\":[[\"x\"]]")); }, "/frames/0/0");
  expect_format_error([&] { parse_tracks_json(j(",\"fps\":25,\"names\":[\"a\"]")); }, "frames");
  expect_format_error([&] { parse_tracks_json(j(",\"fps\":25,\"names\":[\"a\"],\"frames\":[[1e999]]")); }, "");
  expect_format_error([&] { parse_tracks_json("{\"format\":\"emoface.tracks\",\"version\":\"2.0\"}"); }, "/version");
  expect_format_error([&] { parse_tracks_json("{\"format\":\"emoface.tracks\",\"vers"); }, "");
  expect_format_error([&] { parse_tracks_json("[]"); }, "");
}

TEST(Io, BadTracksCsv) {
  expect_format_error([] { parse_tracks_csv(""); }, "empty");
  expect_format_error([] { parse_tracks_csv("t,a\n0,1\n"); }, ":1:1");
  expect_format_error([] { parse_tracks_csv("time,a\n0,1\n0.1\n"); }, ":3:");
  expect_format_error([] { parse_tracks_csv("time,a\n0,1\n0.1,nan\n"); }, ":3:2");
  expect_format_error([] { parse_tracks_csv("time,a\n0,1\n0.1,inf\n"); }, ":3:2");
  expect_format_error([] { parse_tracks_csv("time,a\n0,1\n0.1,2\n0.3,2\n"); }, "uniform");
  expect_format_error([] { parse_tracks_csv("time,a\n0,1\n0,2\n"); }, "increase");
  expect_format_error([] { parse_tracks_csv("time,a,a\n"); }, "repeated");
  expect_format_error([] { parse_tracks_csv("time,a\n0,\"1\n"); }, ":2:");
  expect_format_error([] { parse_tracks_csv("time,a\n0.5,1\n"); }, "time 0");
}

TEST(Io, BadVisemesAndConflicts) {
  const std::string env = "{\"format\":\"emoface.channels.visemes\",\"version\":\"1.0\",";
  expect_format_error([&] { parse_visemes(env + "\"visemes\":[{\"name\":\"sil\",\"dominance\":{\"alpha\":-1}}]}"); },
                      "/visemes/0/dominance");
  expect_format_error([&] { parse_visemes(env + "\"visemes\":[{\"name\":\"sil\",\"targets\":{\"masseter\":\"x\"}}]}"); },
                      "/visemes/0/targets/masseter");
  expect_format_error([&] { parse_visemes(env + "\"visemes\":[{\"name\":\"x\"}]}"); }, "silence");
  expect_format_error([&] { parse_visemes(env + "\"visemes\":[{\"name\":\"sil\",\"bogus\":1}]}"); }, "/visemes/0/bogus");
  const std::string cenv = "{\"format\":\"emoface.channels.conflicts\",\"version\":\"1.0\",";
  expect_format_error([&] { parse_conflicts(cenv + "\"pairs\":[{\"a\":\"masseter\",\"b\":\"nose\"}]}"); }, "/pairs/0");
  expect_format_error([&] { parse_conflicts(cenv + "\"pairs\":[{\"a\":\"masseter\"}]}"); }, "\"b\"");
  expect_format_error([&] { parse_conflicts(cenv + "\"pairs\":{}}"); }, "/pairs");
  // The unknown-field rule (core::JsonReader): a typo in a 1.0 file is an error; 1.1 may add
  // fields.
  expect_format_error([&] { parse_conflicts(cenv + "\"pairs\":[],\"pair\":[]}"); },
                      "at /pair: unknown field \"pair\"");
  const std::string newer = "{\"format\":\"emoface.channels.conflicts\",\"version\":\"1.1\",";
  EXPECT_EQ(parse_conflicts(newer + "\"pairs\":[],\"notes\":\"x\"}").pairs.size(), 0u);
  expect_format_error([&] { parse_visemes(env + "\"visemes\":[],\"silnce\":\"sil\"}"); },
                      "at /silnce: unknown field");
}

TEST(Io, TracksJsonUnknownFieldRule) {
  const std::string body = ",\"fps\":25,\"names\":[\"a\"],\"frames\":[[1]],\"units\":\"s\"}";
  expect_format_error(
      [&] { parse_tracks_json("{\"format\":\"emoface.tracks\",\"version\":\"1.0\"" + body); },
      "at /units: unknown field \"units\"");
  EXPECT_EQ(parse_tracks_json("{\"format\":\"emoface.tracks\",\"version\":\"1.2\"" + body).values,
            std::vector<double>{1.0});
}

}  // namespace
}  // namespace emoface::channels
