#include "emoface/retarget/rbf.hpp"

#include <cmath>
#include <limits>

#include <Eigen/QR>
#include <Eigen/SVD>

#include "emoface/core/errors.hpp"

namespace emoface::retarget {

std::string to_string(RbfTarget target) {
  return target == RbfTarget::Displacement ? "displacement" : "position";
}

RbfTarget rbf_target_from_string(std::string_view name) {
  if (name == "displacement") return RbfTarget::Displacement;
  if (name == "position") return RbfTarget::Position;
  throw InvalidInput("unknown RBF target \"" + std::string(name) + "\" (expected displacement or position)");
}

void RbfOptions::validate() const {
  if (!(regularization >= 0.0 && regularization <= 1.0))
    throw InvalidInput("RbfOptions::regularization must be in [0, 1]");
}

RbfNetwork::RbfNetwork(Eigen::MatrixX3d centres, Eigen::VectorXd widths, Eigen::MatrixX3d weights,
                       RbfTarget target)
    : centres_(std::move(centres)), widths_(std::move(widths)), weights_(std::move(weights)), target_(target) {
  if (widths_.size() != centres_.rows() || weights_.rows() != centres_.rows())
    throw InvalidInput("RbfNetwork: centres, widths and weights must have the same number of rows");
}

Eigen::Vector3d RbfNetwork::evaluate(const Eigen::Vector3d& point) const {
  // thesis §3.4: RBF_i(v) = Σ_j w_ij h_j(v), h_j(v) = sqrt(|v − μ_j|² + s_j²)
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (Eigen::Index j = 0; j < centres_.rows(); ++j) {
    const double h = std::sqrt((point - centres_.row(j).transpose()).squaredNorm() + widths_[j] * widths_[j]);
    sum += h * weights_.row(j).transpose();
  }
  return target_ == RbfTarget::Displacement ? Eigen::Vector3d(point + sum) : sum;
}

void RbfNetwork::evaluate(const facemesh::Vertices& points, facemesh::Vertices& out) const {
  out.resize(points.rows(), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) out.row(i) = evaluate(Eigen::Vector3d(points.row(i))).transpose();
}

facemesh::Vertices RbfNetwork::evaluate(const facemesh::Vertices& points) const {
  facemesh::Vertices out;
  evaluate(points, out);
  return out;
}

Eigen::VectorXd multiquadric_widths(const Eigen::MatrixX3d& centres) {
  const Eigen::Index n = centres.rows();
  if (n < 2) throw InvalidInput("RBF: need at least two centres");
  Eigen::VectorXd s(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    double best = std::numeric_limits<double>::infinity();
    for (Eigen::Index k = 0; k < n; ++k)
      if (k != j) best = std::min(best, (centres.row(k) - centres.row(j)).norm());
    if (!(best > 0.0) || !std::isfinite(best))
      throw InvalidInput("RBF: centre " + std::to_string(j) + " coincides with another centre or is not finite");
    s[j] = best;  // thesis §3.4: s_j = min_{k≠j} |μ_k − μ_j|
  }
  return s;
}

Eigen::MatrixXd multiquadric_matrix(const Eigen::MatrixX3d& centres, const Eigen::VectorXd& widths) {
  const Eigen::Index n = centres.rows();
  Eigen::MatrixXd h(n, n);
  for (Eigen::Index k = 0; k < n; ++k)
    for (Eigen::Index j = 0; j < n; ++j)
      h(k, j) = std::sqrt((centres.row(k) - centres.row(j)).squaredNorm() + widths[j] * widths[j]);
  return h;
}

RbfNetwork fit_rbf(const Eigen::MatrixX3d& source, const Eigen::MatrixX3d& target, const RbfOptions& options) {
  options.validate();
  if (source.rows() != target.rows())
    throw InvalidInput("fit_rbf: source has " + std::to_string(source.rows()) + " landmarks, target " +
                       std::to_string(target.rows()));
  if (!source.allFinite() || !target.allFinite()) throw InvalidInput("fit_rbf: landmarks must be finite");
  const Eigen::Index n = source.rows();
  const Eigen::VectorXd widths = multiquadric_widths(source);
  const Eigen::MatrixXd h = multiquadric_matrix(source, widths);
  Eigen::MatrixX3d rhs = target;
  if (options.target == RbfTarget::Displacement) rhs -= source;
  // Regularised least squares (thesis §3.4, end): min ‖H w − t‖² + λ‖w‖², as [H; √λ I] w = [t; 0].
  const double lambda = options.regularization * h.squaredNorm() / static_cast<double>(n);
  Eigen::MatrixXd a(2 * n, n);
  a.topRows(n) = h;
  a.bottomRows(n) = std::sqrt(lambda) * Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(2 * n, 3);
  b.topRows(n) = rhs;
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  Eigen::MatrixX3d w = qr.solve(b);
  if (!w.allFinite()) throw NumericalError("fit_rbf: the RBF weights are not finite");
  return RbfNetwork(source, widths, std::move(w), options.target);
}

double multiquadric_condition(const Eigen::MatrixX3d& centres) {
  const Eigen::MatrixXd h = multiquadric_matrix(centres, multiquadric_widths(centres));
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(h);
  const auto& sv = svd.singularValues();
  return sv[0] / sv[sv.size() - 1];
}

}  // namespace emoface::retarget
