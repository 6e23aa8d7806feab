#include "emoface/retarget/clean.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "emoface/core/errors.hpp"
#include "union_find.hpp"

namespace emoface::retarget {
using detail::find_root;

void CleanOptions::validate() const {
  if (!(margin >= 0.0 && margin <= 10.0)) throw InvalidInput("CleanOptions::margin must be in [0, 10]");
}

facemesh::Mesh clean_target(const facemesh::Mesh& mesh, const CleanOptions& options, CleanReport* report) {
  options.validate();
  const auto nv = mesh.vertices.rows();
  if (mesh.faces.rows() == 0) throw InvalidInput("clean_target: the mesh has no faces");
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.faces(f, k);
      if (v < 0 || v >= nv) throw InvalidInput("clean_target: face " + std::to_string(f) + " has a vertex id out of range");
      if (!mesh.vertices.row(v).allFinite()) throw InvalidInput("clean_target: vertex " + std::to_string(v) + " has a NaN or infinite coordinate");
    }
  // Components over shared vertices (union-find).
  std::vector<int> parent(static_cast<std::size_t>(nv));
  std::iota(parent.begin(), parent.end(), 0);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int k = 1; k < 3; ++k)
      parent[static_cast<std::size_t>(find_root(parent, mesh.faces(f, k)))] = find_root(parent, mesh.faces(f, 0));
  std::vector<int> id(static_cast<std::size_t>(nv), -1);
  std::vector<double> area;
  std::vector<Eigen::AlignedBox3d> box;
  std::vector<int> face_component(static_cast<std::size_t>(mesh.faces.rows()));
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const int root = find_root(parent, mesh.faces(f, 0));
    int& c = id[static_cast<std::size_t>(root)];
    if (c < 0) {
      c = static_cast<int>(area.size());
      area.push_back(0.0);
      box.emplace_back();
    }
    face_component[static_cast<std::size_t>(f)] = c;
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
                          d = mesh.vertices.row(mesh.faces(f, 2));
    area[static_cast<std::size_t>(c)] += 0.5 * (b - a).cross(d - a).norm();
    box[static_cast<std::size_t>(c)].extend(a).extend(b).extend(d);
  }
  const auto largest = static_cast<std::size_t>(std::max_element(area.begin(), area.end()) - area.begin());
  Eigen::AlignedBox3d head = box[largest];
  const double grow = options.margin * head.diagonal().norm();
  head.min().array() -= grow;
  head.max().array() += grow;
  std::vector<char> keep(area.size(), 0);
  for (std::size_t c = 0; c < area.size(); ++c) keep[c] = c == largest || !options.enabled || head.contains(box[c]);
  // Kept faces and the vertices they use, renumbered in order.
  std::vector<int> new_id(static_cast<std::size_t>(nv), -1);
  std::vector<Eigen::Index> faces;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    if (keep[static_cast<std::size_t>(face_component[static_cast<std::size_t>(f)])]) {
      faces.push_back(f);
      for (int k = 0; k < 3; ++k) new_id[static_cast<std::size_t>(mesh.faces(f, k))] = 0;
    }
  int next = 0;
  for (auto& v : new_id)
    if (v == 0) v = next++;
  facemesh::Mesh out;
  out.vertices.resize(next, 3);
  for (Eigen::Index v = 0; v < nv; ++v)
    if (new_id[static_cast<std::size_t>(v)] >= 0) out.vertices.row(new_id[static_cast<std::size_t>(v)]) = mesh.vertices.row(v);
  out.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t k = 0; k < faces.size(); ++k)
    for (int j = 0; j < 3; ++j) out.faces(static_cast<Eigen::Index>(k), j) = new_id[static_cast<std::size_t>(mesh.faces(faces[k], j))];
  if (report) {
    report->components = area.size();
    report->kept_components = static_cast<std::size_t>(std::count(keep.begin(), keep.end(), 1));
    report->dropped_faces = static_cast<std::size_t>(mesh.faces.rows()) - faces.size();
    report->dropped_vertices = static_cast<std::size_t>(nv - next);
  }
  return out;
}

}  // namespace emoface::retarget
