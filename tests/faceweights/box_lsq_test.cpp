#include "emoface/faceweights/box_lsq.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"

namespace emoface::faceweights {
namespace {

// Exhaustive reference: every assignment of each unknown to {lower bound, upper bound, free},
// solving the free unknowns' normal equations by Gaussian elimination; the feasible assignment of
// least cost is the optimum of the strictly convex problem.
std::vector<double> brute_force(const std::vector<double>& a, std::size_t rows, std::size_t cols,
                                const std::vector<double>& b, double lo, double hi, double ridge) {
  auto cost = [&](const std::vector<double>& x) {
    double c = 0;
    for (std::size_t i = 0; i < rows; ++i) {
      double ax = 0;
      for (std::size_t j = 0; j < cols; ++j) ax += a[i * cols + j] * x[j];
      c += 0.5 * (ax - b[i]) * (ax - b[i]);
    }
    for (double v : x) c += 0.5 * ridge * v * v;
    return c;
  };
  std::size_t combos = 1;
  for (std::size_t j = 0; j < cols; ++j) combos *= 3;
  std::vector<double> best;
  double best_cost = std::numeric_limits<double>::infinity();
  for (std::size_t code = 0; code < combos; ++code) {
    std::vector<int> state(cols);
    std::size_t c = code;
    for (std::size_t j = 0; j < cols; ++j, c /= 3) state[j] = static_cast<int>(c % 3);
    std::vector<double> x(cols, 0.0);
    std::vector<std::size_t> free;
    for (std::size_t j = 0; j < cols; ++j) {
      if (state[j] == 0) x[j] = lo;
      else if (state[j] == 1) x[j] = hi;
      else free.push_back(j);
    }
    const std::size_t n = free.size();
    std::vector<double> m(n * (n + 1), 0.0);
    for (std::size_t p = 0; p < n; ++p) {
      for (std::size_t q = 0; q < n; ++q) {
        double s = 0;
        for (std::size_t i = 0; i < rows; ++i) s += a[i * cols + free[p]] * a[i * cols + free[q]];
        m[p * (n + 1) + q] = s + (p == q ? ridge : 0.0);
      }
      double rhs = 0;
      for (std::size_t i = 0; i < rows; ++i) {
        double fixed = 0;
        for (std::size_t j = 0; j < cols; ++j) {
          if (state[j] != 2) fixed += a[i * cols + j] * x[j];
        }
        rhs += a[i * cols + free[p]] * (b[i] - fixed);
      }
      m[p * (n + 1) + n] = rhs;
    }
    for (std::size_t p = 0; p < n; ++p) {  // elimination (SPD: no pivoting needed)
      for (std::size_t q = p + 1; q < n; ++q) {
        const double f = m[q * (n + 1) + p] / m[p * (n + 1) + p];
        for (std::size_t k = p; k <= n; ++k) m[q * (n + 1) + k] -= f * m[p * (n + 1) + k];
      }
    }
    for (std::size_t p = n; p-- > 0;) {
      double s = m[p * (n + 1) + n];
      for (std::size_t k = p + 1; k < n; ++k) s -= m[p * (n + 1) + k] * x[free[k]];
      x[free[p]] = s / m[p * (n + 1) + p];
    }
    bool feasible = true;
    for (double v : x) feasible = feasible && v >= lo - 1e-12 && v <= hi + 1e-12;
    if (feasible && cost(x) < best_cost) {
      best_cost = cost(x);
      best = x;
    }
  }
  return best;
}

TEST(BoxLsq, HandComputedCases) {
  // mean of two observations of one unknown: (0.2 + 0.6) / 2 = 0.4
  BoxLeastSquares one({1, 1}, 2, 1, {0}, {1}, {1e-12, 1e-14, 1000});
  std::vector<double> x;
  auto r = one.solve({0.2, 0.6}, x);
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(x[0], 0.4, 1e-10);
  // the unconstrained optimum 1.6 is clamped to the upper bound
  r = one.solve({1.5, 1.7}, x);
  EXPECT_NEAR(x[0], 1.0, 1e-12);
  EXPECT_NEAR(r.cost, 0.5 * (0.25 + 0.49), 1e-9);
  // identity with b = (2, −1) in [0, 1]²: (1, 0)
  BoxLeastSquares id({1, 0, 0, 1}, 2, 2, {0, 0}, {1, 1});
  r = id.solve({2, -1}, x);
  EXPECT_NEAR(x[0], 1.0, 1e-12);
  EXPECT_NEAR(x[1], 0.0, 1e-12);
  // two equal columns: the ridge splits 0.8 evenly (the smallest-norm solution): 0.4 each
  BoxLeastSquares twin({1, 1}, 1, 2, {0, 0}, {1, 1}, {1e-9, 1e-14, 100000});
  x.clear();
  r = twin.solve({0.8}, x);
  EXPECT_NEAR(x[0], 0.4, 1e-6);
  EXPECT_NEAR(x[1], 0.4, 1e-6);
}

TEST(BoxLsq, MatchesExhaustiveActiveSetEnumeration) {
  core::Rng rng(42, 0);
  for (int trial = 0; trial < 40; ++trial) {
    const std::size_t rows = 6, cols = 4;
    std::vector<double> a(rows * cols), b(rows);
    for (double& v : a) v = rng.uniform(-1.0, 1.0);
    for (double& v : b) v = rng.uniform(-1.5, 1.5);
    const double ridge = 1e-3;
    BoxLeastSquares solver(a, rows, cols, std::vector<double>(cols, 0.0),
                           std::vector<double>(cols, 1.0), {ridge, 1e-13, 100000});
    std::vector<double> x;
    const auto report = solver.solve(b, x);
    ASSERT_TRUE(report.converged) << report.message;
    const auto ref = brute_force(a, rows, cols, b, 0.0, 1.0, ridge);
    ASSERT_EQ(ref.size(), cols);
    for (std::size_t j = 0; j < cols; ++j) EXPECT_NEAR(x[j], ref[j], 1e-8) << trial << ' ' << j;
  }
}

TEST(BoxLsq, WarmStartGivesSameAnswerInFewerSweeps) {
  core::Rng rng(7, 0);
  std::vector<double> a(30 * 20), b(30);
  for (double& v : a) v = rng.uniform(0.0, 1.0);
  for (double& v : b) v = rng.uniform(0.0, 1.0);
  BoxLeastSquares s(a, 30, 20, std::vector<double>(20, 0.0), std::vector<double>(20, 1.0));
  std::vector<double> cold;
  const auto r1 = s.solve(b, cold);
  std::vector<double> warm = cold;
  const auto r2 = s.solve(b, warm);
  EXPECT_TRUE(r1.converged);
  EXPECT_LE(r2.sweeps, 1);
  for (std::size_t j = 0; j < 20; ++j) EXPECT_NEAR(warm[j], cold[j], 1e-9);
}

TEST(BoxLsq, BadInputs) {
  EXPECT_THROW(BoxLeastSquares({1, 2}, 1, 3, {0, 0, 0}, {1, 1, 1}), InvalidInput);
  EXPECT_THROW(BoxLeastSquares({1}, 1, 1, {1}, {0}), InvalidInput);
  EXPECT_THROW(BoxLeastSquares({std::nan("")}, 1, 1, {0}, {1}), InvalidInput);
  EXPECT_THROW(BoxLeastSquares({0}, 1, 1, {0}, {1}, {0.0, 1e-10, 10}), InvalidInput);
  EXPECT_THROW(BoxLeastSquares({1}, 1, 1, {0}, {1}, {-1.0, 1e-10, 10}), InvalidInput);
  BoxLeastSquares s({1}, 1, 1, {0}, {1});
  std::vector<double> x;
  EXPECT_THROW(s.solve({1, 2}, x), InvalidInput);
  EXPECT_THROW(s.solve({std::nan("")}, x), InvalidInput);
}

}  // namespace
}  // namespace emoface::faceweights
