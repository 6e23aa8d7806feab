#pragma once
// Bringing an arbitrary head mesh into the thesis frame (beyond the thesis, issue #6) and the landmark
// auto-detection heuristics of thesis §3.2.1 ("the tip of the nose is the vertex with the highest z
// value; the top of the head is the vertex with the highest y value").
//
// Thesis frame = the source face's frame: looking down +z, y up (mesh.hpp). A similarity transform
// p' = s·R·p + t maps the input into it: R from the user's up/front axes, s so that the top-of-head to
// nose-tip height equals the source's, t so that the top of the head lies on the source's centreline
// (x, z) and height (y) and the nose tip at the source's nose depth (z).
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

struct AlignOptions {
  Axis up = Axis::PosY;     ///< input axis pointing to the top of the head
  Axis front = Axis::PosZ;  ///< input axis the face looks along; must be perpendicular to `up`
  bool scale = true;        ///< false: keep the input's size (s = 1)
  void validate() const;
};

/// p' = scale·rotation·p + translation (thesis frame from input frame).
struct Alignment {
  double scale = 1.0;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
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

/// The similarity transform into the frame of the source face, given the source's top-of-head and
/// nose-tip positions. Throws InvalidInput for a degenerate target (no height between top and nose).
Alignment align_to_frame(const facemesh::Mesh& target, const Eigen::Vector3d& source_top,
                         const Eigen::Vector3d& source_nose, const AlignOptions& options = {});

}  // namespace emoface::retarget
