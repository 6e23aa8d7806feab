#include "emoface/facemesh/mesh.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>
#include <utility>

#include <Eigen/Geometry>

#include "emoface/core/errors.hpp"

namespace emoface::facemesh {
namespace {

SourceLocation at(const std::string& source, std::size_t element) {
  SourceLocation where;
  where.file = source;
  where.line = element;
  return where;
}

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

}  // namespace

void validate_mesh(const Mesh& mesh, const std::string& source) {
  const auto nv = static_cast<long>(mesh.vertices.rows());
  if (mesh.faces.rows() == 0) throw FormatError(at(source, 0), "mesh has no triangles");
  for (long v = 0; v < nv; ++v) {
    if (!mesh.vertices.row(v).allFinite()) {
      throw FormatError(at(source, static_cast<std::size_t>(v) + 1),
                        "vertex " + std::to_string(v) + " has a NaN or infinite coordinate");
    }
  }
  // Directed edges: each may occur once (two = inconsistent orientation or a non-manifold fan).
  std::unordered_map<std::uint64_t, int> directed;
  directed.reserve(static_cast<std::size_t>(mesh.faces.rows()) * 3);
  for (long f = 0; f < mesh.faces.rows(); ++f) {
    const auto where = at(source, static_cast<std::size_t>(f) + 1);
    const std::string name = "face " + std::to_string(f);
    for (int c = 0; c < 3; ++c) {
      const int id = mesh.faces(f, c);
      if (id < 0 || id >= nv) {
        throw FormatError(where, name + " references vertex " + std::to_string(id) + " (mesh has " +
                                     std::to_string(nv) + " vertices)");
      }
    }
    const int a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
    if (a == b || b == c || a == c) throw FormatError(where, name + " repeats a vertex");
    const Eigen::Vector3d e1 = mesh.vertices.row(b) - mesh.vertices.row(a);
    const Eigen::Vector3d e2 = mesh.vertices.row(c) - mesh.vertices.row(a);
    const double scale = std::max(e1.squaredNorm(), e2.squaredNorm());
    if (!(e1.cross(e2).norm() > 1e-12 * scale)) throw FormatError(where, name + " is degenerate (zero area)");
    const int ids[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      const auto key = edge_key(ids[k], ids[(k + 1) % 3]);
      if (!directed.emplace(key, static_cast<int>(f)).second) {
        throw FormatError(where, name + " makes edge " + std::to_string(ids[k]) + "-" +
                                     std::to_string(ids[(k + 1) % 3]) +
                                     " non-manifold (shared with face " +
                                     std::to_string(directed[key]) + " in the same direction)");
      }
    }
  }
}

OrientationReport orient_consistently(Mesh& mesh) {
  const auto nf = static_cast<std::size_t>(mesh.faces.rows());
  const auto nv = static_cast<long>(mesh.vertices.rows());
  // Undirected edge (min, max) -> up to two (face, direction) entries; direction +1 = face runs min->max.
  struct Slot {
    int face[2] = {-1, -1};
    int dir[2] = {0, 0};
  };
  std::unordered_map<std::uint64_t, Slot> edges;
  edges.reserve(nf * 2);
  for (std::size_t f = 0; f < nf; ++f) {
    const auto fi = static_cast<long>(f);
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces(fi, k), b = mesh.faces(fi, (k + 1) % 3);
      if (a < 0 || a >= nv || b < 0 || b >= nv)
        throw InvalidInput("orient_consistently: face " + std::to_string(f) + " references a vertex out of range");
      if (a == b) throw InvalidInput("orient_consistently: face " + std::to_string(f) + " repeats a vertex");
      Slot& s = edges[edge_key(std::min(a, b), std::max(a, b))];
      const int slot = s.face[0] < 0 ? 0 : (s.face[1] < 0 ? 1 : 2);
      if (slot == 2)
        throw InvalidInput("orient_consistently: face " + std::to_string(f) + " makes edge " + std::to_string(a) + "-" +
                           std::to_string(b) + " shared by more than two triangles (non-manifold: no consistent orientation exists)");
      s.face[slot] = static_cast<int>(f);
      s.dir[slot] = a < b ? 1 : -1;
    }
  }
  auto key_of = [&](std::size_t f, int k) {
    const int a = mesh.faces(static_cast<long>(f), k), b = mesh.faces(static_cast<long>(f), (k + 1) % 3);
    return edge_key(std::min(a, b), std::max(a, b));
  };
  OrientationReport report;
  std::vector<int> flip(nf, -1);  // -1 unvisited, 0 keep, 1 reverse
  std::vector<std::size_t> queue, members;
  for (std::size_t seed = 0; seed < nf; ++seed) {
    if (flip[seed] >= 0) continue;
    ++report.components;
    members.clear();
    queue.assign(1, seed);
    flip[seed] = 0;
    bool closed = true;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const std::size_t f = queue[q];
      members.push_back(f);
      for (int k = 0; k < 3; ++k) {
        const Slot& s = edges[key_of(f, k)];
        if (s.face[1] < 0) {
          closed = false;
          continue;
        }
        const int self = s.face[0] == static_cast<int>(f) ? 0 : 1;
        const auto g = static_cast<std::size_t>(s.face[1 - self]);
        // Final directions must be opposite: dir_g·(−1)^flip_g = −dir_f·(−1)^flip_f.
        const int dir_f = s.dir[self] * (flip[f] ? -1 : 1);
        const int want = s.dir[1 - self] == -dir_f ? 0 : 1;
        if (flip[g] < 0) {
          flip[g] = want;
          queue.push_back(g);
        } else if (flip[g] != want) {
          throw InvalidInput("orient_consistently: the component of face " + std::to_string(seed) +
                             " is not orientable (a Moebius-like strip around face " + std::to_string(g) + ")");
        }
      }
    }
    // Fewest changes first (the majority winding wins), then outward.
    std::size_t flips = 0;
    for (auto f : members) flips += static_cast<std::size_t>(flip[f]);
    if (2 * flips > members.size())
      for (auto f : members) flip[f] = 1 - flip[f];
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double area_sum = 0.0;
    for (auto f : members) {
      const auto fi = static_cast<long>(f);
      const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(fi, 0)), b = mesh.vertices.row(mesh.faces(fi, 1)),
                            c = mesh.vertices.row(mesh.faces(fi, 2));
      const double area = 0.5 * (b - a).cross(c - a).norm();
      centre += area * (a + b + c) / 3.0;
      area_sum += area;
    }
    if (area_sum > 0) centre /= area_sum;
    double outward = 0.0;  // closed: 6 × signed volume about `centre`; open: Σ area·n·(centroid − centre)
    for (auto f : members) {
      const auto fi = static_cast<long>(f);
      Eigen::Vector3d a = Eigen::Vector3d(mesh.vertices.row(mesh.faces(fi, 0))) - centre;
      Eigen::Vector3d b = Eigen::Vector3d(mesh.vertices.row(mesh.faces(fi, 1))) - centre;
      Eigen::Vector3d c = Eigen::Vector3d(mesh.vertices.row(mesh.faces(fi, 2))) - centre;
      if (flip[f]) std::swap(b, c);
      outward += closed ? a.dot(b.cross(c)) : 0.5 * (b - a).cross(c - a).dot((a + b + c) / 3.0);
    }
    if (outward < 0) {
      for (auto f : members) flip[f] = 1 - flip[f];
      ++report.flipped_components;
    }
    if (closed) ++report.closed_components;
  }
  for (std::size_t f = 0; f < nf; ++f)
    if (flip[f] == 1) {
      std::swap(mesh.faces(static_cast<long>(f), 1), mesh.faces(static_cast<long>(f), 2));
      ++report.flipped_faces;
    }
  return report;
}

Vertices face_normals(const Vertices& vertices, const Faces& faces) {
  Vertices n(faces.rows(), 3);
  for (long f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = vertices.row(faces(f, 0));
    const Eigen::Vector3d e1 = Eigen::Vector3d(vertices.row(faces(f, 1))) - a;
    const Eigen::Vector3d e2 = Eigen::Vector3d(vertices.row(faces(f, 2))) - a;
    Eigen::Vector3d c = e1.cross(e2);
    const double len = c.norm();
    n.row(f) = len > 0.0 ? Eigen::Vector3d(c / len) : Eigen::Vector3d::Zero();
  }
  return n;
}

Vertices vertex_normals(const Vertices& vertices, const Faces& faces) {
  Vertices n = Vertices::Zero(vertices.rows(), 3);
  for (long f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = vertices.row(faces(f, 0));
    const Eigen::Vector3d e1 = Eigen::Vector3d(vertices.row(faces(f, 1))) - a;
    const Eigen::Vector3d e2 = Eigen::Vector3d(vertices.row(faces(f, 2))) - a;
    const Eigen::Vector3d c = e1.cross(e2);  // |c| = 2·area: area weighting
    for (int k = 0; k < 3; ++k) n.row(faces(f, k)) += c;
  }
  for (long v = 0; v < n.rows(); ++v) {
    const double len = n.row(v).norm();
    if (len > 0.0) n.row(v) /= len;
  }
  return n;
}

Mesh subdivide_midpoint(const Mesh& mesh, std::vector<std::pair<int, int>>* parent_pairs) {
  std::unordered_map<std::uint64_t, int> mid;
  std::vector<std::pair<int, int>> parents;
  auto midpoint = [&](int a, int b) {
    const auto key = edge_key(std::min(a, b), std::max(a, b));
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    const int id = static_cast<int>(mesh.vertices.rows() + static_cast<long>(parents.size()));
    parents.emplace_back(std::min(a, b), std::max(a, b));
    mid.emplace(key, id);
    return id;
  };
  Mesh out;
  out.faces.resize(mesh.faces.rows() * 4, 3);
  for (long f = 0; f < mesh.faces.rows(); ++f) {
    const int a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
    const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    out.faces.row(4 * f + 0) << a, ab, ca;
    out.faces.row(4 * f + 1) << ab, b, bc;
    out.faces.row(4 * f + 2) << ca, bc, c;
    out.faces.row(4 * f + 3) << ab, bc, ca;
  }
  out.vertices.resize(mesh.vertices.rows() + static_cast<long>(parents.size()), 3);
  out.vertices.topRows(mesh.vertices.rows()) = mesh.vertices;
  for (std::size_t i = 0; i < parents.size(); ++i) {
    out.vertices.row(mesh.vertices.rows() + static_cast<long>(i)) =
        0.5 * (mesh.vertices.row(parents[i].first) + mesh.vertices.row(parents[i].second));
  }
  if (parent_pairs) *parent_pairs = std::move(parents);
  return out;
}

}  // namespace emoface::facemesh
