#include "surface_index.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "emoface/core/errors.hpp"
#include "emoface/retarget/validation.hpp"

namespace emoface::retarget::detail {

Eigen::Vector3d barycentric(const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d v0 = b - a, v1 = c - a, v2 = q - a;
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0),
               d21 = v2.dot(v1);
  const double den = d00 * d11 - d01 * d01;
  if (!(std::abs(den) > 0.0)) return Eigen::Vector3d(1.0, 0.0, 0.0);
  double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
  v = std::clamp(v, 0.0, 1.0);
  w = std::clamp(w, 0.0, 1.0);
  if (v + w > 1.0) {
    const double s = v + w;
    v /= s, w /= s;
  }
  return Eigen::Vector3d(1.0 - v - w, v, w);
}

SurfaceIndex::SurfaceIndex(const facemesh::Mesh& mesh, const std::vector<std::uint8_t>& face_mask,
                           int neighbours)
    : mesh_(mesh), neighbours_(neighbours) {
  const auto nv = static_cast<std::size_t>(mesh.vertices.rows());
  if (!face_mask.empty() && face_mask.size() != static_cast<std::size_t>(mesh.faces.rows()))
    throw InvalidInput("SurfaceIndex: face mask of the wrong size");
  std::vector<int> count(nv, 0);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    if (!face_mask.empty() && !face_mask[static_cast<std::size_t>(f)]) continue;
    for (int k = 0; k < 3; ++k) ++count[static_cast<std::size_t>(mesh.faces(f, k))];
  }
  std::vector<int> slot(nv, -1);
  for (std::size_t v = 0; v < nv; ++v)
    if (count[v] > 0)
      slot[v] = static_cast<int>(points_.size()), points_.push_back(static_cast<int>(v));
  if (points_.empty()) return;
  start_.assign(points_.size() + 1, 0);
  for (std::size_t k = 0; k < points_.size(); ++k)
    start_[k + 1] = start_[k] + count[static_cast<std::size_t>(points_[k])];
  incident_.resize(static_cast<std::size_t>(start_.back()));
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    if (!face_mask.empty() && !face_mask[static_cast<std::size_t>(f)]) continue;
    for (int k = 0; k < 3; ++k) {
      const int s = slot[static_cast<std::size_t>(mesh.faces(f, k))];
      incident_[static_cast<std::size_t>(fill[static_cast<std::size_t>(s)]++)] =
          static_cast<int>(f);
    }
  }
  data_.resize(points_.size() * 3);
  for (std::size_t k = 0; k < points_.size(); ++k)
    for (int c = 0; c < 3; ++c)
      data_[3 * k + static_cast<std::size_t>(c)] = static_cast<float>(mesh.vertices(points_[k], c));
  flann::Matrix<float> dataset(data_.data(), points_.size(), 3);
  index_ = std::make_unique<flann::KDTreeSingleIndex<flann::L2_Simple<float>>>(
      dataset, flann::KDTreeSingleIndexParams(10));
  index_->buildIndex();
}

SurfaceHit SurfaceIndex::closest(const Eigen::Vector3d& p) const {
  SurfaceHit best;
  if (points_.empty()) return best;
  const int k = std::min<int>(neighbours_, static_cast<int>(points_.size()));
  float q[3] = {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
  std::vector<int> ids(static_cast<std::size_t>(k));
  std::vector<float> dists(static_cast<std::size_t>(k));
  flann::Matrix<float> query(q, 1, 3);
  flann::Matrix<int> id_m(ids.data(), 1, static_cast<std::size_t>(k));
  flann::Matrix<float> dist_m(dists.data(), 1, static_cast<std::size_t>(k));
  index_->knnSearch(query, id_m, dist_m, static_cast<std::size_t>(k),
                    flann::SearchParams(flann::FLANN_CHECKS_UNLIMITED));
  best.distance = std::numeric_limits<double>::infinity();
  for (int s : ids) {
    if (s < 0) continue;
    for (int e = start_[static_cast<std::size_t>(s)]; e < start_[static_cast<std::size_t>(s) + 1];
         ++e) {
      const int f = incident_[static_cast<std::size_t>(e)];
      const Eigen::Vector3d a = mesh_.vertices.row(mesh_.faces(f, 0)),
                            b = mesh_.vertices.row(mesh_.faces(f, 1)),
                            c = mesh_.vertices.row(mesh_.faces(f, 2));
      const Eigen::Vector3d cp = closest_point_on_triangle(p, a, b, c);
      const double d = (cp - p).norm();
      if (d < best.distance) {
        best.distance = d;
        best.face = f;
        best.point = cp;
      }
    }
  }
  if (best.face >= 0) {
    const Eigen::Vector3d a = mesh_.vertices.row(mesh_.faces(best.face, 0)),
                          b = mesh_.vertices.row(mesh_.faces(best.face, 1)),
                          c = mesh_.vertices.row(mesh_.faces(best.face, 2));
    best.bary = barycentric(best.point, a, b, c);
  }
  return best;
}

}  // namespace emoface::retarget::detail
