// Surface distance (FLANN) and synthetic warps.
#include "emoface/retarget/validation.hpp"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "test_shapes.hpp"

namespace fm = emoface::facemesh;
namespace rt = emoface::retarget;

TEST(SurfaceDistance, SphereToSphereIsTheRadiusGap) {
  const auto a = emoface::retarget::test::ellipsoid(0.1, 0.1, 0.1, 30, 48);
  const auto b = emoface::retarget::test::ellipsoid(0.12, 0.12, 0.12, 60, 96);
  const auto d = rt::surface_distance(a, b);
  EXPECT_NEAR(d.mean, 0.02, 5e-4);
  EXPECT_NEAR(d.p95, 0.02, 5e-4);
  EXPECT_LE(d.p95, d.max);
  const auto self = rt::surface_distance(a, a);
  EXPECT_LT(self.max, 1e-12);
  EXPECT_THROW(rt::surface_distance(a, b, std::vector<std::uint8_t>(3, 1)), emoface::InvalidInput);
  EXPECT_THROW(rt::surface_distance(a, b, std::vector<std::uint8_t>(a.vertex_count(), 0)), emoface::InvalidInput);
}

TEST(SurfaceDistance, ClosestPointOnTriangle) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(rt::closest_point_on_triangle({0.2, 0.2, 1}, a, b, c).isApprox(Eigen::Vector3d(0.2, 0.2, 0)));
  EXPECT_TRUE(rt::closest_point_on_triangle({-1, -1, 0}, a, b, c).isApprox(a));
  EXPECT_TRUE(rt::closest_point_on_triangle({1, 1, 0}, a, b, c).isApprox(Eigen::Vector3d(0.5, 0.5, 0)));
  EXPECT_TRUE(rt::closest_point_on_triangle({0.5, -2, 0}, a, b, c).isApprox(Eigen::Vector3d(0.5, 0, 0)));
}

TEST(SyntheticWarp, IdentityByDefaultAndValidated) {
  const rt::SyntheticWarp w;
  const Eigen::Vector3d p(0.01, -0.08, 0.05);
  EXPECT_TRUE(w.apply(p).isApprox(p));
  rt::SyntheticWarp bad;
  bad.width = 0.0;
  EXPECT_THROW(bad.validate(), emoface::InvalidInput);
}


TEST(Decimate, HalvesTheVerticesAndStaysAValidSurface) {
  const auto sphere = rt::test::ellipsoid(0.1, 0.12, 0.09, 30, 48);
  const auto d = rt::decimate(sphere, 0.4);
  EXPECT_NO_THROW(fm::validate_mesh(d, "decimated"));
  EXPECT_NEAR(static_cast<double>(d.vertex_count()), 0.4 * static_cast<double>(sphere.vertex_count()), 2.0);
  // Closed surface stays closed: V − E + F = 2 (Euler), i.e. F = 2V − 4.
  EXPECT_EQ(d.face_count(), 2 * d.vertex_count() - 4);
  // Close to the original surface (quadric placement): within 2 mm of a 10 cm ellipsoid.
  const auto dist = rt::surface_distance(d, sphere);
  EXPECT_LT(dist.max, 0.002);
  EXPECT_EQ(rt::decimate(sphere, 1.0).faces, sphere.faces);
  EXPECT_THROW(rt::decimate(sphere, 0.0), emoface::InvalidInput);
  // Open boundaries are kept: a hemisphere keeps its rim vertices.
  fm::Mesh half = sphere;
  std::vector<Eigen::Index> top;
  for (Eigen::Index f = 0; f < sphere.faces.rows(); ++f)
    if (sphere.vertices(sphere.faces(f, 0), 1) + sphere.vertices(sphere.faces(f, 1), 1) + sphere.vertices(sphere.faces(f, 2), 1) > 0) top.push_back(f);
  half.faces.resize(static_cast<Eigen::Index>(top.size()), 3);
  for (std::size_t k = 0; k < top.size(); ++k) half.faces.row(static_cast<Eigen::Index>(k)) = sphere.faces.row(top[k]);
  const auto dh = rt::decimate(half, 0.5);
  EXPECT_NO_THROW(fm::validate_mesh(dh, "decimated half"));
  double lowest = 1;
  for (Eigen::Index i = 0; i < dh.vertices.rows(); ++i) lowest = std::min(lowest, dh.vertices(i, 1));
  EXPECT_LT(lowest, 0.01);  // the rim near y = 0 is still there
}
