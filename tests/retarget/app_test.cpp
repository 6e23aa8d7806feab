// End-to-end: the retarget CLI writes a loadable rig, mesh, report and pictures; exit codes.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "emoface/facemesh/io.hpp"
#include "emoface/facemesh/mesh_io.hpp"

namespace fs = std::filesystem;

namespace {
int run(const std::string& args) {
  const int status = std::system((std::string(RETARGET_EXE) + " " + args + " 2>/dev/null").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("emoface_retarget_app_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};
}  // namespace

TEST(RetargetApp, FitsTheDefaultFaceOntoItself) {
  TempDir t;
  const std::string target = std::string(EMOFACE_SOURCE_DIR) + "/data/face/default_face.obj";
  const auto out = t.path / "out";
  ASSERT_EQ(run("--target " + target + " --out " + out.string() + " --generations 2 --population 6 --quiet"), 0);
  for (const char* f : {"face.rig", "face.obj", "target_aligned.obj", "report.json", "overlay.png", "error_curve.png", "emotions.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto face = emoface::facemesh::load_face((out / "face.rig").string());
  EXPECT_EQ(face.mesh.vertex_count(), face.rig.vertex_count);
  // Same seed: identical rig.
  const auto out2 = t.path / "out2";
  ASSERT_EQ(run("--target " + target + " --out " + out2.string() + " --generations 2 --population 6 --quiet --no-png"), 0);
  std::ifstream a(out / "face.rig"), b(out2 / "face.rig");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}), std::string(std::istreambuf_iterator<char>(b), {}));
  EXPECT_FALSE(fs::exists(out2 / "overlay.png"));
}

TEST(RetargetApp, ExitCodes) {
  TempDir t;
  EXPECT_EQ(run("--help >/dev/null"), 0);
  EXPECT_EQ(run("--out " + t.path.string()), 1);  // --target missing
  EXPECT_EQ(run("--target x.obj --out " + t.path.string() + " --projection sideways"), 1);
  EXPECT_EQ(run("--target " + (t.path / "missing.obj").string() + " --out " + t.path.string()), 2);
  const auto bad = t.path / "bad.obj";
  std::ofstream(bad) << "v 0 0 0\nv nan 1 0\nv 0 0 1\nf 1 2 3\n";
  EXPECT_EQ(run("--target " + bad.string() + " --out " + (t.path / "o").string()), 2);
  EXPECT_FALSE(fs::exists(t.path / "o" / "face.rig"));
  EXPECT_EQ(run("--target x.obj --out " + t.path.string() + " --up +y --front +y"), 1);
}
