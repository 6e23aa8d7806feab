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
// A weighted sum of targets is the linear (blendshape) approximation of the muscle model, whose
// muscles interact (parallel contraction); docs/engines.md reports the difference.
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "emoface/facemesh/gltf_morph.hpp"
#include "emoface/faceweights/mapper.hpp"
#include "emoface/muscles/solver.hpp"

namespace emoface::muscles {

struct BakedRig {
  facemesh::Mesh neutral;                        ///< deform(0) with the rig's faces
  std::vector<facemesh::MorphTarget> targets;    ///< parameter targets first, then set targets
  std::size_t parameter_target_count = 0;        ///< the first targets, driven by parameters
  Eigen::Vector3d head_pivot = Eigen::Vector3d::Zero();
  double gaze_yaw_limit = 0.0, gaze_pitch_limit = 0.0;  ///< radians
};

/// Bakes the rig of `solver` (with `faces` for normals, usually face.mesh.faces). `sets` adds
/// targets per weight set (their mapper must bind muscles::parameter_names()).
BakedRig bake_rig(const FaceSolver& solver, const facemesh::Faces& faces,
                  const std::vector<const faceweights::Mapper*>& sets = {});

/// Weights of all baked targets for one parameter vector (parameter_names() order): the parameter
/// targets from the values, the weight-set targets 0.
std::vector<double> target_weights(const BakedRig& rig, const std::vector<double>& values);

/// The head rotation of a parameter vector, as the muscle model applies it (solver.cpp):
/// R = Ry(head_yaw) · Rx(−head_pitch) · Rz(head_roll) about the head pivot.
Eigen::Quaterniond head_rotation(const std::vector<double>& values);

/// Parameter frames → a glTF animation of the baked targets (and the head node).
facemesh::WeightAnimation bake_animation(const BakedRig& rig, const std::vector<double>& times,
                                         const std::vector<std::vector<double>>& frames,
                                         const std::string& name = "expression");

/// Re-expresses a baked rig and its animations in the mesh file's own frame (facemesh::Frame of a
/// transferred rig; identity = nothing to do): neutral positions and the head pivot through
/// frame.to_mesh, position deltas by Rᵀ·δ / scale, normal deltas by Rᵀ, head rotations by Rᵀ·q·R.
void express_in_mesh_frame(BakedRig& rig, std::vector<facemesh::WeightAnimation>& animations,
                           const facemesh::Frame& frame);

}  // namespace emoface::muscles
