#include "emoface/motiongraph/curves.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "emoface/core/errors.hpp"

namespace emoface::motiongraph {
namespace {

// Tabulated Savitzky–Golay smoothing weights (Savitzky & Golay 1964, table I; Orfanidis 1996 §8.3).
TEST(SavitzkyGolay, KnownCoefficients) {
  Eigen::VectorXd c = savitzky_golay_coefficients(5, 2) * 35.0;
  const double e5[] = {-3, 12, 17, 12, -3};
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(c[i], e5[i], 1e-10);
  c = savitzky_golay_coefficients(7, 2) * 21.0;
  const double e7[] = {-2, 3, 6, 7, 6, 3, -2};
  for (int i = 0; i < 7; ++i) EXPECT_NEAR(c[i], e7[i], 1e-10);
  c = savitzky_golay_coefficients(9, 4) * 429.0;
  const double e9[] = {15, -55, 30, 135, 179, 135, 30, -55, 15};
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(c[i], e9[i], 1e-9);
  c = savitzky_golay_coefficients(5, 0);
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(c[i], 0.2, 1e-12);
  // order 3 equals order 2 for the centre value
  EXPECT_NEAR((savitzky_golay_coefficients(7, 3) - savitzky_golay_coefficients(7, 2)).norm(), 0.0, 1e-10);
}

TEST(SavitzkyGolay, PreservesPolynomialsAndSmoothsNoise) {
  Eigen::MatrixXd q(12, 2);
  for (int t = 0; t < 12; ++t) q.row(t) << 0.5 * t * t - 3 * t + 1, 2.0 * t;
  EXPECT_NEAR((savitzky_golay(q, 5, 2) - q).norm(), 0.0, 1e-9);  // interior and edges
  Eigen::MatrixXd zig(20, 1);
  for (int t = 0; t < 20; ++t) zig(t, 0) = (t % 2 ? 1.0 : -1.0);
  EXPECT_LT(savitzky_golay(zig, 5, 2).middleRows(2, 16).cwiseAbs().maxCoeff(), 0.6);
  Eigen::MatrixXd short_series(3, 1);
  short_series << 1, 2, 3;
  EXPECT_NEAR((savitzky_golay(short_series, 7, 2) - short_series).norm(), 0.0, 1e-9);
}

TEST(SavitzkyGolay, BadArguments) {
  EXPECT_THROW(savitzky_golay_coefficients(4, 2), InvalidInput);
  EXPECT_THROW(savitzky_golay_coefficients(1, 0), InvalidInput);
  EXPECT_THROW(savitzky_golay_coefficients(5, 5), InvalidInput);
  EXPECT_THROW(savitzky_golay_coefficients(5, -1), InvalidInput);
}

TEST(Sigmoid, RecoversKnownParameters) {
  SigmoidCurve truth;
  truth.slope = 0.8;
  truth.midpoint = 7.5;
  truth.offset = Eigen::Vector2d(1.0, -2.0);
  truth.amplitude = Eigen::Vector2d(10.0, -4.0);
  Eigen::VectorXd t(20);
  for (int i = 0; i < 20; ++i) t[i] = i;
  const Eigen::MatrixXd y = truth.evaluate(t);
  SigmoidFitReport rep;
  const SigmoidCurve fit = fit_sigmoid(y, {}, &rep);
  EXPECT_TRUE(rep.converged) << rep.message;
  EXPECT_NEAR(fit.slope, 0.8, 1e-4);
  EXPECT_NEAR(fit.midpoint, 7.5, 1e-4);
  EXPECT_NEAR((fit.offset - truth.offset).norm(), 0.0, 1e-4);
  EXPECT_NEAR((fit.amplitude - truth.amplitude).norm(), 0.0, 1e-4);
  EXPECT_LT(rep.rms, 1e-6);
  EXPECT_LE(rep.final_cost, rep.initial_cost);
}

TEST(Sigmoid, NoisyDataReducesError) {
  Eigen::MatrixXd y(15, 1);
  for (int i = 0; i < 15; ++i) y(i, 0) = 5.0 / (1.0 + std::exp(-(i - 6.0))) + ((i % 2) ? 0.3 : -0.3);
  SigmoidFitReport rep;
  fit_sigmoid(y, {}, &rep);
  EXPECT_LT(rep.rms, 0.35);
  EXPECT_GT(rep.rms, 0.2);  // the zigzag cannot be fitted
}

TEST(Sigmoid, BadInput) {
  EXPECT_THROW(fit_sigmoid(Eigen::MatrixXd::Zero(1, 1)), InvalidInput);
  Eigen::MatrixXd y = Eigen::MatrixXd::Zero(5, 1);
  y(2, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(fit_sigmoid(y), InvalidInput);
  SigmoidFitOptions o;
  o.max_iterations = 0;
  EXPECT_THROW(fit_sigmoid(Eigen::MatrixXd::Zero(5, 1), o), InvalidInput);
}

TEST(Resample, LinearInterpolation) {
  Eigen::MatrixXd s(3, 1);
  s << 0, 10, 40;
  const Eigen::MatrixXd r = resample_linear(s, 5);
  const double e[] = {0, 5, 10, 25, 40};
  for (int i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(r(i, 0), e[i]);
  EXPECT_DOUBLE_EQ(resample_linear(s, 2)(1, 0), 40.0);
  EXPECT_DOUBLE_EQ(resample_linear(s, 1)(0, 0), 0.0);
  EXPECT_THROW(resample_linear(s, 0), InvalidInput);
}

}  // namespace
}  // namespace emoface::motiongraph
