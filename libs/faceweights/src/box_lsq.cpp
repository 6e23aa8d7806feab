#include "emoface/faceweights/box_lsq.hpp"

#include <algorithm>
#include <cmath>

#include "emoface/core/errors.hpp"

namespace emoface::faceweights {

void BoxLsqOptions::validate() const {
  if (!(ridge >= 0.0) || !std::isfinite(ridge)) throw InvalidInput("BoxLsqOptions: ridge must be >= 0");
  if (!(tolerance > 0.0)) throw InvalidInput("BoxLsqOptions: tolerance must be > 0");
  if (max_sweeps < 1) throw InvalidInput("BoxLsqOptions: max_sweeps must be >= 1");
}

BoxLeastSquares::BoxLeastSquares(std::vector<double> a, std::size_t rows, std::size_t cols,
                                 std::vector<double> lo, std::vector<double> hi,
                                 BoxLsqOptions options)
    : a_(std::move(a)), lo_(std::move(lo)), hi_(std::move(hi)), rows_(rows), cols_(cols),
      options_(options) {
  options_.validate();
  if (cols_ == 0) throw InvalidInput("BoxLeastSquares: no unknowns");
  if (a_.size() != rows_ * cols_) throw InvalidInput("BoxLeastSquares: A must have rows*cols values");
  if (lo_.size() != cols_ || hi_.size() != cols_)
    throw InvalidInput("BoxLeastSquares: one bound pair per unknown");
  for (std::size_t j = 0; j < cols_; ++j) {
    if (!(lo_[j] <= hi_[j]) || !std::isfinite(lo_[j]) || !std::isfinite(hi_[j]))
      throw InvalidInput("BoxLeastSquares: bounds must be finite with lo <= hi");
  }
  for (double v : a_) {
    if (!std::isfinite(v)) throw InvalidInput("BoxLeastSquares: A must be finite");
  }
  h_.assign(cols_ * cols_, 0.0);
  for (std::size_t i = 0; i < cols_; ++i) {
    for (std::size_t j = 0; j < cols_; ++j) {
      double s = 0.0;
      for (std::size_t r = 0; r < rows_; ++r) s += a_[r * cols_ + i] * a_[r * cols_ + j];
      h_[i * cols_ + j] = s;
    }
    h_[i * cols_ + i] += options_.ridge;
    if (!(h_[i * cols_ + i] > 0.0))
      throw InvalidInput("BoxLeastSquares: unknown " + std::to_string(i) +
                         " has a zero column and ridge 0 (give ridge > 0)");
  }
}

namespace {

// Solves the SPD system m·y = rhs (n×n, row-major) in place by Cholesky; false if not SPD.
bool cholesky_solve(std::vector<double>& m, std::vector<double>& rhs, std::size_t n) {
  for (std::size_t j = 0; j < n; ++j) {
    double d = m[j * n + j];
    for (std::size_t k = 0; k < j; ++k) d -= m[j * n + k] * m[j * n + k];
    if (!(d > 0.0)) return false;
    d = std::sqrt(d);
    m[j * n + j] = d;
    for (std::size_t i = j + 1; i < n; ++i) {
      double s = m[i * n + j];
      for (std::size_t k = 0; k < j; ++k) s -= m[i * n + k] * m[j * n + k];
      m[i * n + j] = s / d;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    double s = rhs[i];
    for (std::size_t k = 0; k < i; ++k) s -= m[i * n + k] * rhs[k];
    rhs[i] = s / m[i * n + i];
  }
  for (std::size_t i = n; i-- > 0;) {
    double s = rhs[i];
    for (std::size_t k = i + 1; k < n; ++k) s -= m[k * n + i] * rhs[k];
    rhs[i] = s / m[i * n + i];
  }
  return true;
}

}  // namespace

BoxLsqReport BoxLeastSquares::solve(const std::vector<double>& b, std::vector<double>& x) const {
  if (b.size() != rows_) throw InvalidInput("BoxLeastSquares::solve: b must have rows values");
  for (double v : b) {
    if (!std::isfinite(v)) throw InvalidInput("BoxLeastSquares::solve: b must be finite");
  }
  const std::size_t n = cols_;
  if (x.size() != n) x.assign(n, 0.0);
  for (std::size_t j = 0; j < n; ++j)
    x[j] = std::clamp(std::isfinite(x[j]) ? x[j] : 0.0, lo_[j], hi_[j]);
  std::vector<double> g(n, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t i = 0; i < rows_; ++i) g[j] += a_[i * n + j] * b[i];
  }
  auto gradient = [&](std::vector<double>& r) {
    for (std::size_t j = 0; j < n; ++j) {
      double hx = 0.0;
      for (std::size_t k = 0; k < n; ++k) hx += h_[j * n + k] * x[k];
      r[j] = hx - g[j];
    }
  };
  auto projected_residual = [&](const std::vector<double>& r) {
    double m = 0.0;
    for (std::size_t j = 0; j < n; ++j)
      m = std::max(m, std::fabs(x[j] - std::clamp(x[j] - r[j], lo_[j], hi_[j])));
    return m;
  };
  // working set: 0 free, −1 fixed at lo, +1 fixed at hi
  std::vector<int> w(n, 0);
  for (std::size_t j = 0; j < n; ++j) {
    if (lo_[j] == hi_[j] || x[j] == lo_[j]) w[j] = -1;
    else if (x[j] == hi_[j]) w[j] = 1;
  }
  std::vector<double> r(n), m, y;
  std::vector<std::size_t> free;
  BoxLsqReport report;
  gradient(r);
  report.residual = projected_residual(r);
  while (report.residual >= options_.tolerance && report.sweeps < options_.max_sweeps) {
    ++report.sweeps;
    free.clear();
    for (std::size_t j = 0; j < n; ++j) {
      if (w[j] == 0) free.push_back(j);
    }
    const std::size_t nf = free.size();
    m.assign(nf * nf, 0.0);
    y.assign(nf, 0.0);
    for (std::size_t p = 0; p < nf; ++p) {
      double rhs = g[free[p]];
      for (std::size_t k = 0; k < n; ++k) {
        if (w[k] != 0) rhs -= h_[free[p] * n + k] * x[k];
      }
      y[p] = rhs;
      for (std::size_t q = 0; q < nf; ++q) m[p * nf + q] = h_[free[p] * n + free[q]];
    }
    if (nf > 0 && !cholesky_solve(m, y, nf)) {
      report.message = "normal matrix not positive definite (give ridge > 0)";
      break;
    }
    // longest feasible step towards the subspace minimiser y
    double alpha = 1.0;
    std::size_t blocking = n;
    bool blocking_at_lo = false;
    for (std::size_t p = 0; p < nf; ++p) {
      const std::size_t j = free[p];
      const double d = y[p] - x[j];
      if (y[p] < lo_[j] && d < 0.0) {
        const double t = (lo_[j] - x[j]) / d;
        if (t < alpha) alpha = t, blocking = j, blocking_at_lo = true;
      } else if (y[p] > hi_[j] && d > 0.0) {
        const double t = (hi_[j] - x[j]) / d;
        if (t < alpha) alpha = t, blocking = j, blocking_at_lo = false;
      }
    }
    for (std::size_t p = 0; p < nf; ++p) {
      const std::size_t j = free[p];
      x[j] = std::clamp(x[j] + alpha * (y[p] - x[j]), lo_[j], hi_[j]);
    }
    if (blocking < n) {
      x[blocking] = blocking_at_lo ? lo_[blocking] : hi_[blocking];
      w[blocking] = blocking_at_lo ? -1 : 1;
    } else {
      // subspace minimum reached: release the bound with the most wrong-signed multiplier
      gradient(r);
      double worst = options_.tolerance;
      std::size_t release = n;
      for (std::size_t j = 0; j < n; ++j) {
        if (lo_[j] == hi_[j]) continue;
        const double v = w[j] < 0 ? -r[j] : w[j] > 0 ? r[j] : 0.0;  // > 0: wants to move inwards
        if (v > worst) worst = v, release = j;
      }
      if (release < n) w[release] = 0;
    }
    gradient(r);
    report.residual = projected_residual(r);
  }
  report.converged = report.residual < options_.tolerance;
  if (report.converged)
    report.message = "converged";
  else if (report.message.empty())
    report.message = "stopped after max_sweeps with projected gradient " + std::to_string(report.residual);
  double cost = 0.0;
  for (std::size_t i = 0; i < rows_; ++i) {
    double ax = 0.0;
    for (std::size_t j = 0; j < n; ++j) ax += a_[i * n + j] * x[j];
    cost += 0.5 * (ax - b[i]) * (ax - b[i]);
  }
  for (std::size_t j = 0; j < n; ++j) cost += 0.5 * options_.ridge * x[j] * x[j];
  report.cost = cost;
  return report;
}

}  // namespace emoface::faceweights
