#pragma once
// Synthetic validation of the fit (issue #6, beyond the thesis): known smooth warps of a face, rigid
// moves, and the surface distance between two meshes measured with FLANN nearest neighbours.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "emoface/facemesh/mesh.hpp"

namespace emoface::retarget {

/// A smooth non-linear warp followed by a similarity transform, applied to points in the thesis frame.
/// With all defaults it is the identity.
struct SyntheticWarp {
  double width = 1.0;    ///< x scale factor, (0.2, 5)
  double height = 1.0;   ///< y scale factor, (0.2, 5)
  double depth = 1.0;    ///< z scale factor, (0.2, 5)
  double taper = 0.0;    ///< x scale changes by taper·y/0.1 m (a head wider at the top for > 0), [-0.5, 0.5]
  double nose = 0.0;     ///< extra forward push of the nose, m: a Gaussian bump (σ = 2 cm) at `nose_centre`
  Eigen::Vector3d nose_centre = Eigen::Vector3d(0.0, -0.037, 0.1);
  double chin = 0.0;     ///< chin lengthening, m: points below y = −0.06 m move down by chin·smoothstep
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();  ///< rigid rotation (yaw about y, pitch about x, roll about z), radians
  double scale = 1.0;    ///< uniform scale after the warp, > 0
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  ///< after scaling, m
  void validate() const;
  Eigen::Vector3d apply(const Eigen::Vector3d& p) const;
  facemesh::Vertices apply(const facemesh::Vertices& v) const;
};

struct SurfaceDistance {
  double mean = 0.0;          ///< m
  double p95 = 0.0;           ///< 95th percentile, m
  double max = 0.0;           ///< m
  std::size_t samples = 0;    ///< query points used
};

/// For every vertex of `from` with mask[i] != 0 (all when mask is empty), the distance to the surface
/// `to`: the k-d tree (FLANN) finds the 8 nearest vertices and face centroids of `to`, then the exact
/// point–triangle distance to their triangles is taken. Throws InvalidInput for empty meshes or a mask
/// of the wrong size or selecting nothing.
SurfaceDistance surface_distance(const facemesh::Mesh& from, const facemesh::Mesh& to,
                                 const std::vector<std::uint8_t>& mask = {});

/// Re-tessellation for the validation suite: quadric-error edge collapse (Garland & Heckbert 1997)
/// down to `keep_fraction` of the used vertices, each collapse moving the surviving vertex to the
/// best of the two end points and the midpoint under the summed plane quadrics of both. An edge is
/// collapsed only if neither end lies on an open boundary (holes and rims keep their shape), the link
/// condition holds (exactly two common neighbours, so the result stays manifold) and no remaining
/// triangle turns by more than ~78° or degenerates. Unused vertices are dropped. Throws InvalidInput
/// for keep_fraction outside (0, 1] or a mesh that is not a valid triangle mesh. `keep_positions`:
/// half-edge collapses only (the survivor stays where it was, never the midpoint), so every remaining
/// vertex is one of the input's — a remeshing with exactly known correspondence (transfer tests).
facemesh::Mesh decimate(const facemesh::Mesh& mesh, double keep_fraction, bool keep_positions = false);

/// Closest point on triangle (a, b, c) to p (Ericson, Real-Time Collision Detection §5.1.5).
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace emoface::retarget
