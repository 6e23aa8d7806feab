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

// faceanim --weights arkit: ARKit weights are fitted to parameters. jawOpen 0.5 is the masseter at
// 0.5 (data/faceweights/arkit.json), so the frames equal those of the parameter file (to the fit's
// ridge bias, ~1e-6 in the level → far below 1e-5 m).
TEST_F(Apps, FaceanimFitsArkitWeights) {
  std::string header = "time", zero = "0", open = "0.04";
  for (const char* n : {"browDown_L", "browDown_R", "browInnerUp", "browOuterUp_L", "browOuterUp_R",
                        "cheekPuff", "cheekSquint_L", "cheekSquint_R", "eyeBlink_L", "eyeBlink_R",
                        "eyeLookDown_L", "eyeLookDown_R", "eyeLookIn_L", "eyeLookIn_R",
                        "eyeLookOut_L", "eyeLookOut_R", "eyeLookUp_L", "eyeLookUp_R", "eyeSquint_L",
                        "eyeSquint_R", "eyeWide_L", "eyeWide_R", "jawForward", "jawLeft", "jawOpen",
                        "jawRight", "mouthClose", "mouthDimple_L", "mouthDimple_R", "mouthFrown_L",
                        "mouthFrown_R", "mouthFunnel", "mouthLeft", "mouthLowerDown_L",
                        "mouthLowerDown_R", "mouthPress_L", "mouthPress_R", "mouthPucker",
                        "mouthRight", "mouthRollLower", "mouthRollUpper", "mouthShrugLower",
                        "mouthShrugUpper", "mouthSmile_L", "mouthSmile_R", "mouthStretch_L",
                        "mouthStretch_R", "mouthUpperUp_L", "mouthUpperUp_R", "noseSneer_L",
                        "noseSneer_R", "tongueOut"}) {
    header += std::string(",") + n;
    zero += ",0";
    open += std::string(n) == "jawOpen" ? ",0.5" : ",0";
  }
  emoface::core::write_file_atomic(p("w.csv"), header + "\n" + zero + "\n" + open + "\n");
  emoface::core::write_file_atomic(p("m.csv"), "masseter\n0\n0.5\n");
  ASSERT_EQ(run(std::string(FACEANIM_EXE) + " --weights arkit --params " + p("w.csv") + " --out " + p("w")), 0);
  ASSERT_EQ(run(std::string(FACEANIM_EXE) + " --params " + p("m.csv") + " --out " + p("m")), 0);
  const auto a = emoface::facemesh::read_mesh(p("w/frame_0001.obj"));
  const auto b = emoface::facemesh::read_mesh(p("m/frame_0001.obj"));
  EXPECT_TRUE(a.vertices.isApprox(b.vertices, 1e-6));
  EXPECT_FALSE(a.vertices.isApprox(emoface::facemesh::read_mesh(p("w/frame_0000.obj")).vertices, 1e-4));
  // a weight outside [0, 1] is a format error (exit 2), nothing written
  emoface::core::write_file_atomic(p("bad.csv"), header + "\n" + zero.substr(0, zero.size() - 1) + "7\n");
  EXPECT_EQ(run(std::string(FACEANIM_EXE) + " --weights arkit --params " + p("bad.csv") + " --out " + p("bad")), 2);
  EXPECT_FALSE(fs::exists(p("bad/frame_0000.obj")));
  EXPECT_EQ(run(std::string(FACEANIM_EXE) + " --weights vrm --params " + p("w.csv") + " --out " + p("x")), 1);
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
