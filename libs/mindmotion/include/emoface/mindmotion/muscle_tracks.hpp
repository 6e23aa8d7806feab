#pragma once
// Behaviour motion → muscle tracks for faceanim (issue #8): the synthesized landmark frames, taken
// relative to the motion graph's neutral pose and scaled into face units, are fitted frame by frame
// with bridge::LandmarkFitter (warm-started from the previous frame).
#include <vector>

#include <Eigen/Core>

#include "emoface/bridge/landmark_fit.hpp"
#include "emoface/mindmotion/behaviour.hpp"
#include "emoface/muscles/io.hpp"

namespace emoface::mindmotion {

/// The graph's neutral pose as iBUG-68 rows (68 by 2, the graph's units); rows the graph lacks are NaN.
/// Throws InvalidInput for a 3D graph or landmark ids outside 0..67.
Eigen::MatrixXd graph_neutral_ibug68(const motiongraph::MotionGraph& graph);

/// Each frame minus the neutral pose, as 68 by 2 displacements in face units (bridge::image_to_face
/// with `face_neutral`, 68 by 3); landmarks the graph lacks are NaN rows (ignored by the fit).
std::vector<Eigen::MatrixXd> face_displacements(const motiongraph::MotionGraph& graph, const CharacterMotion& motion,
                                                const Eigen::MatrixXd& face_neutral);

struct TrackFitSummary {
  double mean_rms = 0.0;  ///< mean over frames of the surrogate's RMS landmark residual, metres
  double max_rms = 0.0;
  std::size_t not_converged = 0;  ///< frames whose fit stopped at the iteration limit
};

/// Fitted parameter frames (time = frame / frame rate; the 35 side parameters, pose parameters 0).
std::vector<muscles::ParameterFrame> fit_muscle_tracks(const bridge::LandmarkFitter& fitter,
                                                       const motiongraph::MotionGraph& graph,
                                                       const CharacterMotion& motion,
                                                       TrackFitSummary* summary = nullptr);

}  // namespace emoface::mindmotion
