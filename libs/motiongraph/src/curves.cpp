#include "emoface/motiongraph/curves.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <ceres/ceres.h>

#include "emoface/core/errors.hpp"

namespace emoface::motiongraph {

Eigen::MatrixXd SigmoidCurve::evaluate(const Eigen::VectorXd& times) const {
  Eigen::MatrixXd out(times.size(), offset.size());
  for (Eigen::Index t = 0; t < times.size(); ++t) {
    const double s = 1.0 / (1.0 + std::exp(-slope * (times[t] - midpoint)));
    out.row(t) = (offset + amplitude * s).transpose();
  }
  return out;
}

void SigmoidFitOptions::validate() const {
  if (max_iterations < 1) throw InvalidInput("sigmoid fit: max_iterations must be >= 1");
  if (!(max_slope > 1e-3) || !std::isfinite(max_slope))
    throw InvalidInput("sigmoid fit: max_slope must be finite and > 1e-3");
}

namespace {

// Residual of one sample of one coordinate: offset + amplitude·σ(slope·(t − midpoint)) − y.
struct SigmoidResidual {
  SigmoidResidual(double t, double y) : t_(t), y_(y) {}
  template <class T>
  bool operator()(const T* shape, const T* linear, T* residual) const {
    const T s = T(1.0) / (T(1.0) + ceres::exp(-shape[0] * (T(t_) - shape[1])));
    residual[0] = linear[0] + linear[1] * s - T(y_);
    return true;
  }
  double t_, y_;
};

}  // namespace

// paper §4 (cleaning) and §5 step 4 (smoothing): least-squares sigmoid per landmark.
SigmoidCurve fit_sigmoid(const Eigen::MatrixXd& values, const SigmoidFitOptions& options,
                         SigmoidFitReport* report) {
  options.validate();
  const Eigen::Index n = values.rows(), m = values.cols();
  if (n < 2 || m < 1) throw InvalidInput("sigmoid fit: need at least 2 samples and 1 column");
  if (!values.allFinite()) throw InvalidInput("sigmoid fit: NaN or infinite sample");
  // Start: the step from the first to the last value, centred, slope spanning the series.
  double shape[2] = {std::min(8.0 / static_cast<double>(n), options.max_slope),
                     0.5 * static_cast<double>(n - 1)};
  std::vector<std::array<double, 2>> linear(m);
  for (Eigen::Index j = 0; j < m; ++j) linear[j] = {values(0, j), values(n - 1, j) - values(0, j)};

  ceres::Problem problem;
  for (Eigen::Index j = 0; j < m; ++j)
    for (Eigen::Index t = 0; t < n; ++t)
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<SigmoidResidual, 1, 2, 2>(
              new SigmoidResidual(static_cast<double>(t), values(t, j))),
          nullptr, shape, linear[j].data());
  problem.SetParameterLowerBound(shape, 0, 1e-3);
  problem.SetParameterUpperBound(shape, 0, options.max_slope);
  problem.SetParameterLowerBound(shape, 1, -static_cast<double>(n));
  problem.SetParameterUpperBound(shape, 1, 2.0 * static_cast<double>(n));

  ceres::Solver::Options solver;
  solver.max_num_iterations = options.max_iterations;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.logging_type = ceres::SILENT;
  solver.minimizer_progress_to_stdout = false;
  solver.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);

  SigmoidCurve curve;
  curve.slope = shape[0];
  curve.midpoint = shape[1];
  curve.offset.resize(m);
  curve.amplitude.resize(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    curve.offset[j] = linear[j][0];
    curve.amplitude[j] = linear[j][1];
  }
  if (report) {
    report->converged = summary.termination_type == ceres::CONVERGENCE;
    report->iterations = static_cast<int>(summary.iterations.size());
    report->initial_cost = summary.initial_cost;
    report->final_cost = summary.final_cost;
    report->rms = std::sqrt(2.0 * summary.final_cost / static_cast<double>(n * m));
    report->message = summary.message;
  }
  return curve;
}

// Savitzky–Golay (Orfanidis 1996, §8.3; paper §5 step 4): centre value of the least-squares
// polynomial = row 0 of (AᵀA)⁻¹Aᵀ with A_kj = k^j, k = −h..h.
Eigen::VectorXd savitzky_golay_coefficients(int window, int order) {
  if (window < 3 || window % 2 == 0) throw InvalidInput("Savitzky-Golay: window must be odd and >= 3");
  if (order < 0 || order >= window) throw InvalidInput("Savitzky-Golay: need 0 <= order < window");
  const int h = window / 2;
  Eigen::MatrixXd a(window, order + 1);
  for (int k = -h; k <= h; ++k)
    for (int j = 0; j <= order; ++j) a(k + h, j) = std::pow(static_cast<double>(k), j);
  const Eigen::MatrixXd pinv = (a.transpose() * a).ldlt().solve(a.transpose());
  return pinv.row(0).transpose();
}

namespace {
// Values at positions `at` of the least-squares polynomial of degree `order` through rows
// [first, first + count) of `series` (positions relative to `first`).
Eigen::MatrixXd polynomial_fit(const Eigen::MatrixXd& series, Eigen::Index first, Eigen::Index count,
                               int order, const std::vector<double>& at) {
  Eigen::MatrixXd a(count, order + 1);
  for (Eigen::Index k = 0; k < count; ++k)
    for (int j = 0; j <= order; ++j) a(k, j) = std::pow(static_cast<double>(k), j);
  const Eigen::MatrixXd coef = a.colPivHouseholderQr().solve(series.middleRows(first, count));
  Eigen::MatrixXd out(static_cast<Eigen::Index>(at.size()), series.cols());
  for (std::size_t i = 0; i < at.size(); ++i) {
    Eigen::RowVectorXd p(order + 1);
    for (int j = 0; j <= order; ++j) p[j] = std::pow(at[i], j);
    out.row(static_cast<Eigen::Index>(i)) = p * coef;
  }
  return out;
}
}  // namespace

Eigen::MatrixXd savitzky_golay(const Eigen::MatrixXd& series, int window, int order) {
  const Eigen::VectorXd c = savitzky_golay_coefficients(window, order);
  const Eigen::Index n = series.rows();
  const int h = window / 2;
  if (n == 0) return series;
  if (n < window) {
    std::vector<double> at(n);
    for (Eigen::Index i = 0; i < n; ++i) at[i] = static_cast<double>(i);
    return polynomial_fit(series, 0, n, std::min<int>(order, static_cast<int>(n) - 1), at);
  }
  Eigen::MatrixXd out(n, series.cols());
  for (Eigen::Index i = h; i < n - h; ++i)
    out.row(i) = c.transpose() * series.middleRows(i - h, window);
  std::vector<double> head(h), tail(h);
  for (int i = 0; i < h; ++i) {
    head[i] = i;
    tail[i] = window - h + i;
  }
  out.topRows(h) = polynomial_fit(series, 0, window, order, head);
  out.bottomRows(h) = polynomial_fit(series, n - window, window, order, tail);
  return out;
}

Eigen::MatrixXd resample_linear(const Eigen::MatrixXd& series, Eigen::Index length) {
  if (length < 1) throw InvalidInput("resample: length must be >= 1");
  const Eigen::Index n = series.rows();
  if (n == 0) throw InvalidInput("resample: empty series");
  Eigen::MatrixXd out(length, series.cols());
  for (Eigen::Index i = 0; i < length; ++i) {
    const double x = length == 1 ? 0.0
                                 : static_cast<double>(i) * static_cast<double>(n - 1) /
                                       static_cast<double>(length - 1);
    const Eigen::Index k = std::min<Eigen::Index>(static_cast<Eigen::Index>(x), n - 1);
    const double f = x - static_cast<double>(k);
    out.row(i) = k + 1 < n ? ((1.0 - f) * series.row(k) + f * series.row(k + 1)).eval()
                           : series.row(k).eval();
  }
  return out;
}

}  // namespace emoface::motiongraph
