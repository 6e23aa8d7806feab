// OutputSet: a set of files written all or nothing.
#include "emoface/retarget/output_set.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"

namespace emoface::retarget {
namespace {

namespace fs = std::filesystem;

struct Scratch {
  fs::path path = fs::temp_directory_path() / ("emoface_output_set_" + std::to_string(::getpid()));
  Scratch() {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~Scratch() { fs::remove_all(path); }
};

TEST(OutputSet, WritesEveryFileInItsPlace) {
  Scratch s;
  OutputSet out((s.path / "new" / "rig").string());
  out.add("face.obj", "v 0 0 0\n");
  out.add("mats/textures/skin tone.png", "PNG");
  out.add_writer("emotions.png", [](const std::string& p) {
    EXPECT_EQ(fs::path(p).extension(), ".png");  // writers that dispatch on the extension still can
    core::write_file_atomic(p, "image");
  });
  out.commit();
  EXPECT_EQ(core::read_file((s.path / "new/rig/face.obj").string()), "v 0 0 0\n");
  EXPECT_EQ(core::read_file((s.path / "new/rig/mats/textures/skin tone.png").string()), "PNG");
  EXPECT_EQ(core::read_file((s.path / "new/rig/emotions.png").string()), "image");
  std::size_t n = 0;
  for (const auto& e : fs::recursive_directory_iterator(s.path / "new")) n += e.is_regular_file();
  EXPECT_EQ(n, 3u);  // no temporary left
}

TEST(OutputSet, AFailureLeavesNothingBehind) {
  Scratch s;
  {  // a writer fails: no file, no directory the commit made
    OutputSet out((s.path / "new" / "rig").string());
    out.add("face.obj", "v 0 0 0\n");
    out.add("mats/head.mtl", "newmtl a\n");
    out.add_writer("emotions.png", [](const std::string&) { throw IoError("disk full"); });
    EXPECT_THROW(out.commit(), IoError);
    EXPECT_FALSE(fs::exists(s.path / "new"));
  }
  {  // the rename fails (a directory in the way) in an existing directory: only what was there
     // stays
    fs::create_directories(s.path / "old" / "report.json");
    core::write_file_atomic((s.path / "old" / "keep.txt").string(), "mine");
    OutputSet out((s.path / "old").string());
    out.add("face.obj", "v 0 0 0\n");
    out.add("textures/a.png", "PNG");
    out.add("report.json", "{}");
    EXPECT_THROW(out.commit(), IoError);
    std::size_t n = 0;
    for (const auto& e : fs::recursive_directory_iterator(s.path / "old")) ++n, (void)e;
    EXPECT_EQ(n, 2u);  // keep.txt and the report.json directory
    EXPECT_EQ(core::read_file((s.path / "old" / "keep.txt").string()), "mine");
  }
}

TEST(OutputSet, RefusesPathsOutsideTheDirectory) {
  OutputSet out("rig");
  EXPECT_THROW(out.add("../x.png", ""), InvalidInput);
  EXPECT_THROW(out.add("a/../../x.png", ""), InvalidInput);
  EXPECT_THROW(out.add("/tmp/x.png", ""), InvalidInput);
  EXPECT_THROW(out.add("", ""), InvalidInput);
  EXPECT_THROW(out.add("a/..", ""), InvalidInput);
  out.add("a/../b.png", "");
  EXPECT_THROW(out.add("b.png", ""), InvalidInput);  // the same file twice
  EXPECT_THROW(OutputSet(""), InvalidInput);
}

}  // namespace
}  // namespace emoface::retarget
