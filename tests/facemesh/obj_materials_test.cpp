// MeshDocument::companion_files: an OBJ's .mtl files and every texture they name go with a copy of
// the OBJ, at the same relative paths; nothing lands outside the copy's directory.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>

#include "emoface/core/io.hpp"
#include "emoface/facemesh/mesh_document.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "test_util.hpp"

namespace emoface::facemesh {
namespace {

namespace fs = std::filesystem;

class ObjMaterialsTest : public testing::TempDirTest {
 protected:
  void put(const std::string& name, const std::string& bytes) {
    fs::create_directories(fs::path(path(name)).parent_path());
    core::write_file_atomic(path(name), bytes);
  }
  std::map<std::string, std::string> files(const Companions& c) {
    std::map<std::string, std::string> m;
    for (const auto& f : c.files) m[f.path] = f.bytes;
    return m;
  }
};

const char* kObj =
    "mtllib mats/head.mtl\nmtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl skin\nf 1 2 3\n";

TEST_F(ObjMaterialsTest, CopiesEveryTextureTheMaterialsName) {
  put("user/head.obj", kObj);
  put("user/mats/textures/skin tone.png", "PNG skin");
  put("user/mats/textures/disp.png", "PNG disp");
  put("user/mats/refl.png", "PNG refl");
  put("user/mats/normal.png", "PNG normal");
  put("outside/bump.png", "PNG bump");
  put("abs/spec.png", "PNG spec");
  put("abs2/bump.png", "PNG another bump");  // the same base name as ../../outside/bump.png
  const std::string spec = fs::absolute(path("abs/spec.png")).string();
  const std::string bump2 = fs::absolute(path("abs2/bump.png")).string();
  const std::string mtl =
      "# the user's materials\r\n"
      "newmtl skin\r\n"
      "Kd 0.8 0.6 0.5\r\n"
      "map_Kd -s 1 1 1 -bm 0.5 textures/skin tone.png\r\n"
      "map_Ka textures/skin tone.png\r\n"
      "bump -bm 0.5 ../../outside/bump.png\r\n"
      "map_Ks -o 0.5 0.5 " +
      spec +
      "\r\n"
      "map_d -clamp on missing.png\r\n"
      "disp textures/disp.png\r\n"
      "refl -type sphere refl.png\r\n"
      "norm normal.png\r\n"
      "map_Ns -mm 0 1 " +
      bump2 +
      "\r\n"
      "map_aat on\r\n"
      "newmtl eye\r\n"
      "map_Kd\r\n";
  put("user/mats/head.mtl", mtl);
  const MeshDocument doc = read_mesh_document(path("user/head.obj"));
  const Companions c = doc.companion_files();
  const auto f = files(c);
  EXPECT_EQ(f.size(), 8u);  // the .mtl and seven textures (skin tone once)
  EXPECT_EQ(f.at("mats/textures/skin tone.png"), "PNG skin");
  EXPECT_EQ(f.at("mats/textures/disp.png"), "PNG disp");
  EXPECT_EQ(f.at("mats/refl.png"), "PNG refl");
  EXPECT_EQ(f.at("mats/normal.png"), "PNG normal");
  EXPECT_EQ(f.at("mats/bump.png"), "PNG bump");  // from outside: copied in under its base name
  EXPECT_EQ(f.at("mats/spec.png"), "PNG spec");  // absolute: likewise
  EXPECT_EQ(f.at("mats/bump_2.png"), "PNG another bump");  // base name taken: made unique
  for (const auto& [p, bytes] : f) {
    EXPECT_EQ(p.find(".."), std::string::npos) << p;
    EXPECT_FALSE(fs::path(p).is_absolute()) << p;
  }
  // the .mtl: the lines naming files outside rewritten (options kept), every other byte the same
  std::string expected = mtl;
  expected.replace(expected.find("../../outside/bump.png"), 22, "bump.png");
  expected.replace(expected.find(spec), spec.size(), "spec.png");
  expected.replace(expected.find(bump2), bump2.size(), "bump_2.png");
  EXPECT_EQ(f.at("mats/head.mtl"), expected);
  // warnings: the missing library and texture, the three copied in, the statement without a name
  ASSERT_EQ(c.warnings.size(), 6u);
  auto warned = [&](const std::string& what) {
    return std::any_of(c.warnings.begin(), c.warnings.end(),
                       [&](const std::string& w) { return w.find(what) != std::string::npos; });
  };
  EXPECT_TRUE(warned("material library 'missing.mtl' not found"));
  EXPECT_TRUE(warned("texture 'missing.png' ('mats/head.mtl' line 8) not found"));
  EXPECT_TRUE(warned("copied as 'bump.png'"));
  EXPECT_TRUE(warned("copied as 'spec.png'"));
  EXPECT_TRUE(warned("copied as 'bump_2.png'"));
  EXPECT_TRUE(warned("without a file name in 'mats/head.mtl' line 15"));

  // a copy written elsewhere (faceanim frames) takes them along
  fs::create_directories(path("frames"));
  doc.write(path("frames/frame_0000.obj"), doc.triangles().vertices);
  EXPECT_EQ(core::read_file(path("frames/mats/textures/skin tone.png")), "PNG skin");
  EXPECT_EQ(core::read_file(path("frames/mats/head.mtl")), expected);
  EXPECT_EQ(core::read_file(path("frames/mats/bump_2.png")), "PNG another bump");
}

TEST_F(ObjMaterialsTest, LibrariesOutsideStayWhereTheyAre) {
  put("user/head.obj",
      "mtllib ../shared.mtl\nmtllib /nonexistent/abs.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  put("shared.mtl", "newmtl a\nmap_Kd a.png\n");
  const Companions c = read_mesh_document(path("user/head.obj")).companion_files();
  EXPECT_TRUE(c.files.empty());
  ASSERT_EQ(c.warnings.size(), 2u);
  EXPECT_NE(c.warnings[0].find("outside the mesh's directory"), std::string::npos);
  // other formats have none
  write_mesh(path("t.ply"), testing::tetrahedron());
  const Companions none = read_mesh_document(path("t.ply")).companion_files();
  EXPECT_TRUE(none.files.empty() && none.warnings.empty());
}

}  // namespace
}  // namespace emoface::facemesh
