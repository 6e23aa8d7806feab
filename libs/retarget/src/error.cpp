#include "emoface/retarget/error.hpp"

#include <algorithm>
#include <cmath>

#include "emoface/core/errors.hpp"
#include "emoface/retarget/surface.hpp"

namespace emoface::retarget {
namespace {
constexpr double kPi = 3.14159265358979323846;
}

void ErrorOptions::validate() const {
  if (planes < 2 || planes > 360) throw InvalidInput("ErrorOptions::planes must be in [2, 360]");
  if (samples < 2 || samples > 10000) throw InvalidInput("ErrorOptions::samples must be in [2, 10000]");
  if (!(front_half_angle > 0.0 && front_half_angle <= kPi))
    throw InvalidInput("ErrorOptions::front_half_angle must be in (0, pi]");
  if (std::isnan(bottom_y) || std::isnan(top_y) || !(top_y > bottom_y))
    throw InvalidInput("ErrorOptions: bottom_y and top_y must not be NaN and top_y > bottom_y");
  if (!(penalty >= 0.0) || !std::isfinite(penalty)) throw InvalidInput("ErrorOptions::penalty must be finite and >= 0");
  if (band_samples < 0 || band_samples > 10000) throw InvalidInput("ErrorOptions::band_samples must be in [0, 10000]");
  if (band_samples > 0 && !(std::isfinite(band_bottom) && std::isfinite(band_top) && band_top > band_bottom))
    throw InvalidInput("ErrorOptions: the sample band needs finite band_bottom < band_top");
}

bool sample_curve(const std::vector<Eigen::Vector2d>& curve, const std::vector<double>& heights,
                  std::vector<double>& radii) {
  radii.resize(heights.size());
  for (std::size_t j = 0; j < heights.size(); ++j) {
    const double y = heights[j];
    bool found = false;
    for (std::size_t k = 0; k + 1 < curve.size() && !found; ++k) {
      const double ya = curve[k].y(), yb = curve[k + 1].y();
      if ((y - ya) * (y - yb) > 0.0) continue;  // thesis §3.5: pair (e_k, e_k+1) bracketing y
      const double t = ya == yb ? 0.0 : (y - ya) / (yb - ya);
      radii[j] = (1.0 - t) * curve[k].x() + t * curve[k + 1].x();
      found = true;
    }
    if (!found) return false;
  }
  return true;
}

struct ErrorFunction::Impl {
  ErrorOptions options;
  Eigen::Vector3d centre;
  std::vector<double> azimuths;
  MeshWalker source_walker;
  std::vector<std::vector<Eigen::Vector2d>> target_curves;
  Impl(const facemesh::Faces& faces, std::size_t n) : source_walker(faces, n) {}
  void compute(const facemesh::Vertices& deformed, int deformed_top, std::vector<double>& res,
               std::vector<char>* sampled) const;
};

ErrorFunction::ErrorFunction(const facemesh::Mesh& target, int target_top, const facemesh::Faces& source_faces,
                             std::size_t source_vertex_count, const ErrorOptions& options)
    : impl_(std::make_unique<Impl>(source_faces, source_vertex_count)) {
  options.validate();
  if (target_top < 0 || target_top >= target.vertices.rows()) throw InvalidInput("ErrorFunction: target top vertex out of range");
  auto& m = *impl_;
  m.options = options;
  m.centre = target.vertices.row(target_top);
  // thesis §3.5: planes P_i at α = iπ/m; each gives two half-planes (α and α − π), front ones kept.
  for (int i = 0; i < options.planes; ++i) {
    const double alpha = kPi * i / options.planes;
    for (double a : {alpha, alpha - kPi})
      if (std::abs(a) <= options.front_half_angle + 1e-12) m.azimuths.push_back(a);
  }
  std::sort(m.azimuths.begin(), m.azimuths.end());
  const MeshWalker target_walker(target.faces, target.vertex_count());
  for (double a : m.azimuths)
    m.target_curves.push_back(target_walker.half_plane_curve(target.vertices, target_top, m.centre, a, options.bottom_y));
}

ErrorFunction::~ErrorFunction() = default;
ErrorFunction::ErrorFunction(ErrorFunction&&) noexcept = default;
ErrorFunction& ErrorFunction::operator=(ErrorFunction&&) noexcept = default;
const Eigen::Vector3d& ErrorFunction::centre() const { return impl_->centre; }
const std::vector<double>& ErrorFunction::azimuths() const { return impl_->azimuths; }
const ErrorOptions& ErrorFunction::options() const { return impl_->options; }

std::size_t ErrorFunction::residual_count() const {
  return impl_->azimuths.size() * (static_cast<std::size_t>(impl_->options.samples + impl_->options.band_samples) + 1);
}

double ErrorFunction::evaluate(const facemesh::Vertices& deformed, int deformed_top, ErrorBreakdown* breakdown) const {
  std::vector<double> r;
  std::vector<char> sampled;
  impl_->compute(deformed, deformed_top, r, &sampled);
  const auto n = static_cast<std::size_t>(impl_->options.samples + impl_->options.band_samples);
  ErrorBreakdown out;
  out.half_planes = impl_->azimuths.size();
  for (std::size_t i = 0; i < out.half_planes; ++i) {
    const double* block = r.data() + i * (n + 1);
    for (std::size_t j = 0; j < n; ++j) out.distance_term += block[j] * block[j];
    out.penalty_term += block[n] * block[n];
    if (sampled[i]) out.samples += static_cast<std::size_t>(impl_->options.samples);
  }
  if (breakdown) *breakdown = out;
  return out.distance_term + out.penalty_term;
}

void ErrorFunction::residuals(const facemesh::Vertices& deformed, int deformed_top, std::vector<double>& res) const {
  impl_->compute(deformed, deformed_top, res, nullptr);
}

void ErrorFunction::Impl::compute(const facemesh::Vertices& deformed, int deformed_top, std::vector<double>& res,
                                  std::vector<char>* sampled) const {
  const auto& m = *this;
  const auto n = static_cast<std::size_t>(m.options.samples);
  const auto nb = static_cast<std::size_t>(m.options.band_samples);
  res.assign(azimuths.size() * (n + nb + 1), 0.0);
  if (sampled) sampled->assign(azimuths.size(), 0);
  std::vector<double> heights(n), band(nb), rm, rt;
  for (std::size_t i = 0; i < m.azimuths.size(); ++i) {
    double* block = res.data() + i * (n + nb + 1);
    const auto curve_m = m.source_walker.half_plane_curve(deformed, deformed_top, m.centre, m.azimuths[i], m.options.bottom_y);
    const auto& curve_t = m.target_curves[i];
    auto y_range = [&](const std::vector<Eigen::Vector2d>& c, double& hi, double& lo) {
      hi = c.front().y();
      lo = hi;
      for (const auto& q : c) lo = std::min(lo, q.y());
      lo = std::max(lo, m.options.bottom_y);
      hi = std::max(std::min(hi, m.options.top_y), lo);
    };
    double hm, lm, ht, lt;
    y_range(curve_m, hm, lm);
    y_range(curve_t, ht, lt);
    const double y_start = std::min(hm, ht), y_end = std::max(lm, lt);  // thesis §3.5: common range
    if (!(y_start > y_end)) {
      block[n + nb] = std::sqrt(m.options.penalty * static_cast<double>(n));
      continue;
    }
    const double spacing = (y_start - y_end) / static_cast<double>(n - 1);
    // Δ: the parts of the curves outside the common range, in samples (thesis §3.5).
    const double outside = std::abs(hm - ht) + std::abs(lm - lt);
    double penalty = m.options.penalty * outside / spacing;
    for (std::size_t j = 0; j < n; ++j) heights[j] = y_start - static_cast<double>(j) * spacing;
    heights.back() = y_end;
    if (sample_curve(curve_m, heights, rm) && sample_curve(curve_t, heights, rt)) {
      for (std::size_t j = 0; j < n; ++j) block[j] = rm[j] - rt[j];
      if (sampled) (*sampled)[i] = 1;
    } else {
      penalty += m.options.penalty * static_cast<double>(n);
    }
    // Band samples (beyond the thesis), inside the common range only.
    const double b_hi = std::min(m.options.band_top, y_start), b_lo = std::max(m.options.band_bottom, y_end);
    if (nb > 0 && b_hi > b_lo) {
      for (std::size_t j = 0; j < nb; ++j) band[j] = b_hi - (b_hi - b_lo) * (static_cast<double>(j) + 0.5) / static_cast<double>(nb);
      if (sample_curve(curve_m, band, rm) && sample_curve(curve_t, band, rt))
        for (std::size_t j = 0; j < nb; ++j) block[n + j] = rm[j] - rt[j];
    }
    block[n + nb] = std::sqrt(penalty);
  }
}

}  // namespace emoface::retarget
