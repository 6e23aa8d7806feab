#include "emoface/facemesh/mesh_io.hpp"

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "test_util.hpp"

namespace emoface::facemesh {
namespace {

class MeshIo : public testing::TempDirTest {};

TEST_F(MeshIo, RoundTripsAllFormats) {
  const Mesh m = testing::tetrahedron();
  for (const char* ext : {".obj", ".ply", ".off", ".OBJ"}) {
    const std::string p = path(std::string("t") + ext);
    write_mesh(p, m);
    const Mesh r = read_mesh(p);
    ASSERT_EQ(r.vertex_count(), 4u) << ext;
    ASSERT_EQ(r.face_count(), 4u) << ext;
    EXPECT_TRUE(r.vertices.isApprox(m.vertices)) << ext;
    EXPECT_EQ(r.faces, m.faces) << ext;
  }
}

TEST_F(MeshIo, FanTriangulatesPolygons) {
  core::write_file_atomic(path("q.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const Mesh r = read_mesh(path("q.obj"));
  EXPECT_EQ(r.face_count(), 2u);
}

TEST_F(MeshIo, RejectsBadFiles) {
  EXPECT_THROW(read_mesh(path("missing.obj")), IoError);
  core::write_file_atomic(path("x.stl"), "solid\n");
  EXPECT_THROW(read_mesh(path("x.stl")), FormatError);
  EXPECT_THROW(write_mesh(path("x.stl"), testing::tetrahedron()), InvalidInput);
  // out-of-range index
  core::write_file_atomic(path("range.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  EXPECT_THROW(read_mesh(path("range.obj")), FormatError);
  // repeated index
  core::write_file_atomic(path("rep.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\nf 1 2 3\n");
  EXPECT_THROW(read_mesh(path("rep.obj")), FormatError);
  // degenerate (collinear)
  core::write_file_atomic(path("deg.obj"), "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  EXPECT_THROW(read_mesh(path("deg.obj")), FormatError);
  // non-manifold: three faces on edge 1-2
  core::write_file_atomic(path("nm.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
  EXPECT_THROW(read_mesh(path("nm.obj")), FormatError);
  // NaN coordinate
  core::write_file_atomic(path("nan.off"), "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_THROW(read_mesh(path("nan.off")), FormatError);
  // truncated / empty
  core::write_file_atomic(path("empty.obj"), "");
  EXPECT_THROW(read_mesh(path("empty.obj")), FormatError);
  core::write_file_atomic(path("trunc.off"), "OFF\n3 1 0\n0 0 0\n1 0");
  EXPECT_THROW(read_mesh(path("trunc.off")), FormatError);
}

}  // namespace
}  // namespace emoface::facemesh
