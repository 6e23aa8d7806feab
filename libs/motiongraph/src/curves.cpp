#include "emoface/motiongraph/curves.hpp"

#include <algorithm>
#include <array>
#include <vector>
#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <ceres/jet.h>

#include "emoface/core/bounded_lm.hpp"
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
  if (!(function_tolerance > 0.0 && function_tolerance < 1.0))
    throw InvalidInput("sigmoid fit: function_tolerance must be in (0, 1)");
  if (!(rms_tolerance >= 0.0) || !std::isfinite(rms_tolerance))
    throw InvalidInput("sigmoid fit: rms_tolerance must be finite and >= 0");
}

namespace {

// Residual of one sample of one coordinate: offset + amplitude·σ(slope·(t − midpoint)) − y, for
// doubles and for Ceres' Jets (automatic derivatives).
template <class T>
T sigmoid_residual(const T& slope, const T& midpoint, const T& offset, const T& amplitude, double t,
                   double y) {
  using std::exp;
  const T s = T(1.0) / (T(1.0) + exp(-slope * (T(t) - midpoint)));
  return offset + amplitude * s - T(y);
}

// All residuals (column j, time t at j·T + t) over the parameters (slope, midpoint, offset_0,
// amplitude_0, offset_1, …) in the function concept of ceres::TinySolver / core::solve_bounded_lm.
// Each residual depends on 4 of them, so its derivatives come from a 4-dimensional Jet and are
// scattered into the dense Jacobian.
struct SigmoidFunction {
  using Scalar = double;
  enum { NUM_RESIDUALS = Eigen::Dynamic, NUM_PARAMETERS = Eigen::Dynamic };
  const Eigen::MatrixXd& y;
  int NumResiduals() const { return static_cast<int>(y.size()); }
  int NumParameters() const { return static_cast<int>(2 + 2 * y.cols()); }
  bool operator()(const double* x, double* residuals, double* jacobian) const {
    using Jet = ceres::Jet<double, 4>;
    const Eigen::Index n = y.rows(), rows = y.size();
    if (jacobian) std::fill(jacobian, jacobian + rows * NumParameters(), 0.0);
    for (Eigen::Index j = 0; j < y.cols(); ++j) {
      const Eigen::Index c = 2 + 2 * j;  // offset_j, amplitude_j
      for (Eigen::Index t = 0; t < n; ++t) {
        const Eigen::Index i = j * n + t;
        const double tt = static_cast<double>(t);
        if (!jacobian) {
          residuals[i] = sigmoid_residual(x[0], x[1], x[c], x[c + 1], tt, y(t, j));
          continue;
        }
        const Jet r = sigmoid_residual(Jet(x[0], 0), Jet(x[1], 1), Jet(x[c], 2), Jet(x[c + 1], 3),
                                       tt, y(t, j));
        residuals[i] = r.a;
        jacobian[0 * rows + i] = r.v[0];  // column-major
        jacobian[1 * rows + i] = r.v[1];
        jacobian[c * rows + i] = r.v[2];
        jacobian[(c + 1) * rows + i] = r.v[3];
      }
    }
    return true;
  }
};

}  // namespace

std::string to_string(SigmoidSolver solver) {
  return solver == SigmoidSolver::Ceres ? "ceres" : "variable_projection";
}

SigmoidSolver sigmoid_solver_from_string(const std::string& name) {
  if (name == "ceres") return SigmoidSolver::Ceres;
  if (name == "variable_projection") return SigmoidSolver::VariableProjection;
  throw InvalidInput("unknown sigmoid solver \"" + name + "\" (known: ceres, variable_projection)");
}

namespace {

// Variable projection (Golub & Pereyra 1973): for a given p = (slope k, midpoint m) the offsets c_j
// and amplitudes a_j are a linear least-squares problem in closed form (basis 1, σ(t)); Levenberg–
// Marquardt runs on p alone with Kaufman's (1975) Jacobian J_j = P⊥·a_j·W, where W = ∂σ/∂p =
// [σ(1−σ)(t−m), −σ(1−σ)k] and P⊥ projects out span{1, σ}. Because r_j ⊥ span{1, σ},
// Jᵀr = Σ_j a_j·Wᵀr_j is the exact gradient of the reduced cost (same minimum as the full problem),
// and JᵀJ = (Σ_j a_j²)·(WᵀW − Bᵀ G⁻¹ B) with G = [1 σ]ᵀ[1 σ], B = [1 σ]ᵀW: 2×2 sums, one pass over
// the data per evaluation, no allocation. The projection is what lets the steps follow the curved
// valley where midpoint and amplitude trade off (without it LM crawls there).
struct Projection {
  const Eigen::MatrixXd& y;
  Eigen::Index n;
  mutable std::vector<double> sig;
  // ½‖r‖² for p = (slope, midpoint); with `jtj`/`g`, also JᵀJ and Jᵀr; with `coef` (2 by m: offsets,
  // amplitudes) the linear coefficients.
  double cost(const double p[2], Eigen::Matrix2d* jtj = nullptr, Eigen::Vector2d* g = nullptr,
              Eigen::MatrixXd* coef = nullptr) const {
    sig.resize(static_cast<std::size_t>(n));
    double s1 = 0.0, s2 = 0.0;
    Eigen::Matrix2d wtw = Eigen::Matrix2d::Zero(), b = Eigen::Matrix2d::Zero();  // b: rows 1, σ
    for (Eigen::Index t = 0; t < n; ++t) {
      const double v = 1.0 / (1.0 + std::exp(-p[0] * (static_cast<double>(t) - p[1])));
      sig[static_cast<std::size_t>(t)] = v;
      s1 += v;
      s2 += v * v;
      if (jtj) {
        const double dv = v * (1.0 - v);
        const double w0 = dv * (static_cast<double>(t) - p[1]), w1 = -dv * p[0];
        wtw(0, 0) += w0 * w0;
        wtw(0, 1) += w0 * w1;
        wtw(1, 1) += w1 * w1;
        b(0, 0) += w0, b(0, 1) += w1, b(1, 0) += v * w0, b(1, 1) += v * w1;
      }
    }
    const double nn = static_cast<double>(n), det = nn * s2 - s1 * s1;
    const bool flat = !(det > 1e-12 * (1.0 + nn * s2));
    if (coef) coef->resize(2, y.cols());
    if (g) g->setZero();
    double total = 0.0, a2 = 0.0;
    for (Eigen::Index j = 0; j < y.cols(); ++j) {
      double sy = 0.0, ssy = 0.0;
      for (Eigen::Index t = 0; t < n; ++t) {
        sy += y(t, j);
        ssy += sig[static_cast<std::size_t>(t)] * y(t, j);
      }
      // Flat sigmoid (all samples on one side): offsets only.
      const double c = flat ? sy / nn : (s2 * sy - s1 * ssy) / det;
      const double a = flat ? 0.0 : (nn * ssy - s1 * sy) / det;
      if (coef) (*coef)(0, j) = c, (*coef)(1, j) = a;
      a2 += a * a;
      double g0 = 0.0, g1 = 0.0;
      for (Eigen::Index t = 0; t < n; ++t) {
        const double v = sig[static_cast<std::size_t>(t)];
        const double r = c + a * v - y(t, j);
        total += r * r;
        if (g) {
          const double dv = v * (1.0 - v);
          g0 += dv * (static_cast<double>(t) - p[1]) * r;
          g1 -= dv * p[0] * r;
        }
      }
      if (g) (*g)(0) += a * g0, (*g)(1) += a * g1;
    }
    if (jtj) {
      wtw(1, 0) = wtw(0, 1);
      Eigen::Matrix2d proj = wtw;
      if (!flat) {
        Eigen::Matrix2d gi;  // G⁻¹, G = [[n, s1], [s1, s2]]
        gi << s2, -s1, -s1, nn;
        gi /= det;
        proj -= b.transpose() * gi * b;
      }
      *jtj = a2 * proj;
    }
    return 0.5 * total;
  }
};

// Starting point from the data: the mean progress u(t) of all columns from the first to the last
// sample (projection on y_last − y_first) crosses ½ at the midpoint, and a logistic rises from ¼ to
// ¾ in 2·ln3/slope frames. Falls back to (8/T, (T−1)/2) when the series does not move end to end or
// never crosses.
void initial_guess(const Eigen::MatrixXd& y, double max_slope, double p[2]) {
  const Eigen::Index n = y.rows();
  p[0] = std::min(8.0 / static_cast<double>(n), max_slope);
  p[1] = 0.5 * static_cast<double>(n - 1);
  const Eigen::RowVectorXd first = y.row(0), delta = y.row(n - 1) - first;
  const double dd = delta.squaredNorm();
  if (!(dd > 1e-18)) return;
  auto crossing = [&](double level) {  // first t where u(t) reaches level, linear interpolation
    double prev = 0.0;
    for (Eigen::Index t = 1; t < n; ++t) {
      const double u = (y.row(t) - first).dot(delta) / dd;
      if (u >= level) return static_cast<double>(t - 1) + (level - prev) / std::max(u - prev, 1e-12);
      prev = u;
    }
    return -1.0;
  };
  const double t25 = crossing(0.25), t50 = crossing(0.5), t75 = crossing(0.75);
  if (t50 >= 0.0) p[1] = t50;
  if (t25 >= 0.0 && t75 > t25) p[0] = std::clamp(2.0 * std::log(3.0) / (t75 - t25), 1e-3, max_slope);
}

}  // namespace

// paper §4 (cleaning) and §5 step 4 (smoothing): least-squares sigmoid per landmark.
SigmoidCurve fit_sigmoid(const Eigen::MatrixXd& values, const SigmoidFitOptions& options,
                         SigmoidFitReport* report) {
  options.validate();
  const Eigen::Index n = values.rows(), m = values.cols();
  if (n < 2 || m < 1) throw InvalidInput("sigmoid fit: need at least 2 samples and 1 column");
  if (!values.allFinite()) throw InvalidInput("sigmoid fit: NaN or infinite sample");
  const double lo[2] = {1e-3, -static_cast<double>(n)}, hi[2] = {options.max_slope, 2.0 * static_cast<double>(n)};
  if (options.solver == SigmoidSolver::VariableProjection) {
    const Projection proj{values, n, {}};
    const double nm = static_cast<double>(n * m);
    double p[2];
    initial_guess(values, options.max_slope, p);
    Eigen::Matrix2d jtj;
    Eigen::Vector2d g;
    double cost = proj.cost(p, &jtj, &g), mu = 1e-3;
    SigmoidFitReport rep;
    rep.initial_cost = cost;
    for (rep.iterations = 0; rep.iterations < options.max_iterations; ++rep.iterations) {
      if (g.lpNorm<Eigen::Infinity>() < 1e-12 * (1.0 + cost)) {
        rep.converged = true;
        break;
      }
      if (options.rms_tolerance > 0.0) {
        // Gauss–Newton prediction of the decrease still available, ½gᵀ(JᵀJ)⁻¹g (free parameters
        // only), as an RMS change: below rms_tolerance the curve is settled at that resolution.
        bool free[2];
        for (int k = 0; k < 2; ++k) free[k] = !((p[k] <= lo[k] && g[k] > 0.0) || (p[k] >= hi[k] && g[k] < 0.0));
        double predicted = -1.0;
        const double det2 = jtj(0, 0) * jtj(1, 1) - jtj(0, 1) * jtj(1, 0);
        if (free[0] && free[1] && det2 > 1e-300)
          predicted = 0.5 * g.dot(jtj.inverse() * g);
        else if (free[0] != free[1]) {
          const int k = free[0] ? 0 : 1;
          if (jtj(k, k) > 0.0) predicted = 0.5 * g[k] * g[k] / jtj(k, k);
        } else if (!free[0] && !free[1]) {
          predicted = 0.0;
        }
        if (predicted >= 0.0 &&
            std::sqrt(2.0 * cost / nm) - std::sqrt(2.0 * std::max(cost - predicted, 0.0) / nm) < options.rms_tolerance) {
          rep.converged = true;
          break;
        }
      }
      bool improved = false;
      for (int tries = 0; tries < 10 && !improved; ++tries) {
        Eigen::Matrix2d lhs = jtj;
        lhs.diagonal() += mu * (jtj.diagonal().array() + 1e-12).matrix();
        Eigen::Vector2d step = -lhs.ldlt().solve(g);
        // Active bound: a parameter at its bound that the step pushes outwards is held there and the
        // other one takes its own 1D step (plain clamping crawls along the bound).
        for (int k = 0; k < 2; ++k) {
          const bool out = (p[k] <= lo[k] && step[k] < 0.0) || (p[k] >= hi[k] && step[k] > 0.0);
          if (out) {
            step[k] = 0.0;
            step[1 - k] = -g[1 - k] / lhs(1 - k, 1 - k);
          }
        }
        double q[2] = {std::clamp(p[0] + step[0], lo[0], hi[0]), std::clamp(p[1] + step[1], lo[1], hi[1])};
        Eigen::Matrix2d jq;
        Eigen::Vector2d gq;
        const double cq = proj.cost(q, &jq, &gq);
        if (cq < cost) {
          const double decrease = (cost - cq) / std::max(cost, 1e-300);
          p[0] = q[0], p[1] = q[1], cost = cq, mu = std::max(mu / 3.0, 1e-12), improved = true;
          jtj = jq, g = gq;
          if (decrease < options.function_tolerance) rep.converged = true;
        } else {
          mu *= 4.0;
        }
      }
      if (!improved || rep.converged) {
        rep.converged = true;  // no further decrease possible: a (local) minimum
        break;
      }
    }
    Eigen::MatrixXd coef;
    cost = proj.cost(p, nullptr, nullptr, &coef);
    SigmoidCurve curve;
    curve.slope = p[0];
    curve.midpoint = p[1];
    curve.offset = coef.row(0).transpose();
    curve.amplitude = coef.row(1).transpose();
    rep.final_cost = cost;
    rep.rms = std::sqrt(2.0 * cost / static_cast<double>(n * m));
    rep.message = "variable projection";
    if (report) *report = rep;
    return curve;
  }
  // Start: the step from the first to the last value, centred, slope spanning the series. (The
  // data-driven start of the variable-projection path is not used here: on landmarks that hardly move
  // it lets LM fit the noise with a saturated step, which changes what cleaning keeps.)
  double shape[2] = {std::min(8.0 / static_cast<double>(n), options.max_slope),
                     0.5 * static_cast<double>(n - 1)};
  std::vector<std::array<double, 2>> linear(m);
  for (Eigen::Index j = 0; j < m; ++j) linear[j] = {values(0, j), values(n - 1, j) - values(0, j)};

  // Levenberg–Marquardt with the two shape parameters boxed (core::solve_bounded_lm, the tolerances
  // of Ceres' Solver::Options), derivatives from Ceres' Jets.
  Eigen::VectorXd x(2 + 2 * m), lower(x.size()), upper(x.size());
  x[0] = shape[0];
  x[1] = shape[1];
  lower.setConstant(-std::numeric_limits<double>::infinity());
  upper.setConstant(std::numeric_limits<double>::infinity());
  for (int k = 0; k < 2; ++k) lower[k] = lo[k], upper[k] = hi[k];
  for (Eigen::Index j = 0; j < m; ++j) x[2 + 2 * j] = linear[j][0], x[3 + 2 * j] = linear[j][1];
  core::BoundedLmOptions lm;
  lm.max_iterations = options.max_iterations;
  lm.function_tolerance = options.function_tolerance;
  const core::BoundedLmReport summary =
      core::solve_bounded_lm(SigmoidFunction{values}, x, lower, upper, lm);

  SigmoidCurve curve;
  curve.slope = x[0];
  curve.midpoint = x[1];
  curve.offset.resize(m);
  curve.amplitude.resize(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    curve.offset[j] = x[2 + 2 * j];
    curve.amplitude[j] = x[3 + 2 * j];
  }
  if (report) {
    report->converged = summary.converged;
    report->iterations = summary.iterations;
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
