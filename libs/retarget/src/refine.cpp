#include "refine.hpp"

#include <chrono>

#include <ceres/ceres.h>

namespace emoface::retarget::detail {
namespace {
double sum_squares(const std::vector<double>& r) {
  double s = 0;
  for (double x : r) s += x * x;
  return s;
}

// Central differences by hand (the objective walks mesh curves: Ceres' automatic differentiation does
// not apply), wrapped as one Ceres cost function over all 3K coordinates.
class LandmarkCost final : public ceres::CostFunction {
 public:
  LandmarkCost(const ResidualFunction& f, Eigen::Index rows, int residual_count, double step)
      : f_(f), rows_(rows), step_(step) {
    mutable_parameter_block_sizes()->push_back(static_cast<std::int32_t>(rows * 3));
    set_num_residuals(residual_count);
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    Eigen::MatrixX3d p(rows_, 3);
    for (Eigen::Index k = 0; k < rows_; ++k)
      for (int c = 0; c < 3; ++c) p(k, c) = parameters[0][k * 3 + c];
    std::vector<double> r;
    Eigen::MatrixX3d q = p;
    f_(q, r);
    if (static_cast<int>(r.size()) != num_residuals()) return false;
    std::copy(r.begin(), r.end(), residuals);
    if (jacobians && jacobians[0]) {
      const int n = num_residuals();
      std::vector<double> plus, minus;
      for (Eigen::Index k = 0; k < rows_; ++k)
        for (int c = 0; c < 3; ++c) {
          Eigen::MatrixX3d a = p, b = p;
          a(k, c) += step_;
          b(k, c) -= step_;
          f_(a, plus);
          f_(b, minus);
          const auto col = static_cast<int>(k * 3 + c);
          for (int i = 0; i < n; ++i) jacobians[0][i * rows_ * 3 + col] = (plus[static_cast<std::size_t>(i)] - minus[static_cast<std::size_t>(i)]) / (2 * step_);
        }
    }
    return true;
  }

 private:
  const ResidualFunction& f_;
  Eigen::Index rows_;
  double step_;
};
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
  std::vector<double> x(static_cast<std::size_t>(start.size()));
  for (Eigen::Index k = 0; k < start.rows(); ++k)
    for (int c = 0; c < 3; ++c) x[static_cast<std::size_t>(k * 3 + c)] = start(k, c);
  ceres::Problem problem;
  problem.AddResidualBlock(new LandmarkCost(residuals, start.rows(), static_cast<int>(r.size()), options.step), nullptr, x.data());
  ceres::Solver::Options so;
  so.max_num_iterations = options.max_iterations;
  so.linear_solver_type = ceres::DENSE_QR;
  so.num_threads = 1;
  so.logging_type = ceres::SILENT;
  so.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  report.status = ceres::TerminationTypeToString(summary.termination_type);
  report.iterations = static_cast<int>(summary.iterations.size());
  Eigen::MatrixX3d p(start.rows(), 3);
  for (Eigen::Index k = 0; k < start.rows(); ++k)
    for (int c = 0; c < 3; ++c) p(k, c) = x[static_cast<std::size_t>(k * 3 + c)];
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
