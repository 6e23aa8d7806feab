#pragma once
// Private helpers: poses (n by d) <-> flattened landmark-major rows (x0, y0[, z0], x1, ...).
#include <Eigen/Core>

namespace emoface::motiongraph::detail {

inline Eigen::RowVectorXd flatten(const Eigen::MatrixXd& pose) {
  Eigen::RowVectorXd out(pose.size());
  for (Eigen::Index i = 0; i < pose.rows(); ++i)
    for (Eigen::Index j = 0; j < pose.cols(); ++j) out[i * pose.cols() + j] = pose(i, j);
  return out;
}

}  // namespace emoface::motiongraph::detail
