#pragma once
// The error function of thesis §3.5: the difference between the deformed source face and the target,
// measured on sampling curves in m planes through the vertical projection centreline l.
//
//   ErrorFunction error(target_mesh, target_top, source_faces, source_vertex_count, options);
//   double e = error.evaluate(deformed_vertices, deformed_top);   // m², the GA minimises it
//
// Per half-plane (front of the head only): both curves are walked from their top-of-head vertex
// (MeshWalker), cut to the common height range [y_end, y_start] (y_end never below options.bottom_y,
// so the neck is ignored), sampled at n equal heights; E = Σ_i Σ_j |SM_ij − ST_ij|² + Δ. Because both
// samples share plane and height, ST_ij is the cylindrical projection of SM_ij (thesis §3.5).
#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "emoface/facemesh/mesh.hpp"

namespace emoface::retarget {

struct ErrorOptions {
  int planes = 16;    ///< m, sampling planes at angles iπ/m (thesis §3.5), [2, 360]
  int samples = 24;   ///< n, samples per curve at equal heights, [2, 10000]
  /// Half-planes used: |azimuth| ≤ this (0 = straight ahead, +z), radians, (0, π]. The default keeps
  /// the front of the head and drops the back (thesis §3.5: "we ignore the back of the head").
  double front_half_angle = 1.3;
  /// Lowest sampled height, m in the thesis frame (thesis §3.5: "we also ignore the neck"); the
  /// retarget pipeline sets it to the source chin height. −∞ = no limit.
  double bottom_y = -1e300;
  /// Highest sampled height, m (e.g. to drop the scalp); +∞ = from the top of the head. > bottom_y.
  double top_y = 1e300;
  /// Penalty per missing sample, m² (Δ of thesis §3.5): the height by which a curve extends beyond
  /// the common range, divided by the sample spacing, times this. ≥ 0.
  double penalty = 4e-4;
  /// Beyond the thesis: extra samples per curve at equal heights inside the band [band_bottom,
  /// band_top] (m, thesis frame; clipped to the common range), so that a small feature there — the
  /// lips, 1.5 cm tall, between one or two of the n samples of a whole head — is seen by E. 0 = none
  /// (thesis §3.5 exactly); [0, 10000]. The retarget pipeline puts the band between the source's chin and
  /// nose tip (RetargetOptions::mouth_samples).
  int band_samples = 0;
  double band_bottom = 0.0;
  double band_top = 0.0;
  void validate() const;
};

/// Where the error comes from (for reports and tests).
struct ErrorBreakdown {
  double distance_term = 0.0;   ///< Σ |SM − ST|², m²
  double penalty_term = 0.0;    ///< Δ, m²
  std::size_t half_planes = 0;  ///< half-planes used
  std::size_t samples = 0;      ///< sample pairs compared
};

/// Samples a curve (r, y) at the given heights: the first segment (in walking order) whose height
/// interval holds y (thesis §3.5). Returns false if some height is not covered.
bool sample_curve(const std::vector<Eigen::Vector2d>& curve, const std::vector<double>& heights,
                  std::vector<double>& radii);

class ErrorFunction {
 public:
  /// `target_top`: the target's top-of-head vertex (defines l). `source_faces`/`source_vertex_count`:
  /// the connectivity of the source face, shared by every deformed version of it.
  ErrorFunction(const facemesh::Mesh& target, int target_top, const facemesh::Faces& source_faces,
                std::size_t source_vertex_count, const ErrorOptions& options = {});
  ~ErrorFunction();
  ErrorFunction(ErrorFunction&&) noexcept;
  ErrorFunction& operator=(ErrorFunction&&) noexcept;

  /// E for the deformed source vertices (#V by 3, thesis frame), walked from `deformed_top`.
  double evaluate(const facemesh::Vertices& deformed, int deformed_top, ErrorBreakdown* breakdown = nullptr) const;

  /// The same E as a fixed-size residual vector (E = Σ r²) for least-squares refinement:
  /// per half-plane, n sample differences r_M − r_T (m), the band_samples band differences, then √Δ_i
  /// (the half-plane's penalty). A half-plane without a common range contributes zeros and √(penalty·n).
  /// Size residual_count().
  void residuals(const facemesh::Vertices& deformed, int deformed_top, std::vector<double>& out) const;
  std::size_t residual_count() const;

  /// The centreline point (x, ·, z) of l: the target's top-of-head vertex.
  const Eigen::Vector3d& centre() const;
  /// Azimuths of the half-planes used, radians.
  const std::vector<double>& azimuths() const;
  const ErrorOptions& options() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace emoface::retarget
