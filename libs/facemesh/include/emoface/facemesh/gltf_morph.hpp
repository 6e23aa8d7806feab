#pragma once
// glTF 2.0 for engines: a neutral mesh with NAMED morph targets (POSITION + NORMAL deltas, sparse
// accessors where they are smaller), vertex colours and a PBR material, and animations of the target
// weights over time (plus an optional head rotation about a pivot). Engines (three.js, Unity,
// Unreal, Blender, Godot) re-pose or retarget such a file by target name; the per-frame-target
// writer of gltf.hpp cannot be re-posed.
//
// The function takes a neutral mesh and named deltas only, so any rig can be baked into it (the
// muscle rig: muscles/morph_targets.hpp).
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "emoface/facemesh/mesh.hpp"

namespace emoface::facemesh {

struct MorphTarget {
  std::string name;          ///< unique, non-empty; written to mesh.extras.targetNames
  Vertices position_deltas;  ///< #V by 3, metres
  Vertices normal_deltas;    ///< #V by 3 (unit-normal differences) or empty for no NORMAL delta
};

/// One mesh node under a rigid part (e.g. "lower_teeth" under "jaw").
struct PartMesh {
  std::string name;                     ///< node and mesh name, unique in the file
  Mesh mesh;                            ///< vertices in the neutral mesh's frame (not relative), m
  std::vector<Eigen::Vector3f> colors;  ///< per vertex linear RGB in [0, 1] → COLOR_0; empty = none
};

/// A rigid part written as its own node (child of "head") at `pivot`, rotated by the animation
/// about the pivot (eyeballs about the eye centre, the lower teeth and tongue about the jaw axis);
/// its meshes are child nodes holding the vertices relative to the pivot.
struct NodePart {
  std::string name;  ///< transform node name, unique in the file ("eye_r", "jaw")
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();  ///< metres, the neutral mesh's frame
  std::vector<PartMesh> meshes;                     ///< ≥ 1
};

struct WeightAnimation {
  std::string name = "animation";
  std::vector<double> times;                 ///< seconds, finite, strictly increasing, ≥ 1 key
  std::vector<std::vector<double>> weights;  ///< per key: one weight per target (finite)
  /// Optional: per key, the rotation of the head node about MorphGltfOptions::head_pivot
  /// (empty = no rotation channel).
  std::vector<Eigen::Quaterniond> head_rotations;
  /// Optional: per part of MorphGltfOptions::parts, per key, its rotation about its pivot (in the
  /// head's frame); empty = no part channels, else one list per part, each empty (not animated) or
  /// one rotation per key.
  std::vector<std::vector<Eigen::Quaterniond>> part_rotations;
};

struct MorphGltfOptions {
  std::string name = "face";              ///< mesh and node name
  std::vector<Eigen::Vector3f> colors;    ///< per vertex linear RGB in [0, 1] → COLOR_0; empty = none
  Eigen::Vector3d head_pivot = Eigen::Vector3d::Zero();  ///< metres; node "head" rotates about it
  bool normals = true;                    ///< write NORMAL (base) and NORMAL deltas
  /// Rigid parts as nodes under "head" (names must differ from "head", `name` and each other).
  std::vector<NodePart> parts;
  /// A delta component below this (metres, or unit-normal units) counts as zero for sparse storage;
  /// an accessor is written sparse when that takes fewer bytes than dense. ≥ 0.
  double sparse_epsilon = 1e-7;
  void validate() const;
};

/// What was written (sizes for the docs and tests).
struct MorphGltfReport {
  std::size_t bytes = 0;            ///< file size
  std::size_t sparse_accessors = 0;
  std::size_t dense_accessors = 0;  ///< target accessors stored dense
};

/// Writes `.gltf` (buffer embedded as base64) or `.glb`, atomically. Throws InvalidInput for
/// mismatched sizes, repeated/empty target names, bad times or weights, IoError on failure.
MorphGltfReport write_morph_gltf(const std::string& path, const Mesh& neutral,
                                 const std::vector<MorphTarget>& targets,
                                 const std::vector<WeightAnimation>& animations,
                                 const MorphGltfOptions& options = {});

}  // namespace emoface::facemesh
