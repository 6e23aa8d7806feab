#pragma once
// Cubic B-spline surface of the lips (thesis §2.2.2 formula w(u,v) = ΣΣ N_i(u) N_j(v) W_ij, §2.3.2):
// periodic uniform cubic around the mouth, clamped (open uniform) cubic across the lip.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "emoface/facemesh/mesh.hpp"
#include "emoface/facemesh/rig.hpp"

namespace emoface::facemesh {

/// Precomputed basis weights for sampling a LipGrid on its fixed grid: every sample is a fixed
/// combination of at most 16 control points, so re-polygonising after each deformation is one sparse
/// product (thesis §2.3.2: "sampled by vertices that are pre-arranged in a grid").
class LipSampler {
 public:
  /// Throws InvalidInput when the sample counts are below the control counts.
  LipSampler(int samples_around, int samples_across);
  /// Writes samples_around*samples_across points (row-major by across-row) from kAcross*kAround
  /// control points into rows [first_row, first_row + sample_count()) of `out`.
  void evaluate(const std::vector<Eigen::Vector3d>& control_points, Vertices& out, int first_row) const;
  int sample_count() const noexcept { return samples_around_ * samples_across_; }

  struct Term {
    int control;
    double weight;
  };
  const std::vector<std::vector<Term>>& terms() const noexcept { return terms_; }

 private:
  int samples_around_;
  int samples_across_;
  std::vector<std::vector<Term>> terms_;  ///< per sample
};

/// The at most 16 (control point, weight) terms of the lip surface at (u, v): S(u, v) = Σ w·P[control],
/// periodic uniform cubic around (u ∈ [0, 1) from column 0, one turn), clamped cubic across (v ∈ [0, 1],
/// 0 = outer border row). The same basis LipSampler uses at its grid points (sample column i, row j is
/// u = i/samples_around, v = j/(samples_across − 1)). Used for LipBinding vertices. Throws
/// InvalidInput for u or v outside those ranges (or not finite).
std::vector<LipSampler::Term> lip_surface_terms(double u, double v);

/// Uniform cubic B-spline basis values at t ∈ [0,1) (the four weights of consecutive control points).
std::array<double, 4> cubic_bspline_basis(double t);

/// Clamped cubic basis on n control points (open uniform knots), all n values at v ∈ [0, 1].
std::vector<double> clamped_cubic_basis(int n, double v);

}  // namespace emoface::facemesh
