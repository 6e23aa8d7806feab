#include "emoface/retarget/surface.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <unordered_map>

#include "emoface/core/errors.hpp"
#include "union_find.hpp"

namespace emoface::retarget {
namespace {
constexpr double kPi = 3.14159265358979323846;

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

using detail::find_root;
}  // namespace

struct MeshWalker::Impl {
  struct Edge {
    int a, b;
    int faces[2];
  };
  std::vector<Edge> edges;
  std::vector<std::array<int, 3>> face_edges;  // edge ids of face f: (v0v1, v1v2, v2v0)
  facemesh::Faces faces;
  std::vector<int> vertex_face_start, vertex_faces;  // CSR vertex -> faces
  std::vector<int> loop_of_edge;                     // -1 = interior edge
  std::vector<std::vector<int>> loops;               // boundary edge ids per loop
};

MeshWalker::MeshWalker(const facemesh::Faces& faces, std::size_t vertex_count) : impl_(std::make_unique<Impl>()) {
  auto& m = *impl_;
  m.faces = faces;
  const auto nv = static_cast<int>(vertex_count);
  std::unordered_map<std::uint64_t, int> ids;
  ids.reserve(static_cast<std::size_t>(faces.rows()) * 2);
  m.face_edges.resize(static_cast<std::size_t>(faces.rows()));
  std::vector<int> count(vertex_count + 1, 0);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      if (a < 0 || a >= nv || b < 0 || b >= nv) throw InvalidInput("MeshWalker: vertex id out of range in face " + std::to_string(f));
      ++count[static_cast<std::size_t>(a) + 1];
      const auto [it, inserted] = ids.emplace(edge_key(a, b), static_cast<int>(m.edges.size()));
      if (inserted) {
        m.edges.push_back({a, b, {static_cast<int>(f), -1}});
      } else {
        auto& e = m.edges[static_cast<std::size_t>(it->second)];
        if (e.faces[1] != -1) throw InvalidInput("MeshWalker: edge shared by more than two faces (face " + std::to_string(f) + ")");
        e.faces[1] = static_cast<int>(f);
      }
      m.face_edges[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)] = it->second;
    }
  }
  std::partial_sum(count.begin(), count.end(), count.begin());
  m.vertex_face_start = count;
  m.vertex_faces.resize(static_cast<std::size_t>(count.back()));
  std::vector<int> fill(count.begin(), count.end() - 1);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) m.vertex_faces[static_cast<std::size_t>(fill[static_cast<std::size_t>(faces(f, k))]++)] = static_cast<int>(f);
  // Boundary loops: connected components of boundary edges (union-find over their vertices).
  std::vector<int> parent(vertex_count);
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& e : m.edges)
    if (e.faces[1] == -1) parent[static_cast<std::size_t>(find_root(parent, e.a))] = find_root(parent, e.b);
  std::unordered_map<int, int> loop_ids;
  m.loop_of_edge.assign(m.edges.size(), -1);
  for (std::size_t i = 0; i < m.edges.size(); ++i) {
    if (m.edges[i].faces[1] != -1) continue;
    const int root = find_root(parent, m.edges[i].a);
    const auto [it, inserted] = loop_ids.emplace(root, static_cast<int>(m.loops.size()));
    if (inserted) m.loops.emplace_back();
    m.loops[static_cast<std::size_t>(it->second)].push_back(static_cast<int>(i));
    m.loop_of_edge[i] = it->second;
  }
}

MeshWalker::~MeshWalker() = default;
MeshWalker::MeshWalker(MeshWalker&&) noexcept = default;
MeshWalker& MeshWalker::operator=(MeshWalker&&) noexcept = default;
std::size_t MeshWalker::edge_count() const { return impl_->edges.size(); }

bool MeshWalker::on_boundary(int vertex) const {
  const auto& m = *impl_;
  if (vertex < 0 || static_cast<std::size_t>(vertex) + 1 >= m.vertex_face_start.size()) throw InvalidInput("MeshWalker: vertex out of range");
  const auto v = static_cast<std::size_t>(vertex);
  if (m.vertex_face_start[v] == m.vertex_face_start[v + 1]) return true;
  for (int k = m.vertex_face_start[v]; k < m.vertex_face_start[v + 1]; ++k)
    for (int e : m.face_edges[static_cast<std::size_t>(m.vertex_faces[static_cast<std::size_t>(k)])]) {
      const auto& edge = m.edges[static_cast<std::size_t>(e)];
      if ((edge.a == vertex || edge.b == vertex) && edge.faces[1] == -1) return true;
    }
  return false;
}
std::size_t MeshWalker::boundary_loop_count() const { return impl_->loops.size(); }

std::vector<Eigen::Vector2d> MeshWalker::half_plane_curve(const facemesh::Vertices& v, int start,
                                                          const Eigen::Vector3d& c, double azimuth,
                                                          double stop_y) const {
  const auto& m = *impl_;
  if (v.rows() + 1 != static_cast<Eigen::Index>(m.vertex_face_start.size()))
    throw InvalidInput("MeshWalker: vertex count does not match the mesh");
  if (start < 0 || start >= v.rows()) throw InvalidInput("MeshWalker: start vertex out of range");
  // Plane P through l with horizontal direction d (inside the plane) and normal n (thesis §3.5).
  const Eigen::Vector3d d(std::sin(azimuth), 0.0, std::cos(azimuth));
  const Eigen::Vector3d n(std::cos(azimuth), 0.0, -std::sin(azimuth));
  auto signed_distance = [&](int i) {
    return n.x() * (v(i, 0) - c.x()) + n.z() * (v(i, 2) - c.z());
  };
  auto side = [&](int i) { return signed_distance(i) >= 0.0; };
  auto crossing = [&](int edge, Eigen::Vector3d& p) {
    const auto& e = m.edges[static_cast<std::size_t>(edge)];
    if (side(e.a) == side(e.b)) return false;
    const double sa = signed_distance(e.a), sb = signed_distance(e.b);
    const double t = sa / (sa - sb);
    p = (1.0 - t) * Eigen::Vector3d(v.row(e.a)) + t * Eigen::Vector3d(v.row(e.b));
    return true;
  };
  auto radial = [&](const Eigen::Vector3d& p) { return d.x() * (p.x() - c.x()) + d.z() * (p.z() - c.z()); };

  std::vector<Eigen::Vector2d> curve;
  const Eigen::Vector3d top = v.row(start);
  curve.emplace_back(radial(top), top.y());
  // Start: the crossing edge opposite `start` in its fan, on the d side (the top vertex lies on l).
  int current = -1, from_face = -1;
  double best_r = -std::numeric_limits<double>::infinity();
  Eigen::Vector3d p;
  for (int k = m.vertex_face_start[static_cast<std::size_t>(start)]; k < m.vertex_face_start[static_cast<std::size_t>(start) + 1]; ++k) {
    const int f = m.vertex_faces[static_cast<std::size_t>(k)];
    for (int e : m.face_edges[static_cast<std::size_t>(f)]) {
      const auto& edge = m.edges[static_cast<std::size_t>(e)];
      if (edge.a == start || edge.b == start) continue;
      Eigen::Vector3d q;
      if (crossing(e, q) && radial(q) > 0.0 && radial(q) > best_r) {
        best_r = radial(q);
        current = e;
        from_face = f;
        p = q;
      }
    }
  }
  if (current < 0) return curve;
  std::vector<char> visited(m.edges.size(), 0);
  const std::size_t max_steps = m.edges.size();
  for (std::size_t step = 0; step < max_steps; ++step) {
    visited[static_cast<std::size_t>(current)] = 1;
    curve.emplace_back(radial(p), p.y());
    if (p.y() < stop_y) break;
    const auto& e = m.edges[static_cast<std::size_t>(current)];
    const int next_face = e.faces[0] == from_face ? e.faces[1] : e.faces[0];
    int next = -1;
    Eigen::Vector3d q;
    if (next_face >= 0) {
      for (int candidate : m.face_edges[static_cast<std::size_t>(next_face)]) {
        if (candidate == current || visited[static_cast<std::size_t>(candidate)]) continue;
        if (crossing(candidate, q)) {
          next = candidate;
          break;
        }
      }
      from_face = next_face;
    } else {
      // Hole (thesis §3.5, "filling all the holes"): jump to the nearest lower crossing of this loop.
      const auto& loop = m.loops[static_cast<std::size_t>(m.loop_of_edge[static_cast<std::size_t>(current)])];
      double best_y = -std::numeric_limits<double>::infinity();
      for (int candidate : loop) {
        Eigen::Vector3d r;
        if (visited[static_cast<std::size_t>(candidate)] || !crossing(candidate, r)) continue;
        if (radial(r) <= 0.0 || r.y() >= p.y() || r.y() <= best_y) continue;
        best_y = r.y();
        next = candidate;
        q = r;
      }
      from_face = -1;  // the landing edge is a boundary edge: the next step enters its only face
    }
    if (next < 0 || radial(q) < 0.0) break;
    current = next;
    p = q;
  }
  return curve;
}

int top_vertex(const facemesh::Vertices& vertices) {
  if (vertices.rows() == 0) throw InvalidInput("top_vertex: empty mesh");
  Eigen::Index best = 0;
  for (Eigen::Index i = 1; i < vertices.rows(); ++i)
    if (vertices(i, 1) > vertices(best, 1)) best = i;
  return static_cast<int>(best);
}

// ---------------------------------------------------------------------------------------------------
struct CylindricalProjector::Impl {
  facemesh::Mesh mesh;
  Eigen::Vector3d centre;
  int na = 0, ny = 0;
  double y0 = 0, y1 = 0;
  std::vector<std::vector<int>> bins;  // na*ny
  int bin_a(double a) const {
    int i = static_cast<int>(std::floor((a + kPi) / (2 * kPi) * na));
    return std::clamp(i, 0, na - 1);
  }
  int bin_y(double y) const {
    int j = static_cast<int>(std::floor((y - y0) / (y1 - y0) * ny));
    return std::clamp(j, 0, ny - 1);
  }
};

CylindricalProjector::CylindricalProjector(const facemesh::Mesh& mesh, const Eigen::Vector3d& centre,
                                           int azimuth_bins, int height_bins)
    : impl_(std::make_unique<Impl>()) {
  if (mesh.face_count() == 0) throw InvalidInput("CylindricalProjector: empty mesh");
  if (azimuth_bins < 4 || height_bins < 4) throw InvalidInput("CylindricalProjector: need at least 4 bins");
  auto& m = *impl_;
  m.mesh = mesh;
  m.centre = centre;
  m.na = azimuth_bins;
  m.ny = height_bins;
  m.y0 = mesh.vertices.col(1).minCoeff();
  m.y1 = mesh.vertices.col(1).maxCoeff();
  if (!(m.y1 > m.y0)) m.y1 = m.y0 + 1.0;
  m.bins.resize(static_cast<std::size_t>(m.na * m.ny));
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    double amin = 1e9, amax = -1e9, ymin = 1e9, ymax = -1e9;
    bool on_axis = false;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = mesh.vertices.row(mesh.faces(f, k));
      const double dx = p.x() - centre.x(), dz = p.z() - centre.z();
      if (dx * dx + dz * dz < 1e-24) on_axis = true;
      const double a = std::atan2(dx, dz);
      amin = std::min(amin, a);
      amax = std::max(amax, a);
      ymin = std::min(ymin, p.y());
      ymax = std::max(ymax, p.y());
    }
    int a0 = m.bin_a(amin), a1 = m.bin_a(amax);
    if (on_axis || amax - amin > kPi) {  // straddles the back seam or touches the axis: every column
      a0 = 0;
      a1 = m.na - 1;
    }
    for (int j = m.bin_y(ymin); j <= m.bin_y(ymax); ++j)
      for (int i = a0; i <= a1; ++i) m.bins[static_cast<std::size_t>(j * m.na + i)].push_back(static_cast<int>(f));
  }
}

CylindricalProjector::~CylindricalProjector() = default;
CylindricalProjector::CylindricalProjector(CylindricalProjector&&) noexcept = default;
CylindricalProjector& CylindricalProjector::operator=(CylindricalProjector&&) noexcept = default;

bool CylindricalProjector::project(const Eigen::Vector3d& p, Eigen::Vector3d& out) const {
  const auto& m = *impl_;
  if (!p.allFinite()) return false;
  const double dx = p.x() - m.centre.x(), dz = p.z() - m.centre.z();
  const double r = std::hypot(dx, dz);
  if (r < 1e-12) return false;
  const Eigen::Vector3d o(m.centre.x(), p.y(), m.centre.z());
  const Eigen::Vector3d dir(dx / r, 0.0, dz / r);
  const auto& cell = m.bins[static_cast<std::size_t>(m.bin_y(p.y()) * m.na + m.bin_a(std::atan2(dx, dz)))];
  double best = std::numeric_limits<double>::infinity(), best_t = 0;
  for (int f : cell) {
    // Möller–Trumbore ray/triangle intersection.
    const Eigen::Vector3d v0 = m.mesh.vertices.row(m.mesh.faces(f, 0));
    const Eigen::Vector3d e1 = Eigen::Vector3d(m.mesh.vertices.row(m.mesh.faces(f, 1))) - v0;
    const Eigen::Vector3d e2 = Eigen::Vector3d(m.mesh.vertices.row(m.mesh.faces(f, 2))) - v0;
    const Eigen::Vector3d h = dir.cross(e2);
    const double a = e1.dot(h);
    if (std::abs(a) < 1e-18) continue;
    const Eigen::Vector3d s = o - v0;
    const double u = s.dot(h) / a;
    if (u < -1e-9 || u > 1 + 1e-9) continue;
    const Eigen::Vector3d q = s.cross(e1);
    const double w = dir.dot(q) / a;
    if (w < -1e-9 || u + w > 1 + 1e-9) continue;
    const double t = e2.dot(q) / a;
    if (t <= 0.0) continue;
    if (std::abs(t - r) < best) {
      best = std::abs(t - r);
      best_t = t;
    }
  }
  if (!std::isfinite(best)) return false;
  out = o + best_t * dir;
  return true;
}

}  // namespace emoface::retarget
