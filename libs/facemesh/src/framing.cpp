// Camera framing for render(): fit the view to any mesh (render.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Geometry>

#include "emoface/core/errors.hpp"
#include "emoface/facemesh/render.hpp"

namespace emoface::facemesh {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The camera of render() (render.cpp): orbit about the target, three-quarter = 35° to the subject's right.
struct Camera {
  Eigen::Vector3d eye, forward, right, up;
  double focal;  // pixels (image height units)
  Camera(const RenderOptions& o) {
    const double yaw = o.yaw + (o.view == View::ThreeQuarter ? -35.0 * kPi / 180.0 : 0.0);
    forward = Eigen::Vector3d(-std::sin(yaw), 0.0, -std::cos(yaw));
    eye = o.target - o.distance * forward;
    right = forward.cross(Eigen::Vector3d::UnitY()).normalized();
    up = right.cross(forward);
    focal = 0.5 * o.height / std::tan(0.5 * o.field_of_view);
  }
  // pixel position and depth
  Eigen::Vector3d project(const Eigen::Vector3d& p, const RenderOptions& o) const {
    const Eigen::Vector3d d = p - eye;
    const double z = d.dot(forward);
    const double iz = 1.0 / std::max(z, 1e-12);
    return {0.5 * o.width + focal * d.dot(right) * iz, 0.5 * o.height - focal * d.dot(up) * iz, z};
  }
};

void bounds(const Vertices& v, Eigen::Vector3d& lo, Eigen::Vector3d& hi, const char* who) {
  if (v.rows() == 0) throw InvalidInput(std::string(who) + ": no vertices");
  if (!v.allFinite()) throw InvalidInput(std::string(who) + ": non-finite vertex");
  lo = v.colwise().minCoeff().transpose();
  hi = v.colwise().maxCoeff().transpose();
  if (!((hi - lo).norm() > 0.0)) throw InvalidInput(std::string(who) + ": the mesh has no extent (all vertices coincide)");
}

}  // namespace

Eigen::Vector3d project_point(const RenderOptions& options, const Eigen::Vector3d& p) {
  options.validate();
  return Camera(options).project(p, options);
}

RenderOptions fit_camera(const Vertices& vertices, RenderOptions options, double fill) {
  options.validate();
  if (!(fill > 0.0 && fill <= 1.0)) throw InvalidInput("fit_camera: fill must be in (0, 1]");
  Eigen::Vector3d lo, hi;
  bounds(vertices, lo, hi, "fit_camera");
  const double radius = 0.5 * (hi - lo).norm();
  const double half_v = 0.5 * options.field_of_view;
  const double half_h = std::atan(std::tan(half_v) * options.width / options.height);
  // a sphere of radius r at distance d subtends the half-angle asin(r/d)
  options.target = 0.5 * (lo + hi);
  options.distance = radius / std::sin(fill * std::min(half_v, half_h));  // the whole sphere in view
  // then closer, until the projected vertices span `fill` of the image (two rounds: the extent scales
  // about as 1/distance); never inside the bounding sphere
  for (int round = 0; round < 2; ++round) {
    const Camera cam(options);
    double extent = 0.0;  // largest |offset from the image centre| as a fraction of the half-size
    for (long v = 0; v < vertices.rows(); ++v) {
      const Eigen::Vector3d s = cam.project(vertices.row(v).transpose(), options);
      extent = std::max({extent, std::abs(s.x() - 0.5 * options.width) / (0.5 * options.width),
                         std::abs(s.y() - 0.5 * options.height) / (0.5 * options.height)});
    }
    if (!(extent > 0.0)) break;
    options.distance = std::max(1.05 * radius, options.distance * extent / fill);
  }
  return options;
}

double visible_fraction(const Vertices& vertices, const RenderOptions& options) {
  options.validate();
  if (vertices.rows() == 0) return 0.0;
  const Camera cam(options);
  long inside = 0;
  for (long v = 0; v < vertices.rows(); ++v) {
    const Eigen::Vector3d s = cam.project(vertices.row(v).transpose(), options);
    if (s.z() > 1e-4 && s.x() >= 0.0 && s.x() < options.width && s.y() >= 0.0 && s.y() < options.height) ++inside;
  }
  return static_cast<double>(inside) / static_cast<double>(vertices.rows());
}

RenderOptions frame_camera(const Vertices& vertices, const RenderOptions& options, double min_fill) {
  options.validate();
  Eigen::Vector3d lo, hi;
  bounds(vertices, lo, hi, "frame_camera");
  const Camera cam(options);
  double top = std::numeric_limits<double>::infinity(), bottom = -top;
  bool in_front = true;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
    const Eigen::Vector3d s = cam.project(corner, options);
    in_front = in_front && s.z() > 1e-4;
    top = std::min(top, s.y());
    bottom = std::max(bottom, s.y());
  }
  // already framed: in front of the camera, the box centre in the middle half of the image, and a
  // sensible size (the built-in face's box spans about 1.1 image heights in the default view)
  const Eigen::Vector3d centre = cam.project(0.5 * (lo + hi), options);
  const bool centred = std::abs(centre.x() - 0.5 * options.width) <= 0.25 * options.width &&
                       std::abs(centre.y() - 0.5 * options.height) <= 0.25 * options.height;
  const double span = (bottom - top) / options.height;
  if (in_front && centred && span >= min_fill && span <= 2.0) return options;
  return fit_camera(vertices, options);
}

}  // namespace emoface::facemesh
