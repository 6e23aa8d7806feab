#include "emoface/facemesh/mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "emoface/core/errors.hpp"
#include "test_util.hpp"

namespace emoface::facemesh {
namespace {

using testing::tetrahedron;

TEST(ValidateMesh, AcceptsClosedTetrahedron) { EXPECT_NO_THROW(validate_mesh(tetrahedron())); }

TEST(ValidateMesh, RejectsBadMeshes) {
  {
    Mesh m = tetrahedron();
    m.faces(1, 2) = 7;
    EXPECT_THROW(validate_mesh(m), FormatError);
  }
  {
    Mesh m = tetrahedron();
    m.faces(1, 2) = -1;
    EXPECT_THROW(validate_mesh(m), FormatError);
  }
  {
    Mesh m = tetrahedron();
    m.faces(2, 1) = m.faces(2, 0);  // repeated vertex
    EXPECT_THROW(validate_mesh(m), FormatError);
  }
  {
    Mesh m = tetrahedron();
    m.vertices(3, 1) = std::numeric_limits<double>::quiet_NaN();
    try {
      validate_mesh(m, "x.obj");
      FAIL();
    } catch (const FormatError& e) {
      EXPECT_EQ(e.where().file, "x.obj");
      EXPECT_EQ(e.where().line, 4u);
    }
  }
  {
    Mesh m = tetrahedron();
    m.vertices.row(3) = Eigen::RowVector3d(0.5, 0.5, 0.0);  // face 3 becomes collinear? no: make degenerate
    m.vertices.row(3) = m.vertices.row(1);
    EXPECT_THROW(validate_mesh(m), FormatError);
  }
  {
    // three triangles on one edge (non-manifold)
    Mesh m;
    m.vertices.resize(5, 3);
    m.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1;
    m.faces.resize(3, 3);
    m.faces << 0, 1, 2, 0, 1, 3, 1, 0, 4;
    EXPECT_THROW(validate_mesh(m), FormatError);
  }
  EXPECT_THROW(validate_mesh(Mesh{}), FormatError);
}

TEST(Normals, TetrahedronFaceAndVertexNormals) {
  const Mesh m = tetrahedron();
  const Vertices fn = face_normals(m.vertices, m.faces);
  EXPECT_NEAR(fn(0, 2), -1.0, 1e-12);  // face in z = 0 plane, pointing down (outward)
  EXPECT_NEAR(fn(3, 0), 1.0 / std::sqrt(3.0), 1e-12);
  const Vertices vn = vertex_normals(m.vertices, m.faces);
  for (long v = 0; v < 4; ++v) EXPECT_NEAR(vn.row(v).norm(), 1.0, 1e-12);
  // vertex 0: area-weighted mean of the three axis-aligned faces = -(1,1,1)/sqrt3
  EXPECT_NEAR(vn(0, 0), -1.0 / std::sqrt(3.0), 1e-12);
}

TEST(Subdivide, CountsAndMidpoints) {
  std::vector<std::pair<int, int>> parents;
  const Mesh s = subdivide_midpoint(tetrahedron(), &parents);
  EXPECT_EQ(s.face_count(), 16u);
  EXPECT_EQ(s.vertex_count(), 4u + 6u);  // one new vertex per edge
  ASSERT_EQ(parents.size(), 6u);
  for (std::size_t i = 0; i < parents.size(); ++i) {
    const Eigen::RowVector3d mid = 0.5 * (s.vertices.row(parents[i].first) + s.vertices.row(parents[i].second));
    EXPECT_TRUE(s.vertices.row(4 + static_cast<long>(i)).isApprox(mid));
  }
  EXPECT_NO_THROW(validate_mesh(s));
}

}  // namespace
}  // namespace emoface::facemesh
