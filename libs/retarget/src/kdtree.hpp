#pragma once
// Private: a 3-D nearest-neighbour index over a fixed point set (FLANN single k-d tree, exact search).
// FLANN stays out of every public header.
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <flann/flann.hpp>

#include "emoface/facemesh/mesh.hpp"

namespace emoface::retarget::detail {

class PointIndex {
 public:
  /// `points`: #N by 3 (N ≥ 1); copied (as float).
  explicit PointIndex(const facemesh::Vertices& points) : data_(static_cast<std::size_t>(points.rows()) * 3) {
    for (Eigen::Index i = 0; i < points.rows(); ++i)
      for (int k = 0; k < 3; ++k) data_[static_cast<std::size_t>(i) * 3 + static_cast<std::size_t>(k)] = static_cast<float>(points(i, k));
    flann::Matrix<float> dataset(data_.data(), static_cast<std::size_t>(points.rows()), 3);
    index_ = std::make_unique<flann::KDTreeSingleIndex<flann::L2_Simple<float>>>(dataset, flann::KDTreeSingleIndexParams(10));
    index_->buildIndex();
  }
  /// Index of the nearest point and its squared distance.
  int nearest(const Eigen::Vector3d& p, double& squared_distance) const {
    float q[3] = {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
    int id = 0;
    float d = 0.0f;
    flann::Matrix<float> query(q, 1, 3);
    flann::Matrix<int> ids(&id, 1, 1);
    flann::Matrix<float> dists(&d, 1, 1);
    index_->knnSearch(query, ids, dists, 1, flann::SearchParams(flann::FLANN_CHECKS_UNLIMITED));
    squared_distance = d;
    return id;
  }

 private:
  std::vector<float> data_;
  std::unique_ptr<flann::KDTreeSingleIndex<flann::L2_Simple<float>>> index_;
};

}  // namespace emoface::retarget::detail
