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

TEST(Sigmoid, VariableProjectionRecoversParametersAndAgreesWithCeres) {
  SigmoidCurve truth;
  truth.slope = 0.6;
  truth.midpoint = 11.0;
  truth.offset = Eigen::Vector3d(0.0, 5.0, -1.0);
  truth.amplitude = Eigen::Vector3d(3.0, -7.0, 0.5);
  Eigen::VectorXd t(25);
  for (int i = 0; i < 25; ++i) t[i] = i;
  Eigen::MatrixXd y = truth.evaluate(t);
  SigmoidFitOptions vp;
  vp.solver = SigmoidSolver::VariableProjection;
  SigmoidFitReport rep;
  const SigmoidCurve fit = fit_sigmoid(y, vp, &rep);
  EXPECT_TRUE(rep.converged);
  EXPECT_NEAR(fit.slope, 0.6, 1e-4);
  EXPECT_NEAR(fit.midpoint, 11.0, 1e-4);
  EXPECT_NEAR((fit.amplitude - truth.amplitude).norm(), 0.0, 1e-4);
  // Noisy data: both solvers reach the same least-squares cost.
  for (int i = 0; i < 25; ++i) y(i, 1) += (i % 3 - 1) * 0.4;
  SigmoidFitReport a, b;
  fit_sigmoid(y, {}, &a);
  fit_sigmoid(y, vp, &b);
  EXPECT_NEAR(a.final_cost, b.final_cost, 1e-6 * (1.0 + a.final_cost));
  for (SigmoidSolver s : {SigmoidSolver::Ceres, SigmoidSolver::VariableProjection})
    EXPECT_EQ(sigmoid_solver_from_string(to_string(s)), s);
  EXPECT_THROW(sigmoid_solver_from_string("lm"), InvalidInput);
}

TEST(Sigmoid, VariableProjectionStartsFromTheDataAndStopsAtTheRmsTolerance) {
  // Exact sigmoid: the data-driven start (¼, ½, ¾ crossings) is already close, so few iterations.
  SigmoidCurve truth;
  truth.slope = 0.35;
  truth.midpoint = 31.0;
  truth.offset = Eigen::Vector2d(1.0, -2.0);
  truth.amplitude = Eigen::Vector2d(-6.0, 9.0);
  Eigen::VectorXd t(53);
  for (int i = 0; i < 53; ++i) t[i] = i;
  const Eigen::MatrixXd y = truth.evaluate(t);
  SigmoidFitOptions vp;
  vp.solver = SigmoidSolver::VariableProjection;
  SigmoidFitReport rep;
  const SigmoidCurve fit = fit_sigmoid(y, vp, &rep);
  EXPECT_NEAR(fit.slope, 0.35, 1e-5);
  EXPECT_NEAR(fit.midpoint, 31.0, 1e-5);
  EXPECT_LE(rep.iterations, 8);
  // An early-rising, exponential-looking motion (the minimum lies on the midpoint bound): plain
  // Ceres and variable projection agree on the cost; with rms_tolerance the fit stops early but its
  // RMS residual is within a few tolerances of the optimum.
  Eigen::MatrixXd e(30, 2);
  for (int i = 0; i < 30; ++i) {
    e(i, 0) = 4.0 * (1.0 - std::exp(-0.15 * i)) + ((i * 7) % 5 - 2) * 0.05;
    e(i, 1) = -1.5 * (1.0 - std::exp(-0.15 * i)) + ((i * 3) % 5 - 2) * 0.05;
  }
  SigmoidFitReport full, quick, ceres_rep;
  vp.max_iterations = 200;
  fit_sigmoid(e, vp, &full);
  SigmoidFitOptions co;
  co.max_iterations = 200;
  fit_sigmoid(e, co, &ceres_rep);
  EXPECT_NEAR(full.final_cost, ceres_rep.final_cost, 1e-3 * (1.0 + ceres_rep.final_cost));
  vp.rms_tolerance = 0.01;
  fit_sigmoid(e, vp, &quick);
  EXPECT_TRUE(quick.converged);
  EXPECT_LT(quick.iterations, full.iterations);
  EXPECT_LT(quick.rms - full.rms, 0.03) << quick.rms << " " << full.rms << " " << quick.iterations << " "
                                         << full.iterations;
  vp.rms_tolerance = -1.0;
  EXPECT_THROW(fit_sigmoid(e, vp), InvalidInput);
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
