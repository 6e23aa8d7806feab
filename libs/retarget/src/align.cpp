#include "emoface/retarget/align.hpp"

#include <cmath>
#include <functional>
#include <limits>

#include <Eigen/Geometry>

#include "emoface/core/errors.hpp"

namespace emoface::retarget {
namespace {
Eigen::Vector3d axis_vector(Axis a) {
  switch (a) {
    case Axis::PosX: return Eigen::Vector3d::UnitX();
    case Axis::NegX: return -Eigen::Vector3d::UnitX();
    case Axis::PosY: return Eigen::Vector3d::UnitY();
    case Axis::NegY: return -Eigen::Vector3d::UnitY();
    case Axis::PosZ: return Eigen::Vector3d::UnitZ();
    case Axis::NegZ: return -Eigen::Vector3d::UnitZ();
  }
  return Eigen::Vector3d::UnitY();
}

std::vector<char> used_vertices(const facemesh::Mesh& mesh) {
  std::vector<char> used(mesh.vertex_count(), 0);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.faces(f, k);
      if (v < 0 || v >= mesh.vertices.rows()) throw InvalidInput("detect_landmarks: face " + std::to_string(f) + " has a vertex id out of range");
      used[static_cast<std::size_t>(v)] = 1;
    }
  return used;
}

int arg_best(const facemesh::Mesh& mesh, const std::vector<char>& used, const std::function<double(const Eigen::Vector3d&)>& score) {
  int best = -1;
  double best_score = -std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < mesh.vertices.rows(); ++i) {
    if (!used[static_cast<std::size_t>(i)]) continue;
    const double s = score(mesh.vertices.row(i));
    if (s > best_score) {
      best_score = s;
      best = static_cast<int>(i);
    }
  }
  return best;
}
}  // namespace

std::string to_string(Axis axis) {
  static const char* names[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  return names[static_cast<int>(axis)];
}

Axis axis_from_string(std::string_view name) {
  for (int i = 0; i < 6; ++i)
    if (to_string(static_cast<Axis>(i)) == name) return static_cast<Axis>(i);
  throw InvalidInput("unknown axis \"" + std::string(name) + "\" (expected +x, -x, +y, -y, +z or -z)");
}

void AlignOptions::validate() const {
  if (std::abs(axis_vector(up).dot(axis_vector(front))) > 0.5)
    throw InvalidInput("AlignOptions: up (" + to_string(up) + ") and front (" + to_string(front) + ") must be perpendicular");
}

facemesh::Vertices Alignment::apply(const facemesh::Vertices& v) const {
  facemesh::Vertices out(v.rows(), 3);
  for (Eigen::Index i = 0; i < v.rows(); ++i) out.row(i) = apply(Eigen::Vector3d(v.row(i))).transpose();
  return out;
}

facemesh::Vertices Alignment::inverse(const facemesh::Vertices& v) const {
  facemesh::Vertices out(v.rows(), 3);
  for (Eigen::Index i = 0; i < v.rows(); ++i) out.row(i) = inverse(Eigen::Vector3d(v.row(i))).transpose();
  return out;
}

std::vector<DetectedLandmark> detect_landmarks(const facemesh::Mesh& mesh, const std::vector<std::string>& names) {
  if (mesh.face_count() == 0) throw InvalidInput("detect_landmarks: the mesh has no faces");
  const auto used = used_vertices(mesh);
  // thesis §3.2.1: top of the head = highest y; tip of the nose = highest z.
  const int top = arg_best(mesh, used, [](const Eigen::Vector3d& p) { return p.y(); });
  const int nose = arg_best(mesh, used, [](const Eigen::Vector3d& p) { return p.z(); });
  const double h = mesh.vertices(top, 1) - mesh.vertices(nose, 1);
  if (!(h > 0.0)) throw InvalidInput("detect_landmarks: the nose tip (highest z) is not below the top of the head (highest y); check --up/--front");
  const double lo = mesh.vertices(nose, 1) - 0.4 * h, hi = mesh.vertices(nose, 1) + 0.6 * h;
  auto side = [&](double sign) {
    return arg_best(mesh, used, [&](const Eigen::Vector3d& p) {
      return p.y() >= lo && p.y() <= hi ? sign * p.x() : -std::numeric_limits<double>::infinity();
    });
  };
  std::vector<DetectedLandmark> out;
  for (const auto& name : names) {
    if (name == "top_of_head") out.push_back({name, top});
    else if (name == "nose_tip") out.push_back({name, nose});
    else if (name == "ear_r") out.push_back({name, side(-1.0)});  // +x is the subject's left (mesh.hpp)
    else if (name == "ear_l") out.push_back({name, side(1.0)});
    else throw InvalidInput("detect_landmarks: no heuristic for landmark \"" + name + "\"");
  }
  return out;
}

Alignment align_to_frame(const facemesh::Mesh& target, const Eigen::Vector3d& source_top,
                         const Eigen::Vector3d& source_nose, const AlignOptions& options) {
  options.validate();
  Alignment a;
  const Eigen::Vector3d up = axis_vector(options.up), front = axis_vector(options.front);
  // Rows of R are the input axes that become x, y, z: y = up, z = front, x = y × z.
  a.rotation.row(1) = up.transpose();
  a.rotation.row(2) = front.transpose();
  a.rotation.row(0) = up.cross(front).transpose();
  facemesh::Mesh rotated = target;
  rotated.vertices = a.apply(target.vertices);
  const auto lm = detect_landmarks(rotated, {"top_of_head", "nose_tip"});
  const Eigen::Vector3d top = rotated.vertices.row(lm[0].vertex), nose = rotated.vertices.row(lm[1].vertex);
  const double source_h = source_top.y() - source_nose.y();
  if (!(source_h > 0.0)) throw InvalidInput("align_to_frame: the source nose tip is not below its top of head");
  if (options.scale) a.scale = source_h / (top.y() - nose.y());
  if (!std::isfinite(a.scale) || !(a.scale > 0.0)) throw InvalidInput("align_to_frame: degenerate target (cannot determine its scale)");
  a.translation = Eigen::Vector3d(source_top.x() - a.scale * top.x(), source_top.y() - a.scale * top.y(),
                                  source_nose.z() - a.scale * nose.z());
  return a;
}

}  // namespace emoface::retarget
