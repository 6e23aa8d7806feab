#pragma once
// Bringing an arbitrary head mesh into the thesis frame (beyond the thesis, issue #6) and the landmark
// auto-detection heuristics of thesis §3.2.1 ("the tip of the nose is the vertex with the highest z
// value; the top of the head is the vertex with the highest y value").
//
// Thesis frame = the source face's frame: looking down +z, y up, +x towards the subject's left
// (mesh.hpp). A similarity transform p' = s·R·p + t maps the input into it.
//
// R (AlignMode::Auto, default; beyond the thesis, issue #6) is estimated from the geometry, for any input
// rotation:
//   1. area-weighted surface samples (seeded, so the same mesh always gives the same samples);
//   2. bilateral symmetry: the principal axes of the samples are the candidate plane normals (a mirror
//      symmetric mass distribution has its plane normal as a principal axis); each is refined by a
//      trimmed reflect-and-match iteration (FLANN nearest neighbours) and scored by the mismatch of the
//      reflected samples; the best plane gives the left-right axis;
//   3. up/front inside the plane: the source face's samples are matched against the target's for
//      every in-plane angle (5° steps) and both facings (two-sided trimmed chamfer distance), the best
//      poses are refined by a trimmed ICP restricted to rotations about the plane normal (plus scale
//      and translation); the lowest cost wins. Comparing with the source resolves up vs. down and
//      front vs. back and makes the recovered pitch match the source's convention;
//      Each pose's cost includes a cue: its top of head (highest y) and nose tip (highest z) must land
//      where the source's are (a head as deep as it is tall matches the source nearly as well lying
//      on its back; the nose and the top of the head tell);
//   4. cues checked afterwards: the nose tip and the top of the head must lie near the symmetry plane.
// `up`/`front` are hints in Auto mode (they restrict the search to poses within 60° of them) and exact
// axes in AlignMode::Axes (the input is already axis-aligned). s makes the top-of-head to nose-tip
// height equal the source's; t puts the top of the head on the source's centreline (x, z) and height
// (y) and the nose tip at the source's nose depth (z).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "emoface/facemesh/mesh.hpp"

namespace emoface::retarget {

enum class Axis { PosX, NegX, PosY, NegY, PosZ, NegZ };
/// "+x", "-x", "+y", "-y", "+z", "-z".
std::string to_string(Axis axis);
Axis axis_from_string(std::string_view name);

enum class AlignMode {
  Auto,  ///< rotation estimated from the geometry (symmetry plane + matching the source); up/front are hints
  Axes   ///< rotation given by up/front exactly (input already axis-aligned)
};
/// "auto", "axes".
std::string to_string(AlignMode mode);
AlignMode align_mode_from_string(std::string_view name);

struct AlignOptions {
  AlignMode mode = AlignMode::Auto;
  /// Input axis pointing to the top of the head. Auto: optional hint; Axes: required (default +y).
  std::optional<Axis> up;
  /// Input axis the face looks along; must be perpendicular to `up`. Auto: hint; Axes: default +z.
  std::optional<Axis> front;
  bool scale = true;        ///< false: keep the input's size (s = 1)
  int samples = 2000;       ///< Auto: area-weighted surface samples per mesh, [200, 200000]
  std::uint64_t seed = 1;   ///< Auto: seed of the surface sampling (same seed + mesh = same result)
  /// Auto: retarget_face refuses an alignment whose confidence (AlignReport) is below this, with an
  /// error suggesting --align axes; [0, 1]. 0 = accept anything.
  double min_confidence = 0.2;
  /// Auto: an estimated rotation within this many degrees of an axis-aligned frame (one of the 24
  /// signed axis permutations) is replaced by that frame; [0, 10], 0 = never.
  double snap_degrees = 1.5;
  void validate() const;
};

/// What the alignment did and why (Auto mode; Axes mode fills method, rotation fields and confidence 1).
struct AlignReport {
  AlignMode method = AlignMode::Axes;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< rotation axis of R (unit), input frame
  double angle_deg = 0.0;                           ///< rotation angle of R, degrees
  /// Mean mismatch of the samples reflected in the symmetry plane, as a fraction of the RMS radius of
  /// the samples (0 = perfectly symmetric).
  double symmetry_error = 0.0;
  /// 1 − best / second-best symmetry error over distinct candidate planes, [0, 1] (0 = no distinct
  /// plane, e.g. a sphere).
  double symmetry_margin = 1.0;
  /// Trimmed two-sided chamfer distance to the source after the ICP plus 0.05 × landmark_offset, as a
  /// fraction of the source's RMS radius.
  double match_cost = 0.0;
  /// Distance of the target's top of head (highest y) plus that of its nose tip (highest z) from the
  /// source's after the matching, in RMS radii: the §3.2.1 cue that tells up from down and front from
  /// back when the overall shapes alone are ambiguous.
  double landmark_offset = 0.0;
  /// 1 − best / second-best match cost over poses at least 60° apart or facing the other way, [0, 1].
  double orientation_margin = 1.0;
  bool nose_on_plane = true;  ///< the highest-z vertex lies within 10 % of the width from the plane
  bool top_on_plane = true;   ///< the highest-y vertex lies within 10 % of the width from the plane
  bool hints_used = false;    ///< up/front restricted the search
  bool snapped = false;       ///< the estimate was within snap_degrees of an axis-aligned frame and replaced by it
  /// Pitch (rotation about the thesis x axis, degrees) added by retarget_face's search on the initial
  /// error (RetargetOptions::pitch_search_degrees); 0 when not searched.
  double pitch_correction_deg = 0.0;
  /// RetargetOptions::refine_alignment: the frame was refined on the face (similarity ICP of the
  /// source's stable face onto the target), with this many point pairs in the last iteration, by a
  /// rotation of this many degrees and this scale factor (angle and scale also when not applied:
  /// more than RetargetOptions::refine_max_degrees).
  bool refined = false;
  std::size_t refine_points = 0;
  double refine_angle_deg = 0.0;
  double refine_scale = 1.0;
  /// min(symmetry_margin, 2·orientation_margin) clamped to [0, 1], halved for each failed cue.
  double confidence = 1.0;
  std::string message;        ///< one line: which cues decided
};

/// p' = scale·rotation·p + translation (thesis frame from input frame), and how it was found.
struct Alignment {
  double scale = 1.0;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  AlignReport report;
  Eigen::Vector3d apply(const Eigen::Vector3d& p) const { return scale * (rotation * p) + translation; }
  Eigen::Vector3d inverse(const Eigen::Vector3d& q) const { return rotation.transpose() * ((q - translation) / scale); }
  facemesh::Vertices apply(const facemesh::Vertices& v) const;
  facemesh::Vertices inverse(const facemesh::Vertices& v) const;
};

/// Thesis §3.2.1 heuristics on a mesh already in the thesis frame. Only vertices used by some face count.
/// top_of_head: highest y. nose_tip: highest z. ear_r / ear_l: smallest / largest x among vertices
/// between 0.4·h below and 0.6·h above the nose tip (h = top − nose height). Throws InvalidInput for
/// an empty mesh or when the nose tip is not below the top of the head.
struct DetectedLandmark {
  std::string name;
  int vertex = 0;
};
std::vector<DetectedLandmark> detect_landmarks(const facemesh::Mesh& mesh,
                                               const std::vector<std::string>& names = {"top_of_head", "nose_tip", "ear_r", "ear_l"});

/// The similarity transform into the frame of the source face (`source`, in the thesis frame, with its
/// top-of-head and nose-tip positions). Throws InvalidInput for a degenerate target: fewer than 3
/// triangles of non-zero area, all coplanar or collinear, non-finite coordinates, or no height between
/// top and nose. A low confidence is reported, not thrown (see AlignOptions::min_confidence).
Alignment align_to_frame(const facemesh::Mesh& target, const facemesh::Mesh& source, const Eigen::Vector3d& source_top,
                         const Eigen::Vector3d& source_nose, const AlignOptions& options = {});

/// Sets a.scale and a.translation for a.rotation (the rule of align_to_frame: top-of-head to nose-tip
/// height as the source's, top of head on the source's centreline and height, nose at its depth).
void place_in_frame(Alignment& a, const facemesh::Mesh& target, const Eigen::Vector3d& source_top,
                    const Eigen::Vector3d& source_nose, bool scale = true);

/// `count` area-weighted random points on the surface (#count by 3), stratified over the cumulative
/// area and seeded: the same mesh and seed give the same points, and a rotated copy gives the rotated
/// points. Throws InvalidInput if the mesh has no area or a non-finite coordinate.
facemesh::Vertices sample_surface(const facemesh::Mesh& mesh, int count, std::uint64_t seed);

}  // namespace emoface::retarget
