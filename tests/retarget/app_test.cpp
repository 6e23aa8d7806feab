// End-to-end: the retarget CLI writes a loadable rig, mesh, report and pictures; exit codes.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/gltf.hpp"
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
  const std::string target = std::string(EMOFACE_SOURCE_DIR) + "/data/face/generic_face.obj";  // the source itself
  const auto out = t.path / "out";
  ASSERT_EQ(run("--mode deform-source --target " + target + " --out " + out.string() + " --generations 2 --population 6 --quiet"), 0);
  for (const char* f : {"face.rig", "face.obj", "target_aligned.obj", "report.json", "overlay.png", "error_curve.png", "emotions.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto face = emoface::facemesh::load_face((out / "face.rig").string());
  EXPECT_EQ(face.mesh.vertex_count(), face.rig.vertex_count);
  // Same seed: identical rig.
  const auto out2 = t.path / "out2";
  ASSERT_EQ(run("--mode deform-source --target " + target + " --out " + out2.string() + " --generations 2 --population 6 --quiet --no-png"), 0);
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

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The built-in face as a user would hand it in: OBJ with cylindrical UVs, a material library, an
// object, groups for the head and the eyeballs, and comment lines.
void write_user_obj(const fs::path& path) {
  const auto face = emoface::facemesh::make_generic_face();
  std::ostringstream o;
  o << "# a user's head\nmtllib head.mtl\no head\n";
  o.precision(9);
  const auto& v = face.mesh.vertices;
  for (Eigen::Index i = 0; i < v.rows(); ++i) o << "v " << v(i, 0) << " " << v(i, 1) << " " << v(i, 2) << "\n";
  for (Eigen::Index i = 0; i < v.rows(); ++i)
    o << "vt " << (std::atan2(v(i, 0), v(i, 2)) / 6.283185307179586 + 0.5) << " " << (v(i, 1) + 0.2) / 0.4 << "\n";
  std::vector<char> eyeball(static_cast<std::size_t>(v.rows()), 0);
  for (const auto& e : face.rig.eyes)
    for (int i : e.eyeball_vertices) eyeball[static_cast<std::size_t>(i)] = 1;
  for (int pass = 0; pass < 2; ++pass) {
    o << (pass == 0 ? "g skin\nusemtl skin\n" : "g eyes\nusemtl eye\n");
    for (Eigen::Index f = 0; f < face.mesh.faces.rows(); ++f) {
      if (eyeball[static_cast<std::size_t>(face.mesh.faces(f, 0))] != pass) continue;
      o << "f";
      for (int k = 0; k < 3; ++k) o << " " << face.mesh.faces(f, k) + 1 << "/" << face.mesh.faces(f, k) + 1;
      o << "\n";
    }
  }
  std::ofstream(path, std::ios::binary) << o.str();
  std::ofstream(path.parent_path() / "head.mtl") << "newmtl skin\nKd 0.8 0.6 0.5\nnewmtl eye\nKd 1 1 1\n";
}
}  // namespace

TEST(RetargetApp, TransferKeepsTheUsersFileAndRigsIt) {
  TempDir t;
  const auto in = t.path / "in";
  fs::create_directories(in);
  write_user_obj(in / "head.obj");
  const auto out = t.path / "out";
  ASSERT_EQ(run("--target " + (in / "head.obj").string() + " --out " + out.string() + " --generations 3 --population 8 --quiet"), 0);
  // the mesh file is the input, byte for byte (UVs, groups, materials, comments); its .mtl is copied
  EXPECT_EQ(slurp(out / "face.obj"), slurp(in / "head.obj"));
  EXPECT_EQ(slurp(out / "head.mtl"), slurp(in / "head.mtl"));
  for (const char* f : {"face.rig", "report.json", "emotions.png"}) EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto face = emoface::facemesh::load_face((out / "face.rig").string());
  EXPECT_EQ(face.mesh.vertex_count(), emoface::facemesh::make_generic_face().mesh.vertex_count());
  EXPECT_FALSE(face.rig.lips.samples_in_mesh);
  EXPECT_FALSE(face.rig.lips.bound.empty());
  EXPECT_EQ(face.rig.mesh_file, "face.obj");
  // eyeballs named by the group, both found
  EXPECT_FALSE(face.rig.eyes[0].eyeball_vertices.empty());
  EXPECT_FALSE(face.rig.eyes[1].eyeball_vertices.empty());
  const std::string report = slurp(out / "report.json");
  EXPECT_NE(report.find("\"mode\": \"transfer\""), std::string::npos);
  EXPECT_NE(report.find("\"found_by\": \"name\""), std::string::npos);
  // --transfer is the short form; deform-source still writes the thesis export
  const auto out2 = t.path / "out2";
  ASSERT_EQ(run("--transfer --target " + (in / "head.obj").string() + " --out " + out2.string() + " --generations 3 --population 8 --quiet --no-png"), 0);
  EXPECT_EQ(slurp(out2 / "face.rig"), slurp(out / "face.rig"));
}

TEST(RetargetApp, TransferWritesNothingOnBadInput) {
  TempDir t;
  const auto in = t.path / "in";
  fs::create_directories(in);
  write_user_obj(in / "head.obj");
  // a landmark id out of range
  {
    std::ofstream lm(in / "lm.json");
    lm << R"({"format": "emoface.landmarks", "version": "1.0", "scheme": "ibug68", "points": [)";
    for (int k = 0; k < 68; ++k) lm << (k ? ", " : "") << (k < 5 ? "99999999" : "null");
    lm << "]}";
  }
  const auto out = t.path / "out";
  EXPECT_EQ(run("--target " + (in / "head.obj").string() + " --out " + out.string() + " --landmarks " + (in / "lm.json").string() + " --quiet"), 2);
  EXPECT_FALSE(fs::exists(out / "face.obj"));
  EXPECT_FALSE(fs::exists(out / "face.rig"));
  // a malformed landmarks file
  std::ofstream(in / "bad.json") << "{\"format\": \"emoface.landmarks\", \"version\": \"1.0\", \"scheme\": \"ibug68\", \"points\": [1, 2]}";
  EXPECT_EQ(run("--target " + (in / "head.obj").string() + " --out " + out.string() + " --landmarks " + (in / "bad.json").string() + " --quiet"), 2);
  // NaN, no faces
  std::ofstream(in / "nan.obj") << "v 0 0 0\nv nan 1 0\nv 0 0 1\nf 1 2 3\n";
  EXPECT_EQ(run("--target " + (in / "nan.obj").string() + " --out " + out.string() + " --quiet"), 2);
  std::ofstream(in / "nofaces.obj") << "v 0 0 0\nv 1 1 0\nv 0 0 1\n";
  EXPECT_EQ(run("--target " + (in / "nofaces.obj").string() + " --out " + out.string() + " --quiet"), 2);
  EXPECT_FALSE(fs::exists(out / "face.rig"));
  EXPECT_FALSE(fs::exists(out / "report.json"));
  // --landmarks without transfer is a usage error
  EXPECT_EQ(run("--mode deform-source --target " + (in / "head.obj").string() + " --out " + out.string() + " --landmarks " +
                (in / "lm.json").string()), 1);
}

TEST(RetargetApp, TransferOfGltfWritesGlb) {
  TempDir t;
  const auto face = emoface::facemesh::make_generic_face();
  const auto in = t.path / "head.gltf";
  emoface::facemesh::write_animated_gltf(in.string(), face.mesh, {face.mesh.vertices}, {0.0});
  const auto out = t.path / "out";
  ASSERT_EQ(run("--target " + in.string() + " --out " + out.string() + " --generations 2 --population 6 --quiet --no-png"), 0);
  ASSERT_TRUE(fs::exists(out / "face.glb"));
  const auto rigged = emoface::facemesh::load_face((out / "face.rig").string());
  EXPECT_EQ(rigged.rig.mesh_file, "face.glb");
  ASSERT_EQ(rigged.mesh.vertices.rows(), face.mesh.vertices.rows());
  // the glTF's positions come back (through the rig frame) where they were
  double worst = 0.0;
  for (Eigen::Index v = 0; v < face.mesh.vertices.rows(); ++v)
    worst = std::max(worst, (rigged.rig.frame.to_mesh(rigged.mesh.vertices.row(v).transpose()) - face.mesh.vertices.row(v).transpose()).norm());
  EXPECT_LT(worst, 1e-6);  // glTF stores float32
}

#ifdef FACEANIM_EXE
// End to end: faceanim animates the transferred rig, writing frames of the user's own file (UVs, groups,
// materials and every other line kept; only vertex positions change, in the file's own frame).
TEST(RetargetApp, FaceanimAnimatesTheTransferredMesh) {
  TempDir t;
  const auto in = t.path / "in";
  fs::create_directories(in);
  write_user_obj(in / "head.obj");
  const auto out = t.path / "out";
  ASSERT_EQ(run("--target " + (in / "head.obj").string() + " --out " + out.string() + " --generations 2 --population 6 --quiet --no-png"), 0);
  std::ofstream(t.path / "p.csv") << "masseter,zygomatic_major_l,zygomatic_major_r\n0,0,0\n1,0.8,0.8\n";
  const auto frames = t.path / "frames";
  const int status = std::system((std::string(FACEANIM_EXE) + " --rig " + (out / "face.rig").string() + " --params " +
                                  (t.path / "p.csv").string() + " --out " + frames.string() + " 2>/dev/null").c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  auto lines = [](const std::string& text) {
    std::vector<std::string> v;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) v.push_back(l);
    return v;
  };
  const auto input = lines(slurp(in / "head.obj"));
  const auto neutral = lines(slurp(frames / "frame_0000.obj")), open = lines(slurp(frames / "frame_0001.obj"));
  ASSERT_EQ(open.size(), input.size());
  std::size_t moved = 0;
  for (std::size_t i = 0; i < input.size(); ++i) {
    if (input[i].rfind("v ", 0) == 0) {
      moved += open[i] != input[i];
      continue;
    }
    EXPECT_EQ(open[i], input[i]) << "line " << i + 1;  // vt, f, g, usemtl, mtllib, comments: unchanged
  }
  EXPECT_GT(moved, 300u);
  // the neutral frame puts every vertex back where the user had it (input frame and units)
  const auto a = emoface::facemesh::read_mesh((in / "head.obj").string()), b = emoface::facemesh::read_mesh((frames / "frame_0000.obj").string());
  ASSERT_EQ(a.vertices.rows(), b.vertices.rows());
  EXPECT_LT((a.vertices - b.vertices).cwiseAbs().maxCoeff(), 1e-6);
}
#endif
