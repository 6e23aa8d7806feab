#pragma once
// Radial basis function networks (thesis §3.4, after Noh & Neumann 2001): three networks map a point of
// the source face to the x, y and z of the target face, trained on corresponding landmarks.
//
//   RbfNetwork net = fit_rbf(source_landmarks, target_landmarks);   // #L by 3 each, metres
//   Eigen::Vector3d q = net.evaluate(p);                              // one point
//   facemesh::Vertices w = net.evaluate(vertices);                    // #V by 3
//
// Basis (thesis §3.4): h_j(v) = sqrt(|v − μ_j|² + s_j²) with s_j = min_{k≠j} |μ_k − μ_j|.
// The three networks share their centres μ_j (the source landmarks), hence one basis matrix.
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "emoface/facemesh/mesh.hpp"

namespace emoface::retarget {

/// What the networks learn.
enum class RbfTarget {
  Displacement,  ///< target − source (the map is identity + Σ w_j h_j): smooth far from the landmarks
  Position       ///< the target coordinates themselves (thesis §3.4 literally)
};
std::string to_string(RbfTarget target);
RbfTarget rbf_target_from_string(std::string_view name);

struct RbfOptions {
  /// Regularisation term λ·Σ_j w_j² added to the squared training error of each network (thesis §3.4,
  /// end, after Bishop 1995). Dimensionless: the effective λ is regularization·‖H‖²_F/L (H the L×L
  /// basis matrix), so the same value works at any scale. 0 = exact interpolation; [0, 1].
  double regularization = 1e-9;
  /// Default Displacement (deviation from the thesis, docs/retarget.md): with 22 landmarks the literal
  /// form bends the back of the head and the inside of the mouth; learning displacements keeps points
  /// far from every landmark where the nearest landmarks move them.
  RbfTarget target = RbfTarget::Displacement;
  void validate() const;
};

/// A trained set of three RBF networks.
class RbfNetwork {
 public:
  RbfNetwork() = default;
  /// Centres (#L by 3), widths s_j (#L), weights (#L by 3), target mode. Used by fit_rbf.
  RbfNetwork(Eigen::MatrixX3d centres, Eigen::VectorXd widths, Eigen::MatrixX3d weights, RbfTarget target);

  Eigen::Vector3d evaluate(const Eigen::Vector3d& point) const;
  /// Maps every row (#N by 3, metres).
  facemesh::Vertices evaluate(const facemesh::Vertices& points) const;
  /// In-place variant that reuses `out` (resized to points.rows()).
  void evaluate(const facemesh::Vertices& points, facemesh::Vertices& out) const;

  const Eigen::MatrixX3d& centres() const noexcept { return centres_; }
  const Eigen::VectorXd& widths() const noexcept { return widths_; }
  const Eigen::MatrixX3d& weights() const noexcept { return weights_; }
  RbfTarget target() const noexcept { return target_; }

 private:
  Eigen::MatrixX3d centres_;
  Eigen::VectorXd widths_;
  Eigen::MatrixX3d weights_;
  RbfTarget target_ = RbfTarget::Displacement;
};

/// s_j = min_{k≠j} |μ_k − μ_j| (thesis §3.4, after Eck 1991). Throws InvalidInput for fewer than two
/// centres or two coincident centres.
Eigen::VectorXd multiquadric_widths(const Eigen::MatrixX3d& centres);

/// The L×L basis matrix H_kj = h_j(μ_k).
Eigen::MatrixXd multiquadric_matrix(const Eigen::MatrixX3d& centres, const Eigen::VectorXd& widths);

/// Trains the three networks on source → target landmarks (#L by 3 each, L ≥ 2, finite, distinct
/// source points). Solve: min ‖H w − t‖² + λ‖w‖², written as the augmented least-squares system
/// [H; √λ I] w = [t; 0] and solved by column-pivoting Householder QR, which does not square the
/// condition number as the normal equations (HᵀH + λI) would. Throws InvalidInput on bad input and
/// NumericalError if the solve fails (non-finite weights).
RbfNetwork fit_rbf(const Eigen::MatrixX3d& source, const Eigen::MatrixX3d& target,
                   const RbfOptions& options = {});

/// 2-norm condition number of H (largest / smallest singular value), for diagnostics and tests.
double multiquadric_condition(const Eigen::MatrixX3d& centres);

}  // namespace emoface::retarget
