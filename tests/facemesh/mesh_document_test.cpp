#include "emoface/facemesh/mesh_document.hpp"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/gltf.hpp"
#include "emoface/facemesh/io.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "test_util.hpp"

namespace emoface::facemesh {
namespace {

class MeshDocumentTest : public testing::TempDirTest {};

// Every OBJ feature: comments, mtllib, o/g/usemtl/s, coloured vertices, a continued line, vt, vn,
// the four corner forms, negative indices, a quad, a degenerate polygon, a line element, an unknown
// statement, trailing spaces and a last line without a newline.
const char* kFullObj =
    "# emoface test OBJ\n"
    "mtllib head.mtl\n"
    "o head\n"
    "v 0 0 0 1 0 0\n"
    "v 1.0 0 0 0 1 0   # a comment after the colour\n"
    "v 1 1 0 0 0 1\n"
    "v 0 1 0 0.5 0.5 0.5\n"
    "v 0.5 0.5 \\\n"
    "  -1 1 1 1\n"
    "v 1e-3 +2 0.5 0.25 0.25 0.25\n"
    "vt 0 0\n"
    "vt 1 0\n"
    "vt 1 1\n"
    "vt 0 1\n"
    "vn 0 0 1\n"
    "vn 0 -1 0\n"
    "vn 0.577 0.577 0.577\n"
    "g front\n"
    "usemtl skin\n"
    "s 1\n"
    "f 1/1/1 2/2/1 3/3/1 4/4/1\n"
    "f -5//2 -6//2 -2//2\n"
    "g back side\n"
    "usemtl lip\n"
    "s off\n"
    "f 1/1 2/2 5/3\n"
    "f 2 3 5\n"
    "f 3 3 5\n"
    "l 1 2\n"
    "curv 0 1 1 2\n"
    "f 3/3/3 4/4/3 5/1/3 ";

TEST_F(MeshDocumentTest, ParsesEveryObjFeature) {
  const MeshDocument doc = read_mesh_document(put("head.obj", kFullObj));
  EXPECT_EQ(doc.format(), MeshFormat::Obj);
  const Mesh& m = doc.triangles();
  ASSERT_EQ(m.vertex_count(), 6u);
  EXPECT_EQ(Eigen::Vector3d(m.vertices.row(4).transpose()), Eigen::Vector3d(0.5, 0.5, -1));  // continued line
  EXPECT_EQ(Eigen::Vector3d(m.vertices.row(5).transpose()), Eigen::Vector3d(1e-3, 2, 0.5));
  // quad -> 2, relative face -> 1, 3 more triangles, the degenerate "f 3 3 5" dropped
  ASSERT_EQ(m.face_count(), 6u);
  EXPECT_EQ(doc.dropped_faces(), 1u);
  EXPECT_EQ(Eigen::Vector3i(m.faces.row(0).transpose()), Eigen::Vector3i(0, 1, 2));
  EXPECT_EQ(Eigen::Vector3i(m.faces.row(1).transpose()), Eigen::Vector3i(0, 2, 3));
  EXPECT_EQ(Eigen::Vector3i(m.faces.row(2).transpose()), Eigen::Vector3i(1, 0, 4));  // -5, -6, -2 of 6
  EXPECT_EQ(doc.polygon_of_triangle(), (std::vector<int>{0, 0, 1, 2, 3, 5}));
  ASSERT_EQ(doc.groups().size(), 2u);
  EXPECT_EQ(doc.groups()[0].object, "head");
  EXPECT_EQ(doc.groups()[0].group, "front");
  EXPECT_EQ(doc.groups()[0].material, "skin");
  EXPECT_EQ(doc.groups()[0].faces, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(doc.groups()[1].group, "back side");
  EXPECT_EQ(doc.groups()[1].material, "lip");
  EXPECT_EQ(doc.groups()[1].faces, (std::vector<int>{3, 4, 5}));
  EXPECT_TRUE(doc.has_uvs());
  ASSERT_EQ(doc.vertex_colors().size(), 6u);
  EXPECT_EQ(doc.vertex_colors()[1], Eigen::Vector3f(0, 1, 0));
  EXPECT_EQ(doc.vertex_colors()[3], Eigen::Vector3f(0.5f, 0.5f, 0.5f));
  EXPECT_EQ(doc.material_libraries(), (std::vector<std::string>{"head.mtl"}));
}

TEST_F(MeshDocumentTest, IdenticalPositionsGiveAByteIdenticalFile) {
  for (const std::string& text : {std::string(kFullObj), [] {
         std::string crlf;  // the same file with CRLF line ends
         for (const char* c = kFullObj; *c; ++c) {
           if (*c == '\n') crlf += '\r';
           crlf += *c;
         }
         return crlf;
       }()}) {
    const MeshDocument doc = read_mesh_document(put("in.obj", text));
    doc.write(path("out.obj"), doc.triangles().vertices);  // normals recomputed only where something moved
    EXPECT_EQ(core::read_file(path("out.obj")), text);
    // and the default face written by OpenMesh
  }
  save_face(path("face.rig"), make_generic_face());
  const MeshDocument face = read_mesh_document(path("generic_face.obj"));
  face.write(path("again.obj"), face.triangles().vertices);
  EXPECT_EQ(core::read_file(path("again.obj")), core::read_file(path("generic_face.obj")));
}

TEST_F(MeshDocumentTest, WritesOnlyTheNumbersOfMovedVerticesAndTheirNormals) {
  put("head.mtl", "newmtl skin\nKd 1 0.8 0.7\n");
  const MeshDocument doc = read_mesh_document(put("head.obj", kFullObj));
  Vertices p = doc.triangles().vertices;
  p(1, 0) = 0.1 + 0.2;  // not representable in short decimal: needs 17 digits
  std::filesystem::create_directories(path("out"));
  doc.write(path("out/frame.obj"), p);
  const std::string out = core::read_file(path("out/frame.obj"));
  const std::string in = kFullObj;
  // line 5 (vertex 2) changed: new numbers, its colour and comment kept
  EXPECT_NE(out.find("v 0.30000000000000004 0 0 0 1 0   # a comment after the colour\n"), std::string::npos) << out;
  // vertex lines that did not move are the original text (the "1.0" and the continued line)
  EXPECT_NE(out.find("v 0.5 0.5 \\\n  -1 1 1 1\n"), std::string::npos);
  // reading it back gives the positions bit for bit
  const MeshDocument back = read_mesh_document(path("out/frame.obj"));
  EXPECT_EQ(back.triangles().vertices, p);
  EXPECT_EQ(back.triangles().faces, doc.triangles().faces);
  // normals: vn 1 (corners of the quad, all in z = 0) stays (0 0 1) but is recomputed as it moved;
  // vn 2 is used only by triangle (1, 0, 4): recomputed from the new positions
  const Eigen::Vector3d a = p.row(1).transpose(), b = p.row(0).transpose(), c = p.row(4).transpose();
  const Eigen::Vector3d n = (b - a).cross(c - a).normalized();  // (0, -2, -1)/√5 by hand
  EXPECT_LT((n - Eigen::Vector3d(0, -2, -1) / std::sqrt(5.0)).norm(), 1e-15);
  const std::size_t at = out.find("vn 0 0 1\nvn ");
  ASSERT_NE(at, std::string::npos) << out;
  double x, y, z;
  ASSERT_EQ(std::sscanf(out.c_str() + at + 9, "vn %lf %lf %lf", &x, &y, &z), 3);
  EXPECT_LT((Eigen::Vector3d(x, y, z) - n).norm(), 1e-8);
  EXPECT_NE(out.find("vn 0 0 1\n"), std::string::npos);
  // vn 3 is used by a triangle whose vertices (3, 4, 5) did not move: kept verbatim
  EXPECT_NE(out.find("vn 0.577 0.577 0.577\n"), std::string::npos);
  // everything else is unchanged: same line count, same non-v/vn lines
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), std::count(in.begin(), in.end(), '\n'));
  EXPECT_NE(out.find("g back side\nusemtl lip\ns off\n"), std::string::npos);
  // the material library is copied beside the output
  EXPECT_EQ(core::read_file(path("out/head.mtl")), "newmtl skin\nKd 1 0.8 0.7\n");
  // without recompute_normals the vn lines are the original ones
  doc.write(path("out/plain.obj"), p, false, false);
  EXPECT_NE(core::read_file(path("out/plain.obj")).find("vn 0 -1 0\n"), std::string::npos);
}

TEST_F(MeshDocumentTest, NormalsAreAreaWeightedOverTheReferencingCorners) {
  // one vn shared by a unit right triangle in z = 0 (area 0.5, normal +z) and a triangle of area 1 in
  // x = 0 (normal +x): the new normal is (2·x̂·1 + 2·ẑ·0.5)/|..| = (2, 0, 1)/√5
  const std::string text =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 0\nv 0 2 0\nv 0 0 1\nvn 0 0 1\n"
      "f 1//1 2//1 3//1\nf 4//1 5//1 6//1\n";
  const MeshDocument doc = read_mesh_document(put("n.obj", text));
  Vertices p = doc.triangles().vertices;
  p(5, 2) = 1.0 + 0.0;  // same value, different path: still bit-identical, so nothing moves ...
  doc.write(path("same.obj"), p);
  EXPECT_EQ(core::read_file(path("same.obj")), text);
  p(0, 0) = -0.0;  // -0 is not bit-identical to 0: the vertex counts as moved (and its normal)
  doc.write(path("n2.obj"), p);
  const std::string out = core::read_file(path("n2.obj"));
  const std::size_t at = out.find("vn ");
  ASSERT_NE(at, std::string::npos);
  double x, y, z;
  ASSERT_EQ(std::sscanf(out.c_str() + at, "vn %lf %lf %lf", &x, &y, &z), 3);
  EXPECT_LT((Eigen::Vector3d(x, y, z) - Eigen::Vector3d(2, 0, 1) / std::sqrt(5.0)).norm(), 1e-8) << out;
  EXPECT_NE(out.find("v -0 0 0\n"), std::string::npos);
}

// Expects read_mesh_document to fail with a FormatError naming the file and `line`.
void expect_obj_error(const std::string& file, std::size_t line, const std::string& what) {
  try {
    read_mesh_document(file);
    FAIL() << "accepted: " << what;
  } catch (const FormatError& e) {
    EXPECT_EQ(e.where().file, file) << what;
    EXPECT_EQ(e.where().line, line) << what << ": " << e.what();
  }
}

TEST_F(MeshDocumentTest, RejectsBadObj) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expect_obj_error(put("a.obj", "v 0 0\nf 1 1 1\n"), 1, "two coordinates");
  expect_obj_error(put("b.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"), 2, "NaN");
  expect_obj_error(put("c.obj", "v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n"), 2, "inf");
  expect_obj_error(put("d.obj", "v 0 0 0\nv 1 0 1e999\nv 0 1 0\nf 1 2 3\n"), 2, "overflow");
  expect_obj_error(put("e.obj", tri + "f 1 2 9\n"), 4, "vertex id out of range");
  expect_obj_error(put("f.obj", tri + "f 1 2 0\n"), 4, "index 0");
  expect_obj_error(put("g.obj", tri + "f -4 1 2\n"), 4, "relative index before the first vertex");
  expect_obj_error(put("h.obj", tri + "vt 0 0\nf 1/2 2/1 3/1\n"), 5, "vt out of range");
  expect_obj_error(put("i.obj", tri + "f 1//1 2//1 3//1\n"), 4, "vn out of range");
  expect_obj_error(put("j.obj", tri + "f 1 2\n"), 4, "two corners");
  expect_obj_error(put("k.obj", tri + "f 1/x 2 3\n"), 4, "bad index");
  expect_obj_error(put("l.obj", tri + "f 1 2 99999999999\n"), 4, "huge index");
  expect_obj_error(put("m.obj", tri), 0, "no faces");
  expect_obj_error(put("n.obj", tri + "f 1 1 2\nf 1 2 2\n"), 0, "only degenerate faces");
  expect_obj_error(put("o.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n"
                                "f 1 2 3\nf 2 1 4\nf 1 2 5\n"), 8, "edge of three triangles");
  expect_obj_error(put("p.obj", tri + "f 1 2 3\nv 0 0"), 5, "truncated last line");
  expect_obj_error(put("q.obj", "v 0 0 0 1 1\n"), 1, "five numbers");
  expect_obj_error(put("r.obj", tri + "vn 0 0\nf 1 2 3\n"), 4, "short normal");
  // the same edge in two groups (a part touching another) is fine
  EXPECT_NO_THROW(read_mesh_document(put("s.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n"
                                                  "f 1 2 3\nf 2 1 4\ng other\nf 1 2 5\n")));
  EXPECT_THROW(read_mesh_document(path("missing.obj")), IoError);
  EXPECT_THROW(read_mesh_document(put("t.stl", "solid")), FormatError);
  const MeshDocument doc = read_mesh_document(put("u.obj", tri + "f 1 2 3\n"));
  EXPECT_THROW(doc.write(path("w.obj"), Vertices::Zero(2, 3)), InvalidInput);
  Vertices bad = doc.triangles().vertices;
  bad(1, 1) = std::nan("");
  EXPECT_THROW(doc.write(path("w.obj"), bad), InvalidInput);
  EXPECT_FALSE(std::filesystem::exists(path("w.obj")));  // nothing half-written
  EXPECT_THROW(doc.write(path("w.ply"), doc.triangles().vertices), InvalidInput);
  EXPECT_THROW(doc.write_gltf_with_targets(path("w.glb"), {"a"}, {doc.triangles().vertices}), InvalidInput);
}

TEST_F(MeshDocumentTest, PlyAndOffGoThroughMeshIo) {
  write_mesh(path("t.ply"), testing::tetrahedron());
  const MeshDocument doc = read_mesh_document(path("t.ply"));
  EXPECT_EQ(doc.format(), MeshFormat::Ply);
  EXPECT_EQ(doc.triangles().faces, testing::tetrahedron().faces);
  Vertices p = doc.triangles().vertices;
  p(3, 2) = 2.0;
  doc.write(path("t2.off"), p);
  EXPECT_EQ(read_mesh(path("t2.off")).vertices, p);
  ASSERT_EQ(doc.groups().size(), 1u);
  EXPECT_EQ(doc.groups()[0].faces.size(), 4u);
}

// ---- glTF ----

int add_view(tinygltf::Model& m, const void* data, std::size_t bytes) {
  auto& b = m.buffers[0].data;
  while (b.size() % 4) b.push_back(0);
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteOffset = b.size();
  v.byteLength = bytes;
  b.resize(b.size() + bytes);
  std::memcpy(b.data() + v.byteOffset, data, bytes);
  m.bufferViews.push_back(v);
  return static_cast<int>(m.bufferViews.size()) - 1;
}

int add_accessor(tinygltf::Model& m, const void* data, std::size_t bytes, int component, int type, std::size_t count) {
  tinygltf::Accessor a;
  a.bufferView = add_view(m, data, bytes);
  a.componentType = component;
  a.type = type;
  a.count = count;
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size()) - 1;
}

// A model as a character exporter writes it: the head mesh with two primitives (indexed ushort quad
// with TEXCOORD_0/NORMAL/COLOR_0 and a morph target; a non-indexed triangle), a skin with a joint
// node, a second mesh, a material, a data-URI image.
tinygltf::Model character() {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.buffers.resize(1);
  const float quad[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const float normals[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const float uv[] = {0, 0, 1, 0, 1, 1, 0, 1};
  const float color[] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  const std::uint16_t idx[] = {0, 1, 2, 0, 2, 3};
  const float target[] = {0, 0, 0.1f, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  const float tri[] = {2, 0, 0, 3, 0, 0, 2, 1, 0};
  const float other[] = {5, 5, 5, 6, 5, 5, 5, 6, 5};
  tinygltf::Primitive p0;
  p0.mode = TINYGLTF_MODE_TRIANGLES;
  p0.attributes["POSITION"] = add_accessor(m, quad, sizeof quad, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 4);
  m.accessors.back().minValues = {0, 0, 0};
  m.accessors.back().maxValues = {1, 1, 0};
  p0.attributes["NORMAL"] = add_accessor(m, normals, sizeof normals, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 4);
  p0.attributes["TEXCOORD_0"] = add_accessor(m, uv, sizeof uv, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, 4);
  p0.attributes["COLOR_0"] = add_accessor(m, color, sizeof color, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 4);
  p0.indices = add_accessor(m, idx, sizeof idx, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, 6);
  p0.targets.push_back({{"POSITION", add_accessor(m, target, sizeof target, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 4)}});
  m.accessors.back().minValues = {0, 0, 0};
  m.accessors.back().maxValues = {0, 0, 0.1};
  p0.material = 0;
  tinygltf::Primitive p1;
  p1.mode = TINYGLTF_MODE_TRIANGLES;
  p1.attributes["POSITION"] = add_accessor(m, tri, sizeof tri, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 3);
  m.accessors.back().minValues = {2, 0, 0};
  m.accessors.back().maxValues = {3, 1, 0};
  const float tri_target[] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  p1.targets.push_back({{"POSITION", add_accessor(m, tri_target, sizeof tri_target, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 3)}});
  m.accessors.back().minValues = {0, 0, 0};
  m.accessors.back().maxValues = {0, 0, 0};
  tinygltf::Mesh head;
  head.name = "head";
  head.primitives = {p0, p1};
  head.weights = {0.0};
  tinygltf::Value::Object extras;
  extras["targetNames"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(std::string("blink"))});
  head.extras = tinygltf::Value(extras);
  tinygltf::Primitive q;
  q.mode = TINYGLTF_MODE_TRIANGLES;
  q.attributes["POSITION"] = add_accessor(m, other, sizeof other, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 3);
  m.accessors.back().minValues = {5, 5, 5};
  m.accessors.back().maxValues = {6, 6, 5};
  tinygltf::Mesh hat;
  hat.name = "hat";
  hat.primitives = {q};
  m.meshes = {head, hat};
  tinygltf::Material mat;
  mat.name = "skin";
  m.materials.push_back(mat);
  tinygltf::Image image;
  image.uri = "data:image/png;base64,iVBORw0KGgo=";  // kept as it is (never decoded)
  m.images.push_back(image);
  tinygltf::Node joint;
  joint.name = "jaw_joint";
  joint.translation = {0, -0.5, 0};
  tinygltf::Node head_node;
  head_node.name = "head";
  head_node.mesh = 0;
  head_node.skin = 0;
  head_node.children = {0};
  tinygltf::Node hat_node;
  hat_node.name = "hat";
  hat_node.mesh = 1;
  m.nodes = {joint, head_node, hat_node};
  const float ibm[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0.5f, 0, 1};
  tinygltf::Skin skin;
  skin.name = "rig";
  skin.joints = {0};
  skin.inverseBindMatrices = add_accessor(m, ibm, sizeof ibm, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_MAT4, 1);
  m.skins.push_back(skin);
  tinygltf::Scene scene;
  scene.nodes = {1, 2};
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  return m;
}

void save(const tinygltf::Model& m, const std::string& file, bool binary) {
  tinygltf::TinyGLTF w;
  ASSERT_TRUE(w.WriteGltfSceneToFile(&m, file, false, true, true, binary));
}

tinygltf::Model load(const std::string& file) {
  tinygltf::Model m;
  tinygltf::TinyGLTF l;
  l.SetImageLoader([](tinygltf::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes, int size,
                      void*) {
    image->image.assign(bytes, bytes + size);  // raw, undecoded
    return true;
  },
                   nullptr);
  std::string err, warn;
  const bool ok = file.substr(file.size() - 4) == ".glb" ? l.LoadBinaryFromFile(&m, &err, &warn, file) : l.LoadASCIIFromFile(&m, &err, &warn, file);
  EXPECT_TRUE(ok) << err;
  return m;
}

std::vector<float> floats(const tinygltf::Model& m, int accessor) {
  const auto& a = m.accessors[static_cast<std::size_t>(accessor)];
  const auto& v = m.bufferViews[static_cast<std::size_t>(a.bufferView)];
  const int n = a.type == TINYGLTF_TYPE_VEC2 ? 2 : a.type == TINYGLTF_TYPE_MAT4 ? 16 : 3;
  std::vector<float> out(a.count * static_cast<std::size_t>(n));
  std::memcpy(out.data(), m.buffers[static_cast<std::size_t>(v.buffer)].data.data() + v.byteOffset + a.byteOffset, out.size() * 4);
  return out;
}

TEST_F(MeshDocumentTest, ReadsAndRewritesACharacterGltf) {
  for (const bool binary : {false, true}) {
    const std::string in = path(binary ? "c.glb" : "c.gltf");
    save(character(), in, binary);
    const MeshDocument doc = read_mesh_document(in);
    EXPECT_EQ(doc.format(), binary ? MeshFormat::Glb : MeshFormat::Gltf);
    const Mesh& t = doc.triangles();
    ASSERT_EQ(t.vertex_count(), 7u);  // the first mesh only: 4 + 3
    ASSERT_EQ(t.face_count(), 3u);
    EXPECT_EQ(Eigen::Vector3i(t.faces.row(2).transpose()), Eigen::Vector3i(4, 5, 6));
    EXPECT_EQ(Eigen::Vector3d(t.vertices.row(5).transpose()), Eigen::Vector3d(3, 0, 0));
    EXPECT_TRUE(doc.has_uvs());
    EXPECT_TRUE(doc.vertex_colors().empty());  // the second primitive has no COLOR_0
    ASSERT_EQ(doc.groups().size(), 2u);
    EXPECT_EQ(doc.groups()[0].object, "head");
    EXPECT_EQ(doc.groups()[0].material, "skin");
    EXPECT_EQ(doc.groups()[1].faces, (std::vector<int>{2}));

    Vertices p = t.vertices;
    p(2, 2) = 0.5;  // lift a corner of the quad
    p(6, 0) = 2.25;
    const std::string out = path(binary ? "o.glb" : "o.gltf");
    doc.write(out, p);
    const tinygltf::Model m = load(out);
    const tinygltf::Model orig = character();
    ASSERT_EQ(m.meshes.size(), 2u);
    const auto& prim = m.meshes[0].primitives[0];
    const auto pos = floats(m, prim.attributes.at("POSITION"));
    EXPECT_EQ(pos[8], 0.5f);
    EXPECT_EQ(m.accessors[static_cast<std::size_t>(prim.attributes.at("POSITION"))].maxValues, (std::vector<double>{1, 1, 0.5}));
    EXPECT_EQ(floats(m, m.meshes[0].primitives[1].attributes.at("POSITION"))[6], 2.25f);
    EXPECT_EQ(m.accessors[static_cast<std::size_t>(m.meshes[0].primitives[1].attributes.at("POSITION"))].minValues, (std::vector<double>{2, 0, 0}));
    // normals recomputed: vertex 0 is in triangles (0,1,2) and (0,2,3); vertex 1 only in (0,1,2),
    // whose normal is (0,-0.5,1)/|.| after the lift
    const auto nrm = floats(m, prim.attributes.at("NORMAL"));
    const Eigen::Vector3d n1 = Eigen::Vector3d(0, -0.5, 1).normalized();
    EXPECT_NEAR(nrm[3], n1.x(), 1e-7);
    EXPECT_NEAR(nrm[4], n1.y(), 1e-7);
    EXPECT_NEAR(nrm[5], n1.z(), 1e-7);
    // everything else kept
    EXPECT_EQ(floats(m, prim.attributes.at("TEXCOORD_0")), floats(orig, orig.meshes[0].primitives[0].attributes.at("TEXCOORD_0")));
    EXPECT_EQ(floats(m, prim.attributes.at("COLOR_0")), floats(orig, orig.meshes[0].primitives[0].attributes.at("COLOR_0")));
    EXPECT_EQ(floats(m, prim.targets[0].at("POSITION")), floats(orig, orig.meshes[0].primitives[0].targets[0].at("POSITION")));
    EXPECT_EQ(floats(m, m.meshes[1].primitives[0].attributes.at("POSITION")), floats(orig, orig.meshes[1].primitives[0].attributes.at("POSITION")));
    ASSERT_EQ(m.skins.size(), 1u);
    EXPECT_EQ(m.skins[0].joints, (std::vector<int>{0}));
    EXPECT_EQ(floats(m, m.skins[0].inverseBindMatrices), floats(orig, orig.skins[0].inverseBindMatrices));
    EXPECT_EQ(m.nodes.size(), 3u);
    EXPECT_EQ(m.nodes[0].translation, (std::vector<double>{0, -0.5, 0}));
    EXPECT_EQ(m.materials[0].name, "skin");
    ASSERT_EQ(m.images.size(), 1u);
    EXPECT_EQ(m.images[0].mimeType, "image/png");
    EXPECT_EQ(m.images[0].image, (std::vector<unsigned char>{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'}));  // base64 iVBORw0KGgo=
    EXPECT_EQ(m.meshes[0].extras.Get("targetNames").Get(0).Get<std::string>(), "blink");
    // identical positions: the same numbers back
    doc.write(path("same.glb"), t.vertices, false);
    const MeshDocument again = read_mesh_document(path("same.glb"));
    EXPECT_EQ(again.triangles().vertices, t.vertices);
    EXPECT_EQ(again.triangles().faces, t.faces);
  }
}

TEST_F(MeshDocumentTest, AddsNamedMorphTargets) {
  save(character(), path("c.glb"), true);
  const MeshDocument doc = read_mesh_document(path("c.glb"));
  Vertices smile = Vertices::Zero(7, 3), frown = Vertices::Zero(7, 3);
  smile(1, 1) = 0.25;
  frown(5, 2) = -0.5;
  doc.write_gltf_with_targets(path("t.glb"), {"smile", "frown"}, {smile, frown});
  const tinygltf::Model m = load(path("t.glb"));
  const auto& head = m.meshes[0];
  ASSERT_EQ(head.primitives[0].targets.size(), 3u);  // the existing one + 2
  ASSERT_EQ(head.primitives[1].targets.size(), 3u);
  EXPECT_EQ(floats(m, head.primitives[0].targets[1].at("POSITION"))[4], 0.25f);
  EXPECT_EQ(floats(m, head.primitives[1].targets[2].at("POSITION"))[5], -0.5f);
  EXPECT_EQ(floats(m, head.primitives[0].targets[0].at("POSITION"))[2], 0.1f);  // "blink" untouched
  const auto names = head.extras.Get("targetNames");
  ASSERT_EQ(names.ArrayLen(), 3u);
  EXPECT_EQ(names.Get(0).Get<std::string>(), "blink");
  EXPECT_EQ(names.Get(1).Get<std::string>(), "smile");
  EXPECT_EQ(names.Get(2).Get<std::string>(), "frown");
  EXPECT_EQ(head.weights.size(), 3u);
  EXPECT_EQ(m.skins.size(), 1u);
  EXPECT_THROW(doc.write_gltf_with_targets(path("x.glb"), {"a", "b"}, {smile}), InvalidInput);
  EXPECT_THROW(doc.write_gltf_with_targets(path("x.glb"), {"a"}, {Vertices::Zero(3, 3)}), InvalidInput);
}

// A VEC3 float accessor read back whole: dense, or sparse over implicit zeros (no bufferView).
std::vector<float> vec3_values(const tinygltf::Model& m, int accessor) {
  const auto& a = m.accessors[static_cast<std::size_t>(accessor)];
  if (!a.sparse.isSparse) return floats(m, accessor);
  std::vector<float> out(a.count * 3, 0.0f);
  const auto& iv = m.bufferViews[static_cast<std::size_t>(a.sparse.indices.bufferView)];
  const auto& vv = m.bufferViews[static_cast<std::size_t>(a.sparse.values.bufferView)];
  const unsigned char* ib =
      m.buffers[static_cast<std::size_t>(iv.buffer)].data.data() + iv.byteOffset;
  const unsigned char* vb =
      m.buffers[static_cast<std::size_t>(vv.buffer)].data.data() + vv.byteOffset;
  for (int k = 0; k < a.sparse.count; ++k) {
    std::uint32_t i = 0;
    if (a.sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
      std::uint16_t s = 0;
      std::memcpy(&s, ib + 2 * k, 2);
      i = s;
    } else {
      std::memcpy(&i, ib + 4 * k, 4);
    }
    std::memcpy(out.data() + 3 * i, vb + 12 * k, 12);
  }
  return out;
}

// Our targets and a weights animation on a user's character: everything of theirs kept, a clashing
// name renamed, NORMAL deltas only where their targets have them, sparse where smaller, the channel
// on the node holding their (skinned) mesh with their target at its default weight.
TEST_F(MeshDocumentTest, AddsTargetsAndAnimationToAUsersCharacter) {
  tinygltf::Model c = character();
  c.meshes[0].weights = {0.5};
  save(c, path("c.gltf"), false);
  const MeshDocument doc = read_mesh_document(path("c.gltf"));
  MorphTarget lift{"lift", Vertices::Zero(7, 3), Vertices::Zero(7, 3)};
  lift.position_deltas(1, 1) = 0.25;
  lift.normal_deltas(1, 2) = -0.5;
  MorphTarget blink{"blink", Vertices::Zero(7, 3), {}};  // clashes with theirs
  blink.position_deltas(5, 2) = -0.5;
  WeightAnimation a;
  a.name = "ours";
  a.times = {0.0, 2.0};
  a.weights = {{0.0, 1.0}, {1.0, 0.25}};
  a.head_rotations = {Eigen::Quaterniond::Identity(),
                      Eigen::Quaterniond::Identity()};  // not written
  const auto report = doc.write_gltf_with_targets(path("t.glb"), {lift, blink}, {a});
  EXPECT_EQ(report.names, (std::vector<std::string>{"lift", "blink_emoface"}));
  EXPECT_EQ(report.existing_targets, 1u);
  EXPECT_EQ(report.animated_nodes, 1u);
  const tinygltf::Model m = load(path("t.glb"));
  const tinygltf::Model orig = character();
  const auto& head = m.meshes[0];
  ASSERT_EQ(head.primitives[0].targets.size(), 3u);
  ASSERT_EQ(head.primitives[1].targets.size(), 3u);
  // their target: untouched; theirs has no NORMAL delta, so ours have none either
  EXPECT_EQ(floats(m, head.primitives[0].targets[0].at("POSITION")),
            floats(orig, orig.meshes[0].primitives[0].targets[0].at("POSITION")));
  EXPECT_EQ(head.primitives[0].targets[1].count("NORMAL"), 0u);
  const auto d = vec3_values(m, head.primitives[0].targets[1].at("POSITION"));
  EXPECT_EQ(d, (std::vector<float>{0, 0, 0, 0, 0.25f, 0, 0, 0, 0, 0, 0, 0}));
  // vertex 5 of triangles() is vertex 1 of the second primitive
  EXPECT_EQ(vec3_values(m, head.primitives[1].targets[2].at("POSITION")),
            (std::vector<float>{0, 0, 0, 0, 0, -0.5f, 0, 0, 0}));
  EXPECT_EQ(head.extras.Get("targetNames").Get(2).Get<std::string>(), "blink_emoface");
  EXPECT_EQ(head.weights, (std::vector<double>{0.5, 0.0, 0.0}));
  // theirs: skin, UVs, colours, material, image, nodes, the other mesh
  ASSERT_EQ(m.skins.size(), 1u);
  EXPECT_EQ(floats(m, m.skins[0].inverseBindMatrices),
            floats(orig, orig.skins[0].inverseBindMatrices));
  EXPECT_EQ(floats(m, head.primitives[0].attributes.at("TEXCOORD_0")),
            floats(orig, orig.meshes[0].primitives[0].attributes.at("TEXCOORD_0")));
  EXPECT_EQ(m.materials[0].name, "skin");
  EXPECT_EQ(m.images.size(), 1u);
  ASSERT_EQ(m.nodes.size(), 3u);
  EXPECT_EQ(m.nodes[1].skin, 0);
  EXPECT_EQ(m.meshes[1].name, "hat");
  // the animation: one weights channel on node 1 (the skinned head), 3 weights per key, theirs at
  // 0.5
  ASSERT_EQ(m.animations.size(), 1u);
  const auto& an = m.animations[0];
  EXPECT_EQ(an.name, "ours");
  ASSERT_EQ(an.channels.size(), 1u);
  EXPECT_EQ(an.channels[0].target_node, 1);
  EXPECT_EQ(an.channels[0].target_path, "weights");
  const auto& out = m.accessors[static_cast<std::size_t>(an.samplers[0].output)];
  ASSERT_EQ(out.count, 6u);
  const auto& ov = m.bufferViews[static_cast<std::size_t>(out.bufferView)];
  float w[6];
  std::memcpy(w, m.buffers[0].data.data() + ov.byteOffset + out.byteOffset, sizeof w);
  EXPECT_EQ(std::vector<float>(w, w + 6),
            (std::vector<float>{0.5f, 0.0f, 1.0f, 0.5f, 1.0f, 0.25f}));

  // bad inputs: nothing written
  WeightAnimation bad = a;
  bad.weights[1] = {1.0};
  EXPECT_THROW(doc.write_gltf_with_targets(path("x.glb"), {lift, blink}, {bad}), InvalidInput);
  bad = a;
  bad.times = {0.0, 0.0};
  EXPECT_THROW(doc.write_gltf_with_targets(path("x.glb"), {lift, blink}, {bad}), InvalidInput);
  bad = a;
  bad.weights[0][0] = std::nan("");
  EXPECT_THROW(doc.write_gltf_with_targets(path("x.glb"), {lift, blink}, {bad}), InvalidInput);
  MorphTarget nan_target = lift;
  nan_target.position_deltas(0, 0) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(doc.write_gltf_with_targets(path("x.glb"), {nan_target}, {}), InvalidInput);
  MorphTarget short_normals = lift;
  short_normals.normal_deltas = Vertices::Zero(3, 3);
  EXPECT_THROW(doc.write_gltf_with_targets(path("x.glb"), {short_normals}, {}), InvalidInput);
  DocumentTargetsOptions o;
  o.sparse_epsilon = -1.0;
  EXPECT_THROW(doc.write_gltf_with_targets(path("x.glb"), {lift}, {}, o), InvalidInput);
  EXPECT_FALSE(std::filesystem::exists(path("x.glb")));
  // a mesh on no node cannot be animated
  tinygltf::Model orphan = character();
  orphan.nodes[1].mesh = 1;
  save(orphan, path("orphan.gltf"), false);
  const MeshDocument od = read_mesh_document(path("orphan.gltf"));
  EXPECT_THROW(od.write_gltf_with_targets(path("x.glb"), {lift, blink}, {a}), InvalidInput);
  EXPECT_NO_THROW(od.write_gltf_with_targets(path("y.glb"), {lift, blink}, {}));
}

TEST_F(MeshDocumentTest, RoundTripsOurOwnAnimatedGltf) {
  const Face face = make_generic_face();
  Vertices moved = face.mesh.vertices;
  moved.col(2).array() += 0.01;
  write_animated_gltf(path("anim.glb"), face.mesh, {face.mesh.vertices, moved}, {0.0, 1.0});
  const MeshDocument doc = read_mesh_document(path("anim.glb"));
  ASSERT_EQ(doc.triangles().vertex_count(), face.mesh.vertex_count());
  EXPECT_EQ(doc.triangles().faces, face.mesh.faces);
  EXPECT_LT((doc.triangles().vertices - face.mesh.vertices).cwiseAbs().maxCoeff(), 1e-6);  // float
  doc.write(path("out.glb"), moved);
  const tinygltf::Model m = load(path("out.glb"));
  EXPECT_EQ(m.meshes[0].primitives[0].targets.size(), 2u);
  EXPECT_EQ(m.animations.size(), 1u);
  const MeshDocument back = read_mesh_document(path("out.glb"));
  EXPECT_LT((back.triangles().vertices - moved).cwiseAbs().maxCoeff(), 1e-6);
}

void expect_gltf_error(const std::string& file, const std::string& pointer) {
  try {
    read_mesh_document(file);
    FAIL() << "accepted: " << pointer;
  } catch (const FormatError& e) {
    EXPECT_EQ(e.where().file, file);
    EXPECT_EQ(e.where().json_pointer.rfind(pointer, 0), 0u) << e.what() << " expected " << pointer;
  }
}

TEST_F(MeshDocumentTest, RejectsBadGltf) {
  {
    tinygltf::Model m = character();
    const std::uint16_t bad[] = {0, 1, 9, 0, 2, 3};
    auto& a = m.accessors[static_cast<std::size_t>(m.meshes[0].primitives[0].indices)];
    std::memcpy(m.buffers[0].data.data() + m.bufferViews[static_cast<std::size_t>(a.bufferView)].byteOffset, bad, sizeof bad);
    save(m, path("a.gltf"), false);
    expect_gltf_error(path("a.gltf"), "/accessors/" + std::to_string(m.meshes[0].primitives[0].indices));
  }
  {
    tinygltf::Model m = character();  // a count far beyond its buffer: refused before allocating
    const int pos = m.meshes[0].primitives[0].attributes["POSITION"];
    m.accessors[static_cast<std::size_t>(pos)].count = 4'000'000'000u;
    save(m, path("b.gltf"), false);
    expect_gltf_error(path("b.gltf"), "/accessors/" + std::to_string(pos) + "/count");
  }
  {
    tinygltf::Model m = character();
    const float nan = std::nanf("");
    const int pos = m.meshes[0].primitives[1].attributes["POSITION"];
    std::memcpy(m.buffers[0].data.data() + m.bufferViews[static_cast<std::size_t>(m.accessors[static_cast<std::size_t>(pos)].bufferView)].byteOffset + 4, &nan, 4);
    save(m, path("c.glb"), true);
    expect_gltf_error(path("c.glb"), "/accessors/" + std::to_string(pos));
  }
  {
    tinygltf::Model m = character();
    m.meshes.clear();
    for (auto& n : m.nodes) n.mesh = -1, n.skin = -1;
    save(m, path("d.gltf"), false);
    expect_gltf_error(path("d.gltf"), "/meshes");
  }
  {
    tinygltf::Model m = character();
    m.meshes[0].primitives[0].attributes.erase("POSITION");
    save(m, path("e.gltf"), false);
    expect_gltf_error(path("e.gltf"), "");
  }
  core::write_file_atomic(path("f.gltf"), "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [");
  expect_gltf_error(path("f.gltf"), "");
  core::write_file_atomic(path("g.glb"), "glTF\x02\x00\x00\x00");
  expect_gltf_error(path("g.glb"), "");
}

// ---- glTF sparse accessors (glTF 2.0 §3.6.2.3) ----

// Makes accessor `id` sparse: `rows` (indices) replaced by `values` (packed, the accessor's element
// type, float), indices of `index_type`; without `keep_base` the buffer view goes (zeros below).
void make_sparse(tinygltf::Model& m, int id, const std::vector<std::uint32_t>& rows,
                 const std::vector<float>& values, bool keep_base,
                 int index_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
  auto& a = m.accessors[static_cast<std::size_t>(id)];
  std::vector<unsigned char> idx;
  for (std::uint32_t r : rows) {
    if (index_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE)
      idx.push_back(static_cast<unsigned char>(r));
    const int size = index_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE  ? 1
                     : index_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT ? 4
                                                                          : 2;
    if (size == 2) {
      const auto s = static_cast<std::uint16_t>(r);
      idx.insert(idx.end(), reinterpret_cast<const unsigned char*>(&s),
                 reinterpret_cast<const unsigned char*>(&s) + 2);
    } else if (size == 4) {
      idx.insert(idx.end(), reinterpret_cast<const unsigned char*>(&r),
                 reinterpret_cast<const unsigned char*>(&r) + 4);
    }
  }
  const int iv = add_view(m, idx.data(), idx.size());
  const int vv = add_view(m, values.data(), values.size() * 4);
  if (!keep_base) a.bufferView = -1;
  a.sparse.isSparse = true;
  a.sparse.count = static_cast<int>(rows.size());
  a.sparse.indices.bufferView = iv;
  a.sparse.indices.byteOffset = 0;
  a.sparse.indices.componentType = index_type;
  a.sparse.values.bufferView = vv;
  a.sparse.values.byteOffset = 0;
}

// The character with its blink target sparse (zeros + one row, as engines export targets), the
// second primitive's target sparse too, and the quad's POSITION sparse over its base view (vertex 2
// raised to z = 0.25).
tinygltf::Model sparse_character() {
  tinygltf::Model m = character();
  auto& p0 = m.meshes[0].primitives[0];
  make_sparse(m, p0.targets[0].at("POSITION"), {0}, {0, 0, 0.1f}, false);
  make_sparse(m, m.meshes[0].primitives[1].targets[0].at("POSITION"), {2}, {0.5f, 0, 0}, false,
              TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE);
  m.accessors[static_cast<std::size_t>(m.meshes[0].primitives[1].targets[0].at("POSITION"))]
      .maxValues = {0.5, 0, 0};
  make_sparse(m, p0.attributes.at("POSITION"), {2}, {1, 1, 0.25f}, true,
              TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  m.accessors[static_cast<std::size_t>(p0.attributes.at("POSITION"))].maxValues = {1, 1, 0.25};
  return m;
}

TEST_F(MeshDocumentTest, ReadsSparseAccessors) {
  for (const bool binary : {false, true}) {
    const std::string in = path(binary ? "s.glb" : "s.gltf");
    save(sparse_character(), in, binary);
    const MeshDocument doc = read_mesh_document(in);
    const Mesh& t = doc.triangles();
    ASSERT_EQ(t.vertex_count(), 7u);
    EXPECT_EQ(Eigen::Vector3d(t.vertices.row(2).transpose()),
              Eigen::Vector3d(1, 1, 0.25));  // replaced
    EXPECT_EQ(Eigen::Vector3d(t.vertices.row(3).transpose()), Eigen::Vector3d(0, 1, 0));  // base
    ASSERT_EQ(doc.morph_targets().size(), 1u);
    const MorphTarget& blink = doc.morph_targets()[0];
    EXPECT_EQ(blink.name, "blink");
    ASSERT_EQ(blink.position_deltas.rows(), 7);
    EXPECT_EQ(blink.normal_deltas.rows(), 0);
    Vertices expected = Vertices::Zero(7, 3);
    expected(0, 2) = 0.1f;  // float in the file
    expected(6, 0) = 0.5;   // the second primitive's row 2 = vertex 4 + 2
    EXPECT_EQ(blink.position_deltas, expected);

    // written unchanged: the sparse accessors stay sparse, the same numbers come back
    doc.write(path("same.glb"), t.vertices, false);
    const tinygltf::Model same = load(path("same.glb"));
    EXPECT_TRUE(same.accessors[static_cast<std::size_t>(
                                   same.meshes[0].primitives[0].attributes.at("POSITION"))]
                    .sparse.isSparse);
    EXPECT_TRUE(same.accessors[static_cast<std::size_t>(
                                   same.meshes[0].primitives[0].targets[0].at("POSITION"))]
                    .sparse.isSparse);
    const MeshDocument again = read_mesh_document(path("same.glb"));
    EXPECT_EQ(again.triangles().vertices, t.vertices);
    EXPECT_EQ(again.morph_targets()[0].position_deltas, expected);

    // moved: the sparse POSITION becomes dense with every row; the targets stay sparse
    Vertices moved = t.vertices;
    moved(1, 1) = -0.5;
    doc.write(path("moved.gltf"), moved, false);
    const tinygltf::Model m = load(path("moved.gltf"));
    const auto& pa =
        m.accessors[static_cast<std::size_t>(m.meshes[0].primitives[0].attributes.at("POSITION"))];
    EXPECT_FALSE(pa.sparse.isSparse);
    EXPECT_EQ(floats(m, m.meshes[0].primitives[0].attributes.at("POSITION")),
              (std::vector<float>{0, 0, 0, 1, -0.5f, 0, 1, 1, 0.25f, 0, 1, 0}));
    EXPECT_EQ(pa.minValues, (std::vector<double>{0, -0.5, 0}));
    EXPECT_TRUE(
        m.accessors[static_cast<std::size_t>(m.meshes[0].primitives[0].targets[0].at("POSITION"))]
            .sparse.isSparse);
    const MeshDocument back = read_mesh_document(path("moved.gltf"));
    EXPECT_EQ(back.triangles().vertices, moved);
    EXPECT_EQ(back.morph_targets()[0].position_deltas, expected);
  }
}

TEST_F(MeshDocumentTest, SparseTargetsSurviveAddingOurs) {
  save(sparse_character(), path("s.glb"), true);
  const MeshDocument doc = read_mesh_document(path("s.glb"));
  Vertices smile = Vertices::Zero(7, 3);
  smile(3, 1) = 0.125;
  doc.write_gltf_with_targets(path("out.glb"), {MorphTarget{"smile", smile, {}}});
  const MeshDocument back = read_mesh_document(path("out.glb"));
  ASSERT_EQ(back.morph_targets().size(), 2u);
  EXPECT_EQ(back.morph_targets()[0].name, "blink");
  EXPECT_EQ(back.morph_targets()[0].position_deltas, doc.morph_targets()[0].position_deltas);
  EXPECT_EQ(back.morph_targets()[1].name, "smile");
  EXPECT_EQ(back.morph_targets()[1].position_deltas, smile);
  EXPECT_EQ(back.triangles().vertices, doc.triangles().vertices);
}

TEST_F(MeshDocumentTest, RejectsBadSparseAccessors) {
  const auto target_of = [](const tinygltf::Model& m) {
    return m.meshes[0].primitives[0].targets[0].at("POSITION");
  };
  struct Case {
    const char* name;
    std::function<void(tinygltf::Model&)> damage;
    std::string pointer_tail;  // after /accessors/<target>
  };
  const std::vector<Case> cases = {
      {"index out of range",
       [&](tinygltf::Model& m) {
         make_sparse(m, target_of(m), {1, 4}, {0, 0, 1, 0, 0, 1}, false);
       },
       "/sparse/indices"},
      {"indices not increasing",
       [&](tinygltf::Model& m) {
         make_sparse(m, target_of(m), {2, 1}, {0, 0, 1, 0, 0, 1}, false);
       },
       "/sparse/indices"},
      {"repeated index",
       [&](tinygltf::Model& m) {
         make_sparse(m, target_of(m), {1, 1}, {0, 0, 1, 0, 0, 1}, false);
       },
       "/sparse/indices"},
      {"count above the accessor's",
       [&](tinygltf::Model& m) {
         make_sparse(m, target_of(m), {0, 1, 2, 3, 4}, std::vector<float>(15, 0.0f), false);
       },
       "/sparse/count"},
      {"count 0",
       [&](tinygltf::Model& m) {
         make_sparse(m, target_of(m), {1}, {0, 0, 1}, false);
         m.accessors[static_cast<std::size_t>(target_of(m))].sparse.count = 0;
       },
       "/sparse/count"},
      {"float indices",
       [&](tinygltf::Model& m) {
         make_sparse(m, target_of(m), {1}, {0, 0, 1}, false, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
         m.accessors[static_cast<std::size_t>(target_of(m))].sparse.indices.componentType =
             TINYGLTF_COMPONENT_TYPE_FLOAT;
       },
       "/sparse/indices/componentType"},
      {"signed short indices",
       [&](tinygltf::Model& m) {
         make_sparse(m, target_of(m), {1}, {0, 0, 1}, false);
         m.accessors[static_cast<std::size_t>(target_of(m))].sparse.indices.componentType =
             TINYGLTF_COMPONENT_TYPE_SHORT;
       },
       "/sparse/indices/componentType"},
      {"truncated indices",
       [&](tinygltf::Model& m) {
         make_sparse(m, target_of(m), {1}, {0, 0, 1}, false);
         m.accessors[static_cast<std::size_t>(target_of(m))].sparse.count = 2;
       },
       "/sparse/indices"},
      {"truncated values",
       [&](tinygltf::Model& m) {
         make_sparse(m, target_of(m), {1, 2}, {0, 0, 1}, false);
       },
       "/sparse/values"},
      {"values offset beyond the view",
       [&](tinygltf::Model& m) {
         make_sparse(m, target_of(m), {1}, {0, 0, 1}, false);
         m.accessors[static_cast<std::size_t>(target_of(m))].sparse.values.byteOffset = 1 << 30;
       },
       "/sparse/values"},
      {"negative indices offset",
       [&](tinygltf::Model& m) {
         make_sparse(m, target_of(m), {1}, {0, 0, 1}, false);
         m.accessors[static_cast<std::size_t>(target_of(m))].sparse.indices.byteOffset = -4;
       },
       "/sparse/indices"},
      {"no such values view",
       [&](tinygltf::Model& m) {
         make_sparse(m, target_of(m), {1}, {0, 0, 1}, false);
         m.accessors[static_cast<std::size_t>(target_of(m))].sparse.values.bufferView = 999;
       },
       "/sparse/values/bufferView"},
      {"strided indices view",
       [&](tinygltf::Model& m) {
         make_sparse(m, target_of(m), {1}, {0, 0, 1}, false);
         m
             .bufferViews[static_cast<std::size_t>(
                 m.accessors[static_cast<std::size_t>(target_of(m))].sparse.indices.bufferView)]
             .byteStride = 4;
       },
       "/sparse/indices/bufferView"},
      {"NaN value",
       [&](tinygltf::Model& m) {
         make_sparse(m, target_of(m), {1}, {0, std::nanf(""), 1}, false);
       },
       ""},
      {"infinite value",
       [&](tinygltf::Model& m) {
         make_sparse(m, target_of(m), {3}, {0, 0, std::numeric_limits<float>::infinity()}, false);
       },
       ""},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    tinygltf::Model m = character();
    c.damage(m);
    save(m, path("bad.gltf"), false);
    expect_gltf_error(path("bad.gltf"),
                      "/accessors/" + std::to_string(target_of(m)) + c.pointer_tail);
  }
  {  // a sparse POSITION with NaN: the POSITION accessor is named
    tinygltf::Model m = character();
    const int pos = m.meshes[0].primitives[1].attributes.at("POSITION");
    make_sparse(m, pos, {0}, {std::nanf(""), 0, 0}, true);
    save(m, path("nan.glb"), true);
    expect_gltf_error(path("nan.glb"), "/accessors/" + std::to_string(pos));
  }
  {  // primitives with different target counts
    tinygltf::Model m = character();
    m.meshes[0].primitives[1].targets.clear();
    save(m, path("t.gltf"), false);
    expect_gltf_error(path("t.gltf"), "/meshes/0/primitives/1/targets");
  }
  {  // a target with the wrong number of elements
    tinygltf::Model m = character();
    m.accessors[static_cast<std::size_t>(target_of(m))].count = 3;
    save(m, path("c.gltf"), false);
    expect_gltf_error(path("c.gltf"), "/accessors/" + std::to_string(target_of(m)) + "/count");
  }
}

TEST_F(MeshDocumentTest, LoadFaceReadsObjThroughTheDocument) {
  save_face(path("face.rig"), make_generic_face());
  const Face face = load_face(path("face.rig"));
  ASSERT_TRUE(face.document != nullptr);
  EXPECT_EQ(face.document->format(), MeshFormat::Obj);
  EXPECT_EQ(face.mesh.faces, make_generic_face().mesh.faces);
  // same order as OpenMesh's reader, which parses single precision; ours keeps every digit
  EXPECT_TRUE(face.mesh.vertices.isApprox(read_mesh(path("generic_face.obj")).vertices, 1e-7));
  const std::string text = core::read_file(path("generic_face.obj"));
  const std::size_t v0 = text.find("\nv ") + 3;
  EXPECT_EQ(face.mesh.vertices(0, 0), std::strtod(text.c_str() + v0, nullptr));
}

TEST_F(MeshDocumentTest, SaveFaceWritesTheDocumentBackInTheMeshFrame) {
  Face face = make_generic_face();
  save_face(path("face.rig"), face);
  // the user's file: decimetres, a comment and a group the loader must keep
  const MeshDocument plain = read_mesh_document(path("generic_face.obj"));
  Vertices dm = plain.triangles().vertices * 10.0;
  plain.write(path("dm.obj"), dm);
  core::write_file_atomic(path("user.obj"), "# made by the user\ng head\n" + core::read_file(path("dm.obj")));
  face.rig.mesh_file = "user.obj";
  face.rig.frame.scale = 0.1;
  write_rig(path("user.rig"), face.rig);
  const Face loaded = load_face(path("user.rig"));
  EXPECT_LT((loaded.mesh.vertices - plain.triangles().vertices).cwiseAbs().maxCoeff(), 1e-15);  // rig frame: metres
  std::filesystem::create_directories(path("out"));
  Face moved = loaded;
  moved.mesh.vertices(0, 1) += 0.001;  // 1 mm in the rig frame
  save_face(path("out/user.rig"), moved);
  const std::string text = core::read_file(path("out/user.obj"));
  EXPECT_EQ(text.rfind("# made by the user\ng head\n", 0), 0u);
  const MeshDocument back = read_mesh_document(path("out/user.obj"));
  EXPECT_NEAR(back.triangles().vertices(0, 1), dm(0, 1) + 0.01, 1e-12);  // 1 mm = 0.01 dm
  EXPECT_EQ(back.triangles().vertices.bottomRows(100), dm.bottomRows(100));  // unmoved: bit for bit
}

}  // namespace
}  // namespace emoface::facemesh
