// End-to-end: the retarget CLI writes a loadable rig, mesh, report and pictures; exit codes.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/gltf.hpp"
#include "emoface/facemesh/io.hpp"
#include "emoface/facemesh/mesh_document.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "user_gltf.hpp"

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

// The .mtl's textures go along (relative layout kept, names with spaces, option flags); one from
// outside the input's directory is copied in under its base name and the .mtl line rewritten; a
// missing one is a warning in report.json. A failure while writing leaves nothing of the set
// behind.
TEST(RetargetApp, TransferCopiesTheTextures) {
  TempDir t;
  const auto in = t.path / "in" / "user";
  fs::create_directories(in / "textures");
  fs::create_directories(t.path / "elsewhere");
  write_user_obj(in / "head.obj");
  const std::string mtl =
      "newmtl skin\nKd 0.8 0.6 0.5\nmap_Kd -s 1 1 1 -bm 0.5 textures/skin tone.png\n"
      "bump ../../elsewhere/bump.png\nmap_Ks missing.png\nnewmtl eye\nKd 1 1 1\n";
  std::ofstream(in / "head.mtl") << mtl;
  std::ofstream(in / "textures" / "skin tone.png") << "PNG skin";
  std::ofstream(t.path / "elsewhere" / "bump.png") << "PNG bump";
  const auto out = t.path / "out";
  ASSERT_EQ(run("--target " + (in / "head.obj").string() + " --out " + out.string() +
                " --generations 2 --population 6 --quiet --no-png"),
            0);
  EXPECT_EQ(slurp(out / "face.obj"), slurp(in / "head.obj"));
  EXPECT_EQ(slurp(out / "textures" / "skin tone.png"), "PNG skin");
  EXPECT_EQ(slurp(out / "bump.png"), "PNG bump");
  std::string expected = mtl;
  expected.replace(expected.find("../../elsewhere/bump.png"), 24, "bump.png");
  EXPECT_EQ(slurp(out / "head.mtl"), expected);
  EXPECT_FALSE(fs::exists(t.path / "in" / "bump.png"));
  const std::string report = slurp(out / "report.json");
  EXPECT_NE(report.find("texture 'missing.png' ('head.mtl' line 5) not found"), std::string::npos)
      << report;
  EXPECT_NE(report.find("copied as 'bump.png'"), std::string::npos);
  // report.json cannot be written (a directory in its place): none of the set is left
  const auto blocked = t.path / "blocked";
  fs::create_directories(blocked / "report.json");
  EXPECT_EQ(run("--target " + (in / "head.obj").string() + " --out " + blocked.string() +
                " --generations 2 --population 6 --quiet --no-png"),
            2);
  std::size_t n = 0;
  for (const auto& e : fs::recursive_directory_iterator(blocked)) ++n, (void)e;
  EXPECT_EQ(n, 1u);  // only the directory that was there
}

// A second real mesh: MediaPipe's canonical face model (Apache-2.0, ../shared/meshes only, never in
// the repository) is a face mask, not a head — refused with a clear message, nothing written.
TEST(RetargetApp, TransferRefusesAFaceMask) {
  const std::string mask =
      std::string(EMOFACE_SOURCE_DIR) + "/../shared/meshes/mediapipe_canonical_face_model.obj";
  if (!fs::exists(mask)) GTEST_SKIP() << "../shared/meshes absent";
  TempDir t;
  const auto out = t.path / "out";
  const int status =
      std::system((std::string(RETARGET_EXE) + " --target " + mask + " --out " + out.string() +
                   " --quiet --no-png 2>" + (t.path / "err.txt").string())
                      .c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_NE(slurp(t.path / "err.txt").find("no top of head (a face mask"), std::string::npos)
      << slurp(t.path / "err.txt");
  EXPECT_FALSE(fs::exists(out));
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
  EXPECT_FALSE(fs::exists(out));  // not even the directory
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

// A glTF whose image is a file of its own ("uri": "tex/skin.png"): the transfer copies it with the
// output, and as part of the all-or-nothing set: when writing fails late (here report.json cannot
// be renamed into place, a directory of that name is in the way), the image goes too (the glTF
// writer used to copy it itself, outside the set, and left it behind).
TEST(RetargetApp, TransferOfGltfCopiesItsImageFilesAllOrNothing) {
  TempDir t;
  const auto face = emoface::facemesh::make_generic_face();
  const auto in = t.path / "in";
  fs::create_directories(in / "tex");
  const auto written = t.path / "plain.gltf";
  emoface::facemesh::write_animated_gltf(written.string(), face.mesh, {face.mesh.vertices}, {0.0});
  std::string json = slurp(written);
  ASSERT_EQ(json.front(), '{');
  json.insert(1, "\"images\":[{\"uri\":\"tex/skin.png\"}],");
  std::ofstream(in / "head.gltf", std::ios::binary) << json;
  const std::string png = "\x89PNG\r\n\x1a\nnot decoded";
  std::ofstream(in / "tex" / "skin.png", std::ios::binary) << png;
  const std::string args = " --generations 2 --population 6 --quiet --no-png";
  const auto out = t.path / "out";
  ASSERT_EQ(run("--target " + (in / "head.gltf").string() + " --out " + out.string() + args), 0);
  EXPECT_EQ(slurp(out / "tex" / "skin.png"), png);
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader([](tinygltf::Image*, const int, std::string*, std::string*, int, int,
                           const unsigned char*, int, void*) { return true; },
                        nullptr);
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, (out / "face.glb").string())) << err;
  ASSERT_EQ(m.images.size(), 1u);
  EXPECT_EQ(m.images[0].uri, "tex/skin.png");
  // a late failure leaves nothing of the set behind (and keeps what was there)
  const auto failed = t.path / "failed";
  fs::create_directories(failed / "report.json");
  EXPECT_NE(run("--target " + (in / "head.gltf").string() + " --out " + failed.string() + args), 0);
  EXPECT_FALSE(fs::exists(failed / "tex" / "skin.png"));
  EXPECT_FALSE(fs::exists(failed / "tex"));
  EXPECT_FALSE(fs::exists(failed / "face.glb"));
  EXPECT_FALSE(fs::exists(failed / "face.rig"));
  EXPECT_TRUE(fs::is_directory(failed / "report.json"));
}

// A user's glTF whose own morph target is a sparse accessor (as engines export them, glTF 2.0
// §3.6.2.3): the transfer reads it and writes it back — still sparse, the same deltas.
TEST(RetargetApp, TransferKeepsSparseMorphTargets) {
  TempDir t;
  const auto face = emoface::facemesh::make_default_face();
  const auto in = t.path / "user.glb";
  ASSERT_TRUE(emoface::testing::write_user_gltf(in.string(), face.mesh, true));
  const auto out = t.path / "out";
  ASSERT_EQ(run("--target " + in.string() + " --out " + out.string() +
                " --generations 2 --population 6 --quiet --no-png"),
            0);
  const auto before = emoface::facemesh::read_mesh_document(in.string());
  const auto after = emoface::facemesh::read_mesh_document((out / "face.glb").string());
  ASSERT_EQ(before.morph_targets().size(), 1u);
  ASSERT_EQ(after.morph_targets().size(), 1u);
  EXPECT_EQ(after.morph_targets()[0].name, "user_smile");
  EXPECT_GT(before.morph_targets()[0].position_deltas.maxCoeff(), 0.0019);  // 2 mm rows read
  EXPECT_EQ(after.morph_targets()[0].position_deltas, before.morph_targets()[0].position_deltas);
  EXPECT_EQ(after.triangles().vertices, before.triangles().vertices);
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, (out / "face.glb").string())) << err;
  EXPECT_TRUE(
      m.accessors[static_cast<std::size_t>(m.meshes[0].primitives[0].targets[0].at("POSITION"))]
          .sparse.isSparse);
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
// A scanner's binary PLY with vertex colours and a property of its own: the transfer copies it, the
// faceanim frames are that PLY with only the moved vertices' x/y/z bytes changed (colours and the
// unknown property kept), and facerender shows the file's colours on the user's rig.
TEST(RetargetApp, PlyColoursSurviveTransferAndAnimation) {
  TempDir t;
  const auto face = emoface::facemesh::make_generic_face();
  const auto& v = face.mesh.vertices;
  std::string ply = "ply\nformat binary_little_endian 1.0\ncomment a scanner\nelement vertex " +
                    std::to_string(v.rows()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar "
                    "red\nproperty uchar green\n"
                    "property uchar blue\nproperty float confidence\nelement face " +
                    std::to_string(face.mesh.faces.rows()) +
                    "\nproperty list uchar int vertex_indices\nend_header\n";
  auto put = [&ply](const void* p, std::size_t n) { ply.append(static_cast<const char*>(p), n); };
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const auto f = static_cast<float>(v(i, k));
      put(&f, 4);
    }
    const unsigned char rgb[3] = {40, static_cast<unsigned char>(v(i, 0) > 0 ? 200 : 90),
                                  60};  // green, darker on the right
    put(rgb, 3);
    const float confidence = 0.75f;
    put(&confidence, 4);
  }
  for (Eigen::Index f = 0; f < face.mesh.faces.rows(); ++f) {
    const unsigned char n = 3;
    put(&n, 1);
    for (int k = 0; k < 3; ++k) put(&face.mesh.faces(f, k), 4);
  }
  std::ofstream(t.path / "scan.ply", std::ios::binary) << ply;
  const auto out = t.path / "out";
  ASSERT_EQ(run("--target " + (t.path / "scan.ply").string() + " --out " + out.string() +
                " --generations 2 --population 6 --quiet --no-png"),
            0);
  EXPECT_TRUE(slurp(out / "face.ply") == ply);  // byte for byte (not printed: binary)
  int status = 0;
#ifdef FACEANIM_EXE
  std::ofstream(t.path / "p.csv")
      << "masseter,zygomatic_major_l,zygomatic_major_r\n0,0,0\n1,0.8,0.8\n";
  const auto frames = t.path / "frames";
  status = std::system((std::string(FACEANIM_EXE) + " --rig " + (out / "face.rig").string() +
                        " --params " + (t.path / "p.csv").string() + " --out " + frames.string() +
                        " 2>/dev/null")
                           .c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  const std::string open = slurp(frames / "frame_0001.ply");
  ASSERT_EQ(open.size(), ply.size());  // the same binary layout
  const auto in_doc = emoface::facemesh::read_mesh_document((t.path / "scan.ply").string());
  const auto frame = emoface::facemesh::read_mesh_document((frames / "frame_0001.ply").string());
  EXPECT_EQ(frame.vertex_colors(), in_doc.vertex_colors());
  ASSERT_EQ(frame.vertex_colors().size(), static_cast<std::size_t>(v.rows()));
  std::size_t moved = 0, other_bytes_changed = 0;
  const std::size_t body = ply.find("end_header\n") + 11;
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    moved += (frame.triangles().vertices.row(i) - in_doc.triangles().vertices.row(i)).norm() > 0.0;
    const std::size_t rec = body + static_cast<std::size_t>(i) * 19;
    other_bytes_changed += open.compare(rec + 12, 7, ply, rec + 12, 7) != 0;  // colour + confidence
  }
  EXPECT_GT(moved, 300u);
  EXPECT_EQ(other_bytes_changed, 0u);
  EXPECT_TRUE(open.substr(body + static_cast<std::size_t>(v.rows()) * 19) ==
              ply.substr(body + static_cast<std::size_t>(v.rows()) * 19));
  EXPECT_TRUE(open.substr(0, body) == ply.substr(0, body));  // the header
  // neutral: every vertex back where the user had it (float file, through the rig frame and back)
  const auto neutral = emoface::facemesh::read_mesh_document((frames / "frame_0000.ply").string());
  EXPECT_LT((neutral.triangles().vertices - in_doc.triangles().vertices).cwiseAbs().maxCoeff(),
            1e-6);
  EXPECT_EQ(neutral.vertex_colors(), in_doc.vertex_colors());
#endif
#ifdef FACERENDER_EXE
  // facerender on the user's rig: the file's colours, not the rig's material colours
  emoface::facemesh::write_mesh((t.path / "plain.ply").string(),
                                emoface::facemesh::read_mesh((out / "face.ply").string()));
  for (const char* m : {"face", "plain"}) {
    const std::string mesh =
        m == std::string("face") ? (out / "face.ply").string() : (t.path / "plain.ply").string();
    status = std::system((std::string(FACERENDER_EXE) + " " + mesh + " --rig " +
                          (out / "face.rig").string() + " --out " +
                          (t.path / (std::string(m) + ".png")).string() + " 2>/dev/null")
                             .c_str());
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << m;
  }
  EXPECT_NE(slurp(t.path / "face.png"), slurp(t.path / "plain.png"));
  if (const char* keep = std::getenv("EMOFACE_KEEP_PNG"))
    fs::copy_file(t.path / "face.png", keep, fs::copy_options::overwrite_existing);
#endif
}

// A user's own glTF (skin with inverse bind matrices, UVs + texture under their material, a target
// and an animation of theirs), rigged by the transfer and animated by faceanim --gltf: everything
// of theirs comes back unchanged, our targets (parameters + the 52 ARKit shapes) and our weights
// animation are added to their mesh (issue 15). The validator checks the same file in
// gltf.validator.
TEST(RetargetApp, FaceanimGltfKeepsTheUsersCharacter) {
  TempDir t;
  const auto face = emoface::facemesh::make_default_face();
  const auto in = t.path / "user.gltf";
  ASSERT_TRUE(emoface::testing::write_user_gltf(in.string(), face.mesh));
  const auto out = t.path / "out";
  ASSERT_EQ(run("--target " + in.string() + " --out " + out.string() +
                " --generations 2 --population 6 --quiet --no-png"),
            0);
  std::ofstream(t.path / "p.csv")
      << "time,masseter,zygomatic_major_l,zygomatic_major_r\n0,0,0,0\n0.5,0.6,1,1\n";
  const auto glb = t.path / "anim.glb";
  const int status = std::system(
      (std::string(FACEANIM_EXE) + " --rig " + (out / "face.rig").string() + " --params " +
       (t.path / "p.csv").string() + " --gltf " + glb.string() + " 2>/dev/null")
          .c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  tinygltf::Model mine, theirs;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&mine, &err, &warn, glb.string())) << err;
  theirs = emoface::testing::user_gltf_model(face.mesh);
  auto bytes = [](const tinygltf::Model& m, int accessor) {
    const auto& a = m.accessors[static_cast<std::size_t>(accessor)];
    const auto& v = m.bufferViews[static_cast<std::size_t>(a.bufferView)];
    const auto* b =
        m.buffers[static_cast<std::size_t>(v.buffer)].data.data() + v.byteOffset + a.byteOffset;
    const std::size_t size =
        a.count * static_cast<std::size_t>(tinygltf::GetNumComponentsInType(a.type)) *
        static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(a.componentType));
    return std::vector<unsigned char>(b, b + size);
  };
  // their nodes, skin, material, texture, image, animation
  ASSERT_EQ(mine.nodes.size(), theirs.nodes.size());
  for (std::size_t n = 0; n < theirs.nodes.size(); ++n) {
    EXPECT_EQ(mine.nodes[n].name, theirs.nodes[n].name);
    EXPECT_EQ(mine.nodes[n].translation, theirs.nodes[n].translation);
    EXPECT_EQ(mine.nodes[n].children, theirs.nodes[n].children);
  }
  ASSERT_EQ(mine.skins.size(), 1u);
  EXPECT_EQ(mine.skins[0].joints, theirs.skins[0].joints);
  EXPECT_EQ(mine.skins[0].skeleton, 1);
  EXPECT_EQ(bytes(mine, mine.skins[0].inverseBindMatrices),
            bytes(theirs, theirs.skins[0].inverseBindMatrices));
  EXPECT_EQ(mine.nodes[0].skin, 0);
  ASSERT_EQ(mine.materials.size(), 1u);
  EXPECT_EQ(mine.materials[0].name, "user_skin");
  EXPECT_EQ(mine.materials[0].pbrMetallicRoughness.baseColorFactor,
            theirs.materials[0].pbrMetallicRoughness.baseColorFactor);
  EXPECT_EQ(mine.materials[0].pbrMetallicRoughness.baseColorTexture.index, 0);
  ASSERT_EQ(mine.images.size(), 1u);
  ASSERT_EQ(mine.animations.size(), 2u);  // theirs, then ours
  EXPECT_EQ(mine.animations[0].name, "user_jaw");
  EXPECT_EQ(mine.animations[0].channels[0].target_node, 2);
  // their attributes byte for byte (the positions: float32 through the rig frame and back)
  const auto& p = mine.meshes[0].primitives[0];
  const auto& q = theirs.meshes[0].primitives[0];
  for (const char* attr : {"TEXCOORD_0", "JOINTS_0", "WEIGHTS_0"})
    EXPECT_EQ(bytes(mine, p.attributes.at(attr)), bytes(theirs, q.attributes.at(attr))) << attr;
  EXPECT_EQ(bytes(mine, p.indices), bytes(theirs, q.indices));
  EXPECT_EQ(p.material, 0);
  // their target first and unchanged; ours after it
  ASSERT_GT(p.targets.size(), 1u + 52u);
  EXPECT_EQ(bytes(mine, p.targets[0].at("POSITION")), bytes(theirs, q.targets[0].at("POSITION")));
  const auto& names = mine.meshes[0].extras.Get("targetNames");
  ASSERT_EQ(names.ArrayLen(), p.targets.size());
  EXPECT_EQ(names.Get(0).Get<std::string>(), "user_smile");
  std::vector<std::string> ours;
  for (std::size_t i = 1; i < names.ArrayLen(); ++i)
    ours.push_back(names.Get(static_cast<int>(i)).Get<std::string>());
  for (const char* n :
       {"zygomatic_major_l", "masseter", "jawOpen", "mouthSmile_L", "eyeBlink_R", "tongueOut"})
    EXPECT_NE(std::find(ours.begin(), ours.end(), n), ours.end()) << n;
  // our zygomatic target moves the left mouth corner (+x) up and out, by millimetres
  const auto zyg = static_cast<std::size_t>(
                       std::find(ours.begin(), ours.end(), "zygomatic_major_l") - ours.begin()) +
                   1;
  const auto& acc = mine.accessors[static_cast<std::size_t>(p.targets[zyg].at("POSITION"))];
  EXPECT_GT(acc.maxValues[1], 0.001);
  EXPECT_LT(acc.maxValues[1], 0.03);
  // our animation: one weights channel on their skinned node, their target at its default weight 0
  const auto& an = mine.animations[1];
  ASSERT_EQ(an.channels.size(), 1u);
  EXPECT_EQ(an.channels[0].target_node, 0);
  EXPECT_EQ(an.channels[0].target_path, "weights");
  const auto& w = mine.accessors[static_cast<std::size_t>(an.samplers[0].output)];
  EXPECT_EQ(w.count, 2 * p.targets.size());
  std::vector<float> weights(w.count);
  std::memcpy(weights.data(), bytes(mine, an.samplers[0].output).data(), w.count * 4);
  const std::size_t nt = p.targets.size();
  EXPECT_EQ(weights[nt + 0], 0.0f);          // user_smile
  EXPECT_FLOAT_EQ(weights[nt + zyg], 1.0f);  // zygomatic_major_l at t = 0.5
  EXPECT_EQ(*std::max_element(weights.begin(), weights.begin() + static_cast<long>(nt)),
            0.0f);  // t = 0: neutral
}
#endif
