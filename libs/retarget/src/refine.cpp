#include "refine.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <ceres/tiny_solver.h>

namespace emoface::retarget::detail {
namespace {
double sum_squares(const std::vector<double>& r) {
  double s = 0;
  for (double x : r) s += x * x;
  return s;
}

// The residuals of all 3K coordinates for ceres::TinySolver (header-only LM, dense normal
// equations), with a central-difference Jacobian by hand: the objective walks mesh curves, so
// automatic differentiation does not apply. A residual count that changes, or a non-finite value,
// yields NaN residuals, which TinySolver rejects as a step (cost change NaN, ρ not > 0).
struct LandmarkFunction {
  using Scalar = double;
  enum { NUM_RESIDUALS = Eigen::Dynamic, NUM_PARAMETERS = Eigen::Dynamic };

  const ResidualFunction& f;
  Eigen::Index rows;
  int residual_count;
  double step;
  mutable std::vector<double> r, plus, minus;

  int NumResiduals() const { return residual_count; }
  int NumParameters() const { return static_cast<int>(rows * 3); }

  Eigen::MatrixX3d positions(const double* x) const {
    Eigen::MatrixX3d p(rows, 3);
    for (Eigen::Index k = 0; k < rows; ++k)
      for (int c = 0; c < 3; ++c) p(k, c) = x[k * 3 + c];
    return p;
  }
  bool evaluate(Eigen::MatrixX3d p, std::vector<double>& out) const {
    f(p, out);
    if (static_cast<int>(out.size()) != residual_count) return false;
    for (double v : out)
      if (!std::isfinite(v)) return false;
    return true;
  }
  bool operator()(const double* x, double* residuals, double* jacobian) const {
    const Eigen::MatrixX3d p = positions(x);
    if (!evaluate(p, r)) {
      std::fill(residuals, residuals + residual_count, std::numeric_limits<double>::quiet_NaN());
      return false;
    }
    std::copy(r.begin(), r.end(), residuals);
    if (!jacobian) return true;
    const int n = residual_count;
    for (Eigen::Index k = 0; k < rows; ++k)
      for (int c = 0; c < 3; ++c) {
        Eigen::MatrixX3d a = p, b = p;
        a(k, c) += step;
        b(k, c) -= step;
        double* column = jacobian + (k * 3 + c) * n;  // column-major, n rows
        if (!evaluate(a, plus) || !evaluate(b, minus)) {
          std::fill(column, column + n, 0.0);  // no slope where the objective is undefined
          continue;
        }
        for (int i = 0; i < n; ++i) {
          const auto u = static_cast<std::size_t>(i);
          column[i] = (plus[u] - minus[u]) / (2 * step);
        }
      }
    return true;
  }
};

const char* status_name(ceres::TinySolver<LandmarkFunction>::Status status) {
  using Solver = ceres::TinySolver<LandmarkFunction>;
  switch (status) {
    case Solver::GRADIENT_TOO_SMALL:
    case Solver::RELATIVE_STEP_SIZE_TOO_SMALL:
    case Solver::COST_TOO_SMALL:
    case Solver::COST_CHANGE_TOO_SMALL:
      return "CONVERGENCE";
    case Solver::HIT_MAX_ITERATIONS:
      break;
  }
  return "NO_CONVERGENCE";
}
}  // namespace

Eigen::MatrixX3d refine_landmarks(const Eigen::MatrixX3d& start, const ResidualFunction& residuals,
                                  const RefineOptions& options, RefineReport& report) {
  const auto t0 = std::chrono::steady_clock::now();
  report = {};
  report.ran = true;
  std::vector<double> r;
  Eigen::MatrixX3d p0 = start;
  residuals(p0, r);
  report.initial_error = sum_squares(r);
  Eigen::VectorXd x(start.size());
  for (Eigen::Index k = 0; k < start.rows(); ++k)
    for (int c = 0; c < 3; ++c) x[k * 3 + c] = start(k, c);
  const LandmarkFunction function{residuals, start.rows(), static_cast<int>(r.size()),
                                  options.step, {}, {}, {}};
  ceres::TinySolver<LandmarkFunction> solver;
  // TinySolver counts the first evaluation as an iteration and stops at max_num_iterations − 1
  // steps; its function tolerance is absolute (on ‖r‖² − ‖r_new‖²), so it is scaled to Ceres'
  // relative default (1e-6 of the initial cost).
  solver.options.max_num_iterations = options.max_iterations + 1;
  solver.options.function_tolerance = 1e-6 * report.initial_error;
  solver.options.gradient_tolerance = 1e-10;
  solver.options.parameter_tolerance = 1e-8;
  const auto& summary = solver.Solve(function, &x);
  report.status = status_name(summary.status);
  report.iterations = std::max(summary.iterations, 1);
  Eigen::MatrixX3d p = function.positions(x.data());
  residuals(p, r);  // p becomes the symmetrised/projected positions actually used
  report.final_error = sum_squares(r);
  if (!(report.final_error <= report.initial_error)) {
    p = p0;
    report.final_error = report.initial_error;
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return p;
}

}  // namespace emoface::retarget::detail
