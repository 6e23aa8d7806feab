#pragma once
// The rig of a face (thesis §2.3): everything the muscle model needs beside the mesh — the 11 regions
// (§2.3.1), the B-spline lip grid (§2.3.2), muscles (Table 2.1, Appendix B), jaw pivot (§2.4.4), eyes
// and eyelids (§2.4.3, §2.4.5), landmarks (iBUG 68 and the retargeting landmarks of chapter 3).
// Units: metres and radians; axes as in mesh.hpp (+x subject's left, +y up, +z out of the face).
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

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
enum class Material { Skin, Lip, EyeWhite, Iris, Pupil, Brow, Hair, MouthInterior, Teeth, Tongue, Lash };
inline constexpr int kMaterialCount = 11;
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
/// A mesh vertex driven by the lip surface instead of being one of the grid's samples (rigs transferred
/// onto a user's mesh, rig format 1.1). After the muscles, the jaw and the lip actions the vertex moves to
///   x = (1 − weight)·x_muscles + weight·(S(u, v) + offset),
/// S the deformed lip B-spline surface (u ∈ [0, 1) around the mouth from column 0, v ∈ [0, 1] across,
/// 0 = outer border row), `offset` the vertex's neutral offset from S(u, v) (rig frame, m).
struct LipBinding {
  int vertex = 0;
  double u = 0.0;
  double v = 0.0;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  double weight = 1.0;  ///< [0, 1]
};

struct LipGrid {
  static constexpr int kAround = 24;
  static constexpr int kAcross = 6;
  std::vector<Eigen::Vector3d> control_points;  ///< kAcross*kAround, index row*kAround + column, m; empty = no lips
  int samples_around = 48;                      ///< [kAround, 1024]
  int samples_across = 8;                       ///< [kAcross, 256]
  int first_vertex = 0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< mouth centre, m
  /// true (the built-in face): the samples are mesh vertices [first_vertex, ...) as above. false (a
  /// transferred rig): no grid sample is a mesh vertex; the lip surface drives the `bound` vertices.
  bool samples_in_mesh = true;
  std::vector<LipBinding> bound;  ///< vertices driven through (u, v, offset); may be used with either mode
  /// Jaw weight of the skin beside each border control point (column c of row 0), kAround values in
  /// [0, 1]: how far the border turns with the jaw (thesis §2.4.4; inner rows blend towards the
  /// thesis' lower/upper-lip weights). Empty: the solver takes the weight of the jaw vertex nearest
  /// to the control point (within 4 mm), which depends on the mesh's vertices — a transferred rig
  /// carries the source's values here (rig format 1.2) so that a remeshed face moves its lips as
  /// the source does (muscles::lip_border_jaw_weights).
  std::vector<double> border_jaw;
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
  /// The angle the lid tightener (AU7) and the cheek's push on the lower lid (AU6) are fractions of
  /// (muscles::SolverOptions::lid_tighten_upper/lower, lid_cheek_raise), rad, in [0, close_angle];
  /// empty: close_angle (rig format 1.3; absent before). The default head closes its lids by an
  /// angle measured where the eye is widest and tightens them by one measured over the whole
  /// margin, so that a full blink closes the eye without making AU7 and AU6 stronger (issue 14).
  std::optional<double> tighten_angle;
  double open_angle = 0.15;   ///< extra upper-lid raise at full levator contraction, rad
  double yaw_limit = 0.6;     ///< elliptical eye-hole limit: (yaw/yaw_limit)^2+(pitch/pitch_limit)^2 <= 1
  double pitch_limit = 0.4;
};

/// Separate parts of a user's mesh (found by the transfer, rig format 1.1). What moves them is expressed
/// through the ordinary rig lists (an eyeball's vertices in Eye::eyeball_vertices, lower teeth and tongue
/// in Jaw::vertices with weight 1, lashes in the lid lists); Part records what was found, for reports,
/// colours and tools.
enum class PartKind { Head, Eyeball, UpperTeeth, LowerTeeth, Tongue, Lashes, Brows, Other };
std::string to_string(PartKind kind);
PartKind part_kind_from_string(std::string_view name);

struct Part {
  std::string name;           ///< e.g. the OBJ group/object/material name, or "component_3"
  PartKind kind = PartKind::Other;
  int side = -1;              ///< −1 none/both, 0 right, 1 left (as Rig::eyes)
  std::vector<int> vertices;  ///< ascending
};

/// Mesh frame → rig frame (rig format 1.1). The rig (muscles, pivots, eyes, lips) and FaceSolver live in
/// the thesis frame (metres, +x subject's left, +y up, +z out of the face); a user's mesh file keeps its
/// own frame and units: p_rig = scale·rotation·p_mesh + translation. Identity for the built-in face.
struct Frame {
  double scale = 1.0;                                          ///< > 0
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();      ///< proper rotation
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();       ///< m
  Eigen::Vector3d to_rig(const Eigen::Vector3d& p) const { return scale * (rotation * p) + translation; }
  Eigen::Vector3d to_mesh(const Eigen::Vector3d& p) const { return rotation.transpose() * (p - translation) / scale; }
  bool is_identity() const { return scale == 1.0 && rotation == Eigen::Matrix3d::Identity() && translation.isZero(0.0); }
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
  Frame frame;                  ///< mesh file frame → this rig's frame (format 1.1; identity = absent)
  std::vector<Part> parts;      ///< separate parts found by a transfer (format 1.1; may be empty)
};

/// Checks the rig on its own and against a mesh of `vertex_count` vertices: sizes, ids in range,
/// finite numbers, Rs < Rf, non-zero muscle length, unique muscle names, weights in [0,1].
/// Throws FormatError naming `source` and the JSON pointer of the problem.
void validate_rig(const Rig& rig, const std::string& source = "<rig>");

/// Vertex ids per region (index = enum value), ascending.
std::array<std::vector<int>, kRegionCount> region_vertices(const Rig& rig);

}  // namespace emoface::facemesh
