#pragma once
// The rig of a face (thesis §2.3): everything the muscle model needs beside the mesh — the 11 regions
// (§2.3.1), the B-spline lip grid (§2.3.2), muscles (Table 2.1, Appendix B), jaw pivot (§2.4.4), eyes
// and eyelids (§2.4.3, §2.4.5), landmarks (iBUG 68 and the retargeting landmarks of chapter 3).
// Units: metres and radians; axes as in mesh.hpp (+x subject's left, +y up, +z out of the face).
#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace emoface::facemesh {

/// The 11 regions of thesis §2.3.1, in the thesis' order (thesis number = enum value + 1).
enum class Region {
  RightLowerFace, RightMiddleFace, RightLowerEyelid, RightUpperEyelid, RightUpperFace,
  LeftLowerFace, LeftMiddleFace, LeftLowerEyelid, LeftUpperEyelid, LeftUpperFace,
  Rest  ///< (11) the non-animated rest of the head (also eyeballs and lips, moved by their own code)
};
inline constexpr int kRegionCount = 11;
std::string to_string(Region region);
/// "right_lower_face" ... "rest"; throws InvalidInput for anything else.
Region region_from_string(std::string_view name);
/// Thesis numbering 1..11.
inline int thesis_number(Region region) { return static_cast<int>(region) + 1; }

/// Surface material per vertex, used only for rendering colours.
enum class Material { Skin, Lip, EyeWhite, Iris, Pupil, Brow, Hair, MouthInterior };
std::string to_string(Material material);
Material material_from_string(std::string_view name);

/// Muscle kinds that carry geometry in the rig. Lips (Orbicularis Oris), eyelids, jaw and eyes are
/// parametric (thesis §2.4.2–2.4.5) and use LipGrid, Eye and Jaw instead.
enum class MuscleKind {
  Vector,    ///< Waters linear muscle (thesis §2.2.3, §2.4.1; reading in seeds/README.md)
  Sphincter  ///< Waters elliptical sphincter (Orbicularis Oculi orbitalis, thesis §2.4.3)
};
std::string to_string(MuscleKind kind);
MuscleKind muscle_kind_from_string(std::string_view name);

struct MuscleSpec {
  std::string name;       ///< unique, e.g. "frontalis_medialis_r_1"
  std::string parameter;  ///< driving parameter, e.g. "frontalis_medialis_r" (several muscles may share one)
  MuscleKind kind = MuscleKind::Vector;
  Eigen::Vector3d head = Eigen::Vector3d::Zero();  ///< v1, bony attachment (vector) or centre (sphincter), m
  Eigen::Vector3d tail = Eigen::Vector3d::Zero();  ///< v2, skin insertion (vector only), m; |tail-head| > 0
  double omega = 0.5;         ///< zone half-angle Ω, radians, (0, π)
  double rs = 0.02;           ///< fall-off start radius Rs, m, > 0
  double rf = 0.04;           ///< fall-off end radius Rf, m, > rs
  double k = 0.01;            ///< elasticity: displacement at full contraction, m, >= 0
  Eigen::Vector2d semi_axes = Eigen::Vector2d::Zero();  ///< sphincter ellipse semi-axes (x, y), m, > 0
  std::vector<Region> regions;  ///< regions the muscle may move (cut-off, thesis §2.4.1)
  bool moves_lips = false;      ///< also moves lip control points (thesis §2.3.2)
  int wrinkle_count = 0;        ///< Nw, number of wrinkles (0 = none), thesis §2.4.1
  double wrinkle_height = 0.0;  ///< a, wrinkle height at full contraction, m, >= 0
};

/// The lip B-spline surface (thesis §2.3.2, after King et al. 2000): kAround × kAcross control points,
/// periodic cubic around the mouth, clamped cubic across (row 0 = outer lip border stitched to the face,
/// row kAcross-1 = inside the mouth). Sampled on a fixed (samples_around × samples_across) grid whose
/// vertices occupy [first_vertex, first_vertex + samples_around*samples_across) in the mesh, index
/// first_vertex + j*samples_around + i for sample column i (around) and row j (across).
struct LipGrid {
  static constexpr int kAround = 24;
  static constexpr int kAcross = 6;
  std::vector<Eigen::Vector3d> control_points;  ///< kAcross*kAround, index row*kAround + column, m; empty = no lips
  int samples_around = 48;                      ///< >= kAround
  int samples_across = 8;                       ///< >= kAcross
  int first_vertex = 0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< mouth centre, m
  /// Column c sits at angle 2πc/kAround around the mouth, counter-clockwise seen from the front,
  /// starting at the subject's left corner; columns with sin < 0 belong to the lower lip.
};

/// Jaw rotation about an axis parallel to x through the pivot (thesis §2.4.4, after Parke 1974).
struct Jaw {
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();  ///< m
  double max_angle = 0.3;     ///< opening at masseter = 1, radians, [0, π/2]
  std::vector<int> vertices;  ///< lower-face vertices rotated by the jaw
  std::vector<double> weights;  ///< per vertex in [0, 1] (1 = rotates fully)
};

/// One eye: eyeball, eyelids and gaze limit (thesis §2.4.3, §2.4.5).
struct Eye {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< eyeball centre, m
  double radius = 0.012;                             ///< eyeball radius, m
  std::vector<int> eyeball_vertices;
  std::vector<int> upper_lid;  ///< upper-eyelid vertices
  std::vector<double> upper_lid_weights;  ///< [0,1], 1 at the lid margin
  std::vector<int> lower_lid;
  std::vector<double> lower_lid_weights;
  double close_angle = 0.6;   ///< upper-lid rotation (rad, about +x through centre) that closes the eye
  double open_angle = 0.15;   ///< extra upper-lid raise at full levator contraction, rad
  double yaw_limit = 0.6;     ///< elliptical eye-hole limit: (yaw/yaw_limit)^2+(pitch/pitch_limit)^2 <= 1
  double pitch_limit = 0.4;
};

struct NamedLandmark {
  std::string name;
  int vertex = 0;
};

struct Rig {
  std::string mesh_file;        ///< mesh path, relative to the rig file's directory (may be empty in memory)
  std::size_t vertex_count = 0; ///< vertices the mesh must have
  std::vector<Region> regions;  ///< per vertex
  std::vector<Material> materials;  ///< per vertex
  LipGrid lips;
  Jaw jaw;
  std::array<Eye, 2> eyes;      ///< [0] right, [1] left
  Eigen::Vector3d head_pivot = Eigen::Vector3d::Zero();  ///< centre of head rotation (neck), m
  std::vector<int> ibug68;      ///< 68 landmark vertices, iBUG/CK+ order (0-based: jaw 0–16, brows 17–26, ...)
  std::vector<NamedLandmark> retarget_landmarks;  ///< chapter 3 landmarks, incl. "top_of_head", "nose_tip"
  std::vector<MuscleSpec> muscles;
};

/// Checks the rig on its own and against a mesh of `vertex_count` vertices: sizes, ids in range,
/// finite numbers, Rs < Rf, non-zero muscle length, unique muscle names, weights in [0,1].
/// Throws FormatError naming `source` and the JSON pointer of the problem.
void validate_rig(const Rig& rig, const std::string& source = "<rig>");

/// Vertex ids per region (index = enum value), ascending.
std::array<std::vector<int>, kRegionCount> region_vertices(const Rig& rig);

}  // namespace emoface::facemesh
