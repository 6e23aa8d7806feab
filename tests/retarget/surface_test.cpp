#include "emoface/retarget/surface.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "test_shapes.hpp"

namespace rt = emoface::retarget;
using emoface::retarget::test::ellipsoid;

TEST(MeshWalker, EllipsoidCurveLiesOnTheEllipse) {
  const double a = 0.08, b = 0.12, c = 0.1;
  const auto m = ellipsoid(a, b, c, 48, 72, 0.013);
  const rt::MeshWalker walker(m.faces, m.vertex_count());
  EXPECT_EQ(walker.boundary_loop_count(), 0u);
  for (double az : {0.0, 0.4, -1.0, 1.5}) {
    const auto curve = walker.half_plane_curve(m.vertices, 0, Eigen::Vector3d::Zero(), az, -1e300);
    ASSERT_GT(curve.size(), 40u) << az;
    EXPECT_NEAR(curve.front().y(), b, 1e-15);
    EXPECT_NEAR(curve.back().y(), -b, 0.01 * b);  // walked all the way down
    for (const auto& q : curve) {
      const double x = q.x() * std::sin(az), z = q.x() * std::cos(az);
      EXPECT_GE(q.x(), -1e-12);
      const double e = x * x / (a * a) + q.y() * q.y() / (b * b) + z * z / (c * c);
      EXPECT_NEAR(e, 1.0, 0.01) << az;  // chords lie just inside the ellipsoid
    }
    // Stops early below stop_y.
    const auto part = walker.half_plane_curve(m.vertices, 0, Eigen::Vector3d::Zero(), az, 0.0);
    EXPECT_LT(part.size(), curve.size() * 2 / 3);
    EXPECT_LT(part.back().y(), 0.0);
  }
}

TEST(MeshWalker, FillsHolesAndStopsAtOpenEnds) {
  auto m = ellipsoid(0.1, 0.1, 0.1, 40, 64);
  // Remove the faces of rings 18–21 in front (an "eye hole") and the bottom cap (an open neck).
  std::vector<int> keep;
  const auto nf = m.faces.rows();
  for (Eigen::Index f = 0; f < nf; ++f) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) centroid += m.vertices.row(m.faces(f, k)).transpose() / 3.0;
    const bool hole = centroid.z() > 0.07 && std::abs(centroid.y()) < 0.02 && std::abs(centroid.x()) < 0.03;
    const bool neck = centroid.y() < -0.09;
    if (!hole && !neck) keep.push_back(static_cast<int>(f));
  }
  emoface::facemesh::Faces faces(static_cast<Eigen::Index>(keep.size()), 3);
  for (std::size_t i = 0; i < keep.size(); ++i) faces.row(static_cast<Eigen::Index>(i)) = m.faces.row(keep[i]);
  const rt::MeshWalker walker(faces, m.vertex_count());
  EXPECT_EQ(walker.boundary_loop_count(), 2u);
  EXPECT_FALSE(walker.on_boundary(0));
  EXPECT_TRUE(walker.on_boundary(static_cast<int>(m.vertex_count()) - 1));  // the removed bottom pole
  EXPECT_THROW(walker.on_boundary(-1), emoface::InvalidInput);
  const auto curve = walker.half_plane_curve(m.vertices, 0, Eigen::Vector3d::Zero(), 0.0, -1e300);
  // Crossed the hole (reached below it) and ended at the open neck.
  EXPECT_LT(curve.back().y(), -0.08);
  EXPECT_GT(curve.back().y(), -0.1);
  bool jumped = false;
  for (std::size_t k = 1; k < curve.size(); ++k)
    if (curve[k - 1].y() - curve[k].y() > 0.02) jumped = true;
  EXPECT_TRUE(jumped);
}

TEST(MeshWalker, RejectsBadConnectivity) {
  emoface::facemesh::Faces f(3, 3);
  f << 0, 1, 2, 0, 1, 3, 0, 1, 4;  // edge 0-1 in three faces
  EXPECT_THROW(rt::MeshWalker(f, 5), emoface::InvalidInput);
  emoface::facemesh::Faces g(1, 3);
  g << 0, 1, 7;
  EXPECT_THROW(rt::MeshWalker(g, 3), emoface::InvalidInput);
  const auto m = ellipsoid(0.1, 0.1, 0.1, 8, 8);
  const rt::MeshWalker w(m.faces, m.vertex_count());
  EXPECT_THROW(w.half_plane_curve(m.vertices, -1, Eigen::Vector3d::Zero(), 0.0, 0.0), emoface::InvalidInput);
  emoface::facemesh::Vertices fewer = m.vertices.topRows(5);
  EXPECT_THROW(w.half_plane_curve(fewer, 0, Eigen::Vector3d::Zero(), 0.0, 0.0), emoface::InvalidInput);
}

TEST(CylindricalProjector, ProjectsOntoASphereHorizontally) {
  const double r = 0.1;
  const auto m = ellipsoid(r, r, r, 60, 90);
  const rt::CylindricalProjector proj(m, Eigen::Vector3d::Zero());
  for (const Eigen::Vector3d p : {Eigen::Vector3d(0.02, 0.03, 0.05), Eigen::Vector3d(-0.2, -0.05, 0.01),
                                  Eigen::Vector3d(0.0, 0.08, -0.3)}) {
    Eigen::Vector3d q;
    ASSERT_TRUE(proj.project(p, q));
    EXPECT_DOUBLE_EQ(q.y(), p.y());  // horizontal ray
    const double expected = std::sqrt(r * r - p.y() * p.y());
    EXPECT_NEAR(std::hypot(q.x(), q.z()), expected, 2e-3 * r);
    // Same azimuth as p.
    EXPECT_NEAR(std::atan2(q.x(), q.z()), std::atan2(p.x(), p.z()), 1e-9);
  }
  Eigen::Vector3d q(7, 7, 7);
  EXPECT_FALSE(proj.project(Eigen::Vector3d(0, 0.5, 0.1), q));  // above the head: misses
  EXPECT_FALSE(proj.project(Eigen::Vector3d(0, 0.0, 0.0), q));  // on the axis
  EXPECT_EQ(q, Eigen::Vector3d(7, 7, 7));
}

TEST(Surface, TopVertex) {
  emoface::facemesh::Vertices v(3, 3);
  v << 0, 1, 0, 0, 2, 0, 1, 2, 0;
  EXPECT_EQ(rt::top_vertex(v), 1);
  EXPECT_THROW(rt::top_vertex(emoface::facemesh::Vertices()), emoface::InvalidInput);
}
