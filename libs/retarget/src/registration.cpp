// Landmark-guided non-rigid ICP (registration.hpp).
#include "emoface/retarget/registration.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <utility>

#include "emoface/core/errors.hpp"
#include "surface_index.hpp"

namespace emoface::retarget {

void RegistrationOptions::validate() const {
  if (stiffness.empty() || stiffness.size() > 20)
    throw InvalidInput("RegistrationOptions::stiffness needs 1 to 20 stages");
  for (double a : stiffness)
    if (!(a > 0.0) || !std::isfinite(a))
      throw InvalidInput("RegistrationOptions::stiffness values must be finite and > 0");
  if (iterations_per_stage < 1 || iterations_per_stage > 50)
    throw InvalidInput("RegistrationOptions::iterations_per_stage must be in [1, 50]");
  if (!(landmark_weight >= 0.0 && landmark_weight <= 1e6))
    throw InvalidInput("RegistrationOptions::landmark_weight must be in [0, 1e6]");
  if (!(max_distance > 0.0 && max_distance <= 1.0))
    throw InvalidInput("RegistrationOptions::max_distance must be in (0, 1]");
  if (!(max_normal_angle_deg > 0.0 && max_normal_angle_deg <= 180.0))
    throw InvalidInput("RegistrationOptions::max_normal_angle_deg must be in (0, 180]");
}

RegistrationResult register_nonrigid(const facemesh::Mesh& source,
                                     const std::vector<std::uint8_t>& mask,
                                     const facemesh::Mesh& target,
                                     const std::vector<RegistrationLandmark>& landmarks,
                                     const RegistrationOptions& options) {
  options.validate();
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::Index n = source.vertices.rows();
  if (n == 0 || source.faces.rows() == 0)
    throw InvalidInput("register_nonrigid: the source mesh is empty");
  if (target.faces.rows() == 0)
    throw InvalidInput("register_nonrigid: the target mesh has no faces");
  if (!mask.empty() && mask.size() != static_cast<std::size_t>(n))
    throw InvalidInput("register_nonrigid: data mask has " + std::to_string(mask.size()) +
                       " entries, the source " + std::to_string(n) + " vertices");
  if (!source.vertices.allFinite() || !target.vertices.allFinite())
    throw InvalidInput("register_nonrigid: non-finite vertex coordinates");
  for (const auto& l : landmarks)
    if (l.vertex < 0 || l.vertex >= n || !l.target.allFinite())
      throw InvalidInput("register_nonrigid: landmark vertex " + std::to_string(l.vertex) +
                         " out of range or not finite");
  for (Eigen::Index f = 0; f < source.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (source.faces(f, k) < 0 || source.faces(f, k) >= n)
        throw InvalidInput("register_nonrigid: source face id out of range");

  // Undirected edges of the source.
  std::vector<std::pair<int, int>> edges;
  edges.reserve(static_cast<std::size_t>(source.faces.rows()) * 3);
  for (Eigen::Index f = 0; f < source.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = source.faces(f, k), b = source.faces(f, (k + 1) % 3);
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());

  const Eigen::Vector3d lo = source.vertices.colwise().minCoeff(),
                        hi = source.vertices.colwise().maxCoeff();
  const double diagonal = (hi - lo).norm();
  const double max_d = options.max_distance * diagonal;
  const double cos_max = std::cos(options.max_normal_angle_deg * 3.14159265358979323846 / 180.0);
  const detail::SurfaceIndex index(target);
  const facemesh::Vertices target_normals = facemesh::face_normals(target.vertices, target.faces);

  RegistrationResult r;
  const facemesh::Vertices& x0 = source.vertices;
  facemesh::Vertices x = x0;
  auto data = [&](Eigen::Index i) {
    return mask.empty() || mask[static_cast<std::size_t>(i)] != 0;
  };
  auto rms = [&](const facemesh::Vertices& v) {
    double s = 0.0;
    std::size_t c = 0;
    for (Eigen::Index i = 0; i < n; ++i)
      if (data(i)) s += std::pow(index.closest(v.row(i).transpose()).distance, 2), ++c;
    return c ? std::sqrt(s / static_cast<double>(c)) : 0.0;
  };
  r.report.initial_rms = rms(x);
  Eigen::MatrixX3d rhs(n, 3);
  std::vector<Eigen::Triplet<double>> trip;
  for (double alpha : options.stiffness) {
    for (int it = 0; it < options.iterations_per_stage; ++it) {
      const facemesh::Vertices normals = facemesh::vertex_normals(x, source.faces);
      trip.clear();
      rhs.setZero();
      std::size_t accepted = 0;
      Eigen::VectorXd diag = Eigen::VectorXd::Constant(n, 1e-8);
      for (Eigen::Index i = 0; i < n; ++i) {
        if (!data(i)) continue;
        const Eigen::Vector3d p = x.row(i).transpose();
        const auto hit = index.closest(p);
        if (hit.face < 0 || hit.distance > max_d) continue;
        const Eigen::Vector3d tn = target_normals.row(hit.face).transpose();
        const Eigen::Vector3d sn = normals.row(i).transpose();
        if (sn.squaredNorm() > 0.0 && tn.squaredNorm() > 0.0 && sn.dot(tn) < cos_max) continue;
        diag(i) += 1.0;
        rhs.row(i) += (hit.point - Eigen::Vector3d(x0.row(i).transpose())).transpose();
        ++accepted;
      }
      for (const auto& l : landmarks) {
        diag(l.vertex) += options.landmark_weight;
        rhs.row(l.vertex) += options.landmark_weight *
                             (l.target - Eigen::Vector3d(x0.row(l.vertex).transpose())).transpose();
      }
      for (Eigen::Index i = 0; i < n; ++i)
        trip.emplace_back(static_cast<int>(i), static_cast<int>(i), diag(i));
      for (const auto& [a, b] : edges) {
        trip.emplace_back(a, a, alpha);
        trip.emplace_back(b, b, alpha);
        trip.emplace_back(a, b, -alpha);
        trip.emplace_back(b, a, -alpha);
      }
      Eigen::SparseMatrix<double> A(n, n);
      A.setFromTriplets(trip.begin(), trip.end());
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
      if (solver.info() != Eigen::Success)
        throw NumericalError("register_nonrigid: factorisation failed");
      const Eigen::MatrixX3d d = solver.solve(rhs);
      if (!d.allFinite()) throw NumericalError("register_nonrigid: non-finite solution");
      x = x0 + d;
      r.report.correspondences = accepted;
      ++r.report.iterations;
    }
  }
  r.report.final_rms = rms(x);
  r.vertices = x;
  r.report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace emoface::retarget
