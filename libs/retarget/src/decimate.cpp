// Quadric-error edge collapse for the synthetic validation suite (see validation.hpp).
#include <algorithm>
#include <limits>
#include <cmath>
#include <queue>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>

#include "emoface/core/errors.hpp"
#include "emoface/retarget/validation.hpp"

namespace emoface::retarget {
namespace {
struct Candidate {
  double cost;
  int u, v;
  unsigned su, sv;  // stamps of u and v when queued
  bool operator<(const Candidate& o) const {  // min-heap on cost, ties by ids (deterministic)
    return std::tie(cost, u, v) > std::tie(o.cost, o.u, o.v);
  }
};
}  // namespace

facemesh::Mesh decimate(const facemesh::Mesh& mesh, double keep_fraction, bool keep_positions) {
  if (!(keep_fraction > 0.0 && keep_fraction <= 1.0)) throw InvalidInput("decimate: keep_fraction must be in (0, 1]");
  facemesh::validate_mesh(mesh, "decimate input");
  const auto nv = static_cast<int>(mesh.vertices.rows());
  const auto nf = static_cast<int>(mesh.faces.rows());
  facemesh::Vertices v = mesh.vertices;
  facemesh::Faces f = mesh.faces;
  std::vector<char> face_alive(static_cast<std::size_t>(nf), 1), vertex_alive(static_cast<std::size_t>(nv), 0);
  std::vector<std::vector<int>> vf(static_cast<std::size_t>(nv));
  for (int i = 0; i < nf; ++i)
    for (int k = 0; k < 3; ++k) {
      vf[static_cast<std::size_t>(f(i, k))].push_back(i);
      vertex_alive[static_cast<std::size_t>(f(i, k))] = 1;
    }
  // Boundary vertices: ends of edges with one face (validate_mesh guaranteed ≤ 2 faces per edge).
  std::vector<char> boundary(static_cast<std::size_t>(nv), 0);
  for (int i = 0; i < nf; ++i)
    for (int k = 0; k < 3; ++k) {
      const int a = f(i, k), b = f(i, (k + 1) % 3);
      int count = 0;
      for (int g : vf[static_cast<std::size_t>(a)])
        for (int j = 0; j < 3; ++j)
          if (f(g, j) == b) ++count;
      if (count == 1) boundary[static_cast<std::size_t>(a)] = boundary[static_cast<std::size_t>(b)] = 1;
    }
  // Plane quadrics, area-weighted.
  std::vector<Eigen::Matrix4d> q(static_cast<std::size_t>(nv), Eigen::Matrix4d::Zero());
  for (int i = 0; i < nf; ++i) {
    const Eigen::Vector3d a = v.row(f(i, 0)), b = v.row(f(i, 1)), c = v.row(f(i, 2));
    const Eigen::Vector3d n2 = (b - a).cross(c - a);
    const double area2 = n2.norm();
    if (!(area2 > 0)) continue;
    const Eigen::Vector3d n = n2 / area2;
    const Eigen::Vector4d p(n.x(), n.y(), n.z(), -n.dot(a));
    for (int k = 0; k < 3; ++k) q[static_cast<std::size_t>(f(i, k))] += 0.5 * area2 * p * p.transpose();
  }
  std::vector<unsigned> stamp(static_cast<std::size_t>(nv), 0);
  auto quadric_cost = [&](const Eigen::Matrix4d& m, const Eigen::Vector3d& x) {
    const Eigen::Vector4d h(x.x(), x.y(), x.z(), 1.0);
    return h.dot(m * h);
  };
  auto best_position = [&](int a, int b, double& cost) {
    const Eigen::Matrix4d m = q[static_cast<std::size_t>(a)] + q[static_cast<std::size_t>(b)];
    Eigen::Vector3d best = 0.5 * (Eigen::Vector3d(v.row(a)) + Eigen::Vector3d(v.row(b)));
    cost = keep_positions ? std::numeric_limits<double>::infinity() : quadric_cost(m, best);
    for (const Eigen::Vector3d& x : {Eigen::Vector3d(v.row(a)), Eigen::Vector3d(v.row(b))}) {
      const double c = quadric_cost(m, x);
      if (c < cost) {
        cost = c;
        best = x;
      }
    }
    return best;
  };
  std::priority_queue<Candidate> heap;
  auto push = [&](int a, int b) {
    if (boundary[static_cast<std::size_t>(a)] || boundary[static_cast<std::size_t>(b)]) return;
    if (a > b) std::swap(a, b);
    double cost = 0;
    best_position(a, b, cost);
    // Ties broken towards short edges (flat regions have zero quadric cost everywhere).
    cost += 1e-9 * (v.row(a) - v.row(b)).squaredNorm();
    heap.push({cost, a, b, stamp[static_cast<std::size_t>(a)], stamp[static_cast<std::size_t>(b)]});
  };
  for (int i = 0; i < nf; ++i)
    for (int k = 0; k < 3; ++k) {
      const int a = f(i, k), b = f(i, (k + 1) % 3);
      if (a < b) push(a, b);
    }
  auto neighbours = [&](int a) {
    std::vector<int> out;
    for (int g : vf[static_cast<std::size_t>(a)])
      if (face_alive[static_cast<std::size_t>(g)])
        for (int j = 0; j < 3; ++j)
          if (f(g, j) != a) out.push_back(f(g, j));
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  };
  int alive = static_cast<int>(std::count(vertex_alive.begin(), vertex_alive.end(), 1));
  const int target = std::max(4, static_cast<int>(std::ceil(keep_fraction * alive)));
  while (alive > target && !heap.empty()) {
    const Candidate c = heap.top();
    heap.pop();
    const int a = c.u, b = c.v;
    if (!vertex_alive[static_cast<std::size_t>(a)] || !vertex_alive[static_cast<std::size_t>(b)] ||
        stamp[static_cast<std::size_t>(a)] != c.su || stamp[static_cast<std::size_t>(b)] != c.sv)
      continue;
    // Faces on the edge, and the link condition.
    std::vector<int> shared, others;
    for (int g : vf[static_cast<std::size_t>(a)])
      if (face_alive[static_cast<std::size_t>(g)]) {
        const bool has_b = f(g, 0) == b || f(g, 1) == b || f(g, 2) == b;
        (has_b ? shared : others).push_back(g);
      }
    for (int g : vf[static_cast<std::size_t>(b)])
      if (face_alive[static_cast<std::size_t>(g)] && f(g, 0) != a && f(g, 1) != a && f(g, 2) != a) others.push_back(g);
    if (shared.size() != 2) continue;
    const auto na = neighbours(a), nb = neighbours(b);
    std::vector<int> common;
    std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
    if (common.size() != 2) continue;
    double cost = 0;
    const Eigen::Vector3d p = best_position(a, b, cost);
    // No triangle may flip or degenerate.
    bool ok = true;
    for (int g : others) {
      Eigen::Vector3d x[3], y[3];
      for (int j = 0; j < 3; ++j) {
        x[j] = v.row(f(g, j));
        y[j] = f(g, j) == a || f(g, j) == b ? p : x[j];
      }
      const Eigen::Vector3d before = (x[1] - x[0]).cross(x[2] - x[0]), after = (y[1] - y[0]).cross(y[2] - y[0]);
      if (!(after.norm() > 1e-12 * std::max(1e-30, before.norm())) || before.normalized().dot(after.normalized()) < 0.2) {
        ok = false;
        break;
      }
    }
    if (!ok) continue;
    // Collapse b into a.
    v.row(a) = p.transpose();
    for (int g : shared) face_alive[static_cast<std::size_t>(g)] = 0;
    for (int g : vf[static_cast<std::size_t>(b)])
      if (face_alive[static_cast<std::size_t>(g)]) {
        for (int j = 0; j < 3; ++j)
          if (f(g, j) == b) f(g, j) = a;
        vf[static_cast<std::size_t>(a)].push_back(g);
      }
    vertex_alive[static_cast<std::size_t>(b)] = 0;
    q[static_cast<std::size_t>(a)] += q[static_cast<std::size_t>(b)];
    ++stamp[static_cast<std::size_t>(a)];
    ++stamp[static_cast<std::size_t>(b)];
    --alive;
    for (int w : neighbours(a)) {
      ++stamp[static_cast<std::size_t>(w)];  // the costs of w's other edges are unchanged, but re-queue them lazily
      for (int x : neighbours(w)) push(w, x);
    }
  }
  // Compact.
  std::vector<int> id(static_cast<std::size_t>(nv), -1);
  int next = 0;
  facemesh::Mesh out;
  std::vector<int> kept;
  for (int i = 0; i < nf; ++i)
    if (face_alive[static_cast<std::size_t>(i)]) kept.push_back(i);
  for (int i : kept)
    for (int j = 0; j < 3; ++j)
      if (id[static_cast<std::size_t>(f(i, j))] < 0) id[static_cast<std::size_t>(f(i, j))] = 0;
  for (auto& x : id)
    if (x == 0) x = next++;
  out.vertices.resize(next, 3);
  for (int i = 0; i < nv; ++i)
    if (id[static_cast<std::size_t>(i)] >= 0) out.vertices.row(id[static_cast<std::size_t>(i)]) = v.row(i);
  out.faces.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t k = 0; k < kept.size(); ++k)
    for (int j = 0; j < 3; ++j) out.faces(static_cast<Eigen::Index>(k), j) = id[static_cast<std::size_t>(f(kept[k], j))];
  return out;
}

}  // namespace emoface::retarget
