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

