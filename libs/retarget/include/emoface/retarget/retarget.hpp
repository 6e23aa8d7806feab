#pragma once
// The whole fit of thesis chapter 3 (Fig. 3.1): align the target head into the source frame, detect the
// easy landmarks (§3.2.1), initialise the others with an RBF trained on the detected ones (§3.3), adjust
// them with the GA (§3.6) on the error function (§3.5), then deform the source face — mesh, muscles, lip
// grid, jaw pivot, eyes, head pivot — with the final RBF networks (§3.4, §3.7).
//
//   facemesh::Face source = facemesh::make_generic_face();
//   facemesh::Mesh target = facemesh::read_mesh("head.obj");
//   RetargetResult r = retarget_face(source, target, options);
//   facemesh::save_face("out/face.rig", r.face);
//
// The result lives in the source (thesis) frame — looking down +z, y up, the source's size — because
// the muscle model's jaw, eyelid and eye rotations assume that frame; `alignment` maps the input target
// into it (and back with Alignment::inverse).
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "emoface/facemesh/io.hpp"
#include "emoface/retarget/align.hpp"
#include "emoface/retarget/clean.hpp"
#include "emoface/retarget/error.hpp"
#include "emoface/retarget/ga.hpp"
#include "emoface/retarget/rbf.hpp"

namespace emoface::retarget {

/// Beyond the thesis: local least-squares refinement of the searched landmarks after the GA
/// (Levenberg–Marquardt on the residuals of ErrorFunction, numeric central differences; Ceres).
struct RefineOptions {
  bool enabled = false;
  int max_iterations = 15;      ///< LM iterations, [1, 1000]
  double step = 2e-4;           ///< finite-difference step, m, (0, 0.01]
  void validate() const;
};

struct RefineReport {
  bool ran = false;
  std::string status;           ///< Ceres termination type, e.g. "CONVERGENCE", "NO_CONVERGENCE"
  int iterations = 0;
  double initial_error = 0.0;   ///< E after the GA (including the prior term)
  double final_error = 0.0;     ///< E after refinement
  double seconds = 0.0;         ///< wall time (non-deterministic)
};

struct RetargetOptions {
  CleanOptions clean;  ///< stray components dropped before everything else
  AlignOptions align;
  RbfOptions rbf;
  /// bottom_y left at its default (−∞) is replaced by the height of the source's "chin" landmark.
  ErrorOptions error;
  GaOptions ga;
  /// Landmarks found by the §3.2.1 heuristics and kept fixed; every other rig landmark is searched.
  std::vector<std::string> detected = {"top_of_head", "nose_tip", "ear_r", "ear_l"};
  /// Beyond the thesis: keep the landmarks mirror-symmetric about the plane x = centreline x (pairs
  /// "<name>_l"/"<name>_r" are averaged with their mirror, others get x = centreline x) before each
  /// evaluation. Without it the GA trades feature placement for surface fit (docs/retarget.md).
  bool symmetric = true;
  /// Beyond the thesis: E + prior_weight·Σ_k |l_k − l_k⁰|² (l⁰ the initial landmarks of §3.3), so
  /// searched landmarks only leave their initial place when the surface fit pays for it. m⁻²·m² = 1, ≥ 0;
  /// default 0 (off): on the MakeHuman head a weight of 1 pulled the mouth corners down (docs/retarget.md).
  double prior_weight = 0.0;
  RefineOptions refine;
  /// Beyond the thesis: with AlignMode::Auto, the alignment's pitch (about the thesis x axis) is
  /// corrected within ±this many degrees (2° steps, then 0.5°) to minimise the error E (§3.5) of the
  /// source deformed by the RBF on the detected landmarks alone (§3.3). The shape matching of
  /// align_to_frame finds the left-right axis and up/front reliably, but its pitch follows the overall
  /// head shape (a neck, a long jaw); E measures what the fit needs. [0, 60]; 0 = off.
  double pitch_search_degrees = 30.0;
  /// Beyond the thesis (issue 13): after the alignment (and the pitch search), refine the frame on
  /// the face itself: a similarity ICP (Umeyama 1991 on closest-point pairs) of the source's stable
  /// face (skin of the upper and middle face regions, no jaw or lid weight) onto the target. The
  /// detected landmarks (§3.2.1: highest y, highest z, extreme x) move with a tilt of the frame, so
  /// a frame 0.5° off cost the fit and everything transferred from it. Off by default (the
  /// thesis' export, `--mode deform-source`); TransferOptions::refine_frame turns it on.
  bool refine_alignment = false;
  /// The refinement is applied only when it turns the frame by at most this many degrees: it
  /// corrects an alignment that is nearly right (a copy of the source 0.5° off); on a face shaped
  /// unlike the source (MakeHuman: 7.7°) the ICP's pose is a compromise between shapes and the
  /// alignment's pitch (chosen on E) fits better (its mouth landmarks were misplaced). [0, 30].
  double refine_max_degrees = 2.0;
  /// Beyond the thesis, experimental: ErrorOptions::band_samples between the source's chin and nose tip
  /// heights when error.band_samples is 0, so that E samples the lips more densely. Off by default: on the
  /// MakeHuman head 12 band samples moved the mouth further down (docs/retarget.md). [0, 1000].
  int mouth_samples = 0;
  void validate() const;
};

struct RetargetResult {
  facemesh::Face face;                     ///< the deformed source face: mesh + complete rig
  CleanReport cleaning;                    ///< what clean_target dropped
  Alignment alignment;                     ///< input target → thesis frame
  facemesh::Mesh aligned_target;           ///< the cleaned target in the thesis frame
  std::vector<std::string> landmark_names; ///< rig retarget landmarks, rig order
  std::vector<bool> detected;              ///< per landmark: auto-detected (fixed) or searched
  Eigen::MatrixX3d source_landmarks;       ///< #L by 3, m
  Eigen::MatrixX3d initial_landmarks;      ///< on the target before the GA (§3.3), #L by 3, m
  Eigen::MatrixX3d target_landmarks;       ///< final, #L by 3, m
  double length_scale = 1.0;               ///< factor applied to muscle radii, elasticities, eye radii
  GaReport ga;
  RefineReport refine;
};

/// Position of a named rig landmark; throws InvalidInput if the rig lacks it.
Eigen::Vector3d landmark_position(const facemesh::Face& face, const std::string& name);

/// Applies `network` to every point of the face (mesh vertices, muscle ends, lip control points and
/// centre, jaw pivot, eye centres, head pivot) and multiplies the rig's lengths (Rs, Rf, k, wrinkle
/// height, sphincter semi-axes, eye radius) by `length_scale` (lengths in muscles::SolverOptions, such
/// as the lip funnel extrusion, are not part of the rig and stay as they are). Topology, regions,
/// materials, weights and landmark vertex ids are kept. Throws InvalidInput unless length_scale > 0.
facemesh::Face transfer_face(const facemesh::Face& source, const RbfNetwork& network, double length_scale);

/// The fit. Throws InvalidInput for a rig without the needed landmarks or a degenerate target.
RetargetResult retarget_face(const facemesh::Face& source, const facemesh::Mesh& target,
                             const RetargetOptions& options = {},
                             const std::function<void(const GaProgress&)>& progress = {});

}  // namespace emoface::retarget
