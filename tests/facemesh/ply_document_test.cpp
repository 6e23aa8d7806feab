// PLY through MeshDocument: every element and property kept, vertex colours read, only the numbers
// of moved vertices rewritten (ASCII, binary little and big endian); bad input refused with the
// file and line (or byte offset) named.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/io.hpp"
#include "emoface/facemesh/mesh_document.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "test_util.hpp"

namespace emoface::facemesh {
namespace {

class PlyDocumentTest : public testing::TempDirTest {};

// A scanner's PLY: a quad and a triangle, float positions, float normals, uchar colours with alpha,
// a property we do not know (quality), a texture-coordinate list on the faces, an edge element.
const char* kHeader =
    "ply\n"
    "format ascii 1.0\n"
    "comment made by a scanner\n"
    "element vertex 5\n"
    "property float x\n"
    "property float y\n"
    "property float z\n"
    "property float nx\n"
    "property float ny\n"
    "property float nz\n"
    "property uchar red\n"
    "property uchar green\n"
    "property uchar blue\n"
    "property uchar alpha\n"
    "property float quality\n"
    "element face 2\n"
    "property list uchar int vertex_indices\n"
    "property list uchar float texcoord\n"
    "element edge 1\n"
    "property int vertex1\n"
    "property int vertex2\n"
    "end_header\n";

const char* kBody =
    "0 0 0 0 0 1 255 0 0 255 0.5\n"
    "1 0 0 0 0 1 0 255 0 255 0.25\n"
    "1 1 0 0 0 1 0 0 255 128 1\n"
    "0 1 0 0 0 1 51 102 153 255 0\n"
    "2 0.5 0.125 0 0 1 255 255 255 255 7\n"
    "4 0 1 2 3 8 0 0 1 0 1 1 0 1\n"
    "3 1 4 2 6 0 0 1 0 1 1\n"
    "0 4\n";

struct Vertex {
  float x, y, z, nx, ny, nz;
  std::uint8_t r, g, b, a;
  float quality;
};
const Vertex kVertices[5] = {{0, 0, 0, 0, 0, 1, 255, 0, 0, 255, 0.5f},
                             {1, 0, 0, 0, 0, 1, 0, 255, 0, 255, 0.25f},
                             {1, 1, 0, 0, 0, 1, 0, 0, 255, 128, 1},
                             {0, 1, 0, 0, 0, 1, 51, 102, 153, 255, 0},
                             {2, 0.5f, 0.125f, 0, 0, 1, 255, 255, 255, 255, 7}};

template <class T>
void put_binary(std::string& out, T value, bool big) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if (big) std::reverse(b, b + sizeof(T));
  out.append(reinterpret_cast<const char*>(b), sizeof(T));
}

// The same file in a binary encoding.
std::string binary_ply(bool big) {
  std::string header = kHeader;
  header.replace(header.find("ascii"), 5, big ? "binary_big_endian" : "binary_little_endian");
  std::string out = header;
  for (const Vertex& v : kVertices) {
    for (float f : {v.x, v.y, v.z, v.nx, v.ny, v.nz}) put_binary(out, f, big);
    for (std::uint8_t c : {v.r, v.g, v.b, v.a}) put_binary(out, c, big);
    put_binary(out, v.quality, big);
  }
  const std::vector<std::vector<int>> polys = {{0, 1, 2, 3}, {1, 4, 2}};
  for (const auto& p : polys) {
    put_binary(out, static_cast<std::uint8_t>(p.size()), big);
    for (int i : p) put_binary(out, static_cast<std::int32_t>(i), big);
    put_binary(out, static_cast<std::uint8_t>(2 * p.size()), big);
    for (std::size_t i = 0; i < 2 * p.size(); ++i)
      put_binary(out, 0.5f * static_cast<float>(i % 3), big);
  }
  put_binary(out, std::int32_t{0}, big);
  put_binary(out, std::int32_t{4}, big);
  return out;
}

void expect_scanner_content(const MeshDocument& doc) {
  EXPECT_EQ(doc.format(), MeshFormat::Ply);
  const Mesh& t = doc.triangles();
  ASSERT_EQ(t.vertex_count(), 5u);
  ASSERT_EQ(t.face_count(), 3u);  // the quad fanned
  EXPECT_EQ(Eigen::Vector3i(t.faces.row(1).transpose()), Eigen::Vector3i(0, 2, 3));
  EXPECT_EQ(Eigen::Vector3i(t.faces.row(2).transpose()), Eigen::Vector3i(1, 4, 2));
  EXPECT_EQ(Eigen::Vector3d(t.vertices.row(4).transpose()), Eigen::Vector3d(2, 0.5, 0.125));
  EXPECT_EQ(doc.polygon_of_triangle(), (std::vector<int>{0, 0, 1}));
  ASSERT_EQ(doc.vertex_colors().size(), 5u);
  EXPECT_EQ(doc.vertex_colors()[0], Eigen::Vector3f(1, 0, 0));
  EXPECT_EQ(doc.vertex_colors()[3], Eigen::Vector3f(51 / 255.0f, 102 / 255.0f, 153 / 255.0f));
}

TEST_F(PlyDocumentTest, ReadsColoursAndKeepsEveryPropertyInAscii) {
  const std::string in = put("scan.ply", std::string(kHeader) + kBody);
  const MeshDocument doc = read_mesh_document(in);
  expect_scanner_content(doc);
  // the same positions: the same bytes
  doc.write(path("same.ply"), doc.triangles().vertices);
  EXPECT_EQ(core::read_file(path("same.ply")), core::read_file(in));
  // one vertex moved: its x y z change, the normals of the vertices around it are recomputed,
  // everything else (colours, quality, texcoords, the edge, the header) byte for byte
  Vertices p = doc.triangles().vertices;
  p(2, 2) = 0.5;
  doc.write(path("moved.ply"), p);
  const std::string out = core::read_file(path("moved.ply"));
  const std::string expected_prefix = std::string(kHeader) + "0 0 0 ";
  EXPECT_EQ(out.rfind(expected_prefix, 0), 0u);
  EXPECT_NE(out.find("\n1 1 0.5 "), std::string::npos) << out;
  EXPECT_NE(out.find(" 0 0 255 128 1\n"), std::string::npos);  // vertex 2's colour and quality
  EXPECT_NE(out.find("\n4 0 1 2 3 8 0 0 1 0 1 1 0 1\n3 1 4 2 6 0 0 1 0 1 1\n0 4\n"),
            std::string::npos);
  const MeshDocument back = read_mesh_document(path("moved.ply"));
  EXPECT_EQ(back.triangles().vertices, p);
  EXPECT_EQ(back.vertex_colors(), doc.vertex_colors());
  // vertex 3 is only in the quad's triangle (0, 2, 3): its normal is that triangle's,
  // (1, 1, 0.5) × (0, 1, 0) = (−0.5, 0, 1), normalised — found as the text the writer gives (%.9g)
  const Eigen::Vector3f n3 = Eigen::Vector3d(-0.5, 0, 1).normalized().cast<float>();
  char buf[80];
  std::snprintf(buf, sizeof buf, "\n0 1 0 %.9g %.9g %.9g 51 102 153 255 0\n",
                static_cast<double>(n3.x()), static_cast<double>(n3.y()),
                static_cast<double>(n3.z()));
  EXPECT_NE(out.find(buf), std::string::npos) << buf << out;
  // without normal recomputation only the position changes
  doc.write(path("moved_only.ply"), p, false);
  std::string expected = std::string(kHeader) + kBody;
  expected.replace(expected.find("1 1 0 0 0 1 0 0 255"), 5, "1 1 0.5");
  EXPECT_EQ(core::read_file(path("moved_only.ply")), expected);
}

TEST_F(PlyDocumentTest, BinaryBothByteOrders) {
  for (const bool big : {false, true}) {
    SCOPED_TRACE(big ? "big endian" : "little endian");
    const std::string bytes = binary_ply(big);
    const std::string in = put("scan.ply", bytes);
    const MeshDocument doc = read_mesh_document(in);
    expect_scanner_content(doc);
    doc.write(path("same.ply"), doc.triangles().vertices);
    EXPECT_EQ(core::read_file(path("same.ply")), bytes);
    Vertices p = doc.triangles().vertices;
    p(4, 0) = -3.0;
    doc.write(path("moved.ply"), p, false);
    const std::string out = core::read_file(path("moved.ply"));
    ASSERT_EQ(out.size(), bytes.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < out.size(); ++i) differ += out[i] != bytes[i];
    EXPECT_GE(differ, 1u);
    EXPECT_LE(differ, 4u);  // one float's bytes
    const MeshDocument back = read_mesh_document(path("moved.ply"));
    EXPECT_EQ(back.triangles().vertices, p);
    EXPECT_EQ(back.vertex_colors(), doc.vertex_colors());
  }
}

TEST_F(PlyDocumentTest, FloatColoursDoublePositionsAndOtherFormats) {
  const std::string in =
      put("c.ply",
          "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
          "property double z\nproperty float red\nproperty float green\nproperty float blue\n"
          "element face 1\nproperty list uchar uint vertex_index\nend_header\n"
          "0 0 0 0.25 0.5 1\n1 0 0 0 0 0\n0.1 0.7 0.30000000000000004 1 1 1\n3 0 1 2\n");
  const MeshDocument doc = read_mesh_document(in);
  ASSERT_EQ(doc.vertex_colors().size(), 3u);
  EXPECT_EQ(doc.vertex_colors()[0], Eigen::Vector3f(0.25f, 0.5f, 1.0f));
  EXPECT_EQ(doc.triangles().vertices(2, 2), 0.30000000000000004);  // double kept to the last bit
  Vertices p = doc.triangles().vertices;
  p(1, 0) = 0.1 + 0.2;
  doc.write(path("d.ply"), p);
  EXPECT_EQ(read_mesh_document(path("d.ply")).triangles().vertices, p);
  // written as another format: plain geometry through write_mesh
  doc.write(path("d.off"), p);
  EXPECT_EQ(read_mesh(path("d.off")).vertex_count(), 3u);
  // a PLY without colours has none
  write_mesh(path("t.ply"), testing::tetrahedron());
  EXPECT_TRUE(read_mesh_document(path("t.ply")).vertex_colors().empty());
}

// A rig whose mesh is a coloured PLY (the built-in face written as a scanner would, in decimetres):
// load_face keeps the document, write_face_mesh writes the colours and the unknown property back
// (faceanim frames of a PLY keep them).
TEST_F(PlyDocumentTest, FaceMeshesKeepTheirColours) {
  Face face = make_default_face();
  const long nv = face.mesh.vertices.rows();
  std::string text = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(nv) +
                     "\nproperty double x\nproperty double y\nproperty double z\nproperty uchar "
                     "red\nproperty uchar green\n"
                     "property uchar blue\nproperty float confidence\nelement face " +
                     std::to_string(face.mesh.faces.rows()) +
                     "\nproperty list uchar int vertex_indices\nend_header\n";
  char buf[160];
  for (long v = 0; v < nv; ++v) {
    std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g %d %d %d 0.5\n",
                  face.mesh.vertices(v, 0) * 10, face.mesh.vertices(v, 1) * 10,
                  face.mesh.vertices(v, 2) * 10, static_cast<int>(v % 256), 100, 200);
    text += buf;
  }
  for (long f = 0; f < face.mesh.faces.rows(); ++f) {
    std::snprintf(buf, sizeof buf, "3 %d %d %d\n", face.mesh.faces(f, 0), face.mesh.faces(f, 1),
                  face.mesh.faces(f, 2));
    text += buf;
  }
  put("head.ply", text);
  face.rig.mesh_file = "head.ply";
  face.rig.frame.scale = 0.1;
  write_rig(path("face.rig"), face.rig);
  const Face loaded = load_face(path("face.rig"));
  ASSERT_TRUE(loaded.document != nullptr);
  EXPECT_EQ(loaded.document->format(), MeshFormat::Ply);
  EXPECT_EQ(loaded.document->vertex_colors()[7],
            Eigen::Vector3f(7 / 255.0f, 100 / 255.0f, 200 / 255.0f));
  EXPECT_LT((loaded.mesh.vertices - face.mesh.vertices).cwiseAbs().maxCoeff(),
            1e-15);  // rig frame: metres
  write_face_mesh(path("same.ply"), loaded, loaded.mesh.vertices);
  EXPECT_EQ(core::read_file(path("same.ply")), text);
  Vertices moved = loaded.mesh.vertices;
  moved(5, 2) += 0.001;  // 1 mm in the rig frame
  write_face_mesh(path("frame.ply"), loaded, moved);
  const MeshDocument back = read_mesh_document(path("frame.ply"));
  EXPECT_EQ(back.vertex_colors(), loaded.document->vertex_colors());
  EXPECT_NEAR(back.triangles().vertices(5, 2), face.mesh.vertices(5, 2) * 10 + 0.01, 1e-12);
  EXPECT_EQ(back.triangles().vertices.bottomRows(nv - 6),
            loaded.document->triangles().vertices.bottomRows(nv - 6));
  const std::string out = core::read_file(path("frame.ply"));
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), std::count(text.begin(), text.end(), '\n'));
  EXPECT_NE(out.find(" 5 100 200 0.5\n"), std::string::npos);
}

void expect_ply_error(const std::string& file, std::size_t line, const std::string& what) {
  try {
    read_mesh_document(file);
    FAIL() << "accepted: " << what;
  } catch (const FormatError& e) {
    EXPECT_EQ(e.where().file, file) << what;
    EXPECT_EQ(e.where().line, line) << what << ": " << e.what();
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

TEST_F(PlyDocumentTest, RejectsBadPly) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float "
      "z\n";
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string good = "0 0 0\n1 0 0\n0 1 0\n";
  struct Case {
    std::string text;
    std::size_t line;
    std::string what;
  };
  const std::vector<Case> cases = {
      {"plx\n", 1, "not a PLY file"},
      {head + faces.substr(0, faces.size() - 11), 9, "no end_header"},
      {"ply\nformat ascii 2.0\n", 2, "format"},
      {"ply\nformat utf8 1.0\nend_header\n", 2, "unknown PLY encoding"},
      {"ply\nformat ascii 1.0\nelement vertex -3\n", 3, "bad count"},
      {"ply\nformat ascii 1.0\nproperty float x\n", 3, "before any element"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\n", 4, "unknown property type"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nwhat\n", 5,
       "unknown header keyword"},
      {head + faces + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", 11, "vertex 1 y is not finite"},
      {head + faces + "0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n", 11, "vertex 1 y is not finite"},
      {head + faces + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n", 11, "expected a number"},
      {head + faces + good + "3 0 1 3\n", 13, "vertex index 3 out of range"},
      {head + faces + good + "3 0 1 -1\n", 13, "vertex index -1 out of range"},
      {head + faces + good + "2 0 1\n", 13, "has 2 vertices"},
      {head + faces + good + "3 0 1\n", 13, "truncated"},
      {head + faces + "0.000000 0 0\n1.0000000 0 0\n", 12, "truncated"},
      {head + faces + good + "3 0 1 1e3\n", 13, "expected an integer"},
      {head + faces + good + "300 0 1 2\n", 13, "out of range for uchar"},
      {"ply\nformat ascii 1.0\nelement vertex 999999999\nproperty float x\nproperty float "
       "y\nproperty float z\n" +
           faces + good,
       1, "more than the"},
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty int x\nproperty float y\nproperty float "
       "z\n" +
           faces + good + "3 0 1 2\n",
       1, "positions must be float or double"},
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n" + faces +
           good + "3 0 1 2\n",
       1, "no z property"},
      {head + "end_header\n" + good, 1, "no face element"},
      {head + "element face 1\nproperty list uchar float vertex_indices\nend_header\n" + good +
           "3 0 1 2\n",
       1, "indices must be integers"},
      {head + "property float red\nproperty float green\nproperty float blue\n" + faces +
           "0 0 0 1 1 1\n1 0 0 1.5 0 0\n0 1 0 0 0 0\n3 0 1 2\n",
       14, "out of range (float colours are 0 to 1)"},
      {head + "property float red\nproperty float green\nproperty float blue\n" + faces +
           "0 0 0 1 1 1\n1 0 0 nan 0 0\n0 1 0 0 0 0\n3 0 1 2\n",
       14, "out of range"},
      {head + "property short red\nproperty short green\nproperty short blue\n" + faces +
           "0 0 0 1 1 1\n1 0 0 1 1 1\n0 1 0 1 1 1\n3 0 1 2\n",
       1, "not supported"},
      {head + "property uchar red\n" + faces + "0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2\n", 1,
       "need red, green and blue"},
      {head + faces + good + "3 0 0 1\n", 0, "no non-degenerate triangle"},
  };
  for (std::size_t k = 0; k < cases.size(); ++k) {
    SCOPED_TRACE(cases[k].what);
    expect_ply_error(put("bad" + std::to_string(k) + ".ply", cases[k].text), cases[k].line,
                     cases[k].what);
  }
  // non-manifold: three triangles on one edge
  expect_ply_error(put("nm.ply",
                       "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float "
                       "y\nproperty float z\n"
                       "element face 3\nproperty list uchar int vertex_indices\nend_header\n"
                       "0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 0 1 3\n3 0 1 4\n"),
                   17, "non-manifold");
  // binary: truncated inside a vertex, a face list past the end — named by byte offset
  std::string bin = binary_ply(false);
  const std::size_t body = bin.find("end_header\n") + 11;
  expect_ply_error(put("trunc.ply", bin.substr(0, bin.size() - 4)), 0, "truncated");
  std::string huge = bin;
  huge[body + 5 * 32] = static_cast<char>(200);  // the quad's vertex count: 200 ids, past the end
  expect_ply_error(put("huge.ply", huge), 0, "at byte");
  std::string nan_bin = bin;
  const float nan = std::nanf("");
  std::memcpy(&nan_bin[body + 32 + 4], &nan, 4);  // vertex 1 y
  expect_ply_error(put("nan.ply", nan_bin), 0, "vertex 1 y is not finite");
}

}  // namespace
}  // namespace emoface::facemesh
