#pragma once
// The muscle rig baked into named morph targets for engines (facemesh/gltf_morph.hpp):
//
//   * one target per level parameter (the 35 muscle parameters and eye_blink_l/r), named as the
//     parameter: delta = deform(parameter = 1) − deform(0);
//   * the gaze as four half targets "eye_gaze_yaw+", "eye_gaze_yaw-", "eye_gaze_pitch+",
//     "eye_gaze_pitch-": delta = deform(angle = ±limit of the rig's eyes) − deform(0), weight =
//     |angle| / limit on that side (a linear blend of a rotation: at half weight the eyeball points
//     move on the chord, ≤ 1 − cos(limit/2) ≈ 4 % inside the sphere for a 0.55 rad limit);
//   * optionally one target per target of a weight set (e.g. the 52 ARKit shapes, named as in the
//     set): the parameters Mapper::inverse fits to that target alone at weight 1, deformed.
// Head pose is not a morph target: it is the rotation of the glTF head node (head_rotation()).
// split_rigid_parts() then takes the eyeballs and the parts only the jaw moves (lower teeth,
// tongue) out of the skin into nodes rotated about their pivots (eye centre, jaw axis), so engines
// get eyes and a jaw to turn; the skin keeps its morph targets. A weighted sum of targets is the
// linear (blendshape) approximation of the muscle model, whose muscles interact (parallel
// contraction); docs/engines.md reports the difference.
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/facemesh/gltf_morph.hpp"
#include "emoface/facemesh/io.hpp"
#include "emoface/faceweights/mapper.hpp"
#include "emoface/muscles/solver.hpp"

namespace emoface::muscles {

/// What a rigid part of a BakedRig is driven by (BakedRig::parts, same order).
enum class PartDrive { EyeRight, EyeLeft, Jaw };
std::string to_string(PartDrive drive);
PartDrive part_drive_from_string(std::string_view name);

struct BakedRig {
  facemesh::Mesh neutral;                        ///< deform(0) with the rig's faces (the skin
                                                 ///< after split_rigid_parts)
  std::vector<facemesh::MorphTarget> targets;    ///< parameter targets first, then set targets
  std::size_t parameter_target_count = 0;        ///< the first targets, driven by parameters
  Eigen::Vector3d head_pivot = Eigen::Vector3d::Zero();
  double gaze_yaw_limit = 0.0, gaze_pitch_limit = 0.0;  ///< radians
  /// After split_rigid_parts: the rigid parts (nodes), what drives each, and per skin vertex its id
  /// in the face mesh (empty = not split, the skin is the whole mesh).
  std::vector<facemesh::NodePart> parts;
  std::vector<PartDrive> part_drives;
  std::vector<int> skin_vertices;
  bool gaze_targets = true;  ///< false once both eyes are nodes (the four gaze halves dropped)
  std::array<Eigen::Vector2d, 2> eye_limits{};  ///< per eye (right, left): yaw, pitch limits, rad
  double jaw_max_angle = 0.0;                   ///< jaw rotation at masseter = 1, rad (about +x)
};

/// Bakes the rig of `solver` (with `faces` for normals, usually face.mesh.faces). `sets` adds
/// targets per weight set (their mapper must bind muscles::parameter_names()).
BakedRig bake_rig(const FaceSolver& solver, const facemesh::Faces& faces,
                  const std::vector<const faceweights::Mapper*>& sets = {});

/// Options of split_rigid_parts.
struct SplitOptions {
  bool eyes = true;  ///< eyeballs as nodes "eye_r"/"eye_l" (meshes "eyeball_r"/"eyeball_l")
  bool jaw = true;   ///< node "jaw" with meshes "lower_teeth", "tongue", "jaw_rigid" (other parts)
  /// A candidate part's vertices count as unmoved by a target when every delta component is below
  /// this (metres), and as rigidly rotated by the jaw when within it of the rotation. > 0.
  double tolerance = 1e-9;
  void validate() const;
};

/// Moves the rigid parts of a baked rig out of the skin into facemesh::NodePart nodes: an eyeball
/// (Eye::eyeball_vertices) when no face joins it to the rest and no level parameter moves it; a
/// connected component of jaw vertices of weight 1 when no face joins it to the rest, no level
/// parameter but masseter moves it, and masseter moves it by the rigid jaw rotation (so the node
/// reproduces the muscle model exactly). Part meshes are grouped by material (Teeth → lower_teeth,
/// Tongue → tongue, anything else → jaw_rigid). Targets are restricted to the remaining skin; the
/// gaze halves are dropped when both eyes became nodes. `colors` (per face-mesh vertex, may be
/// empty) are restricted to the skin and copied to the parts. Call before express_in_mesh_frame.
void split_rigid_parts(BakedRig& rig, const facemesh::Rig& face_rig,
                       std::vector<Eigen::Vector3f>& colors, const SplitOptions& options = {});

/// Weights of all baked targets for one parameter vector (parameter_names() order): the parameter
/// targets from the values, the weight-set targets 0.
std::vector<double> target_weights(const BakedRig& rig, const std::vector<double>& values);

/// The baked rig posed as a blendshape character, as an engine poses the glTF: neutral +
/// Σ weights[t] · targets[t].position_deltas, `weights` one per target (rig.targets order, finite).
/// #V by 3 (the skin's vertices after split_rigid_parts). Throws InvalidInput on a size mismatch.
facemesh::Vertices blend_targets(const BakedRig& rig, const std::vector<double>& weights);

/// All-target weights for the weight-set targets of a rig baked with exactly one set (bake_rig's
/// `sets` = {&mapper}): parameter targets 0, then `set_weights` (the set's order, e.g. one frame of
/// a faceweights::WeightTrack). Throws InvalidInput when the count does not fit.
std::vector<double> set_target_weights(const BakedRig& rig, const std::vector<double>& set_weights);

/// The head rotation of a parameter vector, as the muscle model applies it (solver.cpp):
/// R = Ry(head_yaw) · Rx(−head_pitch) · Rz(head_roll) about the head pivot.
Eigen::Quaterniond head_rotation(const std::vector<double>& values);

/// Parameter frames → a glTF animation of the baked targets (and the head node, and after
/// split_rigid_parts the eye nodes (gaze through limit_gaze, R = Ry(yaw)·Rx(−pitch)) and the jaw
/// node (Rx(masseter · jaw_max_angle))).
facemesh::WeightAnimation bake_animation(const BakedRig& rig, const std::vector<double>& times,
                                         const std::vector<std::vector<double>>& frames,
                                         const std::string& name = "expression");

/// Re-expresses a baked rig and its animations in the mesh file's own frame (facemesh::Frame of a
/// transferred rig; identity = nothing to do): neutral positions and the head pivot through
/// frame.to_mesh, position deltas by Rᵀ·δ / scale, normal deltas by Rᵀ, head rotations by Rᵀ·q·R;
/// rigid parts' vertices and pivots through frame.to_mesh, their rotations by Rᵀ·q·R.
void express_in_mesh_frame(BakedRig& rig, std::vector<facemesh::WeightAnimation>& animations,
                           const facemesh::Frame& frame);

struct RigGltfOptions {
  std::string animation_name = "expression";
  SplitOptions split;       ///< eyes and jaw as nodes (not for a user's glTF document)
  bool split_parts = true;  ///< false: everything stays in the skin's morph targets
};

struct RigGltfReport {
  bool user_document = false;        ///< written through the face's glTF document (their file kept)
  std::size_t targets = 0;           ///< our targets written
  std::vector<std::string> parts;    ///< node names of the rigid parts written
  std::vector<std::string> renamed;  ///< our target names renamed on a clash with the user's
};

/// The face's rig baked (parameter targets + the 52 ARKit shapes) and written as glTF 2.0 with
/// `frames` (parameter_names() order, one per time, times increasing) as the animation. A face
/// whose mesh is a glTF document (a user's .glb/.gltf transferred by `retarget`) is written through
/// MeshDocument::write_gltf_with_targets: their nodes, skins, materials, UVs and targets kept, ours
/// added (in their file's frame); otherwise write_morph_gltf with the head node and, after
/// split_rigid_parts, eye and jaw nodes.
RigGltfReport write_rig_gltf(const std::string& path, const facemesh::Face& face,
                             const FaceSolver& solver, const std::vector<double>& times,
                             const std::vector<std::vector<double>>& frames,
                             const RigGltfOptions& options = {});

}  // namespace emoface::muscles
