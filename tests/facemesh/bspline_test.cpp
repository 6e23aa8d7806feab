#include "emoface/facemesh/bspline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "emoface/core/errors.hpp"

namespace emoface::facemesh {
namespace {

TEST(BSpline, UniformBasisValues) {
  const auto b0 = cubic_bspline_basis(0.0);
  EXPECT_DOUBLE_EQ(b0[0], 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(b0[1], 4.0 / 6.0);
  EXPECT_DOUBLE_EQ(b0[2], 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(b0[3], 0.0);
  for (double t : {0.1, 0.37, 0.5, 0.99}) {
    const auto b = cubic_bspline_basis(t);
    EXPECT_NEAR(b[0] + b[1] + b[2] + b[3], 1.0, 1e-15);
  }
  const auto h = cubic_bspline_basis(0.5);  // (1/48, 23/48, 23/48, 1/48)
  EXPECT_NEAR(h[0], 1.0 / 48.0, 1e-15);
  EXPECT_NEAR(h[1], 23.0 / 48.0, 1e-15);
}

TEST(BSpline, ClampedBasisInterpolatesEndsAndSumsToOne) {
  for (double v : {0.0, 0.2, 0.5, 0.77, 1.0}) {
    const auto b = clamped_cubic_basis(6, v);
    ASSERT_EQ(b.size(), 6u);
    EXPECT_NEAR(std::accumulate(b.begin(), b.end(), 0.0), 1.0, 1e-12) << v;
    for (double x : b) EXPECT_GE(x, -1e-15);
  }
  EXPECT_DOUBLE_EQ(clamped_cubic_basis(6, 0.0)[0], 1.0);
  EXPECT_DOUBLE_EQ(clamped_cubic_basis(6, 1.0)[5], 1.0);
  // n = 4: Bernstein polynomials; at v = 0.5: (1/8, 3/8, 3/8, 1/8)
  const auto bern = clamped_cubic_basis(4, 0.5);
  EXPECT_NEAR(bern[1], 0.375, 1e-15);
  EXPECT_THROW(clamped_cubic_basis(3, 0.5), InvalidInput);
}

TEST(LipSampler, ReproducesAffineGrids) {
  // A B-spline reproduces affine functions: a planar control grid gives planar samples.
  std::vector<Eigen::Vector3d> cps(144);
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 24; ++c) cps[static_cast<std::size_t>(r * 24 + c)] = {2.0, 1.0 + 0.5 * r, 3.0 - 2.0 * r};
  }
  const LipSampler s(48, 8);
  Vertices out(s.sample_count() + 2, 3);
  s.evaluate(cps, out, 2);
  for (int j = 0; j < 8; ++j) {
    for (int i = 0; i < 48; ++i) {
      const Eigen::RowVector3d p = out.row(2 + j * 48 + i);
      EXPECT_NEAR(p.x(), 2.0, 1e-12);
      EXPECT_NEAR(p.z(), 3.0 - 4.0 * (p.y() - 1.0), 1e-12);  // on the plane z = 3 − 2r, y = 1 + r/2
    }
  }
  // row 0 samples = periodic B-spline of the row-0 control points; last row interpolates row 5.
  EXPECT_NEAR(out(2 + 0, 1), 1.0, 1e-12);
  EXPECT_NEAR(out(2 + 7 * 48, 1), 3.5, 1e-12);
  EXPECT_THROW(LipSampler(10, 8), InvalidInput);
  EXPECT_THROW(s.evaluate(std::vector<Eigen::Vector3d>(10), out, 0), InvalidInput);
  EXPECT_THROW(s.evaluate(cps, out, 5), InvalidInput);
}

TEST(LipSurfaceTerms, MatchTheSamplerAtItsGridPointsAndRejectOutOfRange) {
  const LipSampler sampler(48, 8);
  std::vector<Eigen::Vector3d> cps(144);
  for (std::size_t c = 0; c < cps.size(); ++c) cps[c] = Eigen::Vector3d(std::sin(0.3 * c), std::cos(0.7 * c), 0.01 * c);
  Vertices grid(sampler.sample_count(), 3);
  sampler.evaluate(cps, grid, 0);
  for (int j = 0; j < 8; ++j) {
    for (int i = 0; i < 48; ++i) {
      const auto terms = lip_surface_terms(i / 48.0, j / 7.0);
      EXPECT_LE(terms.size(), 16u);
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      double sum = 0.0;
      for (const auto& t : terms) p += t.weight * cps[static_cast<std::size_t>(t.control)], sum += t.weight;
      EXPECT_NEAR(sum, 1.0, 1e-14);  // partition of unity
      EXPECT_LT((p - Eigen::Vector3d(grid.row(j * 48 + i).transpose())).norm(), 1e-13);
    }
  }
  // just below u = 1 the surface closes on column 0 (periodic)
  Eigen::Vector3d end = Eigen::Vector3d::Zero(), start = Eigen::Vector3d::Zero();
  for (const auto& t : lip_surface_terms(std::nextafter(1.0, 0.0), 0.4)) end += t.weight * cps[static_cast<std::size_t>(t.control)];
  for (const auto& t : lip_surface_terms(0.0, 0.4)) start += t.weight * cps[static_cast<std::size_t>(t.control)];
  EXPECT_LT((end - start).norm(), 1e-12);
  EXPECT_THROW(lip_surface_terms(1.0, 0.5), InvalidInput);
  EXPECT_THROW(lip_surface_terms(-0.01, 0.5), InvalidInput);
  EXPECT_THROW(lip_surface_terms(0.5, 1.01), InvalidInput);
  EXPECT_THROW(lip_surface_terms(std::nan(""), 0.5), InvalidInput);
}

}  // namespace
}  // namespace emoface::facemesh
