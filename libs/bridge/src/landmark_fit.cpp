#include "emoface/bridge/landmark_fit.hpp"

#include <algorithm>
#include <cmath>

#include "emoface/core/bounded_lm.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/muscles/parameters.hpp"

namespace emoface::bridge {

namespace {

constexpr std::size_t kLandmarks = 68;
constexpr std::size_t kParams = muscles::kSideParameterCount;

Eigen::MatrixXd landmarks_of(const facemesh::Vertices& v, const std::vector<int>& ids) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(ids.size()), 3);
  for (std::size_t i = 0; i < ids.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = v.row(ids[i]);
  return out;
}

Eigen::VectorXd flat(const Eigen::MatrixXd& m) {  // row-major 68×3 → 204
  Eigen::VectorXd f(m.size());
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) f(r * m.cols() + c) = m(r, c);
  return f;
}

void check_side(const std::vector<double>& side) {
  if (side.size() != kParams) throw InvalidInput("bridge: expected 35 side parameters");
  for (double v : side)
    if (!(v >= 0.0 && v <= 1.0)) throw InvalidInput("bridge: side parameters must be in [0, 1]");
}

// Residuals: surrogate landmark displacements minus target (used coordinates only), then the
// smoothness terms √w·(p_j − anchor_j). Analytic Jacobian: the surrogate is piecewise linear per
// parameter (slope of the knot segment containing p_j). The function concept of ceres::TinySolver
// and core::solve_bounded_lm (Jacobian column-major).
class SurrogateCost {
 public:
  using Scalar = double;
  enum { NUM_RESIDUALS = Eigen::Dynamic, NUM_PARAMETERS = Eigen::Dynamic };

  SurrogateCost(const std::vector<double>& knots, const std::vector<std::vector<Eigen::VectorXd>>& responses,
                std::vector<int> coords, Eigen::VectorXd target, std::vector<double> anchor, double smooth)
      : knots_(knots), responses_(responses), coords_(std::move(coords)), target_(std::move(target)),
        anchor_(std::move(anchor)), smooth_(smooth),
        residuals_(static_cast<int>(coords_.size() + (smooth > 0.0 ? kParams : 0))) {}

  int NumResiduals() const { return residuals_; }
  int NumParameters() const { return static_cast<int>(kParams); }

  bool operator()(const double* p, double* residuals, double* J) const {
    const std::size_t nc = coords_.size();
    const auto m = static_cast<std::size_t>(residuals_);
    for (std::size_t k = 0; k < nc; ++k) residuals[k] = -target_(static_cast<Eigen::Index>(k));
    if (J) std::fill(J, J + m * kParams, 0.0);
    for (std::size_t j = 0; j < kParams; ++j) {
      const double x = std::clamp(p[j], 0.0, 1.0);
      std::size_t s = 0;  // segment [knots[s], knots[s+1]] containing x
      while (s + 2 < knots_.size() && x > knots_[s + 1]) ++s;
      const double t = (x - knots_[s]) / (knots_[s + 1] - knots_[s]);
      const double inv = 1.0 / (knots_[s + 1] - knots_[s]);
      const Eigen::VectorXd& a = responses_[j][s];
      const Eigen::VectorXd& b = responses_[j][s + 1];
      for (std::size_t k = 0; k < nc; ++k) {
        const double ra = a(coords_[k]), rb = b(coords_[k]);
        residuals[k] += ra + t * (rb - ra);
        if (J) J[j * m + k] = (rb - ra) * inv;
      }
    }
    if (m > nc)
      for (std::size_t j = 0; j < kParams; ++j) {
        residuals[nc + j] = smooth_ * (p[j] - anchor_[j]);
        if (J) J[j * m + nc + j] = smooth_;
      }
    return true;
  }

 private:
  const std::vector<double>& knots_;
  const std::vector<std::vector<Eigen::VectorXd>>& responses_;
  std::vector<int> coords_;
  Eigen::VectorXd target_;
  std::vector<double> anchor_;
  double smooth_;
  int residuals_;
};

}  // namespace

void FitOptions::validate() const {
  if (!(smoothness >= 0.0 && std::isfinite(smoothness))) throw InvalidInput("FitOptions: smoothness must be finite and >= 0");
  if (max_iterations < 1 || max_iterations > 1000) throw InvalidInput("FitOptions: max_iterations must be in [1, 1000]");
  if (sample_levels.empty() || sample_levels.back() != 1.0)
    throw InvalidInput("FitOptions: sample_levels must end at 1");
  double prev = 0.0;
  for (double l : sample_levels) {
    if (!(l > prev && l <= 1.0)) throw InvalidInput("FitOptions: sample_levels must increase strictly in (0, 1]");
    prev = l;
  }
}

LandmarkFitter::LandmarkFitter(const muscles::FaceSolver& solver, FitOptions options)
    : solver_(solver), options_(std::move(options)) {
  options_.validate();
  const auto& ids = solver_.rig().ibug68;
  if (ids.size() != kLandmarks) throw InvalidInput("bridge: the rig has no 68 iBUG landmarks");
  neutral_ = landmarks_of(solver_.neutral().vertices, ids);
  knots_.push_back(0.0);
  knots_.insert(knots_.end(), options_.sample_levels.begin(), options_.sample_levels.end());
  responses_.assign(kParams, {});
  std::vector<double> values(muscles::kParameterCount, 0.0);
  muscles::Deformation d;
  for (std::size_t j = 0; j < kParams; ++j) {
    responses_[j].push_back(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(kLandmarks * 3)));
    for (double level : options_.sample_levels) {
      values[j] = level;
      solver_.deform(values, d);
      responses_[j].push_back(flat(landmarks_of(d.vertices, ids) - neutral_));
    }
    values[j] = 0.0;
  }
}

Eigen::MatrixXd LandmarkFitter::model_displacements(const std::vector<double>& side) const {
  check_side(side);
  std::vector<double> values(muscles::kParameterCount, 0.0);
  std::copy(side.begin(), side.end(), values.begin());
  return landmarks_of(solver_.deform(values).vertices, solver_.rig().ibug68) - neutral_;
}

Eigen::MatrixXd LandmarkFitter::predicted_displacements(const std::vector<double>& side) const {
  check_side(side);
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(kLandmarks * 3));
  for (std::size_t j = 0; j < kParams; ++j) {
    std::size_t s = 0;
    while (s + 2 < knots_.size() && side[j] > knots_[s + 1]) ++s;
    const double t = (side[j] - knots_[s]) / (knots_[s + 1] - knots_[s]);
    sum += responses_[j][s] + t * (responses_[j][s + 1] - responses_[j][s]);
  }
  Eigen::MatrixXd out(static_cast<Eigen::Index>(kLandmarks), 3);
  for (Eigen::Index r = 0; r < out.rows(); ++r)
    for (Eigen::Index c = 0; c < 3; ++c) out(r, c) = sum(r * 3 + c);
  return out;
}

FitReport LandmarkFitter::fit(const Eigen::MatrixXd& target, std::vector<double>& side, bool evaluate_model) const {
  check_side(side);
  if (target.rows() != static_cast<Eigen::Index>(kLandmarks) || (target.cols() != 2 && target.cols() != 3))
    throw InvalidInput("bridge: target must be 68 by 2 or 68 by 3");
  std::vector<int> coords;
  std::vector<double> values;
  for (Eigen::Index r = 0; r < target.rows(); ++r) {
    if (!target.row(r).allFinite()) continue;  // NaN row: landmark not observed
    for (Eigen::Index c = 0; c < target.cols(); ++c) {
      coords.push_back(static_cast<int>(r * 3 + c));
      values.push_back(target(r, c));
    }
  }
  if (coords.empty()) throw InvalidInput("bridge: the target has no finite landmark");
  const Eigen::VectorXd t = Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
  std::vector<double> p = side;
  const SurrogateCost cost(knots_, responses_, coords, t, side, options_.smoothness);
  // Initial guess: the bounded minimum of the model linearised at the warm start (projected
  // Gauss–Seidel on the normal equations), so the solver starts near the answer.
  double warm_cost = 0.0;
  const int m = cost.NumResiduals(), n = static_cast<int>(kParams);
  Eigen::VectorXd r(m);
  Eigen::MatrixXd J(m, n);
  for (int outer = 0; outer < 3; ++outer) {  // re-linearised where a parameter crossed a knot
    cost(p.data(), r.data(), J.data());
    if (outer == 0) warm_cost = 0.5 * r.squaredNorm();
    const Eigen::MatrixXd A = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    Eigen::VectorXd delta = Eigen::VectorXd::Zero(n);
    for (int sweep = 0; sweep < 300; ++sweep) {
      double change = 0.0;
      for (int j = 0; j < n; ++j) {
        if (!(A(j, j) > 0.0)) continue;
        const double grad = g(j) + A.row(j).dot(delta);
        const double next = std::clamp(p[static_cast<std::size_t>(j)] + delta(j) - grad / A(j, j), 0.0, 1.0) -
                            p[static_cast<std::size_t>(j)];
        change = std::max(change, std::fabs(next - delta(j)));
        delta(j) = next;
      }
      if (change < 1e-9) break;
    }
    for (int j = 0; j < n; ++j) p[static_cast<std::size_t>(j)] += delta(j);
  }
  // Bounded Levenberg–Marquardt on [0, 1]^35 (core::solve_bounded_lm), the tolerances used with
  // Ceres before.
  core::BoundedLmOptions lm;
  lm.max_iterations = options_.max_iterations;
  lm.function_tolerance = 1e-8;
  lm.gradient_tolerance = 1e-12;
  lm.parameter_tolerance = 1e-8;
  Eigen::Map<Eigen::VectorXd> x(p.data(), n);
  const core::BoundedLmReport summary = core::solve_bounded_lm(
      cost, x, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Ones(n), lm);
  FitReport rep;
  rep.converged = summary.converged;
  rep.message = summary.message;
  rep.iterations = summary.iterations;
  rep.initial_cost = warm_cost;
  rep.final_cost = summary.final_cost;
  for (double& v : p) v = std::clamp(v, 0.0, 1.0);
  side = p;
  auto rms = [&](const Eigen::MatrixXd& pred) {
    double s = 0.0;
    for (std::size_t k = 0; k < coords.size(); ++k) {
      const double d = pred(coords[k] / 3, coords[k] % 3) - values[k];
      s += d * d;
    }
    return std::sqrt(s / static_cast<double>(coords.size() / static_cast<std::size_t>(target.cols())));
  };
  rep.rms_surrogate = rms(predicted_displacements(side));
  if (evaluate_model) rep.rms_model = rms(model_displacements(side));
  return rep;
}

std::vector<std::vector<double>> LandmarkFitter::fit_track(const std::vector<Eigen::MatrixXd>& targets,
                                                           std::vector<FitReport>* reports) const {
  std::vector<std::vector<double>> out;
  std::vector<double> side(kParams, 0.0);
  if (reports) reports->clear();
  for (const auto& t : targets) {
    FitReport r = fit(t, side);
    if (reports) reports->push_back(std::move(r));
    out.push_back(side);
  }
  return out;
}

Eigen::MatrixXd image_to_face(const Eigen::MatrixXd& displacement_px, const Eigen::MatrixXd& neutral_px,
                              const Eigen::MatrixXd& face_neutral) {
  if (displacement_px.rows() != 68 || displacement_px.cols() != 2 || neutral_px.rows() != 68 ||
      neutral_px.cols() != 2 || face_neutral.rows() != 68 || face_neutral.cols() != 3)
    throw InvalidInput("image_to_face: expected 68 by 2 displacements and neutral pose, 68 by 3 face landmarks");
  const double px = (neutral_px.row(45) - neutral_px.row(36)).norm();
  const double m = (face_neutral.row(45).head<2>() - face_neutral.row(36).head<2>()).norm();
  if (!(px > 0.0) || !(m > 0.0) || !std::isfinite(px / m)) throw InvalidInput("image_to_face: the outer eye corners (iBUG 36, 45) are missing or coincide");
  Eigen::MatrixXd out = displacement_px * (m / px);
  out.col(1) *= -1.0;  // image y points down, face y up
  return out;
}

}  // namespace emoface::bridge
