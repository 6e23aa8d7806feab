#pragma once
// Private: closest point on a triangle mesh (a subset of its triangles), with the triangle and the
// barycentric coordinates of the hit. The k nearest vertices of the subset (FLANN k-d tree) give
// the candidate triangles (those incident to them); the exact point–triangle distance decides.
// Exact whenever the closest triangle touches one of the k nearest vertices, which holds for any
// mesh whose triangles are not much larger than the distance between the query and the surface.
#include <Eigen/Core>
#include <cstdint>
#include <flann/flann.hpp>
#include <memory>
#include <vector>

#include "emoface/facemesh/mesh.hpp"

namespace emoface::retarget::detail {

struct SurfaceHit {
  int face = -1;                                   ///< triangle id in the mesh, −1 = none
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();  ///< weights of faces(face, 0..2)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double distance = 0.0;
};

/// Barycentric coordinates of q (on or near triangle a, b, c), clamped to the triangle.
Eigen::Vector3d barycentric(const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c);

class SurfaceIndex {
 public:
  /// `face_mask` (#F, or empty = all) selects the triangles searched. The mesh is copied.
  SurfaceIndex(const facemesh::Mesh& mesh, const std::vector<std::uint8_t>& face_mask = {},
               int neighbours = 12);
  SurfaceHit closest(const Eigen::Vector3d& p) const;
  bool empty() const noexcept { return points_.empty(); }

 private:
  facemesh::Mesh mesh_;
  std::vector<int> points_;  // vertex ids in the index
  std::vector<float> data_;
  std::vector<int> start_, incident_;  // per indexed point, its selected triangles (CSR)
  int neighbours_;
  std::unique_ptr<flann::KDTreeSingleIndex<flann::L2_Simple<float>>> index_;
};

}  // namespace emoface::retarget::detail
