#include "emoface/retarget/rbf.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"

namespace rt = emoface::retarget;

namespace {
Eigen::MatrixX3d random_points(int n, std::uint64_t seed, double scale = 0.1) {
  emoface::core::Rng rng(seed);
  Eigen::MatrixX3d p(n, 3);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) p(i, k) = rng.uniform(-scale, scale);
  return p;
}
}  // namespace

TEST(Rbf, WidthsAreNearestNeighbourDistances) {
  Eigen::MatrixX3d c(3, 3);
  c << 0, 0, 0, 1, 0, 0, 0, 3, 0;
  const auto s = rt::multiquadric_widths(c);
  EXPECT_DOUBLE_EQ(s[0], 1.0);
  EXPECT_DOUBLE_EQ(s[1], 1.0);
  EXPECT_DOUBLE_EQ(s[2], 3.0);
  const auto h = rt::multiquadric_matrix(c, s);
  EXPECT_DOUBLE_EQ(h(0, 2), std::sqrt(9.0 + 9.0));  // |μ0 − μ2|² + s_2²
  EXPECT_DOUBLE_EQ(h(2, 0), std::sqrt(9.0 + 1.0));
}

TEST(Rbf, HandComputedTwoCentreCase) {
  // μ = (0,0,0), (1,0,0); s = 1; H = [[1, √2], [√2, 1]]; x targets (1, 2) → w = H⁻¹ t = (2√2 − 1, √2 − 2).
  Eigen::MatrixX3d src(2, 3), dst(2, 3);
  src << 0, 0, 0, 1, 0, 0;
  dst << 1, 0, 0, 2, 0, 0;
  rt::RbfOptions o;
  o.regularization = 0.0;
  o.target = rt::RbfTarget::Position;
  const auto net = rt::fit_rbf(src, dst, o);
  const double r2 = std::sqrt(2.0);
  EXPECT_NEAR(net.weights()(0, 0), 2 * r2 - 1, 1e-12);
  EXPECT_NEAR(net.weights()(1, 0), r2 - 2, 1e-12);
  const Eigen::Vector3d mid = net.evaluate(Eigen::Vector3d(0.5, 0, 0));
  EXPECT_NEAR(mid.x(), (3 * r2 - 3) * std::sqrt(1.25), 1e-12);
  EXPECT_NEAR(mid.y(), 0.0, 1e-12);
}

TEST(Rbf, InterpolatesCentresExactlyWithoutRegularisation) {
  const Eigen::MatrixX3d src = random_points(22, 1), dst = src + 0.02 * random_points(22, 2);
  for (auto mode : {rt::RbfTarget::Position, rt::RbfTarget::Displacement}) {
    rt::RbfOptions o;
    o.regularization = 0.0;
    o.target = mode;
    const auto net = rt::fit_rbf(src, dst, o);
    emoface::facemesh::Vertices v = src;
    const auto out = net.evaluate(v);
    EXPECT_LT((out - dst).cwiseAbs().maxCoeff(), 1e-10) << rt::to_string(mode);
  }
}

TEST(Rbf, DisplacementModeIsIdentityForIdenticalLandmarks) {
  const auto src = random_points(10, 3);
  const auto net = rt::fit_rbf(src, src);
  const Eigen::Vector3d p(0.3, -0.2, 0.5);
  EXPECT_LT((net.evaluate(p) - p).norm(), 1e-12);
}

TEST(Rbf, RegularisationShrinksWeightsAndStopsInterpolating) {
  const Eigen::MatrixX3d src = random_points(15, 4), dst = src + 0.03 * random_points(15, 5);
  double previous = std::numeric_limits<double>::infinity();
  for (double reg : {0.0, 1e-6, 1e-3, 1e-1}) {
    rt::RbfOptions o;
    o.regularization = reg;
    const auto net = rt::fit_rbf(src, dst, o);
    const double norm = net.weights().norm();
    EXPECT_LT(norm, previous) << reg;
    previous = norm;
  }
  rt::RbfOptions strong;
  strong.regularization = 1e-1;
  const auto net = rt::fit_rbf(src, dst, strong);
  emoface::facemesh::Vertices v = src;
  EXPECT_GT((net.evaluate(v) - dst).norm(), 1e-4);
}

TEST(Rbf, ClusteredCentresStillSolveAccurately) {
  // Two tight clusters far apart: H is badly conditioned, QR still interpolates.
  Eigen::MatrixX3d src = random_points(12, 6, 1e-3);
  src.bottomRows(6).array() += 1.0;
  const double cond = rt::multiquadric_condition(src);
  EXPECT_GT(cond, 1e3);
  EXPECT_TRUE(std::isfinite(cond));
  const Eigen::MatrixX3d dst = src + 1e-4 * random_points(12, 7);
  rt::RbfOptions o;
  o.regularization = 0.0;
  const auto net = rt::fit_rbf(src, dst, o);
  emoface::facemesh::Vertices v = src;
  EXPECT_LT((net.evaluate(v) - dst).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(Rbf, RejectsBadInput) {
  Eigen::MatrixX3d one(1, 3);
  one << 0, 0, 0;
  EXPECT_THROW(rt::fit_rbf(one, one), emoface::InvalidInput);
  Eigen::MatrixX3d dup(2, 3);
  dup << 1, 2, 3, 1, 2, 3;
  EXPECT_THROW(rt::fit_rbf(dup, dup), emoface::InvalidInput);
  const auto a = random_points(4, 8), b = random_points(5, 9);
  EXPECT_THROW(rt::fit_rbf(a, b), emoface::InvalidInput);
  auto nan = a;
  nan(2, 1) = std::nan("");
  EXPECT_THROW(rt::fit_rbf(a, nan), emoface::InvalidInput);
  rt::RbfOptions bad;
  bad.regularization = -1;
  EXPECT_THROW(rt::fit_rbf(a, a, bad), emoface::InvalidInput);
  EXPECT_EQ(rt::rbf_target_from_string(rt::to_string(rt::RbfTarget::Position)), rt::RbfTarget::Position);
  EXPECT_EQ(rt::rbf_target_from_string("displacement"), rt::RbfTarget::Displacement);
  EXPECT_THROW(rt::rbf_target_from_string("x"), emoface::InvalidInput);
}
