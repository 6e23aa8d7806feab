#pragma once
// Bounded (box-constrained) linear least squares, the solver behind from_arkit():
//
//   minimise ½‖A x − b‖² + ½ λ ‖x‖²   subject to lo ≤ x ≤ hi
//
// Solver: the primal active-set method for convex quadratic programs (Nocedal & Wright, Numerical
// Optimization, 2nd ed., §16.5, Algorithm 16.3) specialised to bounds. H = AᵀA + λI, g = Aᵀb. The
// working set W holds unknowns fixed at a bound; each iteration minimises exactly over the free
// unknowns (Cholesky of H_FF), then either steps towards that minimiser until the first bound blocks
// (adding it to W) or, if the minimiser is feasible, releases the bound unknown whose multiplier has
// the wrong sign. For λ > 0 the problem is strictly convex and the method ends after finitely many
// iterations at the unique minimiser. Chosen because the ARKit columns contain proportional pairs
// (e.g. corrugator and depressor supercilii both feed only browDown): coordinate descent crawls on
// such near-collinear columns, while an active-set step solves them exactly; Lawson–Hanson NNLS has
// no upper bounds (BVLS, its bounded version, is the same idea). The problem is tiny (≤ 50 unknowns).
// A warm start (the previous frame) starts with the right working set and usually ends in 1–2
// iterations. It stops when the largest projected-gradient component |x − clamp(x − ∇, lo, hi)|
// is below `tolerance`.
#include <cstddef>
#include <string>
#include <vector>

namespace emoface::faceweights {

struct BoxLsqOptions {
  double ridge = 1e-6;       ///< λ ≥ 0 (must be > 0 if some column of A is zero); picks the
                             ///< smallest-norm solution among near-equal fits
  double tolerance = 1e-10;  ///< projected-gradient stopping threshold, > 0
  int max_sweeps = 1000;     ///< ≥ 1: active-set iterations
  void validate() const;     ///< throws InvalidInput
};

struct BoxLsqReport {
  bool converged = false;
  int sweeps = 0;         ///< active-set iterations
  double cost = 0.0;      ///< ½‖Ax − b‖² + ½λ‖x‖² at the solution
  double residual = 0.0;  ///< largest projected-gradient component at the end
  std::string message;
};

/// Precomputed normal equations of a fixed A (rows × cols, row-major), reused for many b.
class BoxLeastSquares {
 public:
  BoxLeastSquares(std::vector<double> a, std::size_t rows, std::size_t cols, std::vector<double> lo,
                  std::vector<double> hi, BoxLsqOptions options = {});
  /// Solves for `b` (rows values). `x` (cols values) is the warm start and receives the solution;
  /// a wrong-sized x is reset to the projection of 0 onto the box. Throws InvalidInput on bad sizes or
  /// non-finite b. Non-convergence is reported, not thrown.
  BoxLsqReport solve(const std::vector<double>& b, std::vector<double>& x) const;
  std::size_t rows() const noexcept { return rows_; }
  std::size_t cols() const noexcept { return cols_; }

 private:
  std::vector<double> a_, h_, lo_, hi_;
  std::size_t rows_, cols_;
  BoxLsqOptions options_;
};

}  // namespace emoface::faceweights
