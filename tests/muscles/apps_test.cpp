// faceanim and facerender end to end.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "emoface/core/io.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/gltf.hpp"
#include "emoface/facemesh/io.hpp"
#include "emoface/facemesh/mesh_document.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "emoface/facemesh/render.hpp"
#include "emoface/muscles/morph_targets.hpp"
#include "emoface/muscles/solver.hpp"

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
  const auto face = emoface::facemesh::make_default_face();  // faceanim's face without --rig
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
  ASSERT_EQ(run(std::string(FACEANIM_EXE) + " --write-generic-face " + p("face")), 0);
  const std::string data = std::string(EMOFACE_SOURCE_DIR) + "/data/face/";
  if (!fs::exists(data + "generic.rig")) GTEST_SKIP();
  EXPECT_EQ(emoface::core::read_file(p("face/generic.rig")), emoface::core::read_file(data + "generic.rig"));
  EXPECT_EQ(emoface::core::read_file(p("face/generic_face.obj")), emoface::core::read_file(data + "generic_face.obj"));
}

TEST_F(Apps, FaceanimErrors) {
  emoface::core::write_file_atomic(p("bad.csv"), "smile\n1\n");
  EXPECT_EQ(run(std::string(FACEANIM_EXE) + " --params " + p("bad.csv") + " --out " + p("out")), 2);
  EXPECT_FALSE(fs::exists(p("out/frame_0000.obj")));
  EXPECT_EQ(run(std::string(FACEANIM_EXE) + " --params " + p("missing.csv") + " --out " + p("out")), 2);
  EXPECT_EQ(run(std::string(FACEANIM_EXE) + " --params " + p("bad.csv") + " --format stl --out " + p("out")), 1);
}

TEST_F(Apps, FacerenderPngAndSheet) {
  const auto face = emoface::facemesh::make_generic_face();
  emoface::facemesh::write_mesh(p("a.obj"), face.mesh);
  ASSERT_EQ(run(std::string(FACERENDER_EXE) + " " + p("a.obj") + " " + p("a.obj") + " --sheet 2 --width 64 --height 72 --out " + p("s.png")), 0);
  EXPECT_EQ(emoface::core::read_file(p("s.png")).substr(1, 3), "PNG");
  ASSERT_EQ(run(std::string(FACERENDER_EXE) + " " + p("a.obj") + " --view threequarter --width 64 --height 72 --out " + p("t.png")), 0);
  EXPECT_TRUE(fs::exists(p("t.png")));
  EXPECT_EQ(run(std::string(FACERENDER_EXE) + " " + p("a.obj") + " --view side --out " + p("x.png")), 1);
  EXPECT_EQ(run(std::string(FACERENDER_EXE) + " " + p("nope.obj") + " --out " + p("x.png")), 2);
  EXPECT_FALSE(fs::exists(p("x.png")));
}

// --distance moves the camera back: the head covers fewer pixels (the portrait framing of
// scripts/oracle.sh); out-of-range distances are refused.
TEST_F(Apps, FacerenderDistance) {
  const auto face = emoface::facemesh::make_default_face();
  emoface::facemesh::write_mesh(p("a.obj"), face.mesh);
  auto covered = [&](const std::string& file) {  // pixels off the background's colour
    const emoface::core::Image im = emoface::core::read_png(file);
    int n = 0;
    for (std::size_t i = 0; i + 2 < im.rgb.size(); i += 3)
      n += std::abs(im.rgb[i] - im.rgb[0]) + std::abs(im.rgb[i + 1] - im.rgb[1]) +
               std::abs(im.rgb[i + 2] - im.rgb[2]) >
           6;
    return n;
  };
  const std::string base =
      std::string(FACERENDER_EXE) + " " + p("a.obj") + " --width 96 --height 112";
  ASSERT_EQ(run(base + " --distance 1 --out " + p("near.png")), 0);  // the whole head in the frame
  ASSERT_EQ(run(base + " --distance 2 --out " + p("far.png")), 0);
  const int near = covered(p("near.png")), far = covered(p("far.png"));
  // the head's image scales with 1/distance: a quarter of the pixels at twice the distance
  EXPECT_NEAR(static_cast<double>(far) / near, 0.25, 0.06) << near << " " << far;
  EXPECT_EQ(run(base + " --distance 0 --out " + p("x.png")), 1);
  EXPECT_EQ(run(base + " --distance nan --out " + p("x.png")),
            2);  // passes the flag's range, not RenderOptions
  EXPECT_FALSE(fs::exists(p("x.png")));
}

namespace fm = emoface::facemesh;
namespace core = emoface::core;

// A user's rig: the built-in face's rig on an OBJ in decimetres with UVs, a group, a material library.
std::string user_obj_rig(const std::string& dir) {
  const auto face = fm::make_generic_face();
  std::string obj = "# the user's head\nmtllib head.mtl\no head\n";
  char line[160];
  for (long v = 0; v < face.mesh.vertices.rows(); ++v) {
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", 10 * face.mesh.vertices(v, 0), 10 * face.mesh.vertices(v, 1), 10 * face.mesh.vertices(v, 2));
    obj += line;
  }
  for (long v = 0; v < face.mesh.vertices.rows(); ++v) {
    std::snprintf(line, sizeof line, "vt %.6f %.6f\n", face.mesh.vertices(v, 0) + 0.5, face.mesh.vertices(v, 1) + 0.5);
    obj += line;
  }
  obj += "usemtl skin\n";
  for (long f = 0; f < face.mesh.faces.rows(); ++f) {
    const int a = face.mesh.faces(f, 0) + 1, b = face.mesh.faces(f, 1) + 1, c = face.mesh.faces(f, 2) + 1;
    std::snprintf(line, sizeof line, "f %d/%d %d/%d %d/%d\n", a, a, b, b, c, c);
    obj += line;
  }
  emoface::core::write_file_atomic(dir + "/head.obj", obj);
  emoface::core::write_file_atomic(dir + "/head.mtl", "newmtl skin\nKd 0.9 0.7 0.6\n");
  fm::Rig rig = face.rig;
  rig.mesh_file = "head.obj";
  rig.frame.scale = 0.1;  // decimetres -> metres
  fm::write_rig(dir + "/user.rig", rig);
  return dir + "/user.rig";
}

TEST_F(Apps, FaceanimWritesFramesThroughTheUsersObjInItsOwnFrame) {
  const std::string rig = user_obj_rig(dir_.string());
  emoface::core::write_file_atomic(p("p.csv"), "id,masseter,zygomatic_major_l\nneutral,0,0\nsmile,0.3,1\n");
  ASSERT_EQ(run(std::string(FACEANIM_EXE) + " --rig " + rig + " --params " + p("p.csv") + " --out " + p("out") + " --gltf " + p("a.glb")), 0);
  const std::string in = emoface::core::read_file(p("head.obj"));
  const std::string neutral = emoface::core::read_file(p("out/frame_0000.obj"));
  // every line but the re-sampled lip vertices is the user's own text
  auto lines = [](const std::string& t) {
    std::vector<std::string> out;
    std::size_t a = 0;
    while (a < t.size()) {
      const std::size_t b = t.find('\n', a);
      out.push_back(t.substr(a, b - a));
      a = b + 1;
    }
    return out;
  };
  const auto a = lines(in), b = lines(neutral);
  ASSERT_EQ(a.size(), b.size());
  const auto face = fm::load_face(rig);
  std::size_t changed = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] != b[i]) {
      ++changed;
      EXPECT_EQ(a[i].rfind("v ", 0), 0u) << a[i];
    }
  }
  EXPECT_LE(changed, static_cast<std::size_t>(face.rig.lips.samples_around * face.rig.lips.samples_across));
  EXPECT_EQ(emoface::core::read_file(p("out/head.mtl")), "newmtl skin\nKd 0.9 0.7 0.6\n");
  // the smile, read back in the mesh frame (decimetres), is the solver's deformation scaled by 10
  const fm::MeshDocument smile = fm::read_mesh_document(p("out/frame_0001.obj"));
  EXPECT_TRUE(smile.has_uvs());
  ASSERT_EQ(smile.groups().size(), 1u);
  EXPECT_EQ(smile.groups()[0].material, "skin");
  const auto d = emoface::muscles::deform_face(face.mesh, face.rig, {{"masseter", 0.3}, {"zygomatic_major_l", 1.0}});
  EXPECT_LT((smile.triangles().vertices - 10.0 * d.vertices).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT((smile.triangles().vertices - fm::read_mesh_document(p("head.obj")).triangles().vertices).cwiseAbs().maxCoeff(), 0.01);
  // the animation is in the mesh frame too; its first mesh is the skin (eyes and jaw pieces are
  // nodes: muscles::split_rigid_parts), i.e. the user's vertices but those of the parts
  const fm::MeshDocument anim = fm::read_mesh_document(p("a.glb"));
  const emoface::muscles::FaceSolver solver(face.mesh, face.rig);
  emoface::muscles::BakedRig baked = emoface::muscles::bake_rig(solver, face.mesh.faces);
  std::vector<Eigen::Vector3f> no_colors;
  emoface::muscles::split_rigid_parts(baked, face.rig, no_colors);
  const fm::Vertices user = fm::read_mesh_document(p("head.obj")).triangles().vertices;
  fm::Vertices skin(
      static_cast<long>(baked.skin_vertices.empty() ? user.rows() : baked.skin_vertices.size()), 3);
  for (long k = 0; k < skin.rows(); ++k)
    skin.row(k) = user.row(
        baked.skin_vertices.empty() ? k : baked.skin_vertices[static_cast<std::size_t>(k)]);
  ASSERT_EQ(anim.triangles().vertices.rows(), skin.rows());
  EXPECT_LT((anim.triangles().vertices - skin).cwiseAbs().maxCoeff(), 1e-5);
  // ply frames: mesh frame, no document
  ASSERT_EQ(run(std::string(FACEANIM_EXE) + " --rig " + rig + " --params " + p("p.csv") + " --out " + p("ply") + " --format ply"), 0);
  EXPECT_LT((fm::read_mesh(p("ply/frame_0001.ply")).vertices - 10.0 * d.vertices).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_EQ(run(std::string(FACEANIM_EXE) + " --rig " + rig + " --params " + p("p.csv") + " --out " + p("g") + " --format glb"), 2);
}

TEST_F(Apps, FaceanimWritesGlbFramesForAGltfRig) {
  const auto face = fm::make_generic_face();
  fm::write_animated_gltf(p("head.glb"), face.mesh, {face.mesh.vertices}, {0.0});
  fm::Rig rig = face.rig;
  rig.mesh_file = "head.glb";
  fm::write_rig(p("g.rig"), rig);
  emoface::core::write_file_atomic(p("p.csv"), "id,zygomatic_major_r\nsmile,1\n");
  ASSERT_EQ(run(std::string(FACEANIM_EXE) + " --rig " + p("g.rig") + " --params " + p("p.csv") + " --out " + p("out")), 0);
  const fm::MeshDocument frame = fm::read_mesh_document(p("out/frame_0000.glb"));
  const auto loaded = fm::load_face(p("g.rig"));
  const auto d = emoface::muscles::deform_face(loaded.mesh, loaded.rig, {{"zygomatic_major_r", 1.0}});
  EXPECT_LT((frame.triangles().vertices - d.vertices).cwiseAbs().maxCoeff(), 1e-6);  // float storage
  EXPECT_GT((frame.triangles().vertices - loaded.mesh.vertices).cwiseAbs().maxCoeff(), 1e-3);
}

// Size of a PNG of a uniform background (what a blank render compresses to).
std::size_t blank_png_size(int w, int h) {
  core::Image image;
  image.width = w, image.height = h;
  const fm::RenderOptions o;
  image.rgb.resize(static_cast<std::size_t>(w) * h * 3);
  for (std::size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = static_cast<std::uint8_t>(std::lround(o.background[static_cast<long>(i % 3)] * 255));
  return core::encode_png(image).size();
}

TEST_F(Apps, FacerenderFramesAMeshInAnyFrame) {
  const auto face = fm::make_generic_face();
  fm::Mesh far = face.mesh;
  far.vertices *= 10.0;  // decimetres, moved off the default view
  far.vertices.col(1).array() += 15.0;
  fm::write_mesh(p("far.obj"), far);
  ASSERT_EQ(run(std::string(FACERENDER_EXE) + " " + p("far.obj") + " --width 96 --height 112 --out " + p("far.png")), 0);
  EXPECT_GT(emoface::core::read_file(p("far.png")).size(), 4 * blank_png_size(96, 112));
  EXPECT_EQ(run(std::string(FACERENDER_EXE) + " " + p("far.obj") + " --camera fixed --out " + p("x.png")), 2);
  EXPECT_FALSE(fs::exists(p("x.png")));
  // a user's rig: mesh-frame files rendered in the rig frame with the rig's colours and the usual camera
  const std::string rig = user_obj_rig(dir_.string());
  ASSERT_EQ(run(std::string(FACERENDER_EXE) + " " + p("head.obj") + " --rig " + rig + " --width 96 --height 112 --out " + p("u.png")), 0);
  ASSERT_EQ(run(std::string(FACERENDER_EXE) + " " + p("head.obj") + " --rig " + rig + " --camera fixed --width 96 --height 112 --out " + p("uf.png")), 0);
  EXPECT_EQ(emoface::core::read_file(p("u.png")), emoface::core::read_file(p("uf.png")));
  fm::write_mesh(p("m.obj"), face.mesh);
  ASSERT_EQ(run(std::string(FACERENDER_EXE) + " " + p("m.obj") + " --width 96 --height 112 --out " + p("m.png")), 0);
  EXPECT_EQ(emoface::core::read_file(p("u.png")), emoface::core::read_file(p("m.png")));  // same face, same picture
  const std::string mh = std::string(EMOFACE_SOURCE_DIR) + "/../shared/meshes/makehuman_head.obj";
  if (!fs::exists(mh)) GTEST_SKIP() << "../shared/meshes not present";
  ASSERT_EQ(run(std::string(FACERENDER_EXE) + " " + mh + " --width 96 --height 112 --out " + p("mh.png")), 0);
  EXPECT_GT(emoface::core::read_file(p("mh.png")).size(), 4 * blank_png_size(96, 112));
}

}  // namespace
