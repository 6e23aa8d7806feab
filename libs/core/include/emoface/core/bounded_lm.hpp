#pragma once
// Levenberg–Marquardt for small dense least-squares problems with box constraints,
//   minimise ½‖r(x)‖²  subject to  lower ≤ x ≤ upper  (per coordinate; ±∞ = unbounded),
// header-only; needs Eigen on the includer's include path (core links it privately, so core's
// other users do not). It complements Ceres' header-only `ceres::TinySolver`, which has no bounds,
// and takes the same function concept, so a `ceres::TinySolverAutoDiffFunction` (Ceres' Jets) or a
// hand-written Jacobian plugs into either:
//
//   struct Function {
//     using Scalar = double;
//     enum { NUM_RESIDUALS = Eigen::Dynamic or n, NUM_PARAMETERS = Eigen::Dynamic or p };
//     bool operator()(const double* x, double* residuals, double* jacobian) const;
//     int NumResiduals() const;   // when NUM_RESIDUALS is Eigen::Dynamic
//     int NumParameters() const;  // when NUM_PARAMETERS is Eigen::Dynamic
//   };
//   // jacobian: n by p, column-major (Eigen's default), or nullptr when only residuals are wanted;
//   // return false (or non-finite residuals) where r is undefined: that step is rejected.
//
//   Eigen::VectorXd x = start, lo = ..., hi = ...;
//   const BoundedLmReport rep = solve_bounded_lm(function, x, lo, hi);
//
// Each iteration (Kanzow, Yamashita & Fukushima 2004, "Levenberg–Marquardt methods with strong
// local convergence properties for solving nonlinear equations with convex constraints", JCAM 172:
// a projected LM step; Bertsekas 1982, "Projected Newton methods for optimization problems with
// simple constraints", SIAM J. Control Optim. 20: the active set):
//  1. active set: coordinates at a bound whose gradient g = Jᵀr pushes them outwards stay fixed;
//  2. the LM system (JᵀJ + μ·D)s = −g is solved on the free coordinates, D = Marquardt's diagonal
//     with Ceres' Jacobi column scaling and clamping (1e-6 … 1e32 in scaled units);
//  3. coordinates whose step leaves the box are put on that bound and the remaining free ones
//     re-solved with them fixed (at most p times), so a step slides along a face of the box instead
//     of being clamped short;
//  4. gain ratio ρ = actual / predicted decrease (linear model ½‖r + Js‖²): ρ > 1e-3 accepts and
//     μ ← μ·max(⅓, 1 − (2ρ − 1)³); otherwise μ ← μ·ν, ν ← 2ν (Nielsen 1999, as in Ceres' LM and
//     TinySolver). As μ grows the step tends to a short projected scaled-gradient step, a descent
//     direction whenever the projected gradient is non-zero.
// Stopping rules and defaults follow Ceres' Solver::Options (function, gradient, parameter
// tolerances; max_norm(x − P(x − g)) for the gradient of a bounded problem).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

#include "emoface/core/errors.hpp"

namespace emoface::core {

struct BoundedLmOptions {
  int max_iterations = 50;              ///< LM iterations (accepted or rejected steps), >= 1
  double function_tolerance = 1e-6;     ///< stop when |Δcost| ≤ this·cost, [0, 1)
  double gradient_tolerance = 1e-10;    ///< stop when max|x − P(x − g)| ≤ this, >= 0
  double parameter_tolerance = 1e-8;    ///< stop when ‖step‖ ≤ this·(‖x‖ + this), >= 0
  double initial_damping = 1e-4;        ///< μ₀ (1 / Ceres' initial trust-region radius), > 0
  double min_relative_decrease = 1e-3;  ///< accept a step when ρ exceeds this, [0, 1)
  void validate() const;                ///< throws InvalidInput
};

enum class BoundedLmStatus {
  FunctionTolerance,   ///< converged: relative cost change below function_tolerance
  GradientTolerance,   ///< converged: projected gradient below gradient_tolerance
  ParameterTolerance,  ///< converged: step below parameter_tolerance
  MaxIterations,       ///< stopped at max_iterations (not converged)
  DampingTooLarge,  ///< μ exceeded 1e32 (Ceres' minimum trust-region radius): no further decrease
  Failure,          ///< the function failed or was not finite at the start point
};
std::string to_string(BoundedLmStatus status);
/// "function_tolerance" | "gradient_tolerance" | …; throws InvalidInput otherwise.
BoundedLmStatus bounded_lm_status_from_string(const std::string& name);

struct BoundedLmReport {
  BoundedLmStatus status = BoundedLmStatus::Failure;
  bool converged = false;     ///< the tolerances were met (or damping showed no decrease left)
  std::string message;        ///< one line, for logs
  int iterations = 0;         ///< LM iterations (accepted + rejected)
  int accepted = 0;           ///< accepted steps
  int evaluations = 0;        ///< function calls (with or without Jacobian)
  double initial_cost = 0.0;  ///< ½‖r‖² at the (projected) start
  double final_cost = 0.0;    ///< ½‖r‖² at the returned x
  double projected_gradient = 0.0;  ///< max|x − P(x − g)| at the returned x
};

namespace detail {
template <class F>
int bounded_lm_residuals(const F& f) {
  if constexpr (F::NUM_RESIDUALS == Eigen::Dynamic) {
    return f.NumResiduals();
  } else {
    return F::NUM_RESIDUALS;
  }
}
template <class F>
int bounded_lm_parameters(const F& f) {
  if constexpr (F::NUM_PARAMETERS == Eigen::Dynamic) {
    return f.NumParameters();
  } else {
    return F::NUM_PARAMETERS;
  }
}
}  // namespace detail

/// Minimises ½‖r(x)‖² over the box [lower, upper] from `x` (projected into the box first); returns
/// the best point found in `x` (always inside the box, never costlier than the projected start).
/// Throws InvalidInput for wrong sizes, lower > upper, NaN bounds or a non-finite start;
/// non-convergence and a failing function are reported, not thrown.
template <class Function>
BoundedLmReport solve_bounded_lm(const Function& f, Eigen::Ref<Eigen::VectorXd> x,
                                 const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                 const BoundedLmOptions& options = {}) {
  static_assert(std::is_same_v<typename Function::Scalar, double>, "bounded LM: double only");
  options.validate();
  const int p = detail::bounded_lm_parameters(f);
  const int n = detail::bounded_lm_residuals(f);
  if (p < 1 || n < 1) throw InvalidInput("bounded LM: need at least one parameter and residual");
  if (x.size() != p || lower.size() != p || upper.size() != p)
    throw InvalidInput("bounded LM: x, lower and upper must have NumParameters() = " +
                       std::to_string(p) + " entries");
  for (int i = 0; i < p; ++i) {
    if (std::isnan(lower[i]) || std::isnan(upper[i]) || !(lower[i] <= upper[i]))
      throw InvalidInput("bounded LM: bound " + std::to_string(i) + " must satisfy lower <= upper");
    if (!std::isfinite(x[i]))
      throw InvalidInput("bounded LM: start coordinate " + std::to_string(i) + " is not finite");
  }
  using Vector = Eigen::VectorXd;
  using Matrix = Eigen::MatrixXd;
  auto project = [&](const Vector& v) { return v.cwiseMax(lower).cwiseMin(upper).eval(); };
  BoundedLmReport rep;
  Vector xc = project(x);
  Vector r(n), r_new(n), g(p), scale(p), step(p);
  Matrix jac(n, p), jac_new(n, p), h(p, p);
  auto evaluate = [&](const Vector& at, Vector& res, Matrix* j) {
    ++rep.evaluations;
    const bool ok = f(at.data(), res.data(), j ? j->data() : nullptr);
    return ok && res.allFinite() && (!j || j->allFinite());
  };
  auto projected_gradient = [&]() { return (xc - project(xc - g)).cwiseAbs().maxCoeff(); };
  auto finish = [&](BoundedLmStatus status, double cost, const std::string& message) {
    rep.status = status;
    rep.converged = status != BoundedLmStatus::MaxIterations && status != BoundedLmStatus::Failure;
    rep.final_cost = cost;
    rep.message = message;
    x = xc;
    return rep;
  };
  if (!evaluate(xc, r, &jac)) {
    rep.initial_cost = std::numeric_limits<double>::infinity();
    return finish(BoundedLmStatus::Failure, rep.initial_cost,
                  "the function failed or was not finite at the start point");
  }
  double cost = 0.5 * r.squaredNorm();
  rep.initial_cost = cost;
  // Ceres' Jacobi scaling, fixed at the start: s_i = 1 / (1 + ‖J_i‖).
  scale = (1.0 + jac.colwise().norm().array()).inverse().matrix();
  h.noalias() = jac.transpose() * jac;
  g.noalias() = jac.transpose() * r;
  rep.projected_gradient = projected_gradient();
  if (rep.projected_gradient <= options.gradient_tolerance)
    return finish(BoundedLmStatus::GradientTolerance, cost, "projected gradient below tolerance");
  double mu = options.initial_damping, nu = 2.0;
  Eigen::Array<bool, Eigen::Dynamic, 1> fixed(p);
  Eigen::VectorXi free_index(p);
  while (true) {
    if (rep.iterations >= options.max_iterations)
      return finish(BoundedLmStatus::MaxIterations, cost, "maximum number of iterations reached");
    if (mu > 1e32)
      return finish(BoundedLmStatus::DampingTooLarge, cost, "damping too large: no decrease left");
    ++rep.iterations;
    // 1. active set
    for (int i = 0; i < p; ++i)
      fixed[i] = (xc[i] <= lower[i] && g[i] > 0.0) || (xc[i] >= upper[i] && g[i] < 0.0);
    step.setZero();
    // 2.–3. LM step on the free coordinates; those leaving the box go onto it, the rest re-solved.
    for (int pass = 0; pass < p; ++pass) {
      int m = 0;
      for (int i = 0; i < p; ++i)
        if (!fixed[i]) free_index[m++] = i;
      if (m == 0) break;
      Matrix a(m, m);
      Vector rhs(m);
      for (int u = 0; u < m; ++u) {
        const int i = free_index[u];
        rhs[u] = -g[i];
        for (int k = 0; k < p; ++k)
          if (fixed[k]) rhs[u] -= h(i, k) * step[k];
        for (int w = 0; w < m; ++w) a(u, w) = h(i, free_index[w]);
        const double s2 = scale[i] * scale[i];
        a(u, u) += mu * std::clamp(h(i, i) * s2, 1e-6, 1e32) / s2;
      }
      const Vector sol = a.ldlt().solve(rhs);
      if (!sol.allFinite()) {  // singular system: treated as a rejected step (more damping)
        step.setConstant(std::numeric_limits<double>::quiet_NaN());
        break;
      }
      bool left = false;
      for (int u = 0; u < m; ++u) {
        const int i = free_index[u];
        step[i] = sol[u];
        if (xc[i] + step[i] < lower[i] || xc[i] + step[i] > upper[i]) {
          step[i] = std::clamp(xc[i] + step[i], lower[i], upper[i]) - xc[i];
          fixed[i] = true;
          left = true;
        }
      }
      if (!left) break;
    }
    if (!step.allFinite()) {
      mu *= nu;
      nu *= 2.0;
      continue;
    }
    const Vector candidate = project(xc + step);
    step = candidate - xc;
    if (step.norm() <= options.parameter_tolerance * (xc.norm() + options.parameter_tolerance))
      return finish(BoundedLmStatus::ParameterTolerance, cost, "step below parameter tolerance");
    // 4. gain ratio
    const double predicted = -(g.dot(step) + 0.5 * step.dot(h * step));
    const bool ok = evaluate(candidate, r_new, nullptr);
    const double new_cost =
        ok ? 0.5 * r_new.squaredNorm() : std::numeric_limits<double>::infinity();
    const double change = cost - new_cost;
    const bool tiny_change = ok && std::abs(change) <= options.function_tolerance * cost;
    // A point whose Jacobian is not finite is rejected like a failed evaluation.
    const bool accept = ok && predicted > 0.0 &&
                        change > options.min_relative_decrease * predicted &&
                        evaluate(candidate, r_new, &jac_new);
    if (accept) {
      xc = candidate;
      ++rep.accepted;
      r.swap(r_new);
      jac.swap(jac_new);
      cost = 0.5 * r.squaredNorm();
      h.noalias() = jac.transpose() * jac;
      g.noalias() = jac.transpose() * r;
      rep.projected_gradient = projected_gradient();
      if (tiny_change)
        return finish(BoundedLmStatus::FunctionTolerance, cost, "cost change below tolerance");
      if (rep.projected_gradient <= options.gradient_tolerance)
        return finish(BoundedLmStatus::GradientTolerance, cost,
                      "projected gradient below tolerance");
      const double t = 2.0 * change / predicted - 1.0;
      mu *= std::max(1.0 / 3.0, 1.0 - t * t * t);
      mu = std::max(mu, 1e-16);  // Ceres' maximum trust-region radius 1e16
      nu = 2.0;
    } else {
      if (tiny_change)
        return finish(BoundedLmStatus::FunctionTolerance, cost, "cost change below tolerance");
      mu *= nu;
      nu *= 2.0;
    }
  }
}

}  // namespace emoface::core
