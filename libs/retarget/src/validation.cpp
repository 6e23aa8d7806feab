#include "emoface/retarget/validation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>
#include <flann/flann.hpp>

#include "emoface/core/errors.hpp"

namespace emoface::retarget {

void SyntheticWarp::validate() const {
  auto in = [](double v, double lo, double hi) { return std::isfinite(v) && v > lo && v < hi; };
  if (!in(width, 0.2, 5) || !in(height, 0.2, 5) || !in(depth, 0.2, 5)) throw InvalidInput("SyntheticWarp: scale factors must be in (0.2, 5)");
  if (!(std::abs(taper) <= 0.5)) throw InvalidInput("SyntheticWarp: taper must be in [-0.5, 0.5]");
  if (!std::isfinite(nose) || !std::isfinite(chin) || !nose_centre.allFinite() || !rotation.allFinite() ||
      !translation.allFinite() || !(scale > 0.0) || !std::isfinite(scale))
    throw InvalidInput("SyntheticWarp: values must be finite and scale > 0");
}

Eigen::Vector3d SyntheticWarp::apply(const Eigen::Vector3d& p) const {
  Eigen::Vector3d q = p;
  q.x() *= width * (1.0 + taper * p.y() / 0.1);
  q.y() *= height;
  q.z() *= depth;
  const double g = std::exp(-(p - nose_centre).squaredNorm() / (2 * 0.02 * 0.02));
  q.z() += nose * g;
  if (p.y() < -0.06) {
    const double t = std::min(1.0, (-0.06 - p.y()) / 0.05);
    q.y() -= chin * t * t * (3 - 2 * t);
  }
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(rotation.x(), Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(rotation.y(), Eigen::Vector3d::UnitX()) *
                             Eigen::AngleAxisd(rotation.z(), Eigen::Vector3d::UnitZ())).toRotationMatrix();
  return scale * (r * q) + translation;
}

facemesh::Vertices SyntheticWarp::apply(const facemesh::Vertices& v) const {
  facemesh::Vertices out(v.rows(), 3);
  for (Eigen::Index i = 0; i < v.rows(); ++i) out.row(i) = apply(Eigen::Vector3d(v.row(i))).transpose();
  return out;
}

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

SurfaceDistance surface_distance(const facemesh::Mesh& from, const facemesh::Mesh& to,
                                 const std::vector<std::uint8_t>& mask) {
  if (from.vertex_count() == 0 || to.face_count() == 0) throw InvalidInput("surface_distance: empty mesh");
  if (!mask.empty() && mask.size() != from.vertex_count()) throw InvalidInput("surface_distance: mask size differs from the vertex count");
  // Points of `to`: its vertices, then its face centroids; each point knows its triangles.
  const auto nv = static_cast<std::size_t>(to.vertices.rows()), nf = static_cast<std::size_t>(to.faces.rows());
  std::vector<float> data((nv + nf) * 3);
  std::vector<std::vector<int>> point_faces(nv + nf);
  for (std::size_t i = 0; i < nv; ++i)
    for (int k = 0; k < 3; ++k) data[i * 3 + static_cast<std::size_t>(k)] = static_cast<float>(to.vertices(static_cast<Eigen::Index>(i), k));
  for (std::size_t f = 0; f < nf; ++f) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const int v = to.faces(static_cast<Eigen::Index>(f), k);
      c += to.vertices.row(v).transpose() / 3.0;
      point_faces[static_cast<std::size_t>(v)].push_back(static_cast<int>(f));
    }
    for (int k = 0; k < 3; ++k) data[(nv + f) * 3 + static_cast<std::size_t>(k)] = static_cast<float>(c[k]);
    point_faces[nv + f].push_back(static_cast<int>(f));
  }
  flann::Matrix<float> dataset(data.data(), nv + nf, 3);
  flann::KDTreeSingleIndex<flann::L2_Simple<float>> index(dataset, flann::KDTreeSingleIndexParams(12));
  index.buildIndex();
  const int knn = static_cast<int>(std::min<std::size_t>(8, nv + nf));
  std::vector<int> ids(static_cast<std::size_t>(knn));
  std::vector<float> dists(static_cast<std::size_t>(knn));
  std::vector<double> distances;
  for (Eigen::Index i = 0; i < from.vertices.rows(); ++i) {
    if (!mask.empty() && !mask[static_cast<std::size_t>(i)]) continue;
    const Eigen::Vector3d p = from.vertices.row(i);
    float q[3] = {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
    flann::Matrix<float> query(q, 1, 3);
    flann::Matrix<int> id(ids.data(), 1, static_cast<std::size_t>(knn));
    flann::Matrix<float> dist(dists.data(), 1, static_cast<std::size_t>(knn));
    index.knnSearch(query, id, dist, knn, flann::SearchParams(flann::FLANN_CHECKS_UNLIMITED));
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < knn; ++k)
      for (int f : point_faces[static_cast<std::size_t>(ids[static_cast<std::size_t>(k)])]) {
        const Eigen::Vector3d c = closest_point_on_triangle(p, to.vertices.row(to.faces(f, 0)), to.vertices.row(to.faces(f, 1)),
                                                            to.vertices.row(to.faces(f, 2)));
        best = std::min(best, (c - p).norm());
      }
    distances.push_back(best);
  }
  if (distances.empty()) throw InvalidInput("surface_distance: the mask selects no vertex");
  SurfaceDistance out;
  out.samples = distances.size();
  double sum = 0;
  for (double d : distances) sum += d;
  out.mean = sum / static_cast<double>(distances.size());
  std::sort(distances.begin(), distances.end());
  out.p95 = distances[std::min(distances.size() - 1, static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(distances.size()))) - 1)];
  out.max = distances.back();
  return out;
}

}  // namespace emoface::retarget
