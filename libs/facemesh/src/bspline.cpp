// Lip B-spline surface (thesis §2.2.2, §2.3.2).
#include "emoface/facemesh/bspline.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "emoface/core/errors.hpp"

namespace emoface::facemesh {

std::array<double, 4> cubic_bspline_basis(double t) {
  // Uniform cubic B-spline blending functions (weights of P[i-1], P[i], P[i+1], P[i+2]).
  const double t2 = t * t, t3 = t2 * t, s = 1.0 - t;
  return {s * s * s / 6.0, (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0, (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0,
          t3 / 6.0};
}

std::vector<double> clamped_cubic_basis(int n, double v) {
  // Open uniform knot vector with n control points, degree p = 3: p+1 zeros, n-p-1 interior knots,
  // p+1 ones; Cox–de Boor recursion.
  constexpr int p = 3;
  if (n < p + 1) throw InvalidInput("clamped_cubic_basis: needs at least 4 control points");
  std::vector<double> knots;
  for (int i = 0; i <= p; ++i) knots.push_back(0.0);
  for (int i = 1; i < n - p; ++i) knots.push_back(static_cast<double>(i) / (n - p));
  for (int i = 0; i <= p; ++i) knots.push_back(1.0);
  v = std::min(std::max(v, 0.0), 1.0);
  const int m = static_cast<int>(knots.size()) - 1;
  std::vector<double> basis(static_cast<std::size_t>(m), 0.0);
  // degree 0
  for (int i = 0; i < m; ++i) {
    const bool inside = (v >= knots[i] && v < knots[i + 1]) ||
                        (v >= 1.0 && knots[i] < 1.0 && knots[i + 1] >= 1.0);
    basis[static_cast<std::size_t>(i)] = inside ? 1.0 : 0.0;
  }
  for (int d = 1; d <= p; ++d) {
    for (int i = 0; i + d < m; ++i) {
      double value = 0.0;
      const double l = knots[i + d] - knots[i];
      const double r = knots[i + d + 1] - knots[i + 1];
      if (l > 0.0) value += (v - knots[i]) / l * basis[static_cast<std::size_t>(i)];
      if (r > 0.0) value += (knots[i + d + 1] - v) / r * basis[static_cast<std::size_t>(i + 1)];
      basis[static_cast<std::size_t>(i)] = value;
    }
  }
  basis.resize(static_cast<std::size_t>(n));
  return basis;
}

LipSampler::LipSampler(int samples_around, int samples_across)
    : samples_around_(samples_around), samples_across_(samples_across) {
  if (samples_around < LipGrid::kAround || samples_across < LipGrid::kAcross || samples_around > 1024 ||
      samples_across > 256) {
    throw InvalidInput("LipSampler: sample grid must be at least 24 x 6 and at most 1024 x 256");
  }
  constexpr int na = LipGrid::kAround;
  terms_.resize(static_cast<std::size_t>(samples_around * samples_across));
  for (int j = 0; j < samples_across; ++j) {
    const auto bv = clamped_cubic_basis(LipGrid::kAcross, static_cast<double>(j) / (samples_across - 1));
    for (int i = 0; i < samples_around; ++i) {
      const double s = static_cast<double>(i) * na / samples_around;
      const int seg = static_cast<int>(std::floor(s));
      const auto bu = cubic_bspline_basis(s - seg);
      auto& list = terms_[static_cast<std::size_t>(j * samples_around + i)];
      for (int r = 0; r < LipGrid::kAcross; ++r) {
        if (bv[static_cast<std::size_t>(r)] == 0.0) continue;
        for (int k = 0; k < 4; ++k) {
          const int col = ((seg - 1 + k) % na + na) % na;
          list.push_back({r * na + col, bv[static_cast<std::size_t>(r)] * bu[static_cast<std::size_t>(k)]});
        }
      }
    }
  }
}

std::vector<LipSampler::Term> lip_surface_terms(double u, double v) {
  if (!(u >= 0.0 && u < 1.0) || !(v >= 0.0 && v <= 1.0)) {
    throw InvalidInput("lip_surface_terms: (u, v) = (" + std::to_string(u) + ", " + std::to_string(v) +
                       ") outside [0, 1) x [0, 1]");
  }
  constexpr int na = LipGrid::kAround;
  const auto bv = clamped_cubic_basis(LipGrid::kAcross, v);
  const double s = u * na;
  const int seg = std::min(static_cast<int>(std::floor(s)), na - 1);
  const auto bu = cubic_bspline_basis(s - seg);
  std::vector<LipSampler::Term> terms;
  terms.reserve(16);
  for (int r = 0; r < LipGrid::kAcross; ++r) {
    if (bv[static_cast<std::size_t>(r)] == 0.0) continue;
    for (int k = 0; k < 4; ++k) {
      const int col = ((seg - 1 + k) % na + na) % na;
      terms.push_back({r * na + col, bv[static_cast<std::size_t>(r)] * bu[static_cast<std::size_t>(k)]});
    }
  }
  return terms;
}

void LipSampler::evaluate(const std::vector<Eigen::Vector3d>& control_points, Vertices& out, int first_row) const {
  if (control_points.size() != static_cast<std::size_t>(LipGrid::kAround * LipGrid::kAcross)) {
    throw InvalidInput("LipSampler::evaluate: needs 144 control points");
  }
  if (first_row < 0 || out.rows() < first_row + sample_count()) throw InvalidInput("LipSampler::evaluate: output too small");
  for (std::size_t s = 0; s < terms_.size(); ++s) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (const auto& t : terms_[s]) p += t.weight * control_points[static_cast<std::size_t>(t.control)];
    out.row(first_row + static_cast<long>(s)) = p;
  }
}

}  // namespace emoface::facemesh
