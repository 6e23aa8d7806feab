#pragma once
// Pose similarity of the paper, eq. (1) (§4.2):
//   sim(Pa, Pb) = Σ_i [ dist(PaLi, PbLi) + λ · vinfl(PaLi, PbLi) · dist(PaLi, PbLi) ]
//   vinfl = 1 − |V̂(PaLi) · V̂(PbLi)|   (V = instantaneous velocity, V̂ = V/|V|)
// Lower is more similar; units are those of the landmarks (pixels).
#include <Eigen/Core>

namespace emoface::motiongraph {

struct SimilarityOptions {
  double lambda = 0.5;  ///< velocity influence λ of eq. (1), dimensionless, >= 0
  /// Speeds below this (landmark units per frame, >= 0) count as "still": two still landmarks have
  /// vinfl 0, a still and a moving one vinfl 1 (the paper leaves zero velocity undefined).
  double still_speed = 1e-6;
  void validate() const;
};

/// Velocity influence of one landmark: 1 − |cos angle(va, vb)| in [0, 1] (see still_speed).
double velocity_influence(const double* va, const double* vb, int dimensions, double still_speed);

/// eq. (1) for poses flattened landmark-major (x0,y0[,z0],x1,...): pa, pb positions (or
/// displacements: only differences matter), va, vb velocities; all of length n·dimensions.
double similarity(const double* pa, const double* va, const double* pb, const double* vb,
                  Eigen::Index landmark_count, int dimensions, const SimilarityOptions& options);

/// Convenience overload on flattened row vectors of equal length.
double similarity(const Eigen::Ref<const Eigen::RowVectorXd>& pa,
                  const Eigen::Ref<const Eigen::RowVectorXd>& va,
                  const Eigen::Ref<const Eigen::RowVectorXd>& pb,
                  const Eigen::Ref<const Eigen::RowVectorXd>& vb, int dimensions,
                  const SimilarityOptions& options);

}  // namespace emoface::motiongraph
