#include "emoface/muscles/waters.hpp"

#include <algorithm>
#include <cmath>

namespace emoface::muscles {
namespace {
constexpr double kHalfPi = 1.5707963267948966;
constexpr double kPi = 3.14159265358979323846;
}  // namespace

double angular_factor(double alpha, double omega) {
  // seeds/README.md (Waters 1987 / Parke & Waters 1996): A = cos((α/Ω)·π/2) inside the sector.
  if (!(alpha >= 0.0) || alpha >= omega) return 0.0;
  return std::cos(alpha / omega * kHalfPi);
}

double radial_factor(double distance, double rs, double rf) {
  // seeds/README.md: R = cos((1 − D/Rs)·π/2) for D ≤ Rs; cos(((D − Rs)/(Rf − Rs))·π/2) up to Rf.
  if (!(distance >= 0.0) || distance > rf) return 0.0;
  if (distance <= rs) return std::cos((1.0 - distance / rs) * kHalfPi);
  return std::cos((distance - rs) / (rf - rs) * kHalfPi);
}

Eigen::Vector3d vector_muscle_displacement(const VectorMuscle& m, const Eigen::Vector3d& p, double c) {
  const Eigen::Vector3d to_head = m.head - p;  // v1 − p
  const double d = to_head.norm();
  if (d <= 0.0 || d > m.rf) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d axis = (m.tail - m.head).normalized();
  const double cos_alpha = std::min(1.0, std::max(-1.0, (-to_head).dot(axis) / d));
  const double a = angular_factor(std::acos(cos_alpha), m.omega);
  if (a == 0.0) return Eigen::Vector3d::Zero();
  // thesis §2.2.3 with seeds/README.md: p' = p + c·k·A·R·(v1 − p)/|v1 − p|
  return (c * m.k * a * radial_factor(d, m.rs, m.rf) / d) * to_head;
}

Eigen::Vector3d sphincter_displacement(const Eigen::Vector3d& centre, const Eigen::Vector2d& semi_axes, double k,
                                       const Eigen::Vector3d& p, double c) {
  const double dx = p.x() - centre.x(), dy = p.y() - centre.y();
  const double e = std::sqrt((dx / semi_axes.x()) * (dx / semi_axes.x()) + (dy / semi_axes.y()) * (dy / semi_axes.y()));
  const double r = std::sqrt(dx * dx + dy * dy);
  if (e >= 1.0 || r <= 0.0) return Eigen::Vector3d::Zero();
  const double s = c * k * std::sin(kPi * e) / r;  // Waters 1987 sphincter, elliptical fall-off
  return {-s * dx, -s * dy, 0.0};
}

double wrinkle_function(double l, double length, int count, double height) {
  // thesis §2.4.1 (seeds/README.md): b = L/(2Nw), u(l) = l − 2b⌊l/(2b)⌋, f = a(1 − (u − b)²/b²).
  if (!(length > 0.0) || count < 1 || l < 0.0 || l > length) return 0.0;
  const double b = length / (2.0 * count);
  const double u = l - 2.0 * b * std::floor(l / (2.0 * b));
  return height * (1.0 - (u - b) * (u - b) / (b * b));
}

bool wrinkle_foot(double l, double length, int count, double mean_edge, double resolution) {
  if (!(length > 0.0) || count < 1) return false;
  const double b = length / (2.0 * count);
  const double u = l - 2.0 * b * std::floor(l / (2.0 * b));
  return (u < 0.15 * b || u > 1.85 * b) && l > b && l < length - b && mean_edge <= resolution * b;
}

double wrinkle_band_length(const VectorMuscle& m) { return 0.75 * m.rf * std::cos(m.omega); }

double wrinkle_coordinate(const VectorMuscle& m, const Eigen::Vector3d& p) {
  const Eigen::Vector3d axis = (m.tail - m.head).normalized();
  const double s3 = m.rf * std::cos(m.omega);  // |v1 v3|
  return s3 - (p - m.head).dot(axis);
}

EyelidLevels couple_eyelids(double closing, double squeezing, double other_closing) {
  // thesis §2.4.3: if c_sq > 0.5·c_cl then c_cl = min(1, 2·c_sq) (printed as max, see header)
  //                else if only this eye tries to close then c_sq = 0.5·c_cl.
  EyelidLevels out{closing, squeezing};
  if (squeezing > 0.5 * closing) {
    out.closing = std::min(1.0, 2.0 * squeezing);
  } else if (closing > 0.0 && other_closing <= 0.0) {
    out.squeezing = 0.5 * closing;
  }
  return out;
}

Eigen::Vector2d limit_gaze(double yaw, double pitch, double yaw_limit, double pitch_limit) {
  const double q = (yaw / yaw_limit) * (yaw / yaw_limit) + (pitch / pitch_limit) * (pitch / pitch_limit);
  if (q <= 1.0) return {yaw, pitch};
  const double s = 1.0 / std::sqrt(q);
  return {yaw * s, pitch * s};
}

}  // namespace emoface::muscles
