// faceanim and facerender end to end.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <sys/wait.h>

#include "emoface/core/io.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/mesh_io.hpp"

namespace {

namespace fs = std::filesystem;

class Apps : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("emoface_apps_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string p(const std::string& name) const { return (dir_ / name).string(); }
  static int run(const std::string& cmd) {
    const int status = std::system((cmd + " 2>/dev/null").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  fs::path dir_;
};

TEST_F(Apps, FaceanimWritesFramesAndGltf) {
  emoface::core::write_file_atomic(p("p.csv"), "id,masseter,zygomatic_major_l,zygomatic_major_r\nneutral,0,0,0\nsmile,0,1,1\nopen,0.8,0,0\n");
  ASSERT_EQ(run(std::string(FACEANIM_EXE) + " --params " + p("p.csv") + " --out " + p("out") + " --gltf " + p("a.gltf")), 0);
  const auto face = emoface::facemesh::make_default_face();
  for (const char* name : {"frame_0000.obj", "frame_0001.obj", "frame_0002.obj"}) {
    const auto mesh = emoface::facemesh::read_mesh(p("out/") + name);
    EXPECT_EQ(mesh.vertex_count(), face.mesh.vertex_count());
  }
  EXPECT_TRUE(emoface::facemesh::read_mesh(p("out/frame_0000.obj")).vertices.isApprox(face.mesh.vertices, 1e-7));
  EXPECT_FALSE(emoface::facemesh::read_mesh(p("out/frame_0001.obj")).vertices.isApprox(face.mesh.vertices, 1e-4));
  EXPECT_TRUE(fs::exists(p("a.gltf")));
  // sharding: frames 1 of 0..2 only
  ASSERT_EQ(run(std::string(FACEANIM_EXE) + " --params " + p("p.csv") + " --out " + p("shard") + " --format ply --shard 1/2"), 0);
  EXPECT_FALSE(fs::exists(p("shard/frame_0000.ply")));
  EXPECT_TRUE(fs::exists(p("shard/frame_0001.ply")));
}

TEST_F(Apps, FaceanimRegeneratesTheCheckedInFace) {
  ASSERT_EQ(run(std::string(FACEANIM_EXE) + " --write-default-face " + p("face")), 0);
  const std::string data = std::string(EMOFACE_SOURCE_DIR) + "/data/face/";
  if (!fs::exists(data + "default.rig")) GTEST_SKIP();
  EXPECT_EQ(emoface::core::read_file(p("face/default.rig")), emoface::core::read_file(data + "default.rig"));
  EXPECT_EQ(emoface::core::read_file(p("face/default_face.obj")), emoface::core::read_file(data + "default_face.obj"));
}

TEST_F(Apps, FaceanimErrors) {
  emoface::core::write_file_atomic(p("bad.csv"), "smile\n1\n");
  EXPECT_EQ(run(std::string(FACEANIM_EXE) + " --params " + p("bad.csv") + " --out " + p("out")), 2);
  EXPECT_FALSE(fs::exists(p("out/frame_0000.obj")));
  EXPECT_EQ(run(std::string(FACEANIM_EXE) + " --params " + p("missing.csv") + " --out " + p("out")), 2);
  EXPECT_EQ(run(std::string(FACEANIM_EXE) + " --params " + p("bad.csv") + " --format stl --out " + p("out")), 1);
}

TEST_F(Apps, FacerenderPngAndSheet) {
  const auto face = emoface::facemesh::make_default_face();
  emoface::facemesh::write_mesh(p("a.obj"), face.mesh);
  ASSERT_EQ(run(std::string(FACERENDER_EXE) + " " + p("a.obj") + " " + p("a.obj") + " --sheet 2 --width 64 --height 72 --out " + p("s.png")), 0);
  EXPECT_EQ(emoface::core::read_file(p("s.png")).substr(1, 3), "PNG");
  ASSERT_EQ(run(std::string(FACERENDER_EXE) + " " + p("a.obj") + " --view threequarter --width 64 --height 72 --out " + p("t.png")), 0);
  EXPECT_TRUE(fs::exists(p("t.png")));
  EXPECT_EQ(run(std::string(FACERENDER_EXE) + " " + p("a.obj") + " --view side --out " + p("x.png")), 1);
  EXPECT_EQ(run(std::string(FACERENDER_EXE) + " " + p("nope.obj") + " --out " + p("x.png")), 2);
  EXPECT_FALSE(fs::exists(p("x.png")));
}

}  // namespace
