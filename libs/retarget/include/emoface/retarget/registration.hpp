#pragma once
// Dense non-rigid registration of a source surface onto a target surface (beyond the thesis, issue
// 13): landmark-guided non-rigid ICP in the spirit of Amberg, Romdhani & Vetter 2007 ("Optimal step
// nonrigid ICP algorithms for surface registration", CVPR), with a stiffness schedule.
//
// Unknowns: one displacement d_i per source vertex (not Amberg's 3×4 affine per vertex). Energy per
// iteration, correspondences c_i fixed (closest point on the target, rejected beyond a distance or
// when the normals disagree):
//   E(d) = Σ_i w_i |x_i + d_i − c_i|²  +  α Σ_(i,j)∈edges |d_i − d_j|²  +  β Σ_l |x_l + d_l − t_l|²
// The three coordinates decouple, so one sparse Cholesky factorisation (Eigen SimplicialLDLT) of
// (W + αL + βW_l + εI) serves the x, y and z solves. α runs through a decreasing schedule (stiff
// first: the surface moves almost as a whole; then softer: local detail), several iterations each.
//
//   RegistrationResult r = register_nonrigid(source, data_mask, target, landmarks, options);
//   r.vertices;   // #V by 3: the registered source, same units as the inputs
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "emoface/facemesh/mesh.hpp"

namespace emoface::retarget {

struct RegistrationOptions {
  /// Stiffness α per stage (dimensionless: weight of the edge term relative to one data vertex),
  /// decreasing; each > 0, at most 20 stages.
  std::vector<double> stiffness = {50.0, 20.0, 8.0, 3.0, 1.5, 0.5};
  int iterations_per_stage = 4;   ///< correspondence updates per stage, [1, 50]
  double landmark_weight = 20.0;  ///< β, relative to one data vertex, [0, 1e6]
  /// Correspondences farther than this are rejected, as a fraction of the source's bounding-box
  /// diagonal, (0, 1].
  double max_distance = 0.08;
  double max_normal_angle_deg = 70.0;  ///< source/target normal disagreement that rejects, (0, 180]
  void validate() const;
};

struct RegistrationReport {
  int iterations = 0;
  std::size_t correspondences = 0;  ///< accepted in the last iteration
  double initial_rms =
      0.0;  ///< RMS source-to-target distance of the data vertices before, input units
  double final_rms = 0.0;  ///< after
  double seconds = 0.0;    ///< wall time (non-deterministic)
};

/// A landmark: source vertex `vertex` should land on `target` (input units).
struct RegistrationLandmark {
  int vertex = 0;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
};

struct RegistrationResult {
  facemesh::Vertices vertices;  ///< #V by 3, the registered source
  RegistrationReport report;
};

/// Registers `source` onto `target`. `data_mask` (#V of source, or empty = all) selects the source
/// vertices that seek the target surface; the others follow through the edge term (and the
/// landmarks). Throws InvalidInput for empty meshes, a mask of the wrong size, landmark ids out of
/// range or non-finite input.
RegistrationResult register_nonrigid(const facemesh::Mesh& source,
                                     const std::vector<std::uint8_t>& data_mask,
                                     const facemesh::Mesh& target,
                                     const std::vector<RegistrationLandmark>& landmarks = {},
                                     const RegistrationOptions& options = {});

}  // namespace emoface::retarget
