#pragma once
// Private: Ceres-based local refinement of landmark positions (never in a public header).
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "emoface/retarget/retarget.hpp"

namespace emoface::retarget::detail {

/// Fills residuals for positions (#K by 3); may overwrite positions with their symmetrised/projected
/// version (the refinement returns those).
using ResidualFunction = std::function<void(Eigen::MatrixX3d& positions, std::vector<double>& residuals)>;

/// Levenberg–Marquardt from `start`; returns the best positions and fills `report`. Never returns
/// positions with a larger Σr² than `start`.
Eigen::MatrixX3d refine_landmarks(const Eigen::MatrixX3d& start, const ResidualFunction& residuals,
                                  const RefineOptions& options, RefineReport& report);

}  // namespace emoface::retarget::detail
