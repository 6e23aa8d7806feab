#pragma once
// The bridge from landmark motion to the 3D muscle face (issue #8 §2): fits the 35 side parameters
// (muscle contraction levels in [0, 1], masseter = jaw opening) to one frame of iBUG-68 landmark
// displacements by bounded non-linear least squares (core::solve_bounded_lm), warm-started from the
// previous frame.
// The paper (§7) drove blendshapes directly in Maya; emoface drives its muscle model instead.
//
// Model used inside the solver: a separable surrogate of the muscle model, precomputed once per rig —
// for every parameter j the landmark displacements R_j(c) of the full model (muscles::FaceSolver) with
// only that parameter at c, sampled at `sample_levels` and interpolated linearly; the prediction is
// Σ_j R_j(p_j) (like blendshapes, so exact for one muscle at a knot, approximate where muscles overlap).
// Reports give the residual of the surrogate and, when asked, of the full model at the fitted values.
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "emoface/muscles/solver.hpp"

namespace emoface::bridge {

struct FitOptions {
  /// Scale of the residuals smoothness·(p_j − previous_j) that keep a track smooth (warm start =
  /// previous frame), metres of landmark error per unit of contraction change; ≥ 0, 0 = none. The
  /// default (0.1 mm) only decides between near-equivalent muscle combinations.
  double smoothness = 1e-4;
  int max_iterations = 50;  ///< Levenberg–Marquardt iterations, [1, 1000]
  /// Contraction levels at which each parameter's response is sampled (strictly increasing, in (0, 1],
  /// last = 1); 0 is implicit.
  std::vector<double> sample_levels = {0.25, 0.5, 0.75, 1.0};
  void validate() const;  ///< throws InvalidInput
};

struct FitReport {
  bool converged = false;
  std::string message;           ///< the solver's termination message (core::BoundedLmReport)
  int iterations = 0;            ///< LM iterations after the linearised warm start
  double initial_cost = 0.0;     ///< ½‖r‖² at the warm start
  double final_cost = 0.0;
  double rms_surrogate = 0.0;    ///< RMS landmark residual of the surrogate at the result, metres
  double rms_model = -1.0;       ///< RMS residual of the full muscle model (FitFrameOptions::evaluate_model), else −1
};

class LandmarkFitter {
 public:
  /// Precomputes the responses: 35 × sample_levels.size() deformations of `solver`'s face. The rig
  /// must have 68 iBUG landmarks. The solver must outlive the fitter.
  explicit LandmarkFitter(const muscles::FaceSolver& solver, FitOptions options = {});

  /// 68 by 3 landmark displacements (metres) of the full muscle model for 35 side parameters.
  Eigen::MatrixXd model_displacements(const std::vector<double>& side) const;
  /// The same from the surrogate.
  Eigen::MatrixXd predicted_displacements(const std::vector<double>& side) const;

  /// Fits `side` (size 35; in: warm start and smoothness anchor, e.g. the previous frame; out: the fit,
  /// every value in [0, 1]) to `target` (68 by 2 — x, y only — or 68 by 3, metres; rows with a NaN are
  /// ignored). With `evaluate_model` the full model is run once at the result for rms_model.
  FitReport fit(const Eigen::MatrixXd& target, std::vector<double>& side, bool evaluate_model = false) const;

  /// Fits every frame in order, each warm-started from the previous fit (the first from zeros).
  std::vector<std::vector<double>> fit_track(const std::vector<Eigen::MatrixXd>& targets,
                                             std::vector<FitReport>* reports = nullptr) const;

  const FitOptions& options() const noexcept { return options_; }
  /// The 68 iBUG landmarks of the neutral face (68 by 3, metres).
  const Eigen::MatrixXd& neutral_landmarks() const noexcept { return neutral_; }

 private:
  const muscles::FaceSolver& solver_;
  FitOptions options_;
  Eigen::MatrixXd neutral_;                  // 68 by 3
  std::vector<double> knots_;                // 0, sample_levels...
  std::vector<std::vector<Eigen::VectorXd>> responses_;  // [parameter][knot] → 204 (row-major 68×3)
};

/// Converts image-space landmark displacements (68 by 2, pixels, y down, e.g. motion-graph output minus
/// its neutral pose) to face units (metres, y up) by the ratio of the outer eye-corner distance
/// (iBUG 36–45) of the face's neutral landmarks (68 by 3) and of the image's neutral pose (68 by 2).
Eigen::MatrixXd image_to_face(const Eigen::MatrixXd& displacement_px, const Eigen::MatrixXd& neutral_px,
                              const Eigen::MatrixXd& face_neutral);

}  // namespace emoface::bridge
