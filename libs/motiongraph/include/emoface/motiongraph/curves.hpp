#pragma once
// Curve tools used for cleaning (paper §4: a sigmoid fitted to each landmark's displacement per
// sample, least squares) and for smoothing synthesized motion (§5 step 4: Savitzky–Golay, then
// sigmoid fitting).
#include <string>

#include <Eigen/Core>

namespace emoface::motiongraph {

/// y(t) = offset + amplitude / (1 + exp(−slope·(t − midpoint))), one offset/amplitude per column
/// (coordinate) sharing slope and midpoint (one landmark moves along one time course).
struct SigmoidCurve {
  double slope = 1.0;        ///< 1/frame
  double midpoint = 0.0;     ///< frames
  Eigen::VectorXd offset;     ///< per coordinate
  Eigen::VectorXd amplitude;  ///< per coordinate
  /// T by columns values at the given times (frames).
  Eigen::MatrixXd evaluate(const Eigen::VectorXd& times) const;
};

/// How fit_sigmoid solves the least-squares problem.
enum class SigmoidSolver {
  Ceres,               ///< Levenberg–Marquardt on all parameters, slope and midpoint boxed
                       ///< (core::solve_bounded_lm, derivatives by Ceres' Jets; the paper's
                       ///< cleaning, §4). Named "ceres" for files and flags written before.
  VariableProjection,  ///< offsets/amplitudes in closed form, LM on (slope, midpoint) only: same
                       ///< minimum, ~100× faster; used for smoothing synthesized motion (§5 step 4)
};
std::string to_string(SigmoidSolver solver);
/// "ceres" | "variable_projection"; throws InvalidInput otherwise.
SigmoidSolver sigmoid_solver_from_string(const std::string& name);

struct SigmoidFitOptions {
  SigmoidSolver solver = SigmoidSolver::Ceres;
  int max_iterations = 50;    ///< Levenberg–Marquardt iterations, >= 1
  double max_slope = 10.0;    ///< upper bound of slope (1/frame), > 1e-3; lower bound is 1e-3
  double function_tolerance = 1e-6;  ///< stop when the relative cost decrease is below, (0, 1)
                                     ///< (Ceres' default)
  /// Variable projection only: also stop when the Gauss–Newton model predicts that the RMS residual
  /// can still drop by less than this (data units, >= 0; 0 = off).
  double rms_tolerance = 0.0;
  void validate() const;
};

struct SigmoidFitReport {
  bool converged = false;
  int iterations = 0;
  double initial_cost = 0.0;  ///< ½ Σ residual²
  double final_cost = 0.0;
  double rms = 0.0;           ///< root mean square residual (data units)
  std::string message;
};

/// Least-squares sigmoid fit of the T by m samples `values` at frames 0..T−1. T >= 2.
/// Non-convergence is reported, not thrown; NaN input throws InvalidInput.
SigmoidCurve fit_sigmoid(const Eigen::MatrixXd& values, const SigmoidFitOptions& options = {},
                         SigmoidFitReport* report = nullptr);

/// Savitzky–Golay smoothing coefficients (window odd >= 3, 0 <= order < window): weights c_k,
/// k = −h..h (h = window/2), of the least-squares polynomial value at the window centre.
/// Example: window 5, order 2 → (−3, 12, 17, 12, −3)/35.
Eigen::VectorXd savitzky_golay_coefficients(int window, int order);

/// Smooths every column of a T by m series. Interior samples use the centred filter; the first and
/// last h samples take the value of the polynomial fitted to the first/last full window. Series
/// shorter than the window are fitted with one polynomial of degree min(order, T−1).
Eigen::MatrixXd savitzky_golay(const Eigen::MatrixXd& series, int window, int order);

/// Linear resampling of a T by m series to `length` rows (>= 1), end points preserved.
Eigen::MatrixXd resample_linear(const Eigen::MatrixXd& series, Eigen::Index length);

}  // namespace emoface::motiongraph
