// orient_consistently and the orientation-repairing mesh reader (scans with inconsistent winding).
#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/facemesh/mesh.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "test_util.hpp"

namespace emoface::facemesh {
namespace {

void flip(Mesh& m, long f) { std::swap(m.faces(f, 1), m.faces(f, 2)); }

// Signed volume (×6) of a closed mesh: > 0 for outward faces.
double volume6(const Mesh& m) {
  double v = 0;
  for (long f = 0; f < m.faces.rows(); ++f)
    v += Eigen::Vector3d(m.vertices.row(m.faces(f, 0))).dot(Eigen::Vector3d(m.vertices.row(m.faces(f, 1))).cross(Eigen::Vector3d(m.vertices.row(m.faces(f, 2)))));
  return v;
}

// The upper half of an octahedron: 4 faces, open at the bottom square, outward = away from the origin.
Mesh pyramid() {
  Mesh m;
  m.vertices.resize(5, 3);
  m.vertices << 0, 1, 0, 1, 0, 0, 0, 0, 1, -1, 0, 0, 0, 0, -1;
  m.faces.resize(4, 3);
  m.faces << 0, 2, 1, 0, 3, 2, 0, 4, 3, 0, 1, 4;
  return m;
}

TEST(Orientation, RepairsFlippedFacesOfAClosedMesh) {
  const Mesh good = testing::tetrahedron();
  ASSERT_GT(volume6(good), 0);
  Mesh m = good;
  flip(m, 1);
  flip(m, 3);
  EXPECT_THROW(validate_mesh(m), FormatError);
  const auto r = orient_consistently(m);
  EXPECT_EQ(r.flipped_faces, 2u);
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.closed_components, 1u);
  EXPECT_EQ(r.flipped_components, 0u);
  EXPECT_EQ(m.faces, good.faces);
  // Inside out as a whole: consistent but inward; made outward by the signed volume.
  Mesh inside = good;
  for (long f = 0; f < 4; ++f) flip(inside, f);
  const auto r2 = orient_consistently(inside);
  EXPECT_EQ(r2.flipped_faces, 4u);
  EXPECT_EQ(r2.flipped_components, 1u);
  EXPECT_GT(volume6(inside), 0);
  // Already good: nothing changes.
  Mesh same = good;
  EXPECT_EQ(orient_consistently(same).flipped_faces, 0u);
  EXPECT_EQ(same.faces, good.faces);
}

TEST(Orientation, OpenMeshPointsAwayFromItsCentroid) {
  const Mesh good = pyramid();
  EXPECT_NO_THROW(validate_mesh(good));
  Mesh m = good;
  flip(m, 0);
  flip(m, 1);
  flip(m, 2);  // 3 of 4 flipped: the majority is wrong, the outward rule decides
  const auto r = orient_consistently(m);
  EXPECT_EQ(r.closed_components, 0u);
  EXPECT_EQ(r.flipped_faces, 3u);
  EXPECT_EQ(m.faces, good.faces);
  const auto n = face_normals(m.vertices, m.faces);
  for (long f = 0; f < 4; ++f) EXPECT_GT(n(f, 1), 0.0);  // all point up and out
}

TEST(Orientation, SeveralComponentsAreOrientedEach) {
  const Mesh a = testing::tetrahedron(), b = pyramid();
  Mesh m;
  m.vertices.resize(9, 3);
  m.vertices << a.vertices, b.vertices.rowwise() + Eigen::RowVector3d(5, 0, 0);
  m.faces.resize(8, 3);
  m.faces << a.faces, b.faces.array() + 4;
  Mesh expected = m;
  flip(m, 0);   // tetrahedron
  flip(m, 6);   // pyramid
  const auto r = orient_consistently(m);
  EXPECT_EQ(r.components, 2u);
  EXPECT_EQ(r.closed_components, 1u);
  EXPECT_EQ(r.flipped_faces, 2u);
  EXPECT_EQ(m.faces, expected.faces);
}

TEST(Orientation, NonManifoldAndNonOrientableAreClearErrors) {
  Mesh nm;
  nm.vertices.resize(5, 3);
  nm.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1;
  nm.faces.resize(3, 3);
  nm.faces << 0, 1, 2, 1, 0, 3, 0, 1, 4;  // three triangles on edge 0-1
  try {
    orient_consistently(nm);
    ADD_FAILURE();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("more than two"), std::string::npos) << e.what();
  }
  // A Moebius strip of 12 quads.
  const int n = 12;
  Mesh mo;
  mo.vertices.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    const double u = 2 * 3.14159265358979323846 * i / n;
    for (int s = 0; s < 2; ++s) {
      const double v = s ? -0.3 : 0.3;
      mo.vertices.row(2 * i + s) << (1 + v * std::cos(u / 2)) * std::cos(u), (1 + v * std::cos(u / 2)) * std::sin(u), v * std::sin(u / 2);
    }
  }
  mo.faces.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    const int t = 2 * i, b = 2 * i + 1;
    const int tj = i + 1 < n ? 2 * (i + 1) : 1, bj = i + 1 < n ? 2 * (i + 1) + 1 : 0;  // the twist
    mo.faces.row(2 * i) << t, b, tj;
    mo.faces.row(2 * i + 1) << b, bj, tj;
  }
  try {
    orient_consistently(mo);
    ADD_FAILURE();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("not orientable"), std::string::npos) << e.what();
  }
  Mesh bad = testing::tetrahedron();
  bad.faces(0, 0) = 9;
  EXPECT_THROW(orient_consistently(bad), InvalidInput);
}

class OrientationIo : public testing::TempDirTest {};

TEST_F(OrientationIo, ReaderRepairsOnRequest) {
  // Tetrahedron with face 2 written the wrong way round, and a vertex defined after the faces.
  core::write_file_atomic(path("t.obj"),
                          "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 3 2\nf 1 2 4\nf 1 3 4\nv 0 0 1\nf 2 3 4\n");
  EXPECT_THROW(read_mesh(path("t.obj")), FormatError);
  MeshReadReport report;
  const Mesh m = read_mesh(path("t.obj"), MeshReadOptions{true}, &report);
  EXPECT_EQ(report.orientation.flipped_faces, 1u);
  EXPECT_EQ(m.vertex_count(), 4u);
  EXPECT_EQ(m.faces, testing::tetrahedron().faces);
  EXPECT_NO_THROW(validate_mesh(m));
  // The same through PLY and OFF.
  for (const char* name : {"t.off", "t.ply"}) {
    Mesh t = testing::tetrahedron();
    flip(t, 3);
    // write_mesh does not validate, so an inconsistent file can be written
    write_mesh(path(name), t);
    EXPECT_THROW(read_mesh(path(name)), FormatError) << name;
    const Mesh r = read_mesh(path(name), MeshReadOptions{true}, &report);
    EXPECT_EQ(report.orientation.flipped_faces, 1u) << name;
    EXPECT_EQ(r.faces, testing::tetrahedron().faces) << name;
  }
  // Without repair the options overload behaves like read_mesh.
  write_mesh(path("ok.obj"), testing::tetrahedron());
  EXPECT_EQ(read_mesh(path("ok.obj"), MeshReadOptions{}, &report).faces, testing::tetrahedron().faces);
}

TEST_F(OrientationIo, RepairingReaderStillRejectsBadFiles) {
  const MeshReadOptions repair{true};
  EXPECT_THROW(read_mesh(path("missing.obj"), repair), IoError);
  core::write_file_atomic(path("nm.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
  try {
    read_mesh(path("nm.obj"), repair);
    ADD_FAILURE();
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("nm.obj"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("more than two"), std::string::npos) << e.what();
  }
  core::write_file_atomic(path("nan.off"), "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_THROW(read_mesh(path("nan.off"), repair), FormatError);
  core::write_file_atomic(path("empty.obj"), "");
  EXPECT_THROW(read_mesh(path("empty.obj"), repair), FormatError);
  core::write_file_atomic(path("range.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  EXPECT_THROW(read_mesh(path("range.obj"), repair), FormatError);
  core::write_file_atomic(path("deg.obj"), "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  EXPECT_THROW(read_mesh(path("deg.obj"), repair), FormatError);
  core::write_file_atomic(path("trunc.off"), "OFF\n3 1 0\n0 0 0\n1 0");
  EXPECT_THROW(read_mesh(path("trunc.off"), repair), FormatError);
  // A PLY header without end_header (made OpenMesh loop forever; found by fuzz_facemesh_mesh).
  core::write_file_atomic(path("noend.ply"),
                          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                          "element face 1\nproperty list uchar int vertex_indices\nend_heaXer\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_THROW(read_mesh(path("noend.ply"), repair), FormatError);
  EXPECT_THROW(read_mesh(path("noend.ply")), FormatError);
  core::write_file_atomic(path("badprop.ply"),
                          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nprportey float y\nproperty fndices\n"
                          "end_header\n0 1 0\n1 0 0\n0 1 0\n");
  try {
    read_mesh(path("badprop.ply"));
    ADD_FAILURE();
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(":5"), std::string::npos) << e.what();  // names the line
  }
  // Damaged OFF headers (OpenMesh allocated 16 GB for the first one; found by fuzz_facemesh_mesh).
  core::write_file_atomic(path("bad.off"), std::string("OFF2\0v 0 ", 10));
  EXPECT_THROW(read_mesh(path("bad.off")), FormatError);
  core::write_file_atomic(path("huge.off"), "OFF\n999999999 1 0\n0 0 0\n");
  EXPECT_THROW(read_mesh(path("huge.off"), repair), FormatError);
  core::write_file_atomic(path("huge.ply"), "ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\nend_header\n");
  EXPECT_THROW(read_mesh(path("huge.ply")), FormatError);
  core::write_file_atomic(path("bin.off"), std::string("OFF BINARY\n\x0b\x30\x00\x32 4 0\n", 20));
  EXPECT_THROW(read_mesh(path("bin.off")), FormatError);
  // Valid OFF variants still read.
  core::write_file_atomic(path("c.off"), "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(read_mesh(path("c.off")).face_count(), 1u);
}

}  // namespace
}  // namespace emoface::facemesh
