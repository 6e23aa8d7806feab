#include "emoface/retarget/ga.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"

namespace rt = emoface::retarget;

namespace {
// E = |x − goal|² summed over landmarks (a bowl), goal inside the search cube.
struct Bowl {
  Eigen::MatrixX3d goal;
  double operator()(Eigen::MatrixX3d& p) const { return (p - goal).squaredNorm() + 1e-9; }
};
}  // namespace

TEST(Ga, ConvergesOnABowlAndReportsTheCurve) {
  Eigen::MatrixX3d init = Eigen::MatrixX3d::Zero(4, 3);
  Bowl bowl{Eigen::MatrixX3d::Constant(4, 3, 0.006)};
  rt::GaOptions o;
  o.generations = 60;
  o.projection = rt::ProjectionMode::Off;
  o.cube_size = 0.03;
  const auto r = rt::run_ga(init, bowl, o);
  EXPECT_EQ(r.report.generations, 60);
  ASSERT_EQ(r.report.error_curve.size(), 61u);
  for (std::size_t g = 1; g < r.report.error_curve.size(); ++g) EXPECT_LE(r.report.error_curve[g], r.report.error_curve[g - 1]);
  EXPECT_LT(r.report.best_error, 0.05 * r.report.initial_error);
  EXPECT_LT((r.positions - bowl.goal).cwiseAbs().maxCoeff(), 0.003);
  for (double m : r.report.mutation_curve) {
    EXPECT_GE(m, 0.3);
    EXPECT_LE(m, 0.5);
  }
  EXPECT_EQ(r.report.evaluations, 1 + 32 + 60 * 31);  // initial + population + (population − elite) per generation
}

TEST(Ga, DeterministicForASeedAndDifferentOtherwise) {
  Eigen::MatrixX3d init = Eigen::MatrixX3d::Zero(3, 3);
  Bowl bowl{Eigen::MatrixX3d::Constant(3, 3, 0.004)};
  rt::GaOptions o;
  o.generations = 10;
  const auto a = rt::run_ga(init, bowl, o), b = rt::run_ga(init, bowl, o);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.report.error_curve, b.report.error_curve);
  o.seed = 2;
  const auto c = rt::run_ga(init, bowl, o);
  EXPECT_NE(a.report.error_curve, c.report.error_curve);
}

TEST(Ga, InitialLandmarksAreRepresentableAndNeverWorsened) {
  // Minimum exactly at the initial positions: the GA must return them.
  Eigen::MatrixX3d init(2, 3);
  init << 0.1, 0.2, 0.3, -0.1, 0.05, 0.0;
  Bowl bowl{init};
  rt::GaOptions o;
  o.generations = 5;
  const auto r = rt::run_ga(init, bowl, o);
  EXPECT_LT((r.positions - init).norm(), 1e-12);
  EXPECT_NEAR(r.report.best_error, 1e-9, 1e-15);
}

TEST(Ga, ProjectionModes) {
  // "Projection" snaps z to 0. Replace writes it back (the chromosome loses z diversity);
  // EvaluateOnly keeps the chromosome; both return projected positions.
  Eigen::MatrixX3d init = Eigen::MatrixX3d::Zero(2, 3);
  Eigen::MatrixX3d goal = Eigen::MatrixX3d::Constant(2, 3, 0.005);
  goal.col(2).setZero();
  for (auto mode : {rt::ProjectionMode::EvaluateOnly, rt::ProjectionMode::Replace}) {
    rt::GaOptions o;
    o.generations = 30;
    o.projection = mode;
    const auto r = rt::run_ga(init, [&](Eigen::MatrixX3d& p) {
      p.col(2).setZero();
      return (p - goal).squaredNorm() + 1e-9;
    }, o);
    EXPECT_EQ(r.positions.col(2).cwiseAbs().maxCoeff(), 0.0) << rt::to_string(mode);
    EXPECT_LT(r.report.best_error, r.report.initial_error) << rt::to_string(mode);
  }
  for (auto m : {rt::ProjectionMode::Off, rt::ProjectionMode::EvaluateOnly, rt::ProjectionMode::Replace})
    EXPECT_EQ(rt::projection_mode_from_string(rt::to_string(m)), m);
  EXPECT_THROW(rt::projection_mode_from_string("both"), emoface::InvalidInput);
}

TEST(Ga, PatienceStopsEarlyAndNonFiniteErrorsAreWorst) {
  Eigen::MatrixX3d init = Eigen::MatrixX3d::Zero(1, 3);
  rt::GaOptions o;
  o.generations = 100;
  o.patience = 3;
  const auto r = rt::run_ga(init, [](Eigen::MatrixX3d& p) { return p(0, 0) > 0 ? std::nan("") : 1.0; }, o);
  EXPECT_EQ(r.report.status, "converged");
  EXPECT_EQ(r.report.generations, 3);
  EXPECT_EQ(r.report.best_error, 1.0);
}

TEST(Ga, RejectsBadOptions) {
  Eigen::MatrixX3d init = Eigen::MatrixX3d::Zero(1, 3);
  auto f = [](Eigen::MatrixX3d&) { return 1.0; };
  rt::GaOptions o;
  o.bits = 1;
  EXPECT_THROW(rt::run_ga(init, f, o), emoface::InvalidInput);
  o = {};
  o.mutation_rate = 0.6;
  EXPECT_THROW(o.validate(), emoface::InvalidInput);
  o = {};
  o.population = 2;
  EXPECT_THROW(o.validate(), emoface::InvalidInput);
  o = {};
  o.cube_size = 0;
  EXPECT_THROW(o.validate(), emoface::InvalidInput);
  EXPECT_THROW(rt::run_ga(Eigen::MatrixX3d(0, 3), f), emoface::InvalidInput);
  EXPECT_THROW(rt::run_ga(init, rt::GaEvaluate{}), emoface::InvalidInput);
}
