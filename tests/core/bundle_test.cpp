// OutputBundle: several outputs written all or nothing.
#include "emoface/core/bundle.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"

namespace emoface::core {
namespace {

namespace fs = std::filesystem;

class Bundle : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("emoface_bundle_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::size_t entries() const {
    std::size_t n = 0;
    for (auto it = fs::recursive_directory_iterator(dir_); it != fs::recursive_directory_iterator();
         ++it)
      ++n;
    return n;
  }
  fs::path dir_;
};

TEST_F(Bundle, NothingAppearsBeforeCommitThenEverything) {
  {
    OutputBundle b;
    b.add(path("a.csv"), "a\n");
    b.add(path("frames/f0.png"), "png0");
    b.add(path("frames/deep/f1.png"), "png1");
    EXPECT_EQ(b.size(), 3u);
    EXPECT_FALSE(fs::exists(path("a.csv")));
    EXPECT_FALSE(fs::exists(path("frames/f0.png")));
    b.commit();
    EXPECT_TRUE(b.committed());
  }
  EXPECT_EQ(read_file(path("a.csv")), "a\n");
  EXPECT_EQ(read_file(path("frames/f0.png")), "png0");
  EXPECT_EQ(read_file(path("frames/deep/f1.png")), "png1");
  EXPECT_EQ(entries(), 5u);  // a.csv, frames, f0, deep, f1: no temporary file left
}

TEST_F(Bundle, AFailureLeavesNothingHalfWritten) {
  std::ofstream(path("old.csv")) << "old";
  {
    OutputBundle b;
    b.add(path("old.csv"), "new");
    b.add(path("frames/f0.png"), "png0");
    // The third output cannot be written (its parent is a file): IoError, nothing committed.
    EXPECT_THROW(b.add(path("old.csv/x.png"), "x"), IoError);
    EXPECT_THROW(b.add(path("frames/f0.png"), "again"), InvalidInput);  // staged twice
  }                                                                     // destroyed uncommitted
  EXPECT_EQ(read_file(path("old.csv")), "old");                         // untouched
  EXPECT_FALSE(fs::exists(path("frames")));  // the directory it created is gone
  EXPECT_EQ(entries(), 1u);                  // no temporary files
  // An exception between staging and commit (e.g. a later output failing to compute).
  try {
    OutputBundle b;
    b.add(path("old.csv"), "new");
    throw std::runtime_error("later output failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(read_file(path("old.csv")), "old");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(Bundle, StagedPathsKeepTheExtensionAndMustBeWritten) {
  {
    OutputBundle b;
    const std::string temp = b.stage_path(path("out/video.mp4"));
    EXPECT_EQ(fs::path(temp).extension(), ".mp4");
    EXPECT_EQ(fs::path(temp).parent_path(), fs::path(path("out")));
    std::ofstream(temp) << "movie";
    b.add(path("out/a.txt"), "a");
    EXPECT_FALSE(fs::exists(path("out/video.mp4")));
    b.commit();
  }
  EXPECT_EQ(read_file(path("out/video.mp4")), "movie");
  {
    OutputBundle b;
    const std::string temp = b.stage_path(path("lost.glb"));
    fs::remove(temp);  // the writer failed to produce it
    b.add(path("b.txt"), "b");
    EXPECT_THROW(b.commit(), IoError);
  }
  EXPECT_FALSE(fs::exists(path("lost.glb")));
  EXPECT_FALSE(fs::exists(path("b.txt")));
  EXPECT_THROW(OutputBundle().stage_path("-"), InvalidInput);
}

TEST_F(Bundle, DirectoriesAndMisuse) {
  fs::create_directories(path("d"));
  OutputBundle b;
  EXPECT_THROW(b.add(path("d"), "x"), IoError);  // a directory is not a file
  EXPECT_THROW(b.add("", "x"), InvalidInput);
  b.add("-", "to stdout\n");
  EXPECT_THROW(b.add("-", "twice"), InvalidInput);
  testing::internal::CaptureStdout();
  b.commit();
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "to stdout\n");
  EXPECT_THROW(b.commit(), InvalidInput);
  EXPECT_THROW(b.add(path("late"), "x"), InvalidInput);
  OutputBundle null;
  null.add("/dev/null", "discarded");  // written, not replaced
  null.commit();
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

}  // namespace
}  // namespace emoface::core
