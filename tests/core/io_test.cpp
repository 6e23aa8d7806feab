#include "emoface/core/io.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <sys/stat.h>

#include "emoface/core/version.hpp"

namespace emoface::core {
namespace {

namespace fs = std::filesystem;

class TempDir : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("emoface_io_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::size_t file_count() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), {}));
  }
  fs::path dir_;
};

TEST(FormatVersion, ParsesAndPrints) {
  auto v = parse_format_version("2.13");
  EXPECT_EQ(v.major, 2);
  EXPECT_EQ(v.minor, 13);
  EXPECT_EQ(v.to_string(), "2.13");
  for (const char* bad : {"", "1", "1.", ".1", "a.b", "1.2.3", "-1.0", "1.x"})
    EXPECT_THROW(parse_format_version(bad), InvalidInput) << bad;
}

TEST(Envelope, RoundTrip) {
  auto doc = make_envelope("rules", {1, 2});
  EXPECT_EQ(doc["format"], "emoface.rules");
  EXPECT_EQ(doc["version"], "1.2");
  EXPECT_EQ(doc["generator"], kGenerator);
  auto v = check_envelope(doc, "rules", {1, 0}, "f.json");
  EXPECT_EQ(v.minor, 2);  // newer minor accepted
}

TEST(Envelope, RejectsWrongFormatAndVersions) {
  auto expect_error = [](const nlohmann::ordered_json& doc, const std::string& pointer,
                         const std::string& fragment) {
    try {
      check_envelope(doc, "rules", {1, 0}, "f.json");
      FAIL() << "expected FormatError for " << doc.dump();
    } catch (const FormatError& e) {
      EXPECT_EQ(e.where().file, "f.json");
      EXPECT_EQ(e.where().json_pointer, pointer);
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expect_error(nlohmann::ordered_json::array(), "", "object");
  expect_error({{"version", "1.0"}}, "/format", "missing");
  expect_error({{"format", "emoface.mesh"}, {"version", "1.0"}}, "/format", "unknown format");
  expect_error({{"format", "emoface.rules"}}, "/version", "missing");
  expect_error({{"format", "emoface.rules"}, {"version", "one"}}, "/version", "bad version");
  expect_error({{"format", "emoface.rules"}, {"version", "2.0"}}, "/version", "newer");
  expect_error({{"format", "emoface.rules"}, {"version", "0.9"}}, "/version", "old major");
}

TEST(ParseJson, ReportsLineAndColumn) {
  try {
    parse_json("{\n  \"a\": 1,\n  \"b\": ]\n}", "doc.json");
    FAIL();
  } catch (const FormatError& e) {
    EXPECT_EQ(e.where().file, "doc.json");
    EXPECT_EQ(e.where().line, 3u);
    EXPECT_EQ(e.where().column, 8u);
  }
  EXPECT_THROW(parse_json("{\"a\": 1", "t.json"), FormatError);  // truncated
  EXPECT_THROW(parse_json("", "t.json"), FormatError);
  // Found by fuzzing: a number overflow is nlohmann's out_of_range, not a parse_error.
  try {
    parse_json("{\"a\": 5555.5E555}", "big.json");
    FAIL();
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("big.json: invalid JSON: number overflow"), std::string::npos)
        << e.what();
  }
}

TEST_F(TempDir, AtomicWriteReplacesWholeFile) {
  auto path = (dir_ / "out.txt").string();
  write_file_atomic(path, "first");
  write_file_atomic(path, "second version");
  EXPECT_EQ(read_file(path), "second version");
  EXPECT_EQ(file_count(), 1u);  // no temporary left behind
}

TEST_F(TempDir, UncommittedAtomicFileLeavesNothing) {
  auto path = (dir_ / "out.txt").string();
  {
    AtomicFile f(path);
    f.write("partial");
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_EQ(file_count(), 0u);
  write_file_atomic(path, "old");
  {
    AtomicFile f(path);
    f.write("new but abandoned");
  }
  EXPECT_EQ(read_file(path), "old");
}

TEST_F(TempDir, ReadFileErrors) {
  EXPECT_THROW(read_file((dir_ / "missing").string()), IoError);
  auto path = (dir_ / "big.txt").string();
  write_file_atomic(path, std::string(1000, 'x'));
  EXPECT_THROW(read_file(path, 999), IoError);
  EXPECT_EQ(read_file(path, 1000).size(), 1000u);
  EXPECT_THROW(AtomicFile((dir_ / "no" / "such" / "dir.txt").string()), IoError);
}

TEST_F(TempDir, DevicesAreWrittenNotReplaced) {
  // Renaming over /dev/null as root would replace the device node with a regular file.
  write_file_atomic("/dev/null", "discarded");
  struct stat st {};
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  EXPECT_THROW(write_file_atomic(dir_.string(), "x"), IoError);  // a directory
}

TEST_F(TempDir, SymlinkTargetIsReplacedLinkKept) {
  auto real = (dir_ / "real.txt").string(), link = (dir_ / "link.txt").string();
  write_file_atomic(real, "old");
  fs::create_symlink(real, link);
  write_file_atomic(link, "new");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read_file(real), "new");
}

TEST(JsonPointer, EscapesTokens) { EXPECT_EQ(json_pointer_token("a/b~c"), "a~1b~0c"); }

}  // namespace
}  // namespace emoface::core

namespace emoface::core {
namespace {
TEST(StreamHeader, WrittenAndRecognised) {
  const std::string line = ndjson_header("tracks", {1, 2});
  ASSERT_EQ(line.back(), '\n');
  const auto j = nlohmann::json::parse(line);
  EXPECT_EQ(j["format"], "emoface.tracks");
  EXPECT_EQ(j["version"], "1.2");
  EXPECT_EQ(j["generator"], kGenerator);
  EXPECT_TRUE(is_stream_header(j));
  EXPECT_TRUE(is_stream_header(nlohmann::ordered_json::parse(line)));
  EXPECT_TRUE(is_stream_header(nlohmann::json{{"format", "emoface.x"}}));
  EXPECT_FALSE(is_stream_header(nlohmann::json{{"format", "other.x"}, {"version", "1.0"}}));
  EXPECT_FALSE(is_stream_header(nlohmann::json{{"format", "emoface.x"}, {"happiness", 1.0}}));  // a record
  EXPECT_FALSE(is_stream_header(nlohmann::json{{"format", 3}}));
  EXPECT_FALSE(is_stream_header(nlohmann::json::array()));
  EXPECT_FALSE(is_stream_header(nlohmann::json{{"time", 0.0}}));
}
}  // namespace
}  // namespace emoface::core
