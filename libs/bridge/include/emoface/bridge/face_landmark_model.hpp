#pragma once
// The face-driven landmark model of issue #7 §1: the synthetic motion-graph database driven by the
// 3D muscle face instead of a parametric 2D face.
//
//   label → one-hot ESV (intensity) → fuzzyexpr::Engine::convert (thesis ch. 6) → expand_to_sides →
//   35 side parameters → muscles::FaceSolver::deform (thesis §2.4) → the rig's 68 iBUG landmarks
//   (3D, vertices of the deformed mesh, lip landmarks on the re-sampled lip surface) → perspective
//   or orthographic projection to CK+-like pixels (640×490, y down) → Identity (scale, roll,
//   translation, shape offsets).
//
// fuzzyexpr knows six emotions; the two other labels of CK+ get documented recipes:
//   neutral  = all parameters 0;
//   contempt = the EMFACS prototype AU12+AU14 on one side (the subject's left, as in
//              motiongraph::ParametricLandmarkModel): lip corner pulled up and back and tightened,
//              expressed as zygomatic_major_l (AU12) + risorius_l (lateral pull, the AU14 corner
//              tightening has no buccinator in Table 2.1) + orbicularis_oris_pressor (lip
//              tightening), see contempt_parameters().
//
//   bridge::FaceLandmarkModel model;  // built-in default face, solver precomputed once
//   motiongraph::Database db = motiongraph::generate_synthetic_database(model);
#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/motiongraph/synthetic.hpp"
#include "emoface/muscles/solver.hpp"

namespace emoface::bridge {

enum class Projection { Perspective, Orthographic };
std::string_view to_string(Projection p) noexcept;
std::optional<Projection> projection_from_string(std::string_view name) noexcept;

struct FaceLandmarkModelOptions {
  Projection projection = Projection::Perspective;
  /// Perspective: distance from the camera to the centroid of the neutral landmarks along the
  /// face's +z axis (the camera looks straight at the face), metres, [0.2, 100]. CK+ was filmed
  /// frontally from about a metre.
  double camera_distance = 1.0;
  /// Size of the projected neutral face: RMS distance of the 68 neutral landmarks from their
  /// centroid, pixels, (0, 1000]. The default equals motiongraph::ParametricLandmarkModel's neutral
  /// template (face width ≈ 280 px in a 640×490 CK+ frame), so both models give faces of the same
  /// size.
  double face_size_px = 107.4;
  /// Pixel position of the neutral landmarks' centroid (before the identity's translation), x
  /// right, y down. Default: the parametric template's centroid.
  Eigen::Vector2d centre_px = Eigen::Vector2d(320.0, 277.3);
  void validate() const;  ///< throws InvalidInput naming the field
};

/// 35 side parameters (muscles::side_parameter_names() order) of the contempt recipe at `intensity`
/// in [0, 1]: zygomatic_major_l 0.7·i, risorius_l 1.0·i, orbicularis_oris_pressor 0.3·i (EMFACS
/// AU12+14 unilateral: the subject's left corner moves ≈ 11 px out and 9 px up at
/// intensity 1, close to the parametric model's 13 px and 10 px; see docs/motiongraph.md).
std::vector<double> contempt_parameters(double intensity);

class FaceLandmarkModel : public motiongraph::LandmarkModel {
 public:
  /// The built-in default face (facemesh::make_generic_face) and the default rule base.
  explicit FaceLandmarkModel(FaceLandmarkModelOptions options = {});
  /// Any rigged face with 68 iBUG landmarks (InvalidInput otherwise) and any rule base.
  FaceLandmarkModel(muscles::FaceSolver solver, fuzzyexpr::Engine engine,
                    FaceLandmarkModelOptions options = {});

  /// 68 by 2 pixels (iBUG order, y down, 640×490 frame), identity applied. Thread-safe.
  Eigen::MatrixXd landmarks(motiongraph::Label label, double intensity,
                            const motiongraph::Identity& identity) const override;

  /// The 35 side parameters for a label at `intensity` in [0, 1] (one-hot ESV → FMCV → sides, or
  /// the neutral/contempt recipes).
  std::vector<double> side_parameters(motiongraph::Label label, double intensity) const;
  /// The 68 landmarks of the deformed face, 68 by 3, metres (x = subject's left, y up, z out).
  Eigen::MatrixXd landmarks_3d(motiongraph::Label label, double intensity) const;
  /// Projects 68 by 3 face landmarks (metres) to pixels and applies `identity` (as landmarks()).
  Eigen::MatrixXd project(const Eigen::MatrixXd& landmarks_3d,
                          const motiongraph::Identity& identity) const;

  /// Neutral landmarks, 68 by 3 metres (undeformed rig positions).
  const Eigen::MatrixXd& neutral_landmarks_3d() const noexcept { return neutral_; }
  const muscles::FaceSolver& solver() const noexcept { return solver_; }
  const FaceLandmarkModelOptions& options() const noexcept { return options_; }

 private:
  Eigen::MatrixXd project_raw(const Eigen::MatrixXd& landmarks_3d) const;  // camera pixels, y down

  muscles::FaceSolver solver_;
  fuzzyexpr::Engine engine_;
  FaceLandmarkModelOptions options_;
  Eigen::MatrixXd neutral_;     // 68 by 3
  Eigen::Vector3d centroid_;    // of the neutral landmarks
  double pixels_per_unit_ = 1;  // camera scale so the neutral face has face_size_px
  Eigen::Vector2d offset_;      // camera pixels → frame pixels (neutral centroid at centre_px)
};

}  // namespace emoface::bridge
