#include "emoface/retarget/error.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "test_shapes.hpp"

namespace rt = emoface::retarget;
using emoface::retarget::test::ellipsoid;

TEST(SampleCurve, FirstBracketingSegment) {
  const std::vector<Eigen::Vector2d> c = {{0, 1}, {1, 0}, {2, 1}, {3, 0}};
  std::vector<double> r;
  ASSERT_TRUE(rt::sample_curve(c, {1.0, 0.5, 0.0}, r));
  EXPECT_DOUBLE_EQ(r[0], 0.0);
  EXPECT_DOUBLE_EQ(r[1], 0.5);
  EXPECT_DOUBLE_EQ(r[2], 1.0);
  EXPECT_FALSE(rt::sample_curve(c, {2.0}, r));
}

TEST(ErrorFunction, ZeroForIdenticalSurfaces) {
  const auto m = ellipsoid(0.08, 0.12, 0.1, 30, 48);
  const rt::ErrorFunction e(m, 0, m.faces, m.vertex_count());
  rt::ErrorBreakdown b;
  EXPECT_NEAR(e.evaluate(m.vertices, 0, &b), 0.0, 1e-20);
  EXPECT_GT(b.samples, 0u);
  EXPECT_EQ(b.penalty_term, 0.0);
}

TEST(ErrorFunction, MatchesAnalyticValueForTwoSpheroids) {
  // Same height b, horizontal radii R1 (deformed) and R2 (target): at height y the radial gap is
  // (R1 − R2)·sqrt(1 − y²/b²) in every half-plane; heights y_j = b − j·(b − y_end)/(n − 1).
  const double b = 0.1, r1 = 0.09, r2 = 0.08, y_end = -0.05;
  const auto target = ellipsoid(r2, b, r2, 200, 256);
  const auto source = ellipsoid(r1, b, r1, 200, 256);
  rt::ErrorOptions o;
  o.planes = 4;
  o.samples = 11;
  o.front_half_angle = 3.14159265358979323846;  // all 8 half-planes
  o.bottom_y = y_end;
  const rt::ErrorFunction e(target, 0, source.faces, source.vertex_count(), o);
  EXPECT_EQ(e.azimuths().size(), 8u);
  double expected = 0.0;
  for (int j = 0; j < o.samples; ++j) {
    const double y = b - j * (b - y_end) / (o.samples - 1);
    expected += 8 * (r1 - r2) * (r1 - r2) * (1 - y * y / (b * b));
  }
  rt::ErrorBreakdown br;
  const double got = e.evaluate(source.vertices, 0, &br);
  EXPECT_NEAR(got, expected, 0.02 * expected);
  EXPECT_EQ(br.samples, 88u);
  std::vector<double> res;
  e.residuals(source.vertices, 0, res);
  ASSERT_EQ(res.size(), e.residual_count());
  ASSERT_EQ(res.size(), 8u * 12u);
  double sum = 0;
  for (double x : res) sum += x * x;
  EXPECT_NEAR(sum, got, 1e-15);
  EXPECT_NEAR(res[0], 0.0, 1e-12);          // at the top both curves meet
  EXPECT_NEAR(res[5], (r1 - r2) * std::sqrt(1 - 0.0625), 1e-4);  // y_5 = 0.025 = b/4
  // Front only: the default keeps azimuths within ±1.3 rad.
  const rt::ErrorFunction front(target, 0, source.faces, source.vertex_count());
  for (double a : front.azimuths()) EXPECT_LE(std::abs(a), 1.3 + 1e-12);
}

TEST(ErrorFunction, PenalisesHeightMismatch) {
  const auto target = ellipsoid(0.08, 0.10, 0.08, 40, 64);
  auto shorter = target;
  shorter.vertices.col(1) *= 0.9;  // top at 0.09 instead of 0.10
  rt::ErrorOptions o;
  o.bottom_y = -0.05;
  const rt::ErrorFunction e(target, 0, target.faces, target.vertex_count(), o);
  rt::ErrorBreakdown br;
  e.evaluate(shorter.vertices, 0, &br);
  EXPECT_GT(br.penalty_term, 0.0);
  const double spacing = (0.09 - (-0.05)) / (o.samples - 1);
  EXPECT_NEAR(br.penalty_term, br.half_planes * o.penalty * 0.01 / spacing, 1e-9);
}

TEST(ErrorFunction, TopYLimitsTheSampledRange) {
  // Spheroids as in the analytic test, sampled only in [y_end, top_y]: no penalty (both curves cover it).
  const double b = 0.1, r1 = 0.09, r2 = 0.08;
  const auto target = ellipsoid(r2, b, r2, 100, 128);
  const auto source = ellipsoid(r1, b, r1, 100, 128);
  rt::ErrorOptions o;
  o.planes = 2;
  o.samples = 5;
  o.front_half_angle = 0.1;  // only azimuth 0
  o.bottom_y = 0.0;
  o.top_y = 0.06;
  const rt::ErrorFunction e(target, 0, source.faces, source.vertex_count(), o);
  ASSERT_EQ(e.azimuths().size(), 1u);
  double expected = 0;
  for (int j = 0; j < 5; ++j) {
    const double y = 0.06 - j * 0.015;
    expected += (r1 - r2) * (r1 - r2) * (1 - y * y / (b * b));
  }
  rt::ErrorBreakdown br;
  EXPECT_NEAR(e.evaluate(source.vertices, 0, &br), expected, 0.02 * expected);
  EXPECT_EQ(br.penalty_term, 0.0);
}

TEST(ErrorFunction, RejectsBadOptions) {
  const auto m = ellipsoid(0.1, 0.1, 0.1, 8, 8);
  rt::ErrorOptions o;
  o.planes = 1;
  EXPECT_THROW(rt::ErrorFunction(m, 0, m.faces, m.vertex_count(), o), emoface::InvalidInput);
  o = {};
  o.samples = 1;
  EXPECT_THROW(o.validate(), emoface::InvalidInput);
  o = {};
  o.top_y = -2e300;
  EXPECT_THROW(o.validate(), emoface::InvalidInput);
  o = {};
  o.penalty = std::nan("");
  EXPECT_THROW(o.validate(), emoface::InvalidInput);
  EXPECT_THROW(rt::ErrorFunction(m, 999, m.faces, m.vertex_count()), emoface::InvalidInput);
}

TEST(ErrorFunction, BandSamplesAddTheirAnalyticTerm) {
  // As above plus b_s band samples at y_k = top − (top − bottom)(k + ½)/b_s inside [bottom, top].
  const double b = 0.1, r1 = 0.09, r2 = 0.08, y_end = -0.05, band_lo = -0.04, band_hi = 0.0;
  const auto target = ellipsoid(r2, b, r2, 200, 256);
  const auto source = ellipsoid(r1, b, r1, 200, 256);
  rt::ErrorOptions o;
  o.planes = 4;
  o.samples = 11;
  o.front_half_angle = 3.14159265358979323846;
  o.bottom_y = y_end;
  const double plain = rt::ErrorFunction(target, 0, source.faces, source.vertex_count(), o).evaluate(source.vertices, 0);
  o.band_samples = 6;
  o.band_bottom = band_lo;
  o.band_top = band_hi;
  const rt::ErrorFunction e(target, 0, source.faces, source.vertex_count(), o);
  double band = 0.0;
  for (int k = 0; k < o.band_samples; ++k) {
    const double y = band_hi - (band_hi - band_lo) * (k + 0.5) / o.band_samples;
    band += 8 * (r1 - r2) * (r1 - r2) * (1 - y * y / (b * b));
  }
  const double got = e.evaluate(source.vertices, 0);
  EXPECT_NEAR(got - plain, band, 0.03 * band);
  EXPECT_EQ(e.residual_count(), 8u * (11u + 6u + 1u));
  // A band outside the common range contributes nothing; a band without extent is refused.
  o.band_bottom = -0.5;
  o.band_top = -0.3;
  EXPECT_NEAR(rt::ErrorFunction(target, 0, source.faces, source.vertex_count(), o).evaluate(source.vertices, 0), plain, 1e-15);
  o.band_top = o.band_bottom;
  EXPECT_THROW(o.validate(), emoface::InvalidInput);
}
