#include "emoface/core/bounded_lm.hpp"

#include <ceres/tiny_solver.h>
#include <ceres/tiny_solver_autodiff_function.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"

namespace emoface::core {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A residual function with a hand-written Jacobian, in the TinySolver function concept.
struct Fn {
  using Scalar = double;
  enum { NUM_RESIDUALS = Eigen::Dynamic, NUM_PARAMETERS = Eigen::Dynamic };
  int residuals = 0, parameters = 0;
  // r (size residuals) and, when j is not null, the Jacobian (residuals by parameters, col-major)
  std::function<bool(const double*, double*, double*)> f;
  int NumResiduals() const { return residuals; }
  int NumParameters() const { return parameters; }
  bool operator()(const double* x, double* r, double* j) const { return f(x, r, j); }
};

// Rosenbrock as least squares: r = (10(x1 − x0²), 1 − x0), minimum (1, 1).
Fn rosenbrock() {
  return {2, 2, [](const double* x, double* r, double* j) {
            r[0] = 10.0 * (x[1] - x[0] * x[0]);
            r[1] = 1.0 - x[0];
            if (j) {
              j[0] = -20.0 * x[0];  // ∂r0/∂x0 (column 0)
              j[1] = -1.0;          // ∂r1/∂x0
              j[2] = 10.0;          // ∂r0/∂x1 (column 1)
              j[3] = 0.0;
            }
            return true;
          }};
}

// ½‖Ax − b‖² as a residual function.
Fn linear(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  return {static_cast<int>(a.rows()), static_cast<int>(a.cols()),
          [a, b](const double* x, double* r, double* j) {
            const Eigen::Map<const Eigen::VectorXd> xv(x, a.cols());
            Eigen::Map<Eigen::VectorXd>(r, a.rows()) = a * xv - b;
            if (j) Eigen::Map<Eigen::MatrixXd>(j, a.rows(), a.cols()) = a;
            return true;
          }};
}

TEST(BoundedLm, QuadraticWithAnActiveBound) {
  // f = ½[(x0 − 2)² + (x1 − x0 + 0.5)²] on [0, 1]²: the unconstrained minimum (2, 1.5) lies
  // outside; by hand, x0 = 1 on its bound (∂f/∂x0 = −1 < 0 there: pushing outwards), then
  // x1 = x0 − 0.5 = 0.5 inside, cost ½. Clamping the unconstrained minimum gives (1, 1), cost 0.625.
  Eigen::MatrixXd a(2, 2);
  a << 1, 0, -1, 1;
  const Eigen::Vector2d b(2.0, -0.5);
  Eigen::VectorXd x = Eigen::Vector2d(0.0, 0.0);
  const BoundedLmReport rep =
      solve_bounded_lm(linear(a, b), x, Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1));
  EXPECT_TRUE(rep.converged) << rep.message;
  EXPECT_NEAR(x[0], 1.0, 1e-12);
  EXPECT_NEAR(x[1], 0.5, 1e-7);
  EXPECT_NEAR(rep.final_cost, 0.5, 1e-10);
  EXPECT_NEAR(rep.initial_cost, 0.5 * (4.0 + 0.25), 1e-12);
}

TEST(BoundedLm, RosenbrockInABox) {
  // x0 ≤ 0.5: the valley x1 = x0² is feasible, so by hand the minimum of (1 − x0)² + 100(x1 − x0²)²
  // is x0 = 0.5 (upper bound), x1 = 0.25, cost ½·0.25.
  Eigen::VectorXd x = Eigen::Vector2d(-1.2, 1.0);
  BoundedLmOptions o;
  o.max_iterations = 200;
  BoundedLmReport rep =
      solve_bounded_lm(rosenbrock(), x, Eigen::Vector2d(-1.5, -1.0), Eigen::Vector2d(0.5, 2.0), o);
  EXPECT_TRUE(rep.converged) << rep.message;
  EXPECT_EQ(x[0], 0.5);
  EXPECT_NEAR(x[1], 0.25, 1e-8);
  EXPECT_NEAR(rep.final_cost, 0.125, 1e-12);
  // x1 ≤ 0.09 cuts the valley: on that bound the stationarity of (1 − x0)² + 100(0.09 − x0²)² in x0
  // is 400x0³ − 34x0 − 2 = 0 (root ≈ 0.3173 by hand), and ∂f/∂x1 = 200(x1 − x0²) < 0 there, so the
  // bound is rightly active. Interior stationary points: only (1, 1), outside.
  x = Eigen::Vector2d(-1.2, 0.05);
  o.function_tolerance = 1e-15;  // to check the stationarity to 1e-6
  rep =
      solve_bounded_lm(rosenbrock(), x, Eigen::Vector2d(-2.0, -1.0), Eigen::Vector2d(2.0, 0.09), o);
  EXPECT_TRUE(rep.converged) << rep.message;
  EXPECT_EQ(x[1], 0.09);
  EXPECT_NEAR(400.0 * x[0] * x[0] * x[0] - 34.0 * x[0] - 2.0, 0.0, 1e-6);
  EXPECT_NEAR(x[0], 0.3173, 1e-3);
  EXPECT_LT(200.0 * (x[1] - x[0] * x[0]), 0.0);
  EXPECT_LT(rep.projected_gradient, 1e-6);
}

TEST(BoundedLm, UnboundedMatchesCeresTinySolver) {
  // Infinite bounds: plain Levenberg–Marquardt. Rosenbrock from the classic start reaches (1, 1),
  // as Ceres' TinySolver does on the same function.
  Eigen::VectorXd x = Eigen::Vector2d(-1.2, 1.0);
  BoundedLmOptions o;
  o.max_iterations = 200;
  o.function_tolerance = 1e-14;
  const BoundedLmReport rep = solve_bounded_lm(rosenbrock(), x, Eigen::Vector2d(-kInf, -kInf),
                                               Eigen::Vector2d(kInf, kInf), o);
  EXPECT_TRUE(rep.converged) << rep.message;
  EXPECT_NEAR(x[0], 1.0, 1e-7);
  EXPECT_NEAR(x[1], 1.0, 1e-7);
  const Fn f = rosenbrock();
  ceres::TinySolver<Fn> tiny;
  tiny.options.max_num_iterations = 200;
  tiny.options.function_tolerance = 1e-20;  // absolute in TinySolver
  tiny.options.gradient_tolerance = 1e-14;
  Eigen::VectorXd y = Eigen::Vector2d(-1.2, 1.0);
  tiny.Solve(f, &y);
  EXPECT_NEAR((x - y).norm(), 0.0, 1e-7);
  EXPECT_NEAR((y - Eigen::Vector2d(1.0, 1.0)).norm(), 0.0, 1e-7);
  EXPECT_LE(rep.final_cost, 1e-14);
}

// The same box problem with automatic derivatives: Ceres' TinySolverAutoDiffFunction (statically
// sized, Jets) plugs into the bounded solver unchanged.
struct RosenbrockFunctor {
  template <class T>
  bool operator()(const T* x, T* r) const {
    r[0] = T(10.0) * (x[1] - x[0] * x[0]);
    r[1] = T(1.0) - x[0];
    return true;
  }
};

TEST(BoundedLm, AcceptsCeresAutoDiffFunctions) {
  const RosenbrockFunctor functor;
  const ceres::TinySolverAutoDiffFunction<RosenbrockFunctor, 2, 2> f(functor);
  Eigen::VectorXd x = Eigen::Vector2d(-1.2, 1.0);
  BoundedLmOptions o;
  o.max_iterations = 200;
  const BoundedLmReport rep =
      solve_bounded_lm(f, x, Eigen::Vector2d(-1.5, -1.0), Eigen::Vector2d(0.5, 2.0), o);
  EXPECT_TRUE(rep.converged) << rep.message;
  EXPECT_EQ(x[0], 0.5);
  EXPECT_NEAR(x[1], 0.25, 1e-8);
}

TEST(BoundedLm, AParameterWithoutInfluenceStaysWhereItStarts) {
  // r = (x0 − 0.3, 2(x0 − 0.3)); x1 has a zero Jacobian column (JᵀJ singular): the damping keeps
  // the system solvable, x1 does not move, x0 reaches 0.3.
  Eigen::MatrixXd a(2, 2);
  a << 1, 0, 2, 0;
  Eigen::VectorXd x = Eigen::Vector2d(0.9, 0.7);
  const BoundedLmReport rep = solve_bounded_lm(linear(a, Eigen::Vector2d(0.3, 0.6)), x,
                                               Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1));
  EXPECT_TRUE(rep.converged) << rep.message;
  EXPECT_NEAR(x[0], 0.3, 1e-6);
  EXPECT_EQ(x[1], 0.7);
}

// Independent value: a box-constrained linear least-squares problem solved by enumerating every
// assignment of each coordinate to {lower, upper, free} (3^4 = 81 faces), the free ones by a QR
// solve; the best feasible point is the global minimum (the problem is convex).
TEST(BoundedLm, LinearBoxProblemsMatchExhaustiveFaceEnumeration) {
  Rng rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 7, p = 4;
    Eigen::MatrixXd a(n, p);
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < p; ++j) a(i, j) = rng.normal();
      b[i] = 3.0 * rng.normal();
    }
    const Eigen::VectorXd lo = Eigen::VectorXd::Constant(p, -0.5),
                          hi = Eigen::VectorXd::Constant(p, 1.0);
    double best = kInf;
    Eigen::VectorXd best_x;
    for (int code = 0; code < 81; ++code) {
      Eigen::VectorXd xv(p);
      std::vector<int> free;
      for (int j = 0, c = code; j < p; ++j, c /= 3) {
        if (c % 3 == 0) xv[j] = lo[j];
        if (c % 3 == 1) xv[j] = hi[j];
        if (c % 3 == 2) free.push_back(j);
      }
      if (!free.empty()) {
        Eigen::MatrixXd af(n, static_cast<Eigen::Index>(free.size()));
        Eigen::VectorXd rhs = b;
        for (int j = 0; j < p; ++j) {
          bool is_free = false;
          for (std::size_t k = 0; k < free.size(); ++k)
            if (free[k] == j) af.col(static_cast<Eigen::Index>(k)) = a.col(j), is_free = true;
          if (!is_free) rhs -= a.col(j) * xv[j];
        }
        const Eigen::VectorXd s = af.colPivHouseholderQr().solve(rhs);
        for (std::size_t k = 0; k < free.size(); ++k) xv[free[k]] = s[static_cast<Eigen::Index>(k)];
      }
      if ((xv.array() < lo.array() - 1e-12).any() || (xv.array() > hi.array() + 1e-12).any())
        continue;
      const double c = 0.5 * (a * xv - b).squaredNorm();
      if (c < best) best = c, best_x = xv;
    }
    Eigen::VectorXd x = Eigen::VectorXd::Zero(p);
    BoundedLmOptions o;
    o.max_iterations = 100;
    o.function_tolerance = 1e-15;
    const BoundedLmReport rep = solve_bounded_lm(linear(a, b), x, lo, hi, o);
    EXPECT_TRUE(rep.converged) << trial << ": " << rep.message;
    EXPECT_NEAR(rep.final_cost, best, 1e-9 * (1.0 + best)) << trial;
    EXPECT_LT((x - best_x).cwiseAbs().maxCoeff(), 1e-5) << trial;
  }
}

TEST(BoundedLm, StartOutsideTheBoxIsProjectedAndTheResultNeverCostsMore) {
  Eigen::VectorXd x = Eigen::Vector2d(5.0, -3.0);
  BoundedLmOptions o;
  o.max_iterations = 2;  // stops early: still inside the box, no costlier than the projected start
  const BoundedLmReport rep =
      solve_bounded_lm(rosenbrock(), x, Eigen::Vector2d(-1.5, -1.0), Eigen::Vector2d(0.5, 2.0), o);
  // projected start (0.5, −1): r = (10(−1 − 0.25), 0.5), cost ½(156.25 + 0.25)
  EXPECT_NEAR(rep.initial_cost, 78.25, 1e-12);
  EXPECT_EQ(rep.status, BoundedLmStatus::MaxIterations);
  EXPECT_FALSE(rep.converged);
  EXPECT_EQ(rep.iterations, 2);
  EXPECT_LE(rep.final_cost, rep.initial_cost);
  EXPECT_GE(x[0], -1.5);
  EXPECT_LE(x[0], 0.5);
  EXPECT_GE(x[1], -1.0);
  EXPECT_LE(x[1], 2.0);
}

TEST(BoundedLm, FailedEvaluationsAreRejectedSteps) {
  // The function fails on its 2nd and 3rd calls (the first trial steps): they count as rejected
  // steps (more damping) and the solve still reaches the minimum; a failure at the start is
  // reported.
  int calls = 0;
  Fn base = rosenbrock();
  Fn flaky{2, 2, [&](const double* x, double* r, double* j) {
             ++calls;
             if (calls == 2 || calls == 3) return false;
             return base(x, r, j);
           }};
  Eigen::VectorXd x = Eigen::Vector2d(0.0, 0.0);
  BoundedLmOptions o;
  o.max_iterations = 200;
  BoundedLmReport rep =
      solve_bounded_lm(flaky, x, Eigen::Vector2d(-2, -2), Eigen::Vector2d(0.8, 2), o);
  EXPECT_TRUE(rep.converged) << rep.message;
  EXPECT_NEAR(x[0], 0.8, 1e-9);
  EXPECT_NEAR(x[1], 0.64, 1e-6);
  EXPECT_GE(rep.iterations, rep.accepted + 2);
  Fn nan_at_start{2, 2, [](const double*, double* r, double*) {
                    r[0] = std::nan(""), r[1] = 0.0;
                    return true;
                  }};
  x = Eigen::Vector2d(0.1, 0.2);
  rep = solve_bounded_lm(nan_at_start, x, Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1));
  EXPECT_EQ(rep.status, BoundedLmStatus::Failure);
  EXPECT_FALSE(rep.converged);
  EXPECT_EQ(x, Eigen::VectorXd(Eigen::Vector2d(0.1, 0.2)));
}

TEST(BoundedLm, BadInputAndOptionsThrow) {
  const Fn f = rosenbrock();
  Eigen::VectorXd x = Eigen::Vector2d(0, 0);
  const Eigen::VectorXd lo = Eigen::Vector2d(-1, -1), hi = Eigen::Vector2d(1, 1);
  EXPECT_THROW(solve_bounded_lm(f, x, Eigen::Vector3d(-1, -1, -1), hi), InvalidInput);
  Eigen::VectorXd x3 = Eigen::Vector3d(0, 0, 0);
  EXPECT_THROW(solve_bounded_lm(f, x3, lo, hi), InvalidInput);
  EXPECT_THROW(solve_bounded_lm(f, x, hi, lo), InvalidInput);  // lower > upper
  EXPECT_THROW(solve_bounded_lm(f, x, Eigen::Vector2d(std::nan(""), -1), hi), InvalidInput);
  Eigen::VectorXd bad = Eigen::Vector2d(std::nan(""), 0.0);
  EXPECT_THROW(solve_bounded_lm(f, bad, lo, hi), InvalidInput);
  bad = Eigen::Vector2d(kInf, 0.0);
  EXPECT_THROW(solve_bounded_lm(f, bad, lo, hi), InvalidInput);
  auto invalid = [](auto mutate) {
    BoundedLmOptions o;
    mutate(o);
    EXPECT_THROW(o.validate(), InvalidInput);
  };
  invalid([](BoundedLmOptions& o) { o.max_iterations = 0; });
  invalid([](BoundedLmOptions& o) { o.function_tolerance = 1.0; });
  invalid([](BoundedLmOptions& o) { o.function_tolerance = -1e-3; });
  invalid([](BoundedLmOptions& o) { o.gradient_tolerance = std::nan(""); });
  invalid([](BoundedLmOptions& o) { o.parameter_tolerance = -1.0; });
  invalid([](BoundedLmOptions& o) { o.initial_damping = 0.0; });
  invalid([](BoundedLmOptions& o) { o.min_relative_decrease = 1.0; });
  EXPECT_NO_THROW(BoundedLmOptions{}.validate());
  for (BoundedLmStatus s : {BoundedLmStatus::FunctionTolerance, BoundedLmStatus::GradientTolerance,
                            BoundedLmStatus::ParameterTolerance, BoundedLmStatus::MaxIterations,
                            BoundedLmStatus::DampingTooLarge, BoundedLmStatus::Failure})
    EXPECT_EQ(bounded_lm_status_from_string(to_string(s)), s);
  EXPECT_THROW(bounded_lm_status_from_string("converged"), InvalidInput);
}

}  // namespace
}  // namespace emoface::core
