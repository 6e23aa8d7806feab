#include "emoface/muscles/morph_targets.hpp"

#include <algorithm>
#include <cmath>

#include "emoface/core/errors.hpp"
#include "emoface/muscles/parameters.hpp"

namespace emoface::muscles {
namespace {

facemesh::MorphTarget delta_target(const std::string& name, const facemesh::Vertices& base,
                                   const facemesh::Vertices& base_normals,
                                   const facemesh::Vertices& posed, const facemesh::Faces& faces) {
  facemesh::MorphTarget t;
  t.name = name;
  t.position_deltas = posed - base;
  t.normal_deltas = facemesh::vertex_normals(posed, faces) - base_normals;
  return t;
}

}  // namespace

BakedRig bake_rig(const FaceSolver& solver, const facemesh::Faces& faces,
                  const std::vector<const faceweights::Mapper*>& sets) {
  const auto& names = parameter_names();
  BakedRig rig;
  const auto& r = solver.rig();
  rig.head_pivot = r.head_pivot;
  rig.gaze_yaw_limit = r.eyes[0].yaw_limit;
  rig.gaze_pitch_limit = r.eyes[0].pitch_limit;
  std::vector<double> zero(kParameterCount, 0.0);
  const Deformation d0 = solver.deform(zero);
  rig.neutral.vertices = d0.vertices;
  rig.neutral.faces = faces;
  const facemesh::Vertices n0 = facemesh::vertex_normals(d0.vertices, faces);
  Deformation d;
  for (std::size_t i = 0; i < kParameterCount; ++i) {
    if (!is_level_parameter(i)) continue;
    std::vector<double> v = zero;
    v[i] = 1.0;
    solver.deform(v, d);
    rig.targets.push_back(delta_target(names[i], d0.vertices, n0, d.vertices, faces));
  }
  const std::size_t yaw = parameter_index("eye_gaze_yaw"), pitch = parameter_index("eye_gaze_pitch");
  for (const auto& [index, limit, base] : {std::tuple{yaw, rig.gaze_yaw_limit, "eye_gaze_yaw"},
                                           std::tuple{pitch, rig.gaze_pitch_limit, "eye_gaze_pitch"}}) {
    for (int sign : {1, -1}) {
      std::vector<double> v = zero;
      v[index] = sign * limit;
      solver.deform(v, d);
      rig.targets.push_back(delta_target(std::string(base) + (sign > 0 ? "+" : "-"), d0.vertices, n0,
                                         d.vertices, faces));
    }
  }
  rig.parameter_target_count = rig.targets.size();
  for (const faceweights::Mapper* m : sets) {
    if (m->parameter_names() != names)
      throw InvalidInput("bake_rig: a weight-set mapper must bind muscles::parameter_names()");
    for (std::size_t t = 0; t < m->target_count(); ++t) {
      std::vector<double> w(m->target_count(), 0.0);
      w[t] = 1.0;
      std::vector<double> p = zero;
      m->inverse(w, p);
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (!is_level_parameter(i)) p[i] = std::clamp(p[i], -3.14159, 3.14159);
      }
      solver.deform(p, d);
      rig.targets.push_back(delta_target(m->set().targets[t].name, d0.vertices, n0, d.vertices, faces));
    }
  }
  return rig;
}

std::vector<double> target_weights(const BakedRig& rig, const std::vector<double>& values) {
  if (values.size() != kParameterCount)
    throw InvalidInput("target_weights: expected " + std::to_string(kParameterCount) + " values");
  std::vector<double> w(rig.targets.size(), 0.0);
  std::size_t k = 0;
  for (std::size_t i = 0; i < kParameterCount; ++i) {
    if (is_level_parameter(i)) w[k++] = values[i];
  }
  const double yaw = values[parameter_index("eye_gaze_yaw")];
  const double pitch = values[parameter_index("eye_gaze_pitch")];
  w[k++] = std::clamp(std::max(0.0, yaw) / rig.gaze_yaw_limit, 0.0, 1.0);
  w[k++] = std::clamp(std::max(0.0, -yaw) / rig.gaze_yaw_limit, 0.0, 1.0);
  w[k++] = std::clamp(std::max(0.0, pitch) / rig.gaze_pitch_limit, 0.0, 1.0);
  w[k++] = std::clamp(std::max(0.0, -pitch) / rig.gaze_pitch_limit, 0.0, 1.0);
  return w;
}

Eigen::Quaterniond head_rotation(const std::vector<double>& values) {
  const double hy = values[parameter_index("head_yaw")], hp = values[parameter_index("head_pitch")],
               hr = values[parameter_index("head_roll")];
  // the same composition as FaceSolver (solver.cpp, "Head pose")
  return Eigen::Quaterniond(Eigen::AngleAxisd(hy, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(-hp, Eigen::Vector3d::UnitX()) *
                            Eigen::AngleAxisd(hr, Eigen::Vector3d::UnitZ()));
}

facemesh::WeightAnimation bake_animation(const BakedRig& rig, const std::vector<double>& times,
                                         const std::vector<std::vector<double>>& frames,
                                         const std::string& name) {
  if (times.size() != frames.size()) throw InvalidInput("bake_animation: one time per frame");
  facemesh::WeightAnimation a;
  a.name = name;
  a.times = times;
  bool any_head = false;
  for (const auto& f : frames) {
    a.weights.push_back(target_weights(rig, f));
    a.head_rotations.push_back(head_rotation(f));
    any_head = any_head || !a.head_rotations.back().isApprox(Eigen::Quaterniond::Identity(), 1e-12);
  }
  if (!any_head) a.head_rotations.clear();
  return a;
}

void express_in_mesh_frame(BakedRig& rig, std::vector<facemesh::WeightAnimation>& animations,
                           const facemesh::Frame& frame) {
  if (frame.is_identity()) return;
  const Eigen::Matrix3d rt = frame.rotation.transpose();
  for (Eigen::Index v = 0; v < rig.neutral.vertices.rows(); ++v)
    rig.neutral.vertices.row(v) = frame.to_mesh(rig.neutral.vertices.row(v).transpose()).transpose();
  for (auto& t : rig.targets) {
    t.position_deltas = (t.position_deltas * frame.rotation) / frame.scale;  // rows: (Rᵀ·δ)ᵀ = δᵀ·R
    if (t.normal_deltas.rows() > 0) t.normal_deltas = t.normal_deltas * frame.rotation;
  }
  rig.head_pivot = frame.to_mesh(rig.head_pivot);
  const Eigen::Quaterniond r(frame.rotation), r_inv(rt);
  for (auto& a : animations)
    for (auto& q : a.head_rotations) q = (r_inv * q * r).normalized();
}

}  // namespace emoface::muscles
