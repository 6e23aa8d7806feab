#include "emoface/muscles/morph_targets.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "emoface/core/errors.hpp"
#include "emoface/facemesh/mesh_document.hpp"
#include "emoface/facemesh/render.hpp"
#include "emoface/muscles/parameters.hpp"
#include "emoface/muscles/waters.hpp"

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

int find_root(std::vector<int>& parent, int v) {
  while (parent[static_cast<std::size_t>(v)] != v) {
    parent[static_cast<std::size_t>(v)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
    v = parent[static_cast<std::size_t>(v)];
  }
  return v;
}

// Connected components over the faces: per vertex its component id (0-based, dense).
std::vector<int> components(long nv, const facemesh::Faces& faces) {
  std::vector<int> parent(static_cast<std::size_t>(nv));
  std::iota(parent.begin(), parent.end(), 0);
  for (long f = 0; f < faces.rows(); ++f) {
    for (int k = 1; k < 3; ++k) {
      const int a = find_root(parent, faces(f, 0)), b = find_root(parent, faces(f, k));
      if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  }
  std::vector<int> id(static_cast<std::size_t>(nv), -1), out(static_cast<std::size_t>(nv));
  int next = 0;
  for (long v = 0; v < nv; ++v) {
    const int r = find_root(parent, static_cast<int>(v));
    if (id[static_cast<std::size_t>(r)] < 0) id[static_cast<std::size_t>(r)] = next++;
    out[static_cast<std::size_t>(v)] = id[static_cast<std::size_t>(r)];
  }
  return out;
}

// The rotation about +x through `pivot` as solver.cpp's rotate_x applies it.
Eigen::Vector3d rotated_x(const Eigen::Vector3d& p, const Eigen::Vector3d& pivot, double a) {
  const double c = std::cos(a), s = std::sin(a);
  const Eigen::Vector3d q = p - pivot;
  return pivot + Eigen::Vector3d(q.x(), q.y() * c - q.z() * s, q.y() * s + q.z() * c);
}

}  // namespace

std::string to_string(PartDrive drive) {
  switch (drive) {
    case PartDrive::EyeRight:
      return "eye_right";
    case PartDrive::EyeLeft:
      return "eye_left";
    case PartDrive::Jaw:
      return "jaw";
  }
  return "jaw";
}

PartDrive part_drive_from_string(std::string_view name) {
  if (name == "eye_right") return PartDrive::EyeRight;
  if (name == "eye_left") return PartDrive::EyeLeft;
  if (name == "jaw") return PartDrive::Jaw;
  throw InvalidInput("unknown part drive '" + std::string(name) + "' (eye_right, eye_left or jaw)");
}

void SplitOptions::validate() const {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throw InvalidInput("SplitOptions: tolerance must be finite and > 0");
}

BakedRig bake_rig(const FaceSolver& solver, const facemesh::Faces& faces,
                  const std::vector<const faceweights::Mapper*>& sets) {
  const auto& names = parameter_names();
  BakedRig rig;
  const auto& r = solver.rig();
  rig.head_pivot = r.head_pivot;
  rig.gaze_yaw_limit = r.eyes[0].yaw_limit;
  rig.gaze_pitch_limit = r.eyes[0].pitch_limit;
  for (std::size_t e = 0; e < 2; ++e)
    rig.eye_limits[e] = {r.eyes[e].yaw_limit, r.eyes[e].pitch_limit};
  rig.jaw_max_angle = r.jaw.max_angle;
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
  if (!rig.gaze_targets) return w;
  w[k++] = std::clamp(std::max(0.0, yaw) / rig.gaze_yaw_limit, 0.0, 1.0);
  w[k++] = std::clamp(std::max(0.0, -yaw) / rig.gaze_yaw_limit, 0.0, 1.0);
  w[k++] = std::clamp(std::max(0.0, pitch) / rig.gaze_pitch_limit, 0.0, 1.0);
  w[k++] = std::clamp(std::max(0.0, -pitch) / rig.gaze_pitch_limit, 0.0, 1.0);
  return w;
}

facemesh::Vertices blend_targets(const BakedRig& rig, const std::vector<double>& weights) {
  if (weights.size() != rig.targets.size())
    throw InvalidInput("blend_targets: " + std::to_string(weights.size()) + " weights for " +
                       std::to_string(rig.targets.size()) + " targets");
  facemesh::Vertices out = rig.neutral.vertices;
  for (std::size_t t = 0; t < weights.size(); ++t) {
    if (!std::isfinite(weights[t]))
      throw InvalidInput("blend_targets: weight of '" + rig.targets[t].name + "' not finite");
    if (weights[t] != 0.0) out += weights[t] * rig.targets[t].position_deltas;
  }
  return out;
}

std::vector<double> set_target_weights(const BakedRig& rig,
                                       const std::vector<double>& set_weights) {
  if (rig.parameter_target_count + set_weights.size() != rig.targets.size())
    throw InvalidInput(
        "set_target_weights: " + std::to_string(set_weights.size()) + " set weights for " +
        std::to_string(rig.targets.size() - rig.parameter_target_count) + " set targets");
  std::vector<double> w(rig.targets.size(), 0.0);
  std::copy(set_weights.begin(), set_weights.end(),
            w.begin() + static_cast<std::ptrdiff_t>(rig.parameter_target_count));
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
  if (rig.parts.size() != rig.part_drives.size())
    throw InvalidInput("bake_animation: one drive per part");
  if (!rig.parts.empty()) a.part_rotations.resize(rig.parts.size());
  const std::size_t yaw = parameter_index("eye_gaze_yaw"),
                    pitch = parameter_index("eye_gaze_pitch");
  const std::size_t masseter = parameter_index("masseter");
  for (std::size_t p = 0; p < rig.parts.size(); ++p) {
    bool moves = false;
    auto& out = a.part_rotations[p];
    for (const auto& f : frames) {
      Eigen::Quaterniond q;
      if (rig.part_drives[p] == PartDrive::Jaw) {
        // solver.cpp: the jaw rotates its weight-1 vertices by masseter · max_angle about +x
        q = Eigen::AngleAxisd(f[masseter] * rig.jaw_max_angle, Eigen::Vector3d::UnitX());
      } else {
        const auto& lim = rig.eye_limits[rig.part_drives[p] == PartDrive::EyeRight ? 0 : 1];
        const Eigen::Vector2d g = limit_gaze(f[yaw], f[pitch], lim.x(), lim.y());
        q = Eigen::AngleAxisd(g.x(), Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(-g.y(), Eigen::Vector3d::UnitX());
      }
      moves = moves || !q.isApprox(Eigen::Quaterniond::Identity(), 1e-12);
      out.push_back(q);
    }
    if (!moves) out.clear();
  }
  return a;
}

void split_rigid_parts(BakedRig& rig, const facemesh::Rig& face_rig,
                       std::vector<Eigen::Vector3f>& colors, const SplitOptions& options) {
  options.validate();
  if (!rig.parts.empty() || !rig.skin_vertices.empty())
    throw InvalidInput("split_rigid_parts: the rig is already split");
  const long nv = rig.neutral.vertices.rows();
  const auto unv = static_cast<std::size_t>(nv);
  if (!colors.empty() && colors.size() != unv)
    throw InvalidInput("split_rigid_parts: one colour per vertex");
  if (face_rig.materials.size() != unv ||
      face_rig.jaw.vertices.size() != face_rig.jaw.weights.size())
    throw InvalidInput("split_rigid_parts: the rig does not fit the baked mesh");
  if (!rig.gaze_targets || rig.parameter_target_count < 4)
    throw InvalidInput("split_rigid_parts: not a bake_rig result");
  const std::size_t level_count = rig.parameter_target_count - 4;  // then the four gaze halves
  std::size_t masseter_target = rig.targets.size();
  for (std::size_t t = 0; t < level_count; ++t) {
    if (rig.targets[t].name == "masseter") masseter_target = t;
  }
  const std::vector<int> comp = components(nv, rig.neutral.faces);
  const int ncomp = comp.empty() ? 0 : *std::max_element(comp.begin(), comp.end()) + 1;
  std::vector<std::vector<int>> members(static_cast<std::size_t>(ncomp));
  for (long v = 0; v < nv; ++v)
    members[static_cast<std::size_t>(comp[static_cast<std::size_t>(v)])].push_back(
        static_cast<int>(v));
  const double tol = options.tolerance;
  auto moved = [&](const std::vector<int>& vs, std::size_t t) {
    for (int v : vs) {
      if (rig.targets[t].position_deltas.row(v).cwiseAbs().maxCoeff() > tol) return true;
    }
    return false;
  };
  auto still_but = [&](const std::vector<int>& vs, std::size_t except) {
    for (std::size_t t = 0; t < level_count; ++t) {
      if (t != except && moved(vs, t)) return false;
    }
    return true;
  };
  // whole components only: returns the vertices of the components `vs` touches if it covers them
  // all
  auto closed = [&](std::vector<int> vs) {
    std::sort(vs.begin(), vs.end());
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
    std::map<int, std::size_t> count;
    for (int v : vs) {
      if (v < 0 || v >= nv) return false;
      ++count[comp[static_cast<std::size_t>(v)]];
    }
    for (const auto& [c, n] : count) {
      if (members[static_cast<std::size_t>(c)].size() != n) return false;
    }
    return !vs.empty();
  };
  std::vector<int> owner(unv, -1);
  std::vector<std::vector<int>> part_vertices;
  auto sorted_unique = [](std::vector<int> vs) {
    std::sort(vs.begin(), vs.end());
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
    return vs;
  };
  auto make_mesh = [&](const std::string& name, const std::vector<int>& vs) {
    facemesh::PartMesh pm;
    pm.name = name;
    std::map<int, int> local;
    pm.mesh.vertices.resize(static_cast<long>(vs.size()), 3);
    for (std::size_t i = 0; i < vs.size(); ++i) {
      local[vs[i]] = static_cast<int>(i);
      pm.mesh.vertices.row(static_cast<long>(i)) = rig.neutral.vertices.row(vs[i]);
      if (!colors.empty()) pm.colors.push_back(colors[static_cast<std::size_t>(vs[i])]);
    }
    std::vector<Eigen::Vector3i> faces;
    for (long f = 0; f < rig.neutral.faces.rows(); ++f) {
      const auto it = local.find(rig.neutral.faces(f, 0));
      if (it == local.end()) continue;
      faces.emplace_back(it->second, local.at(rig.neutral.faces(f, 1)),
                         local.at(rig.neutral.faces(f, 2)));
    }
    pm.mesh.faces.resize(static_cast<long>(faces.size()), 3);
    for (std::size_t f = 0; f < faces.size(); ++f)
      pm.mesh.faces.row(static_cast<long>(f)) = faces[f].transpose();
    return pm;
  };
  int eyes_split = 0;
  if (options.eyes) {
    for (std::size_t e = 0; e < 2; ++e) {
      const auto vs = sorted_unique(face_rig.eyes[e].eyeball_vertices);
      if (!closed(vs) || !still_but(vs, rig.targets.size())) continue;
      bool taken = false;
      for (int v : vs) taken = taken || owner[static_cast<std::size_t>(v)] >= 0;
      if (taken) continue;
      facemesh::NodePart part;
      part.name = e == 0 ? "eye_r" : "eye_l";
      part.pivot = face_rig.eyes[e].centre;
      auto pm = make_mesh(e == 0 ? "eyeball_r" : "eyeball_l", vs);
      if (pm.mesh.faces.rows() == 0) continue;
      part.meshes.push_back(std::move(pm));
      for (int v : vs) owner[static_cast<std::size_t>(v)] = static_cast<int>(rig.parts.size());
      rig.parts.push_back(std::move(part));
      rig.part_drives.push_back(e == 0 ? PartDrive::EyeRight : PartDrive::EyeLeft);
      ++eyes_split;
    }
  }
  if (options.jaw && masseter_target < rig.targets.size()) {
    std::vector<char> full(unv, 0);
    for (std::size_t k = 0; k < face_rig.jaw.vertices.size(); ++k) {
      const int v = face_rig.jaw.vertices[k];
      if (v >= 0 && v < nv && face_rig.jaw.weights[k] >= 1.0) full[static_cast<std::size_t>(v)] = 1;
    }
    std::map<std::string, std::vector<int>> by_name;
    for (const auto& vs : members) {
      bool ok = !vs.empty();
      for (int v : vs)
        ok = ok && full[static_cast<std::size_t>(v)] && owner[static_cast<std::size_t>(v)] < 0;
      if (!ok || !still_but(vs, masseter_target)) continue;
      // masseter moves it exactly as the jaw rotation (solver.cpp, thesis §2.4.4)
      for (int v : vs) {
        const Eigen::Vector3d p = rig.neutral.vertices.row(v).transpose();
        const Eigen::Vector3d want = rotated_x(p, face_rig.jaw.pivot, face_rig.jaw.max_angle) - p;
        const Eigen::Vector3d got = rig.targets[masseter_target].position_deltas.row(v).transpose();
        ok = ok && (got - want).cwiseAbs().maxCoeff() <= tol;
      }
      if (!ok) continue;
      std::array<int, facemesh::kMaterialCount> votes{};
      for (int v : vs)
        ++votes[static_cast<std::size_t>(face_rig.materials[static_cast<std::size_t>(v)])];
      const auto m = static_cast<facemesh::Material>(std::max_element(votes.begin(), votes.end()) -
                                                     votes.begin());
      const std::string name = m == facemesh::Material::Teeth    ? "lower_teeth"
                               : m == facemesh::Material::Tongue ? "tongue"
                                                                 : "jaw_rigid";
      auto& list = by_name[name];
      list.insert(list.end(), vs.begin(), vs.end());
    }
    if (!by_name.empty()) {
      facemesh::NodePart part;
      part.name = "jaw";
      part.pivot = face_rig.jaw.pivot;
      for (const char* name : {"lower_teeth", "tongue", "jaw_rigid"}) {
        const auto it = by_name.find(name);
        if (it == by_name.end()) continue;
        const auto vs = sorted_unique(it->second);
        for (int v : vs) owner[static_cast<std::size_t>(v)] = static_cast<int>(rig.parts.size());
        part.meshes.push_back(make_mesh(name, vs));
      }
      rig.parts.push_back(std::move(part));
      rig.part_drives.push_back(PartDrive::Jaw);
    }
  }
  if (rig.parts.empty()) return;
  // the skin: the remaining vertices and the faces among them
  std::vector<int> skin_id(unv, -1);
  for (long v = 0; v < nv; ++v) {
    if (owner[static_cast<std::size_t>(v)] >= 0) continue;
    skin_id[static_cast<std::size_t>(v)] = static_cast<int>(rig.skin_vertices.size());
    rig.skin_vertices.push_back(static_cast<int>(v));
  }
  const long ns = static_cast<long>(rig.skin_vertices.size());
  if (ns == 0) throw InvalidInput("split_rigid_parts: nothing left of the skin");
  auto restrict_rows = [&](const facemesh::Vertices& m) {
    if (m.rows() == 0) return m;
    facemesh::Vertices out(ns, 3);
    for (long i = 0; i < ns; ++i)
      out.row(i) = m.row(rig.skin_vertices[static_cast<std::size_t>(i)]);
    return out;
  };
  std::vector<Eigen::Vector3i> faces;
  for (long f = 0; f < rig.neutral.faces.rows(); ++f) {
    const int a = skin_id[static_cast<std::size_t>(rig.neutral.faces(f, 0))];
    if (a < 0) continue;
    faces.emplace_back(a, skin_id[static_cast<std::size_t>(rig.neutral.faces(f, 1))],
                       skin_id[static_cast<std::size_t>(rig.neutral.faces(f, 2))]);
  }
  rig.neutral.vertices = restrict_rows(rig.neutral.vertices);
  rig.neutral.faces.resize(static_cast<long>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    rig.neutral.faces.row(static_cast<long>(f)) = faces[f].transpose();
  for (auto& t : rig.targets) {
    t.position_deltas = restrict_rows(t.position_deltas);
    t.normal_deltas = restrict_rows(t.normal_deltas);
  }
  if (!colors.empty()) {
    std::vector<Eigen::Vector3f> kept;
    for (int v : rig.skin_vertices) kept.push_back(colors[static_cast<std::size_t>(v)]);
    colors = std::move(kept);
  }
  // both eyeballs are nodes: the gaze halves move nothing left in the skin, so they go
  if (eyes_split == 2) {
    bool zero = true;
    for (std::size_t t = level_count; t < level_count + 4; ++t)
      zero = zero && rig.targets[t].position_deltas.cwiseAbs().maxCoeff() <= tol;
    if (zero) {
      rig.targets.erase(rig.targets.begin() + static_cast<std::ptrdiff_t>(level_count),
                        rig.targets.begin() + static_cast<std::ptrdiff_t>(level_count + 4));
      rig.parameter_target_count -= 4;
      rig.gaze_targets = false;
    }
  }
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
  for (auto& a : animations) {
    for (auto& q : a.head_rotations) q = (r_inv * q * r).normalized();
    for (auto& list : a.part_rotations)
      for (auto& q : list) q = (r_inv * q * r).normalized();
  }
  for (auto& part : rig.parts) {
    part.pivot = frame.to_mesh(part.pivot);
    for (auto& pm : part.meshes) {
      for (Eigen::Index v = 0; v < pm.mesh.vertices.rows(); ++v)
        pm.mesh.vertices.row(v) = frame.to_mesh(pm.mesh.vertices.row(v).transpose()).transpose();
    }
  }
}

RigGltfReport write_rig_gltf(const std::string& path, const facemesh::Face& face,
                             const FaceSolver& solver, const std::vector<double>& times,
                             const std::vector<std::vector<double>>& frames,
                             const RigGltfOptions& options) {
  const faceweights::Mapper arkit(faceweights::builtin_weight_set("arkit"), parameter_names());
  BakedRig rig = bake_rig(solver, face.mesh.faces, {&arkit});
  RigGltfReport report;
  report.user_document = face.document && (face.document->format() == facemesh::MeshFormat::Gltf ||
                                           face.document->format() == facemesh::MeshFormat::Glb);
  std::vector<Eigen::Vector3f> colors;
  if (!report.user_document) {
    colors = facemesh::material_colors(face.rig, face.mesh);
    if (options.split_parts) split_rigid_parts(rig, face.rig, colors, options.split);
  }
  std::vector<facemesh::WeightAnimation> animations{
      bake_animation(rig, times, frames, options.animation_name)};
  express_in_mesh_frame(rig, animations, face.rig.frame);  // a user's mesh keeps its own frame
  report.targets = rig.targets.size();
  if (report.user_document) {
    const auto r = face.document->write_gltf_with_targets(path, rig.targets, animations);
    for (std::size_t t = 0; t < r.names.size(); ++t) {
      if (r.names[t] != rig.targets[t].name) report.renamed.push_back(r.names[t]);
    }
    return report;
  }
  facemesh::MorphGltfOptions gopt;
  gopt.colors = colors;
  gopt.head_pivot = rig.head_pivot;
  gopt.parts = rig.parts;
  for (const auto& p : rig.parts) report.parts.push_back(p.name);
  facemesh::write_morph_gltf(path, rig.neutral, rig.targets, animations, gopt);
  return report;
}

}  // namespace emoface::muscles
