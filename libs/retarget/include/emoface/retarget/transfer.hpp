#pragma once
// Transfer of a rig onto the user's own mesh (issue 13): the output rig's mesh *is* the target mesh
// — same vertices in the same order, same faces — and the rig (muscles, regions, lips, jaw, eyes,
// landmarks, parts) is carried onto it. Pipeline:
//   1. connected components; the head = the largest by area; the others are parts (eyeballs, teeth,
//      tongue, lashes, brows: group/material names as hints, sphere fits for eyeballs);
//   2. the thesis fit on the head component (retarget_face: alignment, RBF + GA, chapter 3), or
//   with
//      user iBUG-68 landmarks an RBF that also interpolates them;
//   3. dense registration of the fitted generic face onto the head (registration.hpp);
//   4. every head vertex takes the attributes of its closest point on the registered generic
//   surface
//      (triangle + barycentrics): region, material, jaw weight, lid weights; lip vertices are bound
//      to the lip B-spline surface by (u, v, offset); on the generic's strip between mouth rim and
//      lip border row the weight is the interpolated lip share, fading from 1 to 0 (no seam); a
//      mouth bag behind closed lips gets jaw weights from geodesic distances to the two lips;
//   5. muscle ends, lip grid, pivots and eye centres are mapped with the fit's RBF plus the
//      registration's residual field; lengths scale with the fit.
// The rig lives in the rig (thesis) frame; Rig::frame maps the input frame into it (p_rig =
// scale·R·p_mesh + t), so the mesh file stays in the input's own frame and units.
//
//   TransferResult r = transfer_rig(facemesh::make_generic_face(), doc.triangles(), doc.groups());
//   r.face.mesh   // the target's triangles in the rig frame; r.face.rig.frame maps the file into
//   it
#include <Eigen/Core>
#include <array>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "emoface/facemesh/io.hpp"
#include "emoface/facemesh/mesh_document.hpp"
#include "emoface/retarget/registration.hpp"
#include "emoface/retarget/retarget.hpp"

namespace emoface::retarget {

/// One user landmark of the iBUG-68 scheme: unknown, a vertex id of the target, or a point in the
/// target's own frame and units.
enum class UserLandmarkKind { Missing, Vertex, Point };
struct UserLandmark {
  UserLandmarkKind kind = UserLandmarkKind::Missing;
  int vertex = -1;  ///< Vertex: 0-based id into the target's vertices
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< Point: input frame and units
};
/// The 68 iBUG points (0-based, iBUG/CK+ order, as Rig::ibug68). Empty `points` = none given.
struct UserLandmarks {
  static constexpr int kCount = 68;
  std::vector<UserLandmark> points;  ///< empty or exactly 68
  bool empty() const noexcept { return points.empty(); }
  /// Size 68, vertex ids in [0, vertex_count), finite points; at least 4 given. Throws InvalidInput
  /// naming the landmark.
  void validate(std::size_t vertex_count) const;
};

struct TransferOptions {
  RetargetOptions fit;               ///< the thesis fit on the head component
  RegistrationOptions registration;  ///< dense registration of the fitted face onto the head
  /// A component is a second head (error) when its area is at least this fraction of the largest
  /// component's and its centre lies outside the largest one's bounding box; (0, 1].
  double several_heads_area = 0.3;
  /// Sphere fit accepted as an eyeball when the RMS residual is below this fraction of the radius
  /// and the radius within [0.5, 2] × the source eye radius (scaled); (0, 1].
  double eyeball_tolerance = 0.12;
  /// The rig frame refined on the face before the fit (RetargetOptions::refine_alignment, turned
  /// on here: the fit's landmarks and so every attribute depend on it); false =
  /// fit.refine_alignment.
  bool refine_frame = true;
  void validate() const;
};

/// Residuals of the registration per region: distance from each target vertex of the region to the
/// registered generic surface.
struct RegionResidual {
  std::string region;  ///< Region names, "lips", "mouth_bag"
  std::size_t vertices = 0;
  double mean = 0.0;  ///< input units
  double p95 = 0.0;
  double max = 0.0;
  double mean_percent = 0.0;  ///< of the head height
  double p95_percent = 0.0;
  double max_percent = 0.0;
};

struct LandmarkConfidence {
  int index = 0;          ///< iBUG index 0..67
  int vertex = -1;        ///< target vertex id
  std::string source;     ///< "user" or "fit"
  double distance = 0.0;  ///< registered generic landmark → chosen target vertex, input units
  double confidence =
      0.0;  ///< [0, 1]: 1 for user landmarks; exp(−(distance / 1 % head height)²) otherwise
};

struct PartReport {
  std::string name;
  facemesh::PartKind kind = facemesh::PartKind::Other;
  int side = -1;
  std::size_t vertices = 0;
  std::string found_by;  ///< "head", "name", "sphere fit", "position", "none (rigid)"
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< eyeball sphere centre, input frame
  double radius = 0.0;                               ///< eyeball sphere radius, input units
  double rms = 0.0;                                  ///< sphere fit residual / radius
};

struct TransferReport {
  double head_height = 0.0;  ///< top of head to chin of the registered generic face, input units
  double scale = 1.0;        ///< rig frame units per input unit (Rig::frame.scale)
  std::size_t components = 0;
  RegistrationReport registration;
  std::vector<RegionResidual> residuals;
  std::vector<LandmarkConfidence> landmarks;  ///< 68
  std::vector<PartReport> parts;
  std::size_t lip_bound = 0;  ///< vertices bound to the lip surface (any weight)
  std::size_t lip_full = 0;   ///< of which with weight 1
  std::size_t lip_bag_bound = 0;  ///< of which mouth-bag vertices next to the lips (following them)
  std::size_t jaw_vertices = 0;
  std::size_t mouth_bag = 0;  ///< vertices of a mouth bag (jaw weights from geodesic distances)
  std::array<std::size_t, 2> lid_vertices{};  ///< per eye, upper + lower
  /// per eye: head vertices closing the eye opening in front of the eye centre (a head without
  /// separate eyeballs); they are turned by gaze like an eyeball (Eye::eyeball_vertices), not moved
  /// by the lids
  std::array<std::size_t, 2> eye_hole_vertices{};
  /// per eye (0 right, 1 left): how the lid weights were made: "generic" (the generic's weights at
  /// each vertex's closest point; they give the target's margin full weight), "boundary" or
  /// "crease" (rebuilt from the target's own lid margin, an open boundary loop or the crease of a
  /// closed socket), "none" (no margin found: generic weights)
  std::array<std::string, 2> lid_method{"none", "none"};
  /// per eye: the target's lid margin found (vertex ids, ascending x, the corners in both)
  std::array<std::vector<int>, 2> lid_margin_upper, lid_margin_lower;
  /// inner-lip iBUG points (60–67) placed on the target's own mouth slit (0: the fit's were kept)
  std::size_t mouth_slit_points = 0;
  /// chapter-3 retargeting landmarks replaced by the user's iBUG points (retarget_landmark_ibug)
  std::vector<std::string> replaced_landmarks;
  bool user_landmarks = false;
  double fit_seconds = 0.0;  ///< wall times (non-deterministic)
  double registration_seconds = 0.0;
  double transfer_seconds = 0.0;
  std::vector<std::string> warnings;
};

struct TransferResult {
  /// The target's triangles in the rig frame (all components, target vertex order) and the complete
  /// rig with its frame; rig.mesh_file is empty (the caller names the file).
  facemesh::Face face;
  TransferReport report;
  RetargetResult fit;             ///< the thesis fit on the head component (fit.face: generic face)
  facemesh::Vertices registered;  ///< the generic face after the dense registration, rig frame
};

/// Transfers `source` (the built-in face or any rig with the chapter-3 landmarks) onto `target`
/// (input frame and units). `groups` (optional, MeshDocument::groups()) name triangles: hints for
/// parts. Throws InvalidInput for a target without faces, with NaN/inf, ids out of range,
/// non-manifold edges, several heads, or bad landmarks (naming the problem); the fit's own errors
/// pass through.
TransferResult transfer_rig(const facemesh::Face& source, const facemesh::Mesh& target,
                            const std::vector<facemesh::MeshGroup>& groups = {},
                            const TransferOptions& options = {},
                            const UserLandmarks& landmarks = {},
                            const std::function<void(const GaProgress&)>& progress = {});

/// The chapter-3 retargeting landmarks (Rig::retarget_landmarks names) that have an iBUG-68
/// counterpart, with its 0-based index: a user's iBUG point replaces the fit's landmark of that
/// name.
const std::vector<std::pair<std::string, int>>& retarget_landmark_ibug();

/// Position on the lip B-spline surface of `lips` (thesis §2.3.2): u ∈ [0, 1) around the mouth from
/// column 0, v ∈ [0, 1] across (0 = outer border row), as LipSampler samples it.
Eigen::Vector3d lip_surface_point(const facemesh::LipGrid& lips, double u, double v);

}  // namespace emoface::retarget
