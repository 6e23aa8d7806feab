// Transfer of a rig onto the user's own mesh (transfer.hpp).
#include "emoface/retarget/transfer.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <queue>
#include <set>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/core/text.hpp"
#include "emoface/facemesh/bspline.hpp"
#include "emoface/muscles/solver.hpp"
#include "kdtree.hpp"
#include "surface_index.hpp"

namespace emoface::retarget {
namespace fm = facemesh;
namespace {

constexpr double kPi = 3.14159265358979323846;
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

bool has(const std::string& s, std::string_view w) { return s.find(w) != std::string::npos; }

// Part kind from a group/material/object name; Head when nothing matches.
fm::PartKind kind_from_name(const std::string& raw) {
  const std::string s = core::ascii_lower(raw);
  if (has(s, "lash")) return fm::PartKind::Lashes;
  if (has(s, "brow")) return fm::PartKind::Brows;
  if (has(s, "tongue")) return fm::PartKind::Tongue;
  if (has(s, "teeth") || has(s, "tooth") || has(s, "gum") || has(s, "dent")) {
    if (has(s, "lower") || has(s, "bottom") || has(s, "_lo") || has(s, "low"))
      return fm::PartKind::LowerTeeth;
    if (has(s, "upper") || has(s, "top") || has(s, "_up")) return fm::PartKind::UpperTeeth;
    return fm::PartKind::Other;  // side decided by position (caller)
  }
  if (has(s, "eye") || has(s, "cornea") || has(s, "iris") || has(s, "sclera") || has(s, "pupil"))
    return fm::PartKind::Eyeball;
  return fm::PartKind::Head;
}
bool is_teeth_name(const std::string& raw) {
  const std::string s = core::ascii_lower(raw);
  return has(s, "teeth") || has(s, "tooth") || has(s, "gum") || has(s, "dent");
}

struct Component {
  std::vector<int> vertices;  // ascending
  std::vector<int> faces;
  double area = 0.0;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = Eigen::Vector3d::Constant(-1e300);
};

std::vector<Component> components(const fm::Mesh& m) {
  const auto nv = static_cast<std::size_t>(m.vertices.rows());
  std::vector<int> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int x) {
    while (parent[static_cast<std::size_t>(x)] != x)
      x = parent[static_cast<std::size_t>(x)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
    return x;
  };
  for (Eigen::Index f = 0; f < m.faces.rows(); ++f)
    for (int k = 1; k < 3; ++k) {
      const int a = root(m.faces(f, 0)), b = root(m.faces(f, k));
      if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  std::map<int, std::size_t> id;
  std::vector<Component> out;
  std::vector<std::uint8_t> used(nv, 0);
  for (Eigen::Index f = 0; f < m.faces.rows(); ++f) {
    const int r = root(m.faces(f, 0));
    auto it = id.find(r);
    if (it == id.end()) it = id.emplace(r, out.size()).first, out.emplace_back();
    Component& c = out[it->second];
    c.faces.push_back(static_cast<int>(f));
    const Eigen::Vector3d a = m.vertices.row(m.faces(f, 0)), b = m.vertices.row(m.faces(f, 1)),
                          cc = m.vertices.row(m.faces(f, 2));
    c.area += 0.5 * (b - a).cross(cc - a).norm();
    for (int k = 0; k < 3; ++k) {
      const int v = m.faces(f, k);
      if (used[static_cast<std::size_t>(v)]) continue;
      used[static_cast<std::size_t>(v)] = 1;
      c.vertices.push_back(v);
      c.lo = c.lo.cwiseMin(Eigen::Vector3d(m.vertices.row(v)));
      c.hi = c.hi.cwiseMax(Eigen::Vector3d(m.vertices.row(v)));
    }
  }
  for (auto& c : out) std::sort(c.vertices.begin(), c.vertices.end());
  std::stable_sort(out.begin(), out.end(),
                   [](const Component& a, const Component& b) { return a.area > b.area; });
  return out;
}

// Least-squares sphere: |p|² = 2c·p + (r² − |c|²), linear in (c, d).
bool fit_sphere(const fm::Vertices& v, const std::vector<int>& ids, Eigen::Vector3d& centre,
                double& radius, double& rms) {
  if (ids.size() < 8) return false;
  Eigen::MatrixXd A(static_cast<Eigen::Index>(ids.size()), 4);
  Eigen::VectorXd b(static_cast<Eigen::Index>(ids.size()));
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const Eigen::Vector3d p = v.row(ids[k]);
    A.row(static_cast<Eigen::Index>(k)) << 2 * p.x(), 2 * p.y(), 2 * p.z(), 1.0;
    b(static_cast<Eigen::Index>(k)) = p.squaredNorm();
  }
  const Eigen::Vector4d x = A.colPivHouseholderQr().solve(b);
  centre = x.head<3>();
  const double r2 = x(3) + centre.squaredNorm();
  if (!(r2 > 0.0) || !std::isfinite(r2)) return false;
  radius = std::sqrt(r2);
  double s = 0.0;
  for (int i : ids) s += std::pow((Eigen::Vector3d(v.row(i)) - centre).norm() - radius, 2);
  rms = std::sqrt(s / static_cast<double>(ids.size())) / radius;
  return true;
}

// Multi-source Dijkstra over the edges of `faces`, restricted to vertices with allowed[v] (sources
// always allowed). Unreached: +inf.
std::vector<double> geodesic(const fm::Vertices& x, const std::vector<std::vector<int>>& adjacency,
                             const std::vector<int>& sources,
                             const std::vector<std::uint8_t>& allowed) {
  std::vector<double> d(adjacency.size(), std::numeric_limits<double>::infinity());
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> q;
  for (int s : sources) d[static_cast<std::size_t>(s)] = 0.0, q.push({0.0, s});
  while (!q.empty()) {
    const auto [dist, v] = q.top();
    q.pop();
    if (dist > d[static_cast<std::size_t>(v)]) continue;
    for (int w : adjacency[static_cast<std::size_t>(v)]) {
      if (!allowed[static_cast<std::size_t>(w)]) continue;
      const double nd = dist + (x.row(v) - x.row(w)).norm();
      if (nd < d[static_cast<std::size_t>(w)]) d[static_cast<std::size_t>(w)] = nd, q.push({nd, w});
    }
  }
  return d;
}

double wrap_u(double u) {
  u -= std::floor(u);
  return u >= 1.0 ? 0.0 : u;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto k = static_cast<std::size_t>(std::min<double>(
      static_cast<double>(v.size() - 1), std::ceil(p * static_cast<double>(v.size())) - 1));
  return v[k];
}

// The lid margin of one eye on a mesh (issue 13: lids from the target's own geometry). An open eye
// is a boundary loop of the mesh near the eye's opening; a closed socket (the lid surface folds
// into the head, as MakeHuman's) has no boundary: there the margin is the crease where the lid
// skin, facing away from the eyeball centre, meets the socket surface, facing towards it. The
// margin is split into upper and lower halves at its two corners (extreme x).
struct LidMargin {
  bool ok = false;
  std::string kind;               // "boundary" or "crease"
  std::vector<int> upper, lower;  // margin vertices, ascending x; the two corners in both
  std::vector<int> inner;         // socket vertices behind the margin (crease only)
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double width = 0.0;  // corner to corner, along x
};

LidMargin find_lid_margin(const fm::Vertices& X, const fm::Faces& F, const fm::Vertices& normals,
                          const std::vector<std::vector<int>>& adjacency,
                          const std::vector<int>& candidates,
                          const std::vector<std::uint8_t>& excluded, const Eigen::Vector3d& probe,
                          const Eigen::Vector3d& opening, double size,
                          bool split_by_normal = false) {
  LidMargin out;
  const auto nv = static_cast<std::size_t>(X.rows());
  std::vector<std::uint8_t> region(nv, 0);
  for (int v : candidates)
    if (!excluded[static_cast<std::size_t>(v)] && (X.row(v).transpose() - opening).norm() < size)
      region[static_cast<std::size_t>(v)] = 1;
  auto xy_distance = [&](const Eigen::Vector3d& p) { return (p - opening).head<2>().norm(); };
  // Components of a vertex set (edges within the set).
  auto split = [&](const std::vector<std::uint8_t>& in) {
    std::vector<std::vector<int>> comps;
    std::vector<std::uint8_t> seen(nv, 0);
    for (int s : candidates) {
      if (!in[static_cast<std::size_t>(s)] || seen[static_cast<std::size_t>(s)]) continue;
      comps.emplace_back();
      std::vector<int> stack{s};
      seen[static_cast<std::size_t>(s)] = 1;
      while (!stack.empty()) {
        const int v = stack.back();
        stack.pop_back();
        comps.back().push_back(v);
        for (int w : adjacency[static_cast<std::size_t>(v)])
          if (in[static_cast<std::size_t>(w)] && !seen[static_cast<std::size_t>(w)])
            seen[static_cast<std::size_t>(w)] = 1, stack.push_back(w);
      }
    }
    return comps;
  };
  auto centroid_of = [&](const std::vector<int>& ids) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int v : ids) c += X.row(v).transpose();
    return Eigen::Vector3d(c / static_cast<double>(std::max<std::size_t>(1, ids.size())));
  };
  // 1. a boundary loop around the opening
  std::map<std::pair<int, int>, int> uses;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      if (region[static_cast<std::size_t>(a)] && region[static_cast<std::size_t>(b)])
        ++uses[{std::min(a, b), std::max(a, b)}];
    }
  std::vector<std::uint8_t> on_boundary(nv, 0);
  for (const auto& [e, n] : uses)
    if (n == 1)
      on_boundary[static_cast<std::size_t>(e.first)] = 1,
      on_boundary[static_cast<std::size_t>(e.second)] = 1;
  std::vector<int> margin;
  double best = 0.5 * size;
  for (const auto& c : split(on_boundary)) {
    if (c.size() < 6) continue;
    const double d = xy_distance(centroid_of(c));
    if (d < best) best = d, margin = c, out.kind = "boundary";
  }
  // 2. else the crease between lid skin (facing away from the eyeball centre) and socket
  if (margin.empty()) {
    std::vector<std::uint8_t> facing(nv, 0), inner(nv, 0);
    for (int v : candidates)
      if (region[static_cast<std::size_t>(v)]) {
        const Eigen::Vector3d p = X.row(v).transpose();
        facing[static_cast<std::size_t>(v)] =
            normals.row(v).dot((p - probe).normalized()) < -0.3 ? 1 : 0;
      }
    for (const auto& c : split(facing)) {
      if (c.size() < 4 || xy_distance(centroid_of(c)) > 0.4 * size) continue;
      for (int v : c) inner[static_cast<std::size_t>(v)] = 1, out.inner.push_back(v);
    }
    for (int v : out.inner)
      for (int w : adjacency[static_cast<std::size_t>(v)])
        if (region[static_cast<std::size_t>(w)] && !inner[static_cast<std::size_t>(w)] &&
            !facing[static_cast<std::size_t>(w)])
          margin.push_back(w);
    std::sort(margin.begin(), margin.end());
    margin.erase(std::unique(margin.begin(), margin.end()), margin.end());
    out.kind = "crease";
  }
  if (margin.size() < 6) return out;
  std::sort(margin.begin(), margin.end(), [&](int a, int b) { return X(a, 0) < X(b, 0); });
  const Eigen::Vector3d c0 = X.row(margin.front()).transpose(),
                        c1 = X.row(margin.back()).transpose();
  out.width = c1.x() - c0.x();
  if (!(out.width > 0.2 * size)) return out;
  for (int v : margin) {
    const double t = (X(v, 0) - c0.x()) / out.width;
    const double chord = c0.y() + t * (c1.y() - c0.y());
    const bool corner = v == margin.front() || v == margin.back();
    bool above = X(v, 1) >= chord;
    // A closed mouth's crease is a slit whose two rows lie within a millimetre of the chord, and
    // near its corners a vertex of one lip may lie on the other side of it (MakeHuman: 5 of 32
    // "upper" vertices, lower lip by their normals, which the jaw and AU10 then pulled apart in
    // a spike). There the normal decides: the upper lip's underside faces down, the lower lip's
    // top faces up; only a normal within 30° of the horizontal leaves it to the chord.
    if (split_by_normal && std::abs(normals(v, 1)) > 0.5) above = normals(v, 1) < 0.0;
    if (corner || above) out.upper.push_back(v);
    if (corner || !above) out.lower.push_back(v);
  }
  if (out.upper.size() < 3 || out.lower.size() < 3) return out;
  out.centroid = centroid_of(margin);
  out.ok = true;
  return out;
}

// The point at x of a polyline given by vertex ids in ascending x (linear interpolation; clamped).
Eigen::Vector3d polyline_at(const fm::Vertices& X, const std::vector<int>& ids, double x) {
  if (x <= X(ids.front(), 0)) return X.row(ids.front()).transpose();
  for (std::size_t k = 1; k < ids.size(); ++k) {
    const double x0 = X(ids[k - 1], 0), x1 = X(ids[k], 0);
    if (x <= x1) {
      const double t = x1 > x0 ? (x - x0) / (x1 - x0) : 0.0;
      return ((1.0 - t) * X.row(ids[k - 1]) + t * X.row(ids[k])).transpose();
    }
  }
  return X.row(ids.back()).transpose();
}

// The lip grid fitted to the target's own lips: the registered generic's lips are a smooth
// surface of the generic's shape (MakeHuman's fuller lower lip lay up to 9 mm in front of it), and
// a bound vertex keeps its offset from S(u, v) constant in the rig frame, so a large offset does
// not turn or stretch with the lip and tears it off its neighbours. The control points C = C0 + D
// take the displacement D that minimises  Σ_i |S_D(u_i, v_i) − x_i|²  over the full-weight bindings
// + λ_s Σ_(grid neighbours a, b) |D_a − D_b|² + λ_0 Σ |D|²  (a smooth displacement of the whole
// grid; the three coordinates decouple: one 144×144 LDLT). The offsets are then recomputed (the
// neutral face is kept exactly).
void refit_lip_grid(fm::LipGrid& lips, const fm::Vertices& X) {
  constexpr int na = fm::LipGrid::kAround, nc = na * fm::LipGrid::kAcross;
  constexpr double smooth = 0.3, ridge = 0.02;
  if (lips.control_points.size() != static_cast<std::size_t>(nc)) return;
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(nc, nc);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nc, 3);
  int data = 0;
  for (const auto& b : lips.bound) {
    if (b.weight < 0.999) continue;
    const auto terms = fm::lip_surface_terms(b.u, b.v);
    const Eigen::Vector3d o = X.row(b.vertex).transpose() - lip_surface_point(lips, b.u, b.v);
    for (const auto& t : terms) {
      for (const auto& q : terms) N(t.control, q.control) += t.weight * q.weight;
      rhs.row(t.control) += t.weight * o.transpose();
    }
    ++data;
  }
  if (data < nc / 4) return;  // too few lip vertices to say where the lips are
  for (int r = 0; r < fm::LipGrid::kAcross; ++r)
    for (int c = 0; c < na; ++c) {
      const int a = r * na + c;
      N(a, a) += ridge;
      for (const int b : {r * na + (c + 1) % na, (r + 1) * na + c}) {
        if (b >= nc) continue;
        N(a, a) += smooth, N(b, b) += smooth, N(a, b) -= smooth, N(b, a) -= smooth;
      }
    }
  const Eigen::MatrixXd D = N.ldlt().solve(rhs);
  for (int k = 0; k < nc; ++k)
    lips.control_points[static_cast<std::size_t>(k)] += D.row(k).transpose();
  for (auto& b : lips.bound)
    b.offset = X.row(b.vertex).transpose() - lip_surface_point(lips, b.u, b.v);
}

}  // namespace

void UserLandmarks::validate(std::size_t vertex_count) const {
  if (points.empty()) return;
  if (points.size() != static_cast<std::size_t>(kCount))
    throw InvalidInput("landmarks: expected 68 iBUG points, got " + std::to_string(points.size()));
  int given = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto& p = points[k];
    if (p.kind == UserLandmarkKind::Vertex &&
        (p.vertex < 0 || static_cast<std::size_t>(p.vertex) >= vertex_count))
      throw InvalidInput("landmarks: point " + std::to_string(k) + ": vertex id " +
                         std::to_string(p.vertex) + " out of range (the mesh has " +
                         std::to_string(vertex_count) + " vertices)");
    if (p.kind == UserLandmarkKind::Point && !p.point.allFinite())
      throw InvalidInput("landmarks: point " + std::to_string(k) + " is not finite");
    if (p.kind != UserLandmarkKind::Missing) ++given;
  }
  if (given < 4)
    throw InvalidInput("landmarks: at least 4 of the 68 points must be given, got " +
                       std::to_string(given));
}

void TransferOptions::validate() const {
  fit.validate();
  registration.validate();
  if (!(several_heads_area > 0.0 && several_heads_area <= 1.0))
    throw InvalidInput("TransferOptions::several_heads_area must be in (0, 1]");
  if (!(eyeball_tolerance > 0.0 && eyeball_tolerance <= 1.0))
    throw InvalidInput("TransferOptions::eyeball_tolerance must be in (0, 1]");
}

const std::vector<std::pair<std::string, int>>& retarget_landmark_ibug() {
  // iBUG-68 (0-based): 8 chin, 19/24 brow centres, 27 nose root, 30 nose tip, 36/39 right eye
  // outer/inner corner, 42/45 left eye inner/outer, 48/54 outer mouth corners, 51/57 outer lip
  // centres, 3/13 jaw (the points the built-in face's chapter-3 landmarks are made from,
  // facemesh default_face.cpp step 10)
  static const std::vector<std::pair<std::string, int>> table = {{"chin", 8},
                                                                 {"nose_root", 27},
                                                                 {"nose_tip", 30},
                                                                 {"eye_outer_r", 36},
                                                                 {"eye_inner_r", 39},
                                                                 {"eye_inner_l", 42},
                                                                 {"eye_outer_l", 45},
                                                                 {"brow_centre_r", 19},
                                                                 {"brow_centre_l", 24},
                                                                 {"mouth_corner_r", 48},
                                                                 {"mouth_corner_l", 54},
                                                                 {"upper_lip_centre", 51},
                                                                 {"lower_lip_centre", 57},
                                                                 {"jaw_r", 3},
                                                                 {"jaw_l", 13}};
  return table;
}

Eigen::Vector3d lip_surface_point(const fm::LipGrid& lips, double u, double v) {
  if (lips.control_points.size() !=
      static_cast<std::size_t>(fm::LipGrid::kAround * fm::LipGrid::kAcross))
    throw InvalidInput("lip_surface_point: no lip grid");
  u -= std::floor(u);
  if (u >= 1.0) u = 0.0;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (const auto& t : fm::lip_surface_terms(u, std::clamp(v, 0.0, 1.0)))
    p += t.weight * lips.control_points[static_cast<std::size_t>(t.control)];
  return p;
}

TransferResult transfer_rig(const fm::Face& source, const fm::Mesh& target,
                            const std::vector<fm::MeshGroup>& groups,
                            const TransferOptions& options, const UserLandmarks& user,
                            const std::function<void(const GaProgress&)>& progress) {
  options.validate();
  const auto nv = target.vertices.rows();
  if (target.faces.rows() == 0) throw InvalidInput("transfer: the target mesh has no faces");
  if (!target.vertices.allFinite()) {
    for (Eigen::Index v = 0; v < nv; ++v)
      if (!target.vertices.row(v).allFinite())
        throw InvalidInput("transfer: target vertex " + std::to_string(v) +
                           " has a NaN or infinite coordinate");
  }
  try {
    fm::validate_mesh(target, "target");
  } catch (const FormatError& e) {
    throw InvalidInput(std::string("transfer: ") + e.what());
  }
  user.validate(static_cast<std::size_t>(nv));
  for (const auto& g : groups)
    for (int f : g.faces)
      if (f < 0 || f >= target.faces.rows())
        throw InvalidInput("transfer: group '" + g.group + "' names face " + std::to_string(f) +
                           " out of range");
  const auto& srig = source.rig;
  if (srig.ibug68.size() != 68)
    throw InvalidInput("transfer: the source rig has no iBUG-68 landmarks");
  if (srig.lips.control_points.empty())
    throw InvalidInput("transfer: the source rig has no lip grid");
  if (!srig.lips.samples_in_mesh)
    throw InvalidInput(
        "transfer: the source rig's lips must be sampled in its mesh (a built-in style rig)");

  TransferResult out;
  TransferReport& rep = out.report;
  rep.user_landmarks = !user.empty();
  const auto t_start = Clock::now();

  // ---- 1. components, head, several heads ----
  const auto comps = components(target);
  rep.components = comps.size();
  const Component& head = comps.front();
  for (std::size_t c = 1; c < comps.size(); ++c) {
    const Eigen::Vector3d centre = 0.5 * (comps[c].lo + comps[c].hi);
    const bool inside =
        (centre.array() >= head.lo.array()).all() && (centre.array() <= head.hi.array()).all();
    if (comps[c].area >= options.several_heads_area * head.area && !inside)
      throw InvalidInput("transfer: the mesh holds several heads: components of " +
                         std::to_string(head.vertices.size()) + " and " +
                         std::to_string(comps[c].vertices.size()) +
                         " vertices are both head-sized and apart; give one head per file");
  }
  // Part names per component from the groups (majority of named faces).
  std::vector<int> comp_of_face(static_cast<std::size_t>(target.faces.rows()), -1),
      comp_of_vertex(static_cast<std::size_t>(nv), -1);
  for (std::size_t c = 0; c < comps.size(); ++c) {
    for (int f : comps[c].faces) comp_of_face[static_cast<std::size_t>(f)] = static_cast<int>(c);
    for (int v : comps[c].vertices)
      comp_of_vertex[static_cast<std::size_t>(v)] = static_cast<int>(c);
  }
  std::vector<std::string> comp_name(comps.size());
  {
    std::vector<std::map<std::string, std::size_t>> votes(comps.size());
    for (const auto& g : groups) {
      std::string name = !g.group.empty() ? g.group : !g.material.empty() ? g.material : g.object;
      // a material or object may be more telling than a generic group name
      for (const std::string& n : {g.group, g.material, g.object})
        if (kind_from_name(n) != fm::PartKind::Head || is_teeth_name(n)) name = n;
      if (name.empty()) continue;
      for (int f : g.faces)
        ++votes[static_cast<std::size_t>(comp_of_face[static_cast<std::size_t>(f)])][name];
    }
    for (std::size_t c = 0; c < comps.size(); ++c) {
      std::size_t best = 0;
      for (const auto& [n, k] : votes[c])
        if (k > best) best = k, comp_name[c] = n;
    }
  }

  // ---- 2. the thesis fit on the head component ----
  fm::Mesh head_mesh;
  std::vector<int> local(static_cast<std::size_t>(nv), -1);
  head_mesh.vertices.resize(static_cast<Eigen::Index>(head.vertices.size()), 3);
  for (std::size_t k = 0; k < head.vertices.size(); ++k) {
    local[static_cast<std::size_t>(head.vertices[k])] = static_cast<int>(k);
    head_mesh.vertices.row(static_cast<Eigen::Index>(k)) = target.vertices.row(head.vertices[k]);
  }
  head_mesh.faces.resize(static_cast<Eigen::Index>(head.faces.size()), 3);
  for (std::size_t k = 0; k < head.faces.size(); ++k)
    for (int j = 0; j < 3; ++j)
      head_mesh.faces(static_cast<Eigen::Index>(k), j) =
          local[static_cast<std::size_t>(target.faces(head.faces[k], j))];
  auto t0 = Clock::now();
  RetargetOptions fit_options = options.fit;
  fit_options.refine_alignment = fit_options.refine_alignment || options.refine_frame;
  out.fit = retarget_face(source, head_mesh, fit_options, progress);
  RetargetResult& fit = out.fit;
  const Alignment& al = fit.alignment;
  const fm::Vertices T = al.apply(target.vertices);  // the whole target in the rig frame
  // User landmarks in the rig frame.
  std::vector<std::pair<int, Eigen::Vector3d>> given;  // (iBUG index, rig-frame point)
  for (std::size_t k = 0; k < user.points.size(); ++k) {
    const auto& p = user.points[k];
    if (p.kind == UserLandmarkKind::Vertex)
      given.push_back({static_cast<int>(k), T.row(p.vertex).transpose()});
    if (p.kind == UserLandmarkKind::Point)
      given.push_back({static_cast<int>(k), al.apply(p.point)});
  }
  // The target's own mouth slit (issue 13): the chapter-3 error function does not pin the mouth's
  // height (§3.7; on MakeHuman the fitted mouth sits a lip's height too low, so the upper lip was
  // never bound to the lips). A closed mouth over a bag folds into the head like a closed eye
  // socket: the slit is the crease between the lips (facing away from the mouth cavity) and the
  // bag (facing it), found as the lids' margin is (find_lid_margin); an open mouth is a boundary
  // loop. When the fitted inner-lip iBUG points (60–67) lie off the slit by more than 1 % of the
  // head height, they are placed on it (corners on its corners, the others on its upper/lower
  // rows at proportional x) and join the RBF and the registration as landmarks, unless the user
  // gave them.
  bool closed_slit = false;  // a closed mouth's crease was found: the bag faces the cavity
  Eigen::Vector3d mouth_probe = Eigen::Vector3d::Zero();
  fm::Vertices slit_normals;
  std::vector<int> slit_upper, slit_lower;
  double slit_width = 0.0;
  {
    const auto& fg = fit.face.mesh.vertices;
    const auto& ib = srig.ibug68;
    double hh = 0.0;
    {
      int top_v = -1, chin_v = -1;
      for (const auto& l : srig.retarget_landmarks) {
        if (l.name == "top_of_head") top_v = l.vertex;
        if (l.name == "chin") chin_v = l.vertex;
      }
      if (top_v >= 0 && chin_v >= 0) hh = fg(top_v, 1) - fg(chin_v, 1);
    }
    Eigen::Vector3d probe = Eigen::Vector3d::Zero(), opening = Eigen::Vector3d::Zero();
    int cavity = 0;
    for (Eigen::Index v = 0; v < fg.rows(); ++v)
      if (srig.materials[static_cast<std::size_t>(v)] == fm::Material::MouthInterior)
        probe += fg.row(v).transpose(), ++cavity;
    for (int k = 60; k < 68; ++k)
      opening += fg.row(ib[static_cast<std::size_t>(k)]).transpose() / 8.0;
    const Eigen::Vector3d f60 = fg.row(ib[60]).transpose(), f64 = fg.row(ib[64]).transpose();
    const double inner_width = (f64 - f60).norm();
    bool user_mouth = false;
    for (const auto& [k, p] : given) user_mouth = user_mouth || (k >= 60 && k < 68);
    if (cavity > 0 && hh > 0.0 && inner_width > 0.0 && !user_mouth) {
      probe /= cavity;
      std::vector<std::vector<int>> adj0(static_cast<std::size_t>(nv));
      for (int f : head.faces)
        for (int k = 0; k < 3; ++k) {
          const int a = target.faces(f, k), b = target.faces(f, (k + 1) % 3);
          adj0[static_cast<std::size_t>(a)].push_back(b);
          adj0[static_cast<std::size_t>(b)].push_back(a);
        }
      const fm::Vertices n0 = fm::vertex_normals(T, target.faces);
      LidMargin slit = find_lid_margin(T, target.faces, n0, adj0, head.vertices,
                                       std::vector<std::uint8_t>(static_cast<std::size_t>(nv), 0),
                                       probe, opening, 0.8 * inner_width, true);
      // The crease search also collects creases near the mouth that are no slit (MakeHuman: the
      // nostrils 23 mm above it and the bag's floor 18 mm below, 32 of the 85 vertices); the slit
      // rows are a thin band about the line through the slit's corners (its extremes in x) and
      // lie in front of them: each row keeps the vertices within 15 % of the slit's width of
      // that line's height and no more than 10 % of it behind the corners (polyline_at assumes
      // one row; a stray nostril vertex put the contact line 20 mm up).
      auto clean_row = [&](std::vector<int>& row) {
        if (row.size() < 3 || !(slit.width > 0.0)) return;
        const Eigen::Vector3d a = T.row(row.front()).transpose(), b = T.row(row.back()).transpose();
        std::vector<int> kept;
        for (int q : row) {
          const double t =
              b.x() > a.x() ? std::clamp((T(q, 0) - a.x()) / (b.x() - a.x()), 0.0, 1.0) : 0.5;
          const Eigen::Vector3d l = (1.0 - t) * a + t * b;
          if (std::abs(T(q, 1) - l.y()) < 0.15 * slit.width &&
              T(q, 2) > std::min(a.z(), b.z()) - 0.1 * slit.width)
            kept.push_back(q);
        }
        if (kept.size() >= 2) row = kept;
      };
      if (slit.ok) clean_row(slit.upper), clean_row(slit.lower);
      if (slit.ok && slit.width > 0.6 * inner_width && slit.width < 1.6 * inner_width) {
        closed_slit = slit.kind == "crease";
        mouth_probe = probe;
        slit_normals = n0;
        slit_upper = slit.upper, slit_lower = slit.lower, slit_width = slit.width;
        const double lo = std::min(f60.x(), f64.x()), hi = std::max(f60.x(), f64.x());
        const double c0 = T(slit.upper.front(), 0), c1 = T(slit.upper.back(), 0);
        std::vector<std::pair<int, Eigen::Vector3d>> mouth;
        for (int k = 60; k < 68; ++k) {
          const Eigen::Vector3d f = fg.row(ib[static_cast<std::size_t>(k)]).transpose();
          const double x = c0 + (f.x() - lo) / (hi - lo) * (c1 - c0);
          const bool upper_row = k >= 61 && k <= 63, lower_row = k >= 65;
          Eigen::Vector3d q;
          if (k == 60 || k == 64)
            q = std::abs(f.x() - lo) < std::abs(f.x() - hi)
                    ? Eigen::Vector3d(T.row(slit.upper.front()).transpose())
                    : Eigen::Vector3d(T.row(slit.upper.back()).transpose());
          else
            q = polyline_at(T, upper_row ? slit.upper : slit.lower, x);
          (void)lower_row;
          mouth.push_back({k, q});
        }
        double off = 0.0;
        for (const auto& [k, q] : mouth)
          off += (q - fg.row(ib[static_cast<std::size_t>(k)]).transpose()).norm() / 8.0;
        if (off > 0.01 * hh) {
          // the outer mouth corners (48, 54) go with them, at the source's own offset from its
          // inner corners (scaled by the widths): left to the fit they stayed where the fit put
          // the mouth (MakeHuman: 13 mm outside the slit's corners, the lip grid and the
          // zygomatic insertion as wide)
          const auto& sv = source.mesh.vertices;
          const double s_inner = (sv.row(ib[64]) - sv.row(ib[60])).norm();
          for (const auto& [outer, inner] : {std::pair{48, 60}, std::pair{54, 64}}) {
            if (!(s_inner > 0.0)) break;
            const auto it = std::find_if(mouth.begin(), mouth.end(),
                                         [&](const auto& m) { return m.first == inner; });
            if (it == mouth.end()) continue;
            Eigen::Vector3d d = (sv.row(ib[static_cast<std::size_t>(outer)]) -
                                 sv.row(ib[static_cast<std::size_t>(inner)]))
                                    .transpose() *
                                (slit.width / s_inner);
            mouth.push_back({outer, it->second + d});
          }
          for (const auto& m : mouth) given.push_back(m);
          rep.mouth_slit_points = mouth.size();
        }
      }
    }
  }
  if (!given.empty()) {
    // RBF on the fit's landmarks plus the given points. A chapter-3 landmark with an iBUG
    // counterpart the user gave (retarget_landmark_ibug) is replaced by the user's point; other
    // fit landmarks within 4 mm of a given point are dropped (the given point wins).
    std::vector<Eigen::Vector3d> src, dst;
    std::vector<std::uint8_t> consumed(68, 0);
    std::map<int, Eigen::Vector3d> user_point;
    for (std::size_t k = 0; k < user.points.size(); ++k) {
      const auto& p = user.points[k];
      if (p.kind == UserLandmarkKind::Vertex) user_point[static_cast<int>(k)] = T.row(p.vertex);
      if (p.kind == UserLandmarkKind::Point) user_point[static_cast<int>(k)] = al.apply(p.point);
    }
    std::vector<std::uint8_t> replaced(static_cast<std::size_t>(fit.source_landmarks.rows()), 0);
    for (Eigen::Index i = 0; i < fit.source_landmarks.rows(); ++i) {
      if (static_cast<std::size_t>(i) >= fit.landmark_names.size()) break;
      for (const auto& [name, k] : retarget_landmark_ibug())
        if (name == fit.landmark_names[static_cast<std::size_t>(i)] && user_point.count(k)) {
          src.push_back(fit.source_landmarks.row(i).transpose()), dst.push_back(user_point[k]);
          fit.target_landmarks.row(i) = user_point[k].transpose();
          consumed[static_cast<std::size_t>(k)] = 1;
          replaced[static_cast<std::size_t>(i)] = 1;
          rep.replaced_landmarks.push_back(name);
        }
    }
    for (const auto& [k, p] : given)
      if (!consumed[static_cast<std::size_t>(k)])
        src.push_back(
            source.mesh.vertices.row(srig.ibug68[static_cast<std::size_t>(k)]).transpose()),
            dst.push_back(p);
    const std::size_t fixed_count = src.size();
    for (Eigen::Index i = 0; i < fit.source_landmarks.rows(); ++i) {
      if (replaced[static_cast<std::size_t>(i)]) continue;
      const Eigen::Vector3d s = fit.source_landmarks.row(i).transpose();
      bool near = false;
      for (std::size_t q = 0; q < fixed_count; ++q) near = near || (src[q] - s).norm() < 0.004;
      if (!near) src.push_back(s), dst.push_back(fit.target_landmarks.row(i).transpose());
    }
    Eigen::MatrixX3d S(static_cast<Eigen::Index>(src.size()), 3),
        D(static_cast<Eigen::Index>(src.size()), 3);
    for (std::size_t k = 0; k < src.size(); ++k)
      S.row(static_cast<Eigen::Index>(k)) = src[k], D.row(static_cast<Eigen::Index>(k)) = dst[k];
    fit.face = transfer_face(source, fit_rbf(S, D, options.fit.rbf), fit.length_scale);
  }
  rep.fit_seconds = since(t0);

  // ---- 3. dense registration of the fitted generic face onto the head ----
  t0 = Clock::now();
  const fm::Face& gen = fit.face;  // generic face after the RBF (rig frame)
  const auto ng = gen.mesh.vertices.rows();
  const auto& glips = srig.lips;
  const int lip_first = glips.first_vertex, lip_na = glips.samples_around,
            lip_nac = glips.samples_across;
  auto lip_sample = [&](int v) { return v >= lip_first && v < lip_first + lip_na * lip_nac; };
  std::vector<std::uint8_t> eyeball(static_cast<std::size_t>(ng), 0);
  for (const auto& e : srig.eyes)
    for (int v : e.eyeball_vertices) eyeball[static_cast<std::size_t>(v)] = 1;
  std::vector<std::uint8_t> data_mask(static_cast<std::size_t>(ng), 1),
      socket(static_cast<std::size_t>(ng), 0);
  for (Eigen::Index v = 0; v < ng; ++v) {
    const auto m = srig.materials[static_cast<std::size_t>(v)];
    const Eigen::Vector3d p = source.mesh.vertices.row(v);
    bool in = !eyeball[static_cast<std::size_t>(v)] && m != fm::Material::MouthInterior &&
              m != fm::Material::Teeth && m != fm::Material::Tongue;
    if (lip_sample(static_cast<int>(v)) &&
        (static_cast<int>(v) - lip_first) / lip_na >= lip_nac - 2)
      in = false;
    for (const auto& e : srig.eyes)  // socket caps behind the eyeballs
      if ((p - e.centre).norm() < 2.0 * e.radius && p.z() < e.centre.z())
        in = false, socket[static_cast<std::size_t>(v)] = 1;
    data_mask[static_cast<std::size_t>(v)] = in;
  }
  // Registration mesh: the generic without its eyeballs, teeth and tongue (they are not part of
  // the target's head surface; a head vertex that took the attributes of the generic's teeth would
  // be coloured and moved as teeth).
  fm::Mesh gsurf = gen.mesh;
  {
    std::vector<Eigen::Vector3i> keep;
    for (Eigen::Index f = 0; f < gen.mesh.faces.rows(); ++f)
      if (!eyeball[static_cast<std::size_t>(gen.mesh.faces(f, 0))] &&
          srig.materials[static_cast<std::size_t>(gen.mesh.faces(f, 0))] != fm::Material::Teeth &&
          srig.materials[static_cast<std::size_t>(gen.mesh.faces(f, 0))] != fm::Material::Tongue)
        keep.push_back(gen.mesh.faces.row(f).transpose());
    gsurf.faces.resize(static_cast<Eigen::Index>(keep.size()), 3);
    for (std::size_t k = 0; k < keep.size(); ++k)
      gsurf.faces.row(static_cast<Eigen::Index>(k)) = keep[k].transpose();
  }
  std::vector<RegistrationLandmark> reg_landmarks;
  for (const auto& [k, p] : given)
    reg_landmarks.push_back({srig.ibug68[static_cast<std::size_t>(k)], p});
  fm::Mesh head_rig{al.apply(head_mesh.vertices), head_mesh.faces};
  const RegistrationResult reg =
      register_nonrigid(gsurf, data_mask, head_rig, reg_landmarks, options.registration);
  rep.registration = reg.report;
  out.registered = reg.vertices;
  const fm::Vertices& G = reg.vertices;
  // Residual field: registered − fitted, per generic vertex (eyeballs: none of their own).
  std::vector<int> field_ids;
  for (Eigen::Index v = 0; v < ng; ++v)
    if (!eyeball[static_cast<std::size_t>(v)]) field_ids.push_back(static_cast<int>(v));
  fm::Vertices field_points(static_cast<Eigen::Index>(field_ids.size()), 3);
  for (std::size_t k = 0; k < field_ids.size(); ++k)
    field_points.row(static_cast<Eigen::Index>(k)) = gen.mesh.vertices.row(field_ids[k]);
  const detail::SurfaceIndex field_index(fm::Mesh{gen.mesh.vertices, gsurf.faces});
  auto residual_at = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d {
    // Inverse-square-distance average of the residuals of the 3 vertices of the closest fitted-face
    // triangle and its barycentric interpolation blended by the distance (points inside the head,
    // such as muscle heads, take the residual of the surface above them).
    const auto hit = field_index.closest(p);
    if (hit.face < 0) return Eigen::Vector3d::Zero();
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const int v = gsurf.faces(hit.face, k);
      r += hit.bary(k) * (G.row(v) - gen.mesh.vertices.row(v)).transpose();
    }
    return r;
  };
  rep.registration_seconds = since(t0);
  t0 = Clock::now();

  // ---- 4. attributes of every head vertex from its closest point on the registered generic ----
  fm::Face& face = out.face;
  face.mesh.vertices = T;
  face.mesh.faces = target.faces;
  fm::Rig& rig = face.rig;
  rig = fm::Rig{};
  rig.vertex_count = static_cast<std::size_t>(nv);
  rig.regions.assign(static_cast<std::size_t>(nv), fm::Region::Rest);
  rig.materials.assign(static_cast<std::size_t>(nv), fm::Material::Skin);
  rig.frame.scale = al.scale;
  rig.frame.rotation = al.rotation;
  rig.frame.translation = al.translation;
  rep.scale = al.scale;
  // Transferred rig geometry: the fit's RBF-mapped pieces plus the residual field.
  rig.muscles = gen.rig.muscles;
  for (auto& m : rig.muscles) {
    m.head += residual_at(m.head);
    if (m.kind == fm::MuscleKind::Vector) m.tail += residual_at(m.tail);
  }
  rig.lips = gen.rig.lips;
  for (auto& c : rig.lips.control_points) c += residual_at(c);
  rig.lips.centre += residual_at(rig.lips.centre);
  rig.lips.samples_in_mesh = false;
  rig.lips.first_vertex = 0;
  rig.lips.bound.clear();
  rig.jaw.pivot = gen.rig.jaw.pivot + residual_at(gen.rig.jaw.pivot);
  rig.jaw.max_angle = gen.rig.jaw.max_angle;
  rig.head_pivot = gen.rig.head_pivot + residual_at(gen.rig.head_pivot);
  for (int e = 0; e < 2; ++e) {
    const auto& se = gen.rig.eyes[static_cast<std::size_t>(e)];
    auto& te = rig.eyes[static_cast<std::size_t>(e)];
    te = se;
    te.eyeball_vertices.clear(), te.upper_lid.clear(), te.upper_lid_weights.clear(),
        te.lower_lid.clear(), te.lower_lid_weights.clear();
    te.tighten_angle.reset();  // the target's closing angle is measured below; AU7 is a share of it
    te.centre = se.centre + residual_at(se.centre);
  }

  // Per generic vertex attributes.
  std::vector<double> gjaw(static_cast<std::size_t>(ng), 0.0);
  for (std::size_t k = 0; k < srig.jaw.vertices.size(); ++k)
    gjaw[static_cast<std::size_t>(srig.jaw.vertices[k])] = srig.jaw.weights[k];
  std::array<std::vector<double>, 4> glid;  // eye 0 upper, eye 0 lower, eye 1 upper, eye 1 lower
  for (int e = 0; e < 2; ++e) {
    const auto& se = srig.eyes[static_cast<std::size_t>(e)];
    glid[static_cast<std::size_t>(2 * e)].assign(static_cast<std::size_t>(ng), 0.0);
    glid[static_cast<std::size_t>(2 * e + 1)].assign(static_cast<std::size_t>(ng), 0.0);
    for (std::size_t k = 0; k < se.upper_lid.size(); ++k)
      glid[static_cast<std::size_t>(2 * e)][static_cast<std::size_t>(se.upper_lid[k])] =
          se.upper_lid_weights[k];
    for (std::size_t k = 0; k < se.lower_lid.size(); ++k)
      glid[static_cast<std::size_t>(2 * e + 1)][static_cast<std::size_t>(se.lower_lid[k])] =
          se.lower_lid_weights[k];
  }
  // Lip parameters of the generic's lip samples.
  auto lip_uv = [&](int v) {
    const int s = v - lip_first;
    return Eigen::Vector2d(static_cast<double>(s % lip_na) / lip_na,
                           static_cast<double>(s / lip_na) / (lip_nac - 1));
  };
  auto face_uv = [&](int f,
                     const Eigen::Vector3d& b) {  // (u, v) at barycentrics b of a lip triangle
    const Eigen::Vector2d a = lip_uv(gsurf.faces(f, 0));
    Eigen::Vector2d r = Eigen::Vector2d::Zero();
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector2d q = lip_uv(gsurf.faces(f, k));
      q.x() -= std::round(q.x() - a.x());  // unwrap around the mouth
      r += b(k) * q;
    }
    r.x() -= std::floor(r.x());
    return r;
  };
  const auto nf = gsurf.faces.rows();
  std::vector<std::uint8_t> lip_face(static_cast<std::size_t>(nf), 0),
      upper_face(static_cast<std::size_t>(nf), 0), lower_face(static_cast<std::size_t>(nf), 0);
  for (Eigen::Index f = 0; f < nf; ++f) {
    bool all = true;
    for (int k = 0; k < 3; ++k) all = all && lip_sample(gsurf.faces(f, k));
    if (!all) continue;
    lip_face[static_cast<std::size_t>(f)] = 1;
    // the per-lip indices (a vertex re-bound to its own lip) hold the outer rows only: the inner
    // rows carry no data term in the registration and may fold out in front of the lip
    bool outer_rows = true;
    for (int k = 0; k < 3; ++k)
      outer_rows = outer_rows && (gsurf.faces(f, k) - lip_first) / lip_na <= lip_nac - 2;
    if (!outer_rows) continue;
    const double u = face_uv(static_cast<int>(f), Eigen::Vector3d::Constant(1.0 / 3.0)).x();
    (std::sin(2 * kPi * u) >= 0.0 ? upper_face : lower_face)[static_cast<std::size_t>(f)] = 1;
  }
  // The generic's mouth cavity (triangles touching a MouthInterior vertex): a target vertex near it
  // is part of a mouth bag unless it lies on it (a remeshed copy of the generic itself).
  std::vector<std::uint8_t> cavity_face(static_cast<std::size_t>(nf), 0);
  for (Eigen::Index f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      if (srig.materials[static_cast<std::size_t>(gsurf.faces(f, k))] ==
          fm::Material::MouthInterior)
        cavity_face[static_cast<std::size_t>(f)] = 1;
  const fm::Mesh Gmesh{G, gsurf.faces};
  const detail::SurfaceIndex gindex(Gmesh), upper_index(Gmesh, upper_face),
      lower_index(Gmesh, lower_face), lip_index(Gmesh, lip_face);
  const fm::Vertices gnormals = fm::face_normals(G, gsurf.faces);
  const fm::Vertices tnormals = fm::vertex_normals(T, target.faces);
  std::vector<detail::SurfaceHit> hit(static_cast<std::size_t>(nv));
  std::vector<std::uint8_t> on_lip(static_cast<std::size_t>(nv), 0),
      outer(static_cast<std::size_t>(nv), 0);
  double head_height_rig = 0.0;
  {
    int top_v = -1, chin_v = -1;
    for (const auto& l : srig.retarget_landmarks) {
      if (l.name == "top_of_head") top_v = l.vertex;
      if (l.name == "chin") chin_v = l.vertex;
    }
    if (top_v >= 0 && chin_v >= 0) head_height_rig = G(top_v, 1) - G(chin_v, 1);
    if (!(head_height_rig > 0.0)) head_height_rig = G.col(1).maxCoeff() - G.col(1).minCoeff();
  }
  rep.head_height = head_height_rig / al.scale;
  const double outer_distance = 0.02 * head_height_rig;
  for (int v : head.vertices) {
    const Eigen::Vector3d p = T.row(v).transpose();
    auto& h = hit[static_cast<std::size_t>(v)];
    h = gindex.closest(p);
    if (h.face < 0) continue;
    if (!lip_face[static_cast<std::size_t>(h.face)] && !lip_index.empty()) {
      // ties on the edges shared by the lips and the skin or the mouth cavity go to the lips
      const auto lh = lip_index.closest(p);
      const double tie =
          (cavity_face[static_cast<std::size_t>(h.face)] ? 0.002 : 1e-4) * head_height_rig;
      if (lh.face >= 0 && lh.distance <= h.distance + tie) h = lh;
    }
    const Eigen::Vector3d n = tnormals.row(v).transpose();
    const bool agree = n.dot(gnormals.row(h.face).transpose()) > 0.3;
    // On the generic's surface (within 0.1 % of the head height: a remeshed copy, whose normals at
    // a cone's apex may disagree), or near it and facing the same way; a mouth bag faces into the
    // mouth.
    const bool on_surface = h.distance < 0.001 * head_height_rig;
    // A lip vertex lies near the registered lips (within 4 % of the head height, ≈ 9 mm: a fuller
    // lip than the generic's) and, behind a closed mouth's slit, faces away from the mouth cavity;
    // the bag's floor and roof (up to 22 mm from the lips on MakeHuman) used to be bound to the
    // lip surface with weight 1 and tore across the mouth under every muscle.
    const bool lip_facing = !closed_slit || n.dot((p - mouth_probe).normalized()) > 0.0 ||
                            h.distance < 0.0025 * head_height_rig;
    if (lip_face[static_cast<std::size_t>(h.face)] &&
        (agree || h.distance < 0.0025 * head_height_rig) && h.distance < 0.04 * head_height_rig &&
        lip_facing)
      on_lip[static_cast<std::size_t>(v)] = 1;
    else if (cavity_face[static_cast<std::size_t>(h.face)]
                 ? on_surface
                 : (on_surface || (agree && h.distance < outer_distance)))
      outer[static_cast<std::size_t>(v)] = 1;
  }
  // Adjacency of the target.
  std::vector<std::vector<int>> adjacency(static_cast<std::size_t>(nv));
  for (Eigen::Index f = 0; f < target.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = target.faces(f, k), b = target.faces(f, (k + 1) % 3);
      adjacency[static_cast<std::size_t>(a)].push_back(b);
      adjacency[static_cast<std::size_t>(b)].push_back(a);
    }
  for (auto& a : adjacency)
    std::sort(a.begin(), a.end()), a.erase(std::unique(a.begin(), a.end()), a.end());
  // Mouth bag: reachable from the lip vertices through vertices that are neither outer skin nor
  // lip.
  std::vector<std::uint8_t> bag(static_cast<std::size_t>(nv), 0);
  {
    std::vector<int> stack;
    for (int v : head.vertices)
      if (on_lip[static_cast<std::size_t>(v)]) stack.push_back(v);
    Eigen::Vector3d mouth =
        Eigen::Vector3d::Zero();  // mean lip control point (LipGrid::centre may lie deep inside)
    for (const auto& c : rig.lips.control_points)
      mouth += c / static_cast<double>(rig.lips.control_points.size());
    std::vector<std::uint8_t> seen(static_cast<std::size_t>(nv), 0);
    for (int v : stack) seen[static_cast<std::size_t>(v)] = 1;
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (int w : adjacency[static_cast<std::size_t>(v)]) {
        if (seen[static_cast<std::size_t>(w)]) continue;
        seen[static_cast<std::size_t>(w)] = 1;
        if (outer[static_cast<std::size_t>(w)] || on_lip[static_cast<std::size_t>(w)]) continue;
        // behind a closed mouth's crease the bag faces the cavity; the lips' outer surface (where
        // a coarse registration leaves it off the generic's lips) faces away from it
        if (closed_slit &&
            slit_normals.row(w).dot((T.row(w).transpose() - mouth_probe).normalized()) > 0.5)
          continue;
        if ((T.row(w).transpose() - mouth).norm() > 0.3 * head_height_rig) continue;
        bag[static_cast<std::size_t>(w)] = 1;
        stack.push_back(w);
      }
    }
  }
  // Upper/lower lip labels by geodesic distance from the clearly upper and clearly lower lip
  // halves, through the lips and the bag only (a closed mouth's two lips touch in space, not on the
  // mesh).
  std::vector<std::uint8_t> mouth_allowed(static_cast<std::size_t>(nv), 0);
  std::vector<int> upper_seeds, lower_seeds;
  for (int v : head.vertices) {
    if (!on_lip[static_cast<std::size_t>(v)] && !bag[static_cast<std::size_t>(v)]) continue;
    mouth_allowed[static_cast<std::size_t>(v)] = 1;
    if (!on_lip[static_cast<std::size_t>(v)]) continue;
    const Eigen::Vector2d uv =
        face_uv(hit[static_cast<std::size_t>(v)].face, hit[static_cast<std::size_t>(v)].bary);
    const double s = std::sin(2 * kPi * uv.x());
    if (uv.y() < 0.45 && s > 0.25) upper_seeds.push_back(v);
    if (uv.y() < 0.45 && s < -0.25) lower_seeds.push_back(v);
  }
  const auto du = geodesic(T, adjacency, upper_seeds, mouth_allowed);
  const auto dl = geodesic(T, adjacency, lower_seeds, mouth_allowed);
  // Jaw weights of the bag: geodesic distances through the bag alone from every vertex of each lip
  // (so no path runs round a mouth corner through the lips), by the side of its projection.
  std::vector<std::uint8_t> bag_only(static_cast<std::size_t>(nv), 0);
  std::vector<int> upper_lip, lower_lip;
  for (int v : head.vertices) {
    bag_only[static_cast<std::size_t>(v)] = bag[static_cast<std::size_t>(v)];
    if (!on_lip[static_cast<std::size_t>(v)]) continue;
    const double s = std::sin(
        2 * kPi *
        face_uv(hit[static_cast<std::size_t>(v)].face, hit[static_cast<std::size_t>(v)].bary).x());
    const bool labelled_upper =
        std::isfinite(du[static_cast<std::size_t>(v)]) ||
                std::isfinite(dl[static_cast<std::size_t>(v)])
            ? du[static_cast<std::size_t>(v)] <= dl[static_cast<std::size_t>(v)]
            : s >= 0.0;
    if (std::abs(s) < 0.25) continue;  // corners belong to both
    (labelled_upper ? upper_lip : lower_lip).push_back(v);
  }
  const auto bu = geodesic(T, adjacency, upper_lip, bag_only);
  const auto bl = geodesic(T, adjacency, lower_lip, bag_only);
  // ---- lips: bindings ----
  // Which lip each lip vertex belongs to, by the target's own slit: the geodesic distance from
  // the slit's upper row and from its lower row (corners left out) through the lip vertices alone.
  // The two rows are joined only at the corners and through the bag, so a vertex of the lower
  // lip's front, even one standing at the height of the contact, lies near the lower row and far
  // from the upper (round a corner). Heights against the slit were tried first and split the
  // row of vertices at the contact (spikes from the upper lip in an opened mouth).
  std::vector<double> slit_du, slit_dl;
  if (slit_upper.size() > 2 && slit_lower.size() > 2) {
    std::vector<std::uint8_t> lip_allowed(static_cast<std::size_t>(nv), 0);
    for (int v : head.vertices)
      lip_allowed[static_cast<std::size_t>(v)] = on_lip[static_cast<std::size_t>(v)];
    const std::vector<int> su(slit_upper.begin() + 1, slit_upper.end() - 1),
        sl(slit_lower.begin() + 1, slit_lower.end() - 1);
    for (int v : su) lip_allowed[static_cast<std::size_t>(v)] = 1;
    for (int v : sl) lip_allowed[static_cast<std::size_t>(v)] = 1;
    slit_du = geodesic(T, adjacency, su, lip_allowed);
    slit_dl = geodesic(T, adjacency, sl, lip_allowed);
  }
  std::vector<double> jaw_w(static_cast<std::size_t>(nv), 0.0);
  for (int v : head.vertices) {
    const auto& h = hit[static_cast<std::size_t>(v)];
    if (h.face < 0) continue;
    Eigen::Index arg = 0;
    h.bary.maxCoeff(&arg);
    const int gv = gsurf.faces(h.face, static_cast<int>(arg));
    if (on_lip[static_cast<std::size_t>(v)]) {
      detail::SurfaceHit lh = h;
      const double s = std::sin(2 * kPi * face_uv(h.face, h.bary).x());
      const auto uq = du[static_cast<std::size_t>(v)], lq = dl[static_cast<std::size_t>(v)];
      // A closed mouth's two lips touch in space, not on the mesh: a vertex of one lip may project
      // onto the other. Where the mesh says clearly which lip the vertex belongs to (geodesic
      // distances through the lips and the bag) and that lip's surface is about as near, it is used
      // instead.
      // Between the slit's corners a vertex clearly above or below the slit's middle line (by
      // 3 % of its width) belongs to that lip; at the contact the nearer slit row decides (above;
      // one at most 0.8 of the other), else the height: the lips' rows then cannot cross the
      // target's contact line (on
      // MakeHuman the generic's contact row sat 3 mm below the head's: vertices of the upper lip
      // were bound to the lower lip and the jaw pulled them through the upper lip's rows).
      int slit_side = 0;
      if (!slit_du.empty()) {
        const double x0 = T(slit_upper.front(), 0), x1 = T(slit_upper.back(), 0);
        const double ys = 0.5 * (polyline_at(T, slit_upper, T(v, 0)).y() +
                                 polyline_at(T, slit_lower, T(v, 0)).y());
        const double a = slit_du[static_cast<std::size_t>(v)],
                     c = slit_dl[static_cast<std::size_t>(v)];
        if (T(v, 0) > x0 && T(v, 0) < x1 && std::abs(T(v, 1) - ys) > 0.03 * slit_width)
          slit_side = T(v, 1) > ys ? 1 : -1;  // clearly above or below the slit's middle line
        else if (std::isfinite(a) && (!std::isfinite(c) || a < 0.8 * c))
          slit_side = 1;
        else if (std::isfinite(c) && (!std::isfinite(a) || c < 0.8 * a))
          slit_side = -1;
        else if (T(v, 0) > x0 && T(v, 0) < x1)
          slit_side = T(v, 1) >= ys ? 1 : -1;
      }
      if (slit_side != 0) {
        detail::SurfaceHit alt;
        if (slit_side > 0 && !upper_index.empty()) alt = upper_index.closest(T.row(v).transpose());
        if (slit_side < 0 && !lower_index.empty()) alt = lower_index.closest(T.row(v).transpose());
        if (alt.face >= 0) lh = alt;
      } else if ((std::isfinite(uq) || std::isfinite(lq)) && std::abs(s) > 0.3 &&
                 std::min(uq, lq) < 0.8 * std::max(uq, lq)) {
        const bool is_upper = uq <= lq;
        detail::SurfaceHit alt;
        if (is_upper && s < 0.0 && !upper_index.empty())
          alt = upper_index.closest(T.row(v).transpose());
        if (!is_upper && s > 0.0 && !lower_index.empty())
          alt = lower_index.closest(T.row(v).transpose());
        if (alt.face >= 0 && alt.distance < h.distance + 0.005 * head_height_rig) lh = alt;
      }
      const Eigen::Vector2d uv = face_uv(lh.face, lh.bary);
      fm::LipBinding b;
      b.vertex = v;
      b.u = wrap_u(uv.x()), b.v = uv.y();
      b.offset = T.row(v).transpose() - lip_surface_point(rig.lips, b.u, b.v);
      b.weight = 1.0;
      rig.lips.bound.push_back(b);
      // lip colour only on the target's own lips: inside the border row, and between the
      // corners of its slit (+4 % of its width); the generic's lips reach past a narrower mouth's
      // corners, and coloured the skin beside them in pink spikes
      bool coloured = uv.y() >= 1.0 / (lip_nac - 1) - 1e-9;
      if (!slit_upper.empty() && slit_width > 0.0)
        coloured = coloured && T(v, 0) > T(slit_upper.front(), 0) - 0.04 * slit_width &&
                   T(v, 0) < T(slit_upper.back(), 0) + 0.04 * slit_width;
      rig.materials[static_cast<std::size_t>(v)] =
          coloured ? fm::Material::Lip : fm::Material::Skin;
      rig.regions[static_cast<std::size_t>(v)] = fm::Region::Rest;
      continue;
    }
    if (bag[static_cast<std::size_t>(v)]) {
      const double a = bu[static_cast<std::size_t>(v)], b = bl[static_cast<std::size_t>(v)];
      // the share of the way from the upper lip to the lower, sharpened: the upper half of the bag
      // stays with the skull, the lower half follows the jaw, with a smooth fold at the back
      const double share = std::isfinite(a) && std::isfinite(b) && a + b > 0 ? a / (a + b)
                           : std::isfinite(b)                                ? 1.0
                                                                             : 0.0;
      jaw_w[static_cast<std::size_t>(v)] = smoothstep(0.35, 0.65, share);
      if (closed_slit) {
        // a closed mouth's bag hangs behind a slit the geodesics reach along its whole length,
        // so most of the bag is about as far from either lip: the height against the slit
        // decides instead (below it follows the jaw, above it stays; the fold was within ±1/8 of
        // the slit's width: 6 mm on MakeHuman pulled the inside of the upper lip down with the
        // jaw in spikes), so ±3 % of the width at the slit widening by 10 % of the depth behind
        const Eigen::Vector3d su = polyline_at(T, slit_upper, T(v, 0)),
                              sl = polyline_at(T, slit_lower, T(v, 0));
        const double ys = 0.5 * (su.y() + sl.y());
        const double band =
            0.03 * slit_width + 0.1 * std::max(0.0, 0.5 * (su.z() + sl.z()) - T(v, 2));
        jaw_w[static_cast<std::size_t>(v)] = 1.0 - smoothstep(-band, band, T(v, 1) - ys);
      }
      rig.materials[static_cast<std::size_t>(v)] = fm::Material::MouthInterior;
      continue;
    }
    // Skin. On the strip between the mouth rim and the lip border row (triangles with both skin and
    // lip-sample corners) the vertex belongs to the sheet with the larger barycentric share: the
    // lip border (bound to it with weight 1 at the corners' interpolated (u, v)) or the skin (its
    // muscle-side attributes from the skin corners alone). The strip has no width of its own: the
    // built-in face puts its rim vertices and its border row on one curve (thesis §2.3.2: the lips
    // stitched to the face), so its zipper triangles are 0.2-0.5 mm high while the two sheets move
    // differently (a border vertex moves with the lips, a rim vertex with the skin: up to 5 mm
    // apart under triangularis). Barycentrics across it are noise: on a remeshed copy the
    // registered generic sits 40-96 µm off the target's vertices (the registration lies on the
    // copy's chords), which put the border and rim vertices of the copy at shares 0.64-0.87 and
    // 0.13-0.15 and moved them by up to 10.9 % of a parameter's largest displacement when the share
    // was the weight.
    double lip_share = 0.0, skin_share = 0.0, j = 0.0;
    Eigen::Index skin_arg = -1;
    Eigen::Vector2d uv = Eigen::Vector2d::Zero();
    double u_ref = -1.0;
    for (int k = 0; k < 3; ++k) {
      const int g = gsurf.faces(h.face, k);
      if (lip_sample(g)) {
        Eigen::Vector2d q = lip_uv(g);
        if (u_ref < 0.0) u_ref = q.x();
        q.x() -= std::round(q.x() - u_ref);
        uv += h.bary(k) * q;
        lip_share += h.bary(k);
      } else {
        j += h.bary(k) * gjaw[static_cast<std::size_t>(g)];
        if (skin_arg < 0 || h.bary(k) > h.bary(skin_arg)) skin_arg = k;
        skin_share += h.bary(k);
      }
    }
    if (lip_share > 0.0 && skin_share > 0.0) {  // the strip: the nearer sheet
      if (lip_share >= skin_share)
        uv /= lip_share, lip_share = 1.0;
      else
        lip_share = 0.0;
    }
    const int sv = skin_arg >= 0 ? gsurf.faces(h.face, static_cast<int>(skin_arg)) : gv;
    rig.regions[static_cast<std::size_t>(v)] = srig.regions[static_cast<std::size_t>(sv)];
    const auto m = srig.materials[static_cast<std::size_t>(sv)];
    rig.materials[static_cast<std::size_t>(v)] = m == fm::Material::Lip ? fm::Material::Skin : m;
    jaw_w[static_cast<std::size_t>(v)] = skin_share > 0.0 ? j / skin_share : 0.0;
    if (lip_share > 1e-3) {
      fm::LipBinding b;
      b.vertex = v;
      b.u = wrap_u(uv.x() / lip_share);
      b.v = uv.y() / lip_share;
      b.offset = T.row(v).transpose() - lip_surface_point(rig.lips, b.u, b.v);
      b.weight = std::min(1.0, lip_share);
      rig.lips.bound.push_back(b);
    }
  }
  std::sort(rig.lips.bound.begin(), rig.lips.bound.end(),
            [](const fm::LipBinding& a, const fm::LipBinding& b) { return a.vertex < b.vertex; });
  refit_lip_grid(rig.lips, T);
  // The border's jaw weights (LipGrid::border_jaw, thesis §2.4.4) as the source's solver has them:
  // the grid is carried over column for column, so is the weight with which each border column
  // turns with the jaw. Left to the solver, they came from whichever of the target's jaw vertices
  // lay nearest to each border control point: on a remeshed copy of the built-in face 6 of the 24
  // columns changed (by up to 0.27, where the nearest vertex had been removed) and the jaw moved
  // the copy's lips up to 16 % of its largest displacement away from the built-in face's; on
  // MakeHuman the upper lip's middle turned with the jaw (0.83-0.87) and the lower lip's middle did
  // not (0: no jaw vertex within 4 mm). The same rule on the registered generic was tried:
  // asymmetric on MakeHuman (columns 14 and 22 at 0.71 and 0.64 against 0.29 in the source), 44
  // mouth triangles turned over with the jaw open.
  rig.lips.border_jaw = srig.lips.border_jaw.empty()
                            ? muscles::lip_border_jaw_weights(source.mesh, srig)
                            : srig.lips.border_jaw;
  // The mouth bag next to the lips follows them: its vertices within 20 % of the mouth's width
  // (geodesic, through the bag) of a lip vertex are bound to that lip vertex's (u, v) with a weight
  // falling from 1 at the lip to 0 (smoothstep). Before, the bag stood still (or turned with the
  // jaw) while the lips in front of it moved, and poked through the upper lip under fear and
  // hung in spikes from it in an opened mouth.
  {
    const double mouth_w =
        slit_width > 0.0
            ? slit_width
            : (rig.lips.control_points[0] - rig.lips.control_points[fm::LipGrid::kAround / 2])
                  .norm();
    const double reach = 0.35 * mouth_w;
    // one search per lip; a bag vertex follows the lip on its side of the bag's fold (its jaw
    // weight: below the fold the lower lip, above it the upper)
    std::array<std::vector<double>, 2> d;
    std::array<std::vector<int>, 2> from;
    std::vector<int> seed_binding(static_cast<std::size_t>(nv), -1);
    for (int side = 0; side < 2; ++side) {
      d[side].assign(static_cast<std::size_t>(nv), std::numeric_limits<double>::infinity());
      from[side].assign(static_cast<std::size_t>(nv), -1);
      using Item = std::pair<double, int>;
      std::priority_queue<Item, std::vector<Item>, std::greater<>> q;
      for (std::size_t k = 0; k < rig.lips.bound.size(); ++k) {
        const auto& b = rig.lips.bound[k];
        if (b.weight < 0.999 || !on_lip[static_cast<std::size_t>(b.vertex)] ||
            (std::sin(2 * kPi * b.u) >= 0.0) != (side == 0))
          continue;
        seed_binding[static_cast<std::size_t>(b.vertex)] = static_cast<int>(k);
        d[side][static_cast<std::size_t>(b.vertex)] = 0.0;
        from[side][static_cast<std::size_t>(b.vertex)] = b.vertex;
        q.push({0.0, b.vertex});
      }
      while (!q.empty()) {
        const auto [dist, v] = q.top();
        q.pop();
        if (dist > d[side][static_cast<std::size_t>(v)] || dist > reach) continue;
        for (int w : adjacency[static_cast<std::size_t>(v)]) {
          if (!bag[static_cast<std::size_t>(w)]) continue;
          const double nd = dist + (T.row(v) - T.row(w)).norm();
          if (nd < d[side][static_cast<std::size_t>(w)]) {
            d[side][static_cast<std::size_t>(w)] = nd;
            from[side][static_cast<std::size_t>(w)] = from[side][static_cast<std::size_t>(v)];
            q.push({nd, w});
          }
        }
      }
    }
    std::vector<fm::LipBinding> added;
    for (int v : head.vertices) {
      if (!bag[static_cast<std::size_t>(v)]) continue;
      const int side = jaw_w[static_cast<std::size_t>(v)] > 0.5 ? 1 : 0;
      if (!(d[side][static_cast<std::size_t>(v)] < reach)) continue;
      const auto& src = rig.lips.bound[static_cast<std::size_t>(
          seed_binding[static_cast<std::size_t>(from[side][static_cast<std::size_t>(v)])])];
      fm::LipBinding b;
      b.vertex = v, b.u = src.u, b.v = src.v;
      b.weight = 1.0 - smoothstep(0.0, reach, d[side][static_cast<std::size_t>(v)]);
      b.offset = T.row(v).transpose() - lip_surface_point(rig.lips, b.u, b.v);
      if (b.weight > 1e-3) added.push_back(b);
    }
    rig.lips.bound.insert(rig.lips.bound.end(), added.begin(), added.end());
    std::sort(rig.lips.bound.begin(), rig.lips.bound.end(),
              [](const fm::LipBinding& a, const fm::LipBinding& b) { return a.vertex < b.vertex; });
    rep.lip_bag_bound = added.size();
  }
  for (const auto& b : rig.lips.bound) {
    ++rep.lip_bound;
    if (b.weight >= 1.0) ++rep.lip_full;
  }
  // Eye-hole surfaces: a head that closes its eye openings with a surface of its own (no separate
  // eyeballs, like the MakeHuman head's sockets) has vertices inside the generic's eye opening
  // (seen from the front). They stand in for the eyeball: no lid weights, turned by gaze. The
  // generic's eye opening per eye: its rim (skin vertices sharing a triangle with the socket cap)
  // as a polygon in x/y (registered positions), shrunk to 85 % about its centroid.
  std::array<std::vector<Eigen::Vector2d>, 2> hole_outline;
  std::array<Eigen::Vector2d, 2> hole_centre{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  {
    std::array<std::set<int>, 2> rim;
    for (Eigen::Index f = 0; f < gsurf.faces.rows(); ++f) {
      int sock = -1;
      for (int k = 0; k < 3; ++k)
        if (socket[static_cast<std::size_t>(gsurf.faces(f, k))]) sock = gsurf.faces(f, k);
      if (sock < 0) continue;
      const Eigen::Vector3d sp = source.mesh.vertices.row(sock);
      const int e = (sp - srig.eyes[0].centre).norm() <= (sp - srig.eyes[1].centre).norm() ? 0 : 1;
      for (int k = 0; k < 3; ++k)
        if (!socket[static_cast<std::size_t>(gsurf.faces(f, k))])
          rim[static_cast<std::size_t>(e)].insert(gsurf.faces(f, k));
    }
    for (int e = 0; e < 2; ++e) {
      auto& out_e = hole_outline[static_cast<std::size_t>(e)];
      if (rim[static_cast<std::size_t>(e)].size() < 3) continue;
      Eigen::Vector2d c = Eigen::Vector2d::Zero();
      for (int v : rim[static_cast<std::size_t>(e)]) c += G.row(v).head<2>().transpose();
      c /= static_cast<double>(rim[static_cast<std::size_t>(e)].size());
      for (int v : rim[static_cast<std::size_t>(e)])
        out_e.push_back(c + 0.85 * (G.row(v).head<2>().transpose() - c));
      std::sort(out_e.begin(), out_e.end(),
                [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
                  return std::atan2(a.y() - c.y(), a.x() - c.x()) <
                         std::atan2(b.y() - c.y(), b.x() - c.x());
                });
      hole_centre[static_cast<std::size_t>(e)] = c;
    }
  }
  auto inside = [](const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& q) {
    bool in = false;
    for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
      if ((poly[i].y() > q.y()) != (poly[j].y() > q.y()) &&
          q.x() <
              (poly[j].x() - poly[i].x()) * (q.y() - poly[i].y()) / (poly[j].y() - poly[i].y()) +
                  poly[i].x())
        in = !in;
    return in;
  };
  const std::vector<fm::Material> hole_materials = rig.materials;  // before the eye holes
  const std::vector<fm::Region> hole_regions = rig.regions;
  std::vector<std::uint8_t> eye_hole(static_cast<std::size_t>(nv), 0);
  for (int v : head.vertices) {
    if (on_lip[static_cast<std::size_t>(v)] || bag[static_cast<std::size_t>(v)]) continue;
    for (int e = 0; e < 2; ++e) {
      const auto& poly = hole_outline[static_cast<std::size_t>(e)];
      if (poly.size() < 3 || !inside(poly, T.row(v).head<2>().transpose())) continue;
      // not the generic's own socket cap (a remeshed copy of the generic), nor far in front of the
      // eye
      const auto& h = hit[static_cast<std::size_t>(v)];
      bool socket_face = false;
      for (int k = 0; k < 3 && h.face >= 0; ++k)
        socket_face = socket_face || socket[static_cast<std::size_t>(gsurf.faces(h.face, k))];
      if (socket_face && h.distance < 0.001 * head_height_rig) continue;
      const double dz = T(v, 2) - rig.eyes[static_cast<std::size_t>(e)].centre.z(),
                   r = gen.rig.eyes[static_cast<std::size_t>(e)].radius;
      if (dz > 2.0 * r || dz < -2.0 * r) continue;  // the lids' front, the back of the head
      eye_hole[static_cast<std::size_t>(v)] = 1;
      rig.eyes[static_cast<std::size_t>(e)].eyeball_vertices.push_back(v);
      rig.materials[static_cast<std::size_t>(v)] = fm::Material::EyeWhite;
      rig.regions[static_cast<std::size_t>(v)] = fm::Region::Rest;
      jaw_w[static_cast<std::size_t>(v)] = 0.0;
    }
  }
  for (int e = 0; e < 2; ++e)
    rep.eye_hole_vertices[static_cast<std::size_t>(e)] =
        rig.eyes[static_cast<std::size_t>(e)].eyeball_vertices.size();
  // Eyelids.
  for (int e = 0; e < 2; ++e) {
    auto& te = rig.eyes[static_cast<std::size_t>(e)];
    for (int v : head.vertices) {
      const auto& h = hit[static_cast<std::size_t>(v)];
      if (h.face < 0 || on_lip[static_cast<std::size_t>(v)] || bag[static_cast<std::size_t>(v)] ||
          eye_hole[static_cast<std::size_t>(v)])
        continue;
      // socket-cap corners (behind the eyeball, no lid weight of their own) are left out, so the
      // inside of a closed eye socket follows the lid margin instead of tearing from it
      double up = 0.0, lo = 0.0, sum = 0.0;
      for (int k = 0; k < 3; ++k) {
        const auto gv = static_cast<std::size_t>(gsurf.faces(h.face, k));
        if (socket[gv]) continue;
        up += h.bary(k) * glid[static_cast<std::size_t>(2 * e)][gv];
        lo += h.bary(k) * glid[static_cast<std::size_t>(2 * e + 1)][gv];
        sum += h.bary(k);
      }
      if (!(sum > 1e-9)) continue;
      up /= sum, lo /= sum;
      if (up > 1e-3) te.upper_lid.push_back(v), te.upper_lid_weights.push_back(std::min(1.0, up));
      if (lo > 1e-3) te.lower_lid.push_back(v), te.lower_lid_weights.push_back(std::min(1.0, lo));
    }
  }

  // Eyelids from the target's own lid margins (issue 13). The generic's lid weights, carried over
  // by closest points, fit a target whose eye region is shaped like the generic's; where it is not
  // (MakeHuman: a smaller opening over a deep closed socket), they put full weight on skin far from
  // the target's margin and none on parts of it, and the lids tear. So per eye: the target's margin
  // (boundary loop or crease, find_lid_margin); when the generic's weights already give the margin
  // full weight they are kept; otherwise the lids are rebuilt on the target: margin weight ∝ the
  // local opening angle (so a blink brings each upper margin point onto its lower partner at the
  // same x, and the corners, where the opening is zero, do not move), falling off smoothly with
  // the geodesic distance from the margin (flat to 8 %, zero at 40 % of the eye's width over the
  // skin, zero at 25 % inside the socket); the rotation centre is the eyeball's (a separate
  // eyeball) or placed behind the target's margin as the generic's centre lies behind its own.
  std::array<bool, 2> own_lids{false, false};
  {
    std::vector<std::vector<int>> sadj(static_cast<std::size_t>(ng));
    for (Eigen::Index f = 0; f < source.mesh.faces.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        const int a = source.mesh.faces(f, k), b = source.mesh.faces(f, (k + 1) % 3);
        sadj[static_cast<std::size_t>(a)].push_back(b);
        sadj[static_cast<std::size_t>(b)].push_back(a);
      }
    std::vector<int> scand;
    for (Eigen::Index v = 0; v < ng; ++v)
      if (!eyeball[static_cast<std::size_t>(v)]) scand.push_back(static_cast<int>(v));
    const fm::Vertices snormals = fm::vertex_normals(source.mesh.vertices, source.mesh.faces);
    std::vector<std::uint8_t> excluded(static_cast<std::size_t>(nv), 0);
    for (int v : head.vertices)
      excluded[static_cast<std::size_t>(v)] =
          on_lip[static_cast<std::size_t>(v)] || bag[static_cast<std::size_t>(v)];
    // separate eyeballs (as the parts step below finds them): their sphere centres
    std::array<double, 2> ball_size{0.0, 0.0};
    std::array<Eigen::Vector3d, 2> ball_centre{};
    for (std::size_t c = 1; c < comps.size(); ++c) {
      Eigen::Vector3d sc;
      double sr = 0.0, srms = 1.0;
      if (!fit_sphere(T, comps[c].vertices, sc, sr, srms)) continue;
      const int side = (sc - rig.eyes[0].centre).norm() <= (sc - rig.eyes[1].centre).norm() ? 0 : 1;
      const double r0 = gen.rig.eyes[static_cast<std::size_t>(side)].radius;
      if (srms < options.eyeball_tolerance && sr > 0.5 * r0 && sr < 2.0 * r0 &&
          (sc - rig.eyes[static_cast<std::size_t>(side)].centre).norm() < 2.0 * r0 &&
          static_cast<double>(comps[c].vertices.size()) > ball_size[static_cast<std::size_t>(side)])
        ball_size[static_cast<std::size_t>(side)] = static_cast<double>(comps[c].vertices.size()),
        ball_centre[static_cast<std::size_t>(side)] = sc;
    }
    // multi-source Dijkstra that also returns each vertex's nearest source
    auto geodesic_from = [&](const std::vector<int>& sources, const std::vector<std::uint8_t>& ok,
                             std::vector<double>& d, std::vector<int>& from) {
      d.assign(static_cast<std::size_t>(nv), std::numeric_limits<double>::infinity());
      from.assign(static_cast<std::size_t>(nv), -1);
      using Item = std::pair<double, int>;
      std::priority_queue<Item, std::vector<Item>, std::greater<>> q;
      for (int s : sources)
        d[static_cast<std::size_t>(s)] = 0.0, from[static_cast<std::size_t>(s)] = s,
        q.push({0.0, s});
      while (!q.empty()) {
        const auto [dist, v] = q.top();
        q.pop();
        if (dist > d[static_cast<std::size_t>(v)]) continue;
        for (int w : adjacency[static_cast<std::size_t>(v)]) {
          if (!ok[static_cast<std::size_t>(w)]) continue;
          const double nd = dist + (T.row(v) - T.row(w)).norm();
          if (nd < d[static_cast<std::size_t>(w)])
            d[static_cast<std::size_t>(w)] = nd,
            from[static_cast<std::size_t>(w)] = from[static_cast<std::size_t>(v)], q.push({nd, w});
        }
      }
    };
    for (int e = 0; e < 2; ++e) {
      const auto& se = srig.eyes[static_cast<std::size_t>(e)];
      auto& te = rig.eyes[static_cast<std::size_t>(e)];
      const LidMargin sm = find_lid_margin(
          source.mesh.vertices, source.mesh.faces, snormals, sadj, scand, eyeball, se.centre,
          se.centre + Eigen::Vector3d(0.0, 0.0, se.radius), 2.6 * se.radius);
      if (!sm.ok) continue;
      Eigen::Vector3d opening = Eigen::Vector3d::Zero();
      double lo_x = 1e300, hi_x = -1e300;
      for (const auto* side : {&sm.upper, &sm.lower})
        for (int v : *side)
          opening += G.row(v).transpose(), lo_x = std::min(lo_x, G(v, 0)),
                                           hi_x = std::max(hi_x, G(v, 0));
      opening /= static_cast<double>(sm.upper.size() + sm.lower.size());
      const bool ball = ball_size[static_cast<std::size_t>(e)] > 0.0;
      const Eigen::Vector3d probe = ball ? ball_centre[static_cast<std::size_t>(e)] : te.centre;
      const LidMargin tm = find_lid_margin(T, target.faces, tnormals, adjacency, head.vertices,
                                           excluded, probe, opening, 1.3 * (hi_x - lo_x));
      if (!tm.ok) {
        rep.warnings.push_back(std::string("no lid margin found on the target for the ") +
                               (e == 0 ? "right" : "left") +
                               " eye: the generic's lid weights are used");
        continue;
      }
      // keep the generic's weights when they give most of the target's margin full weight (a
      // copy of the generic: 80-90 %; MakeHuman: none)
      std::map<int, double> old_up, old_lo;
      for (std::size_t k = 0; k < te.upper_lid.size(); ++k)
        old_up[te.upper_lid[k]] = te.upper_lid_weights[k];
      for (std::size_t k = 0; k < te.lower_lid.size(); ++k)
        old_lo[te.lower_lid[k]] = te.lower_lid_weights[k];
      std::size_t full = 0, all = 0;
      for (std::size_t k = 1; k + 1 < tm.upper.size(); ++k, ++all)
        full += old_up.count(tm.upper[k]) && old_up[tm.upper[k]] >= 0.95;
      for (std::size_t k = 1; k + 1 < tm.lower.size(); ++k, ++all)
        full += old_lo.count(tm.lower[k]) && old_lo[tm.lower[k]] >= 0.95;
      rep.lid_margin_upper[static_cast<std::size_t>(e)] = tm.upper;
      rep.lid_margin_lower[static_cast<std::size_t>(e)] = tm.lower;
      rep.lid_method[static_cast<std::size_t>(e)] = "generic";
      if (all > 0 && static_cast<double>(full) >= 0.6 * static_cast<double>(all)) continue;
      rep.lid_method[static_cast<std::size_t>(e)] = tm.kind;
      own_lids[static_cast<std::size_t>(e)] = true;
      const Eigen::Vector3d c =
          ball ? ball_centre[static_cast<std::size_t>(e)]
               : Eigen::Vector3d(tm.centroid + (se.centre - sm.centroid) * (tm.width / sm.width));
      auto angle = [&](const Eigen::Vector3d& p) {
        return std::atan2(p.y() - c.y(), p.z() - c.z());
      };
      std::map<int, double> alpha_up, alpha_lo;
      double alpha_max = 0.0;
      for (int v : tm.upper) {
        const double a =
            std::max(0.0, angle(T.row(v).transpose()) - angle(polyline_at(T, tm.lower, T(v, 0))));
        alpha_up[v] = a, alpha_max = std::max(alpha_max, a);
      }
      for (int v : tm.lower) {
        const double a =
            std::max(0.0, angle(polyline_at(T, tm.upper, T(v, 0))) - angle(T.row(v).transpose()));
        alpha_lo[v] = a, alpha_max = std::max(alpha_max, a);
      }
      alpha_up[tm.upper.front()] = alpha_up[tm.upper.back()] = 0.0;
      alpha_lo[tm.lower.front()] = alpha_lo[tm.lower.back()] = 0.0;
      if (!(alpha_max > 1e-3)) {
        own_lids[static_cast<std::size_t>(e)] = false;
        rep.lid_method[static_cast<std::size_t>(e)] = "generic";
        continue;
      }
      const double W = tm.width;
      std::vector<std::uint8_t> inner(static_cast<std::size_t>(nv), 0), skin_ok = excluded;
      for (int v : tm.inner) inner[static_cast<std::size_t>(v)] = 1;
      for (auto& x : skin_ok) x = 0;
      for (int v : head.vertices)
        skin_ok[static_cast<std::size_t>(v)] =
            !excluded[static_cast<std::size_t>(v)] && !inner[static_cast<std::size_t>(v)] &&
            (T.row(v).transpose() - tm.centroid).norm() < 1.2 * W;
      std::vector<std::uint8_t> inner_ok = inner;
      for (const auto* side : {&tm.upper, &tm.lower})
        for (int v : *side) inner_ok[static_cast<std::size_t>(v)] = 1;
      std::vector<double> du_s, dl_s, du_i, dl_i;
      std::vector<int> fu_s, fl_s, fu_i, fl_i;
      geodesic_from(tm.upper, skin_ok, du_s, fu_s);
      geodesic_from(tm.lower, skin_ok, dl_s, fl_s);
      geodesic_from(tm.upper, inner_ok, du_i, fu_i);
      geodesic_from(tm.lower, inner_ok, dl_i, fl_i);
      te.upper_lid.clear(), te.upper_lid_weights.clear(), te.lower_lid.clear(),
          te.lower_lid_weights.clear();
      // the eye-hole vertices of the generic's opening are decided again: socket vertices only
      for (int v : te.eyeball_vertices) {
        eye_hole[static_cast<std::size_t>(v)] = 0;
        rig.materials[static_cast<std::size_t>(v)] = hole_materials[static_cast<std::size_t>(v)];
        rig.regions[static_cast<std::size_t>(v)] = hole_regions[static_cast<std::size_t>(v)];
      }
      te.eyeball_vertices.clear();
      // Weights per side: the margin weight of the nearest margin vertex of that side, falling off
      // with the geodesic distance; near the corners, where both margins are about as near, the
      // two sides share (so no weight jumps from one side to the other); then smoothed over the
      // mesh (4 Jacobi rounds; the margin keeps its own weights, which close the eye exactly).
      std::vector<double> wu(static_cast<std::size_t>(nv), 0.0),
          wl(static_cast<std::size_t>(nv), 0.0);
      std::vector<std::uint8_t> lid_area(static_cast<std::size_t>(nv), 0),
          fixed(static_cast<std::size_t>(nv), 0);
      for (const auto* side : {&tm.upper, &tm.lower})
        for (int v : *side) fixed[static_cast<std::size_t>(v)] = 1;
      for (int v : head.vertices) {
        const auto i = static_cast<std::size_t>(v);
        const bool in = inner[i];
        const double a = in ? du_i[i] : du_s[i], b = in ? dl_i[i] : dl_s[i];
        if (!std::isfinite(a) && !std::isfinite(b)) continue;
        lid_area[i] = 1;
        auto fall = [&](double d) {
          return in ? 1.0 - smoothstep(0.0, 0.25 * W, d) : 1.0 - smoothstep(0.08 * W, 0.4 * W, d);
        };
        const double share = std::isfinite(a) && std::isfinite(b) && a + b > 0.0
                                 ? smoothstep(0.3, 0.7, b / (a + b))
                                 : (std::isfinite(a) ? 1.0 : 0.0);
        if (std::isfinite(a))
          wu[i] = share * alpha_up[in ? fu_i[i] : fu_s[i]] / alpha_max * fall(a);
        if (std::isfinite(b))
          wl[i] = (1.0 - share) * alpha_lo[in ? fl_i[i] : fl_s[i]] / alpha_max * fall(b);
      }
      for (int v : tm.upper)
        wu[static_cast<std::size_t>(v)] = alpha_up[v] / alpha_max,
        wl[static_cast<std::size_t>(v)] = 0.0;
      for (int v : tm.lower)
        wl[static_cast<std::size_t>(v)] = alpha_lo[v] / alpha_max,
        wu[static_cast<std::size_t>(v)] = 0.0;
      for (int round = 0; round < 4; ++round) {
        const auto pu = wu, pl = wl;
        for (int v : head.vertices) {
          const auto i = static_cast<std::size_t>(v);
          if (!lid_area[i] || fixed[i]) continue;
          double su = pu[i], sl = pl[i];
          int count = 1;
          for (int w : adjacency[i])
            if (lid_area[static_cast<std::size_t>(w)] && !excluded[static_cast<std::size_t>(w)])
              su += pu[static_cast<std::size_t>(w)], sl += pl[static_cast<std::size_t>(w)], ++count;
          wu[i] = su / count, wl[i] = sl / count;
        }
      }
      for (int v : head.vertices) {
        const auto i = static_cast<std::size_t>(v);
        if (!lid_area[i]) continue;
        const double w = std::max(wu[i], wl[i]);
        if (inner[i] && w < 0.5) {
          rig.materials[i] = fm::Material::EyeWhite;
          rig.regions[i] = fm::Region::Rest;
          jaw_w[i] = 0.0;
          if (!ball && w < 1e-3) te.eyeball_vertices.push_back(v), eye_hole[i] = 1;
        }
        if (wu[i] > 1e-3)
          te.upper_lid.push_back(v), te.upper_lid_weights.push_back(std::min(1.0, wu[i]));
        if (wl[i] > 1e-3)
          te.lower_lid.push_back(v), te.lower_lid_weights.push_back(std::min(1.0, wl[i]));
      }
      te.close_angle = std::min(1.5, 0.97 * alpha_max / 1.2);
      te.centre = c;
      rep.eye_hole_vertices[static_cast<std::size_t>(e)] = te.eyeball_vertices.size();
    }
  }

  // ---- parts ----
  PartReport head_report;
  head_report.name = comp_name[0].empty() ? "head" : comp_name[0];
  head_report.kind = fm::PartKind::Head;
  head_report.vertices = head.vertices.size();
  head_report.found_by = "head";
  rep.parts.push_back(head_report);
  rig.parts.push_back({head_report.name, fm::PartKind::Head, -1, head.vertices});
  Eigen::Vector3d mouth_point = Eigen::Vector3d::Zero();  // mean lip control point
  for (const auto& c : rig.lips.control_points)
    mouth_point += c / static_cast<double>(rig.lips.control_points.size());
  const double mouth_y = mouth_point.y();
  const double mouth_width =
      (rig.lips.control_points[0] - rig.lips.control_points[fm::LipGrid::kAround / 2]).norm();
  std::array<bool, 2> eye_fitted{false, false};
  std::array<double, 2> eye_part_size{0.0, 0.0};
  std::vector<int> lid_candidates;
  for (int e = 0; e < 2; ++e) {
    for (int v : rig.eyes[static_cast<std::size_t>(e)].upper_lid) lid_candidates.push_back(v);
    for (int v : rig.eyes[static_cast<std::size_t>(e)].lower_lid) lid_candidates.push_back(v);
  }
  for (std::size_t c = 1; c < comps.size(); ++c) {
    const Component& comp = comps[c];
    PartReport pr;
    pr.name = comp_name[c].empty() ? "component_" + std::to_string(c) : comp_name[c];
    pr.vertices = comp.vertices.size();
    fm::PartKind kind = comp_name[c].empty() ? fm::PartKind::Head : kind_from_name(comp_name[c]);
    const bool named = kind != fm::PartKind::Head || is_teeth_name(comp_name[c]);
    pr.found_by = named ? "name" : "position";
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int v : comp.vertices) centroid += T.row(v).transpose();
    centroid /= static_cast<double>(comp.vertices.size());
    // Eyeballs: a sphere fit (named or not).
    Eigen::Vector3d sc;
    double sr = 0.0, srms = 1.0;
    const bool sphere = fit_sphere(T, comp.vertices, sc, sr, srms);
    int side = (sc - rig.eyes[0].centre).norm() <= (sc - rig.eyes[1].centre).norm() ? 0 : 1;
    const double r0 = gen.rig.eyes[static_cast<std::size_t>(side)].radius;
    const bool eye_like = sphere && srms < options.eyeball_tolerance && sr > 0.5 * r0 &&
                          sr < 2.0 * r0 &&
                          (sc - rig.eyes[static_cast<std::size_t>(side)].centre).norm() < 2.0 * r0;
    if (kind == fm::PartKind::Eyeball || (kind == fm::PartKind::Head && eye_like)) {
      if (!eye_like)
        side = (centroid - rig.eyes[0].centre).norm() <= (centroid - rig.eyes[1].centre).norm() ? 0
                                                                                                : 1;
      kind = fm::PartKind::Eyeball;
      if (!named) pr.found_by = "sphere fit";
      auto& te = rig.eyes[static_cast<std::size_t>(side)];
      for (int v : comp.vertices) te.eyeball_vertices.push_back(v);
      if (eye_like && static_cast<double>(comp.vertices.size()) >
                          eye_part_size[static_cast<std::size_t>(side)]) {
        te.centre = sc;
        te.radius = sr;
        eye_fitted[static_cast<std::size_t>(side)] = true;
        eye_part_size[static_cast<std::size_t>(side)] = static_cast<double>(comp.vertices.size());
      }
      pr.side = side;
      if (sphere) pr.centre = al.inverse(sc), pr.radius = sr / al.scale, pr.rms = srms;
      for (int v : comp.vertices)
        rig.materials[static_cast<std::size_t>(v)] = fm::Material::EyeWhite;
    } else {
      if (kind == fm::PartKind::Other && is_teeth_name(comp_name[c]))
        kind = centroid.y() < mouth_y ? fm::PartKind::LowerTeeth : fm::PartKind::UpperTeeth;
      if (kind == fm::PartKind::Head) {  // unnamed: by position
        // inside the mouth: within a mouth width of the lips and behind their front
        const bool in_mouth =
            (centroid - mouth_point).norm() < mouth_width && centroid.z() < mouth_point.z();
        double lid_d = std::numeric_limits<double>::infinity();
        for (int v : comp.vertices)
          for (int l : lid_candidates) lid_d = std::min(lid_d, (T.row(v) - T.row(l)).norm());
        if (in_mouth)
          kind = centroid.y() < mouth_y ? fm::PartKind::LowerTeeth : fm::PartKind::UpperTeeth;
        else if (lid_d < 0.004 && comp.vertices.size() < head.vertices.size() / 4)
          kind = fm::PartKind::Lashes;
        else
          kind = fm::PartKind::Other, pr.found_by = "none (rigid)";
      }
      if (kind == fm::PartKind::LowerTeeth || kind == fm::PartKind::Tongue) {
        for (int v : comp.vertices) jaw_w[static_cast<std::size_t>(v)] = 1.0;
      }
      if (kind == fm::PartKind::LowerTeeth || kind == fm::PartKind::UpperTeeth)
        for (int v : comp.vertices)
          rig.materials[static_cast<std::size_t>(v)] = fm::Material::Teeth;
      if (kind == fm::PartKind::Tongue)
        for (int v : comp.vertices)
          rig.materials[static_cast<std::size_t>(v)] = fm::Material::Tongue;
      if (kind == fm::PartKind::Lashes) {
        // each lash vertex follows the nearest lid vertex with its weight
        for (int v : comp.vertices) {
          rig.materials[static_cast<std::size_t>(v)] = fm::Material::Lash;
          double best = std::numeric_limits<double>::infinity();
          int be = -1, which = 0;
          double w = 0.0;
          for (int e = 0; e < 2; ++e) {
            const auto& te = rig.eyes[static_cast<std::size_t>(e)];
            for (std::size_t k = 0; k < te.upper_lid.size(); ++k) {
              const double d = (T.row(v) - T.row(te.upper_lid[k])).squaredNorm();
              if (d < best) best = d, be = e, which = 0, w = te.upper_lid_weights[k];
            }
            for (std::size_t k = 0; k < te.lower_lid.size(); ++k) {
              const double d = (T.row(v) - T.row(te.lower_lid[k])).squaredNorm();
              if (d < best) best = d, be = e, which = 1, w = te.lower_lid_weights[k];
            }
          }
          if (be < 0) continue;
          auto& te = rig.eyes[static_cast<std::size_t>(be)];
          (which == 0 ? te.upper_lid : te.lower_lid).push_back(v);
          (which == 0 ? te.upper_lid_weights : te.lower_lid_weights).push_back(w);
          pr.side = be;
        }
      }
      if (kind == fm::PartKind::Brows) {
        // brows sit on the skin: they take the skin's attributes (regions, so the brow muscles move
        // them)
        for (int v : comp.vertices) {
          const auto h = gindex.closest(T.row(v).transpose());
          if (h.face < 0) continue;
          Eigen::Index arg = 0;
          h.bary.maxCoeff(&arg);
          rig.regions[static_cast<std::size_t>(v)] =
              srig.regions[static_cast<std::size_t>(gsurf.faces(h.face, static_cast<int>(arg)))];
          rig.materials[static_cast<std::size_t>(v)] = fm::Material::Brow;
        }
      }
    }
    pr.kind = kind;
    rep.parts.push_back(pr);
    rig.parts.push_back({pr.name, kind, pr.side, comp.vertices});
  }
  for (int e = 0; e < 2; ++e) {
    auto& te = rig.eyes[static_cast<std::size_t>(e)];
    std::sort(te.eyeball_vertices.begin(), te.eyeball_vertices.end());
    if (!eye_fitted[static_cast<std::size_t>(e)])
      te.radius = gen.rig.eyes[static_cast<std::size_t>(e)].radius;
    rep.lid_vertices[static_cast<std::size_t>(e)] = te.upper_lid.size() + te.lower_lid.size();
  }
  // Jaw list.
  for (Eigen::Index v = 0; v < nv; ++v)
    if (jaw_w[static_cast<std::size_t>(v)] > 1e-3)
      rig.jaw.vertices.push_back(static_cast<int>(v)),
          rig.jaw.weights.push_back(std::min(1.0, jaw_w[static_cast<std::size_t>(v)]));
  rep.jaw_vertices = rig.jaw.vertices.size();
  for (int v : head.vertices) rep.mouth_bag += bag[static_cast<std::size_t>(v)];

  // ---- landmarks ----  (the iBUG ids are chosen below; the lid closing angles use them at the
  // end)
  fm::Vertices head_T(static_cast<Eigen::Index>(head.vertices.size()), 3);
  for (std::size_t k = 0; k < head.vertices.size(); ++k)
    head_T.row(static_cast<Eigen::Index>(k)) = T.row(head.vertices[k]);
  const detail::PointIndex head_index(head_T);
  auto nearest_head = [&](const Eigen::Vector3d& p,
                          double& d) {  // nearest vertex of the head component
    double d2 = 0.0;
    const int k = head_index.nearest(p, d2);
    d = (T.row(head.vertices[static_cast<std::size_t>(k)]).transpose() - p).norm();
    return head.vertices[static_cast<std::size_t>(k)];
  };
  std::vector<int> user_vertex(68, -1);
  for (std::size_t k = 0; k < user.points.size(); ++k) {
    const auto& p = user.points[k];
    double d = 0.0;
    if (p.kind == UserLandmarkKind::Vertex) user_vertex[k] = p.vertex;
    if (p.kind == UserLandmarkKind::Point) user_vertex[k] = nearest_head(al.apply(p.point), d);
  }
  // The mouth's landmarks (48–67 are lip samples of the generic) from the lip grid fitted to the
  // target's lips, on the target's own lip of that side (the full-weight lip vertices above or
  // below its slit): the registered generic's lips lie off a fuller or differently set mouth
  // (MakeHuman: iBUG 57, the lower lip's centre, sat at the height of the corners, and 61 and 67
  // on one vertex of the closed slit).
  std::array<std::vector<int>, 2> lip_side;  // 0 upper, 1 lower
  for (const auto& b : rig.lips.bound)
    if (b.weight >= 0.999 && on_lip[static_cast<std::size_t>(b.vertex)])
      lip_side[std::sin(2 * kPi * b.u) >= 0.0 ? 0 : 1].push_back(b.vertex);
  auto mouth_landmark = [&](int gv, const Eigen::Vector3d& fallback, Eigen::Vector3d& p) {
    if (!lip_sample(gv) || lip_side[0].empty() || lip_side[1].empty()) {
      p = fallback;
      return -1;
    }
    const Eigen::Vector2d uv = lip_uv(gv);
    p = lip_surface_point(rig.lips, uv.x(), uv.y());
    const double sn = std::sin(2 * kPi * uv.x());
    int best = -1;
    double bd = std::numeric_limits<double>::infinity();
    for (int side = 0; side < 2; ++side) {
      if ((side == 0 && sn < -0.2) || (side == 1 && sn > 0.2)) continue;
      for (int v : lip_side[side]) {
        const double d = (T.row(v).transpose() - p).norm();
        if (d < bd) bd = d, best = v;
      }
    }
    return best;
  };
  for (int k = 0; k < 68; ++k) {
    const int gv = srig.ibug68[static_cast<std::size_t>(k)];
    Eigen::Vector3d p = G.row(gv).transpose();
    const int on_mouth = mouth_landmark(gv, p, p);
    LandmarkConfidence lc;
    lc.index = k;
    double d = 0.0;
    if (user_vertex[static_cast<std::size_t>(k)] >= 0) {
      lc.vertex = user_vertex[static_cast<std::size_t>(k)];
      lc.source = "user";
      d = (T.row(lc.vertex).transpose() - p).norm();
      lc.confidence = 1.0;
    } else {
      lc.vertex = nearest_head(p, d);
      if (on_mouth >= 0) lc.vertex = on_mouth, d = (T.row(on_mouth).transpose() - p).norm();
      lc.source = "fit";
      lc.confidence = std::exp(-std::pow(d / (0.01 * head_height_rig), 2));
    }
    lc.distance = d / al.scale;
    rig.ibug68.push_back(lc.vertex);
    rep.landmarks.push_back(lc);
  }
  for (const auto& l : srig.retarget_landmarks) {
    double d = 0.0;
    int vertex = nearest_head(G.row(l.vertex).transpose(), d);
    for (const auto& [name, k] : retarget_landmark_ibug())  // the user's point where given
      if (name == l.name && user_vertex[static_cast<std::size_t>(k)] >= 0)
        vertex = user_vertex[static_cast<std::size_t>(k)];
    rig.retarget_landmarks.push_back({l.name, vertex});
  }
  // Lid closing angle per eye: the source's angle scaled by the target's own opening, measured
  // about the eye's x axis (thesis §2.4.3 rotates the upper lid about the eye centre) between the
  // mean points of the upper and the lower lid margins (lid vertices of weight ≥ 0.9), so a taller
  // or shorter eye opening than the built-in one still closes.
  {
    auto margin = [](const fm::Vertices& x, const std::vector<int>& ids,
                     const std::vector<double>& w, Eigen::Vector3d& m) {
      m.setZero();
      int c = 0;
      for (std::size_t k = 0; k < ids.size(); ++k)
        if (w[k] >= 0.9) m += x.row(ids[k]).transpose(), ++c;
      if (c) m /= c;
      return c > 0;
    };
    auto opening = [&](const fm::Vertices& x, const fm::Eye& eye, double& angle) {
      Eigen::Vector3d up, lo;
      if (!margin(x, eye.upper_lid, eye.upper_lid_weights, up) ||
          !margin(x, eye.lower_lid, eye.lower_lid_weights, lo))
        return false;
      angle = std::atan2(up.y() - eye.centre.y(), up.z() - eye.centre.z()) -
              std::atan2(lo.y() - eye.centre.y(), lo.z() - eye.centre.z());
      return true;
    };
    for (int e = 0; e < 2; ++e) {
      double src = 0.0, dst = 0.0;
      auto& te = rig.eyes[static_cast<std::size_t>(e)];
      if (own_lids[static_cast<std::size_t>(e)]) continue;  // set from the target's margin
      if (opening(source.mesh.vertices, srig.eyes[static_cast<std::size_t>(e)], src) &&
          opening(T, te, dst) && src > 1e-3 && dst > 1e-3)
        te.close_angle =
            std::min(1.5, srig.eyes[static_cast<std::size_t>(e)].close_angle * dst / src);
    }
  }

  // ---- residuals per region ----
  {
    std::map<std::string, std::vector<double>> by;
    for (int v : head.vertices) {
      const auto& h = hit[static_cast<std::size_t>(v)];
      if (h.face < 0) continue;
      const std::string name = on_lip[static_cast<std::size_t>(v)] ? "lips"
                               : bag[static_cast<std::size_t>(v)]
                                   ? "mouth_bag"
                                   : fm::to_string(rig.regions[static_cast<std::size_t>(v)]);
      by[name].push_back(h.distance / al.scale);
    }
    for (int r = 0; r < fm::kRegionCount; ++r)
      by.try_emplace(fm::to_string(static_cast<fm::Region>(r)));
    for (const auto& [name, d] : by) {
      RegionResidual rr;
      rr.region = name;
      rr.vertices = d.size();
      if (!d.empty()) {
        rr.mean = std::accumulate(d.begin(), d.end(), 0.0) / static_cast<double>(d.size());
        rr.p95 = percentile(d, 0.95);
        rr.max = *std::max_element(d.begin(), d.end());
      }
      const double hh = rep.head_height > 0 ? rep.head_height : 1.0;
      rr.mean_percent = 100.0 * rr.mean / hh, rr.p95_percent = 100.0 * rr.p95 / hh,
      rr.max_percent = 100.0 * rr.max / hh;
      rep.residuals.push_back(rr);
    }
  }
  if (rep.mouth_bag > 0 && (upper_seeds.empty() || lower_seeds.empty()))
    rep.warnings.push_back(
        "a mouth bag was found but not both lips: the bag's jaw weights are one-sided");
  if (rig.lips.bound.empty())
    rep.warnings.push_back("no lip vertices found on the target: the lips will not move");
  rep.transfer_seconds = since(t0);
  (void)t_start;
  try {
    fm::validate_rig(rig, "transferred rig");
  } catch (const FormatError& e) {
    throw NumericalError(std::string("transfer produced an invalid rig: ") + e.what());
  }
  return out;
}

}  // namespace emoface::retarget
