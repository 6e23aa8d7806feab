// emoface's default face: the MakeHuman head rigged by transfer from the generic face, plus
// eyeballs, teeth, tongue, lashes, a lash line, short hair and a closed neck end (default_head.hpp,
// docs/facemesh.md "The default face").
#include "emoface/retarget/default_head.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>

#include "emoface/core/errors.hpp"
#include "emoface/facemesh/default_face.hpp"

namespace emoface::retarget {
namespace fm = facemesh;

namespace {

using Vec3 = Eigen::Vector3d;

// 0 at e0, 1 at e1, smooth (cubic Hermite) between.
double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// A mesh under construction: positions (rig frame) and triangles, appended part by part.
struct Builder {
  std::vector<Vec3> v;
  std::vector<Eigen::Vector3i> f;
  std::vector<fm::Material> mat;
  int add(const Vec3& p, fm::Material m) {
    v.push_back(p);
    mat.push_back(m);
    return static_cast<int>(v.size()) - 1;
  }
};

// Copies the faces of `source` whose three corners are all in `ids` (and those vertices) into `b`,
// transformed by `map`; returns the new ids (ascending in the source's order).
template <class Map>
std::vector<int> copy_component(const fm::Face& source, const std::vector<int>& ids, const Map& map,
                                Builder& b) {
  std::map<int, int> to_new;
  std::vector<int> sorted(ids);
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> out;
  for (int s : sorted) {
    const int n = b.add(map(source.mesh.vertices.row(s).transpose()),
                        source.rig.materials[static_cast<std::size_t>(s)]);
    to_new[s] = n;
    out.push_back(n);
  }
  for (long t = 0; t < source.mesh.faces.rows(); ++t) {
    Eigen::Vector3i nf;
    bool all = true;
    for (int k = 0; k < 3 && all; ++k) {
      const auto it = to_new.find(source.mesh.faces(t, k));
      all = it != to_new.end();
      if (all) nf[k] = it->second;
    }
    if (all) b.f.push_back(nf);
  }
  return out;
}

// A closed, flattened half-ellipsoid-like tongue: a UV ellipsoid of semi-axes `a` around `c`, its
// lower half squashed (it lies on the floor of the mouth). Returns the new vertex ids.
std::vector<int> add_tongue(const Vec3& c, const Vec3& a, Builder& b) {
  constexpr int kAround = 20, kRings = 10;
  std::vector<int> ids;
  // pole along z (tip forward, root back), rings around it
  const int tip = b.add(c + Vec3(0, 0, a.z()), fm::Material::Tongue);
  ids.push_back(tip);
  for (int r = 1; r < kRings; ++r) {
    const double th = M_PI * r / kRings;  // 0 at the tip (+z), π at the root (−z)
    for (int i = 0; i < kAround; ++i) {
      const double ph = 2.0 * M_PI * i / kAround;
      double y = std::sin(ph);
      y = y > 0 ? 0.55 * y : 0.35 * y;  // flat top with a slight dome, flatter underside
      // a shallow groove along the middle of the top
      const double groove = y > 0 ? 0.15 * std::exp(-std::pow(std::cos(ph) / 0.25, 2)) : 0.0;
      ids.push_back(b.add(c + Vec3(a.x() * std::sin(th) * std::cos(ph),
                                   a.y() * std::sin(th) * (y - groove), a.z() * std::cos(th)),
                          fm::Material::Tongue));
    }
  }
  const int root = b.add(c + Vec3(0, 0, -a.z()), fm::Material::Tongue);
  ids.push_back(root);
  auto ring = [&](int r, int i) { return tip + 1 + (r - 1) * kAround + (i % kAround); };
  for (int i = 0; i < kAround; ++i) b.f.push_back({tip, ring(1, i + 1), ring(1, i)});
  for (int r = 1; r + 1 < kRings; ++r)
    for (int i = 0; i < kAround; ++i) {
      b.f.push_back({ring(r, i), ring(r, i + 1), ring(r + 1, i + 1)});
      b.f.push_back({ring(r, i), ring(r + 1, i + 1), ring(r + 1, i)});
    }
  for (int i = 0; i < kAround; ++i) b.f.push_back({root, ring(kRings - 1, i), ring(kRings - 1, i + 1)});
  return ids;
}

// Outward-facing orientation check for a closed part: flips every face when the signed volume is
// negative.
void orient_outward(Builder& b, std::size_t first_face) {
  double vol = 0.0;
  for (std::size_t t = first_face; t < b.f.size(); ++t)
    vol += b.v[b.f[t][0]].dot(b.v[b.f[t][1]].cross(b.v[b.f[t][2]]));
  if (vol < 0)
    for (std::size_t t = first_face; t < b.f.size(); ++t) std::swap(b.f[t][1], b.f[t][2]);
}

// Boundary loops of a triangle set (directed edges without their opposite), each in walking order.
std::vector<std::vector<int>> boundary_loops(const std::vector<Eigen::Vector3i>& faces) {
  std::set<std::pair<int, int>> edges;
  for (const auto& t : faces)
    for (int k = 0; k < 3; ++k) edges.insert({t[k], t[(k + 1) % 3]});
  std::map<int, int> next;
  for (const auto& [a, b] : edges)
    if (!edges.count({b, a})) next[b] = a;  // walk the boundary reversed: the cap's winding
  std::vector<std::vector<int>> loops;
  std::set<int> seen;
  for (const auto& [start, unused] : next) {
    (void)unused;
    if (seen.count(start)) continue;
    std::vector<int> loop;
    int v = start;
    while (!seen.count(v) && next.count(v)) {
      seen.insert(v);
      loop.push_back(v);
      v = next[v];
    }
    if (v == start && loop.size() >= 3) loops.push_back(loop);
  }
  return loops;
}

// The neck end (issue 14, session 8): MakeHuman's head ends in a ragged edge where the neck widens
// into the shoulders (seen from the front, a flat collar; at 30 mm under the chin still the
// trapezius' flare at the sides). Cut at the plane y = y_cut *after* the transfer (cutting the
// target before it changed the fit's alignment, which samples the whole surface, and left strings
// of skin across opened mouths): the vertices below the plane go, the triangles crossing it are
// clipped (each crossing edge gets a vertex where it meets the plane, exactly on it: a flat rim;
// moving the kept triangles' lower corners onto the plane instead folded thin triangles flat and
// gave the rim downward normals), and the rig's vertex ids are renumbered: the kept vertices in
// their order, then the rim's new ones, which take the material and region of the edge's upper end
// and the jaw weight interpolated along the edge. Throws InvalidInput when a landmark would be cut
// off.
fm::Face cut_neck(const fm::Face& in, double y_cut, std::size_t* dropped) {
  const auto& X = in.mesh.vertices;
  const int n = static_cast<int>(X.rows());
  auto above = [&](int v) { return X(v, 1) >= y_cut; };
  std::vector<int> to_new(static_cast<std::size_t>(n), -1);
  int m = 0;
  for (int v = 0; v < n; ++v)
    if (above(v)) to_new[static_cast<std::size_t>(v)] = m++;
  if (dropped) *dropped = static_cast<std::size_t>(n - m);
  struct Cut {
    int up, down;
    double t;  // position = X(up) + t (X(down) − X(up))
  };
  std::vector<Cut> cuts;
  std::map<std::pair<int, int>, int> cut_id;  // (up, down) → new id
  auto cut = [&](int up, int down) {
    const auto [it, added] = cut_id.insert({{up, down}, m + static_cast<int>(cuts.size())});
    if (added) cuts.push_back({up, down, (X(up, 1) - y_cut) / (X(up, 1) - X(down, 1))});
    return it->second;
  };
  std::vector<Eigen::Vector3i> faces;
  for (long t = 0; t < in.mesh.faces.rows(); ++t) {
    const Eigen::Vector3i f = in.mesh.faces.row(t).transpose();
    // the triangle's polygon above the plane, in its winding order (Sutherland–Hodgman, one plane)
    std::vector<int> poly;
    for (int k = 0; k < 3; ++k) {
      const int p = f[k], q = f[(k + 1) % 3];
      if (above(p)) poly.push_back(to_new[static_cast<std::size_t>(p)]);
      if (above(p) != above(q)) poly.push_back(above(p) ? cut(p, q) : cut(q, p));
    }
    for (std::size_t k = 1; k + 1 < poly.size(); ++k)
      faces.push_back({poly[0], poly[k], poly[k + 1]});
  }
  const int total = m + static_cast<int>(cuts.size());
  fm::Face out;
  out.mesh.vertices.resize(total, 3);
  for (int v = 0; v < n; ++v)
    if (to_new[static_cast<std::size_t>(v)] >= 0)
      out.mesh.vertices.row(to_new[static_cast<std::size_t>(v)]) = X.row(v);
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    const Cut& c = cuts[k];
    Vec3 p = X.row(c.up).transpose() + c.t * (X.row(c.down) - X.row(c.up)).transpose();
    p.y() = y_cut;
    out.mesh.vertices.row(m + static_cast<long>(k)) = p.transpose();
  }
  out.mesh.faces.resize(static_cast<long>(faces.size()), 3);
  for (std::size_t t = 0; t < faces.size(); ++t)
    out.mesh.faces.row(static_cast<long>(t)) = faces[t].transpose();
  // the rig: per-vertex lists shrink, id lists drop the cut vertices (with their weights)
  fm::Rig rig = in.rig;
  auto id = [&](int v) { return to_new[static_cast<std::size_t>(v)]; };
  auto keep = [&](std::vector<int>& ids, std::vector<double>* weights) {
    std::size_t w = 0;
    for (std::size_t k = 0; k < ids.size(); ++k)
      if (id(ids[k]) >= 0) {
        if (weights) (*weights)[w] = (*weights)[k];
        ids[w++] = id(ids[k]);
      }
    ids.resize(w);
    if (weights) weights->resize(w);
  };
  rig.vertex_count = static_cast<std::size_t>(total);
  rig.regions.clear(), rig.materials.clear();
  for (int v = 0; v < n; ++v)
    if (id(v) >= 0) {
      rig.regions.push_back(in.rig.regions[static_cast<std::size_t>(v)]);
      rig.materials.push_back(in.rig.materials[static_cast<std::size_t>(v)]);
    }
  for (const Cut& c : cuts) {
    rig.regions.push_back(in.rig.regions[static_cast<std::size_t>(c.up)]);
    rig.materials.push_back(in.rig.materials[static_cast<std::size_t>(c.up)]);
  }
  if (rig.lips.samples_in_mesh && !rig.lips.control_points.empty())
    throw InvalidInput(
        "default head: the neck cut needs a transferred rig (lip samples not in the mesh)");
  std::vector<fm::LipBinding> bound;
  for (fm::LipBinding lb : rig.lips.bound)
    if (id(lb.vertex) >= 0) lb.vertex = id(lb.vertex), bound.push_back(lb);
  rig.lips.bound = bound;
  std::map<int, double> jaw_w;
  for (std::size_t k = 0; k < in.rig.jaw.vertices.size(); ++k)
    jaw_w[in.rig.jaw.vertices[k]] = in.rig.jaw.weights[k];
  keep(rig.jaw.vertices, &rig.jaw.weights);
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    const Cut& c = cuts[k];
    const double w = (1.0 - c.t) * (jaw_w.count(c.up) ? jaw_w[c.up] : 0.0) +
                     c.t * (jaw_w.count(c.down) ? jaw_w[c.down] : 0.0);
    if (w > 0.0) rig.jaw.vertices.push_back(m + static_cast<int>(k)), rig.jaw.weights.push_back(w);
  }
  for (auto& eye : rig.eyes) {
    keep(eye.eyeball_vertices, nullptr);
    keep(eye.upper_lid, &eye.upper_lid_weights);
    keep(eye.lower_lid, &eye.lower_lid_weights);
  }
  for (auto& p : rig.parts) keep(p.vertices, nullptr);
  for (int& v : rig.ibug68) {
    if (id(v) < 0) throw InvalidInput("default head: the neck cut removes an iBUG landmark");
    v = id(v);
  }
  for (auto& l : rig.retarget_landmarks) {
    if (id(l.vertex) < 0)
      throw InvalidInput("default head: the neck cut removes landmark " + l.name);
    l.vertex = id(l.vertex);
  }
  out.rig = std::move(rig);
  return out;
}

}  // namespace

TransferOptions default_head_transfer_options() {
  TransferOptions o;
  o.fit.ga.seed = 7;
  return o;
}

fm::Face build_default_head(const fm::Face& generic, const fm::MeshDocument& head,
                            DefaultHeadReport* report) {
  const TransferResult r =
      transfer_rig(generic, head.triangles(), head.groups(), default_head_transfer_options());
  if (r.face.rig.ibug68.size() != 68)
    throw InvalidInput("default head: the transferred rig has no iBUG-68 landmarks (the chin)");
  DefaultHeadReport rep;
  rep.transfer = r.report;
  // the neck ends kNeckBelowChin under the chin (iBUG 8, the menton): a short neck, as in a bust
  constexpr double kNeckBelowChin = 0.020;
  const double y_cut = r.face.mesh.vertices(r.face.rig.ibug68[8], 1) - kNeckBelowChin;
  const fm::Face t = cut_neck(r.face, y_cut, &rep.neck_dropped);
  const fm::Rig& tr = t.rig;
  const int nh = static_cast<int>(t.mesh.vertices.rows());
  rep.head_vertices = static_cast<std::size_t>(nh);

  Builder b;
  for (int i = 0; i < nh; ++i) {
    fm::Material m = tr.materials[static_cast<std::size_t>(i)];
    // the head keeps lips and the mouth bag; everything the generic painted (hair, brows) or had as
    // parts (eyes, teeth) is skin here (brows are painted by facemesh, the parts are added below)
    if (m == fm::Material::Teeth || m == fm::Material::Tongue) m = fm::Material::MouthInterior;
    if (m != fm::Material::Lip && m != fm::Material::MouthInterior) m = fm::Material::Skin;
    b.add(t.mesh.vertices.row(i).transpose(), m);
  }
  for (long i = 0; i < t.mesh.faces.rows(); ++i)
    b.f.push_back(t.mesh.faces.row(i).transpose());

  fm::Rig rig = tr;
  rig.frame = fm::Frame{};
  rig.mesh_file = "default_face.obj";
  rig.parts.clear();
  {
    fm::Part p;
    p.name = "head";
    p.kind = fm::PartKind::Head;
    for (int i = 0; i < nh; ++i) p.vertices.push_back(i);
    rig.parts.push_back(p);
  }

  // ---- Eyeballs. The head's eye sockets are closed: the lid skin folds in at the margin and lines a
  // shallow cup. The lid margin is that fold (vertices facing forward or sideways next to ones facing
  // backwards, n_z < −0.3, around
  // the transferred eye centre); the eyeball (the generic's sphere, sclera/iris/pupil, scaled to the
  // transferred radius) is centred on the opening and moved along z until the margin lies 0.6 mm
  // outside it, so the lids rest on the eyeball; every head vertex seen through the opening (inside
  // the margin polygon, in front) is pulled onto a sphere just inside the eyeball, out of sight.
  const fm::Vertices head_normals = fm::vertex_normals(t.mesh.vertices, t.mesh.faces);
  std::vector<std::vector<int>> adjacent(static_cast<std::size_t>(nh));
  for (long i = 0; i < t.mesh.faces.rows(); ++i)
    for (int k = 0; k < 3; ++k) {
      const int p = t.mesh.faces(i, k), q = t.mesh.faces(i, (k + 1) % 3);
      adjacent[static_cast<std::size_t>(p)].push_back(q);
      adjacent[static_cast<std::size_t>(q)].push_back(p);
    }
  // the transfer's mouth bag: MouthInterior, and the generic's teeth/tongue where they were nearest
  auto in_bag = [&](int v) {
    const fm::Material m = tr.materials[static_cast<std::size_t>(v)];
    return m == fm::Material::MouthInterior || m == fm::Material::Teeth || m == fm::Material::Tongue;
  };
  std::vector<char> in_mouth(static_cast<std::size_t>(nh), 0);
  for (const auto& lb : tr.lips.bound) in_mouth[static_cast<std::size_t>(lb.vertex)] = 1;
  for (int v = 0; v < nh; ++v)
    if (in_bag(v)) in_mouth[static_cast<std::size_t>(v)] = 1;
  std::array<std::vector<int>, 2> margins;
  for (int e = 0; e < 2; ++e) {
    auto& eye = rig.eyes[static_cast<std::size_t>(e)];
    const auto& ge = generic.rig.eyes[static_cast<std::size_t>(e)];
    const Vec3 c_old = eye.centre;
    const double r = eye.radius;
    auto& margin = margins[static_cast<std::size_t>(e)];
    for (int v = 0; v < nh; ++v) {
      const Vec3& p = b.v[static_cast<std::size_t>(v)];
      if (in_mouth[static_cast<std::size_t>(v)] || head_normals(v, 2) < 0.0 || p.z() < c_old.z() ||
          (p - c_old).head<2>().norm() > 2.5 * r)
        continue;
      for (int w : adjacent[static_cast<std::size_t>(v)])
        if (head_normals(w, 2) < -0.3) {
          margin.push_back(v);
          break;
        }
    }
    if (margin.size() < 8)
      throw InvalidInput("default head: no lid margin found around the " +
                         std::string(e == 0 ? "right" : "left") + " eye");
    Eigen::Vector2d lo(1e9, 1e9), hi(-1e9, -1e9);
    for (int v : margin)
      lo = lo.cwiseMin(b.v[static_cast<std::size_t>(v)].head<2>()),
      hi = hi.cwiseMax(b.v[static_cast<std::size_t>(v)].head<2>());
    const Eigen::Vector2d o = 0.5 * (lo + hi);
    // z of the centre: median over the margin of (distance − r) = 0.6 mm, by bisection (monotone)
    auto median_gap = [&](double cz) {
      std::vector<double> g;
      for (int v : margin) g.push_back((b.v[static_cast<std::size_t>(v)] - Vec3(o.x(), o.y(), cz)).norm() - r);
      std::nth_element(g.begin(), g.begin() + static_cast<long>(g.size() / 2), g.end());
      return g[g.size() / 2];
    };
    double za = c_old.z() - 2 * r, zb = c_old.z() + 2 * r;  // gap falls as the centre comes forward
    for (int it = 0; it < 60; ++it) {
      const double zm = 0.5 * (za + zb);
      (median_gap(zm) > 0.0006 ? za : zb) = zm;
    }
    const Vec3 c(o.x(), o.y(), 0.5 * (za + zb));
    // the lids now turn about the new centre: keep the closing angle's share of the opening
    // measured over the middle 40 % of the eye's width, where the opening is widest (the whole
    // margin's mean left a 1.4 mm slit at a full blink; issue 14, session 6); towards the corners
    // the upper lid's weights scale the angle down to each margin vertex's own opening (below).
    // The tightener (AU7) and the cheek's push (AU6) keep the whole margin's mean as their angle
    // (Eye::tighten_angle): the wider closing angle is for the blink alone.
    const double middle = 0.2 * (hi.x() - lo.x());
    auto opening = [&](const Vec3& centre, double half_width) {
      Vec3 up = Vec3::Zero(), dn = Vec3::Zero();
      int nu = 0, nd = 0;
      for (int v : margin) {
        const Vec3& p = b.v[static_cast<std::size_t>(v)];
        if (std::abs(p.x() - o.x()) > half_width) continue;
        ((p.y() > o.y()) ? (++nu, up) : (++nd, dn)) += p;
      }
      if (nu == 0 || nd == 0) return 0.0;
      up = up / nu - centre, dn = dn / nd - centre;
      return std::atan2(up.y(), up.z()) - std::atan2(dn.y(), dn.z());
    };
    const double whole = std::numeric_limits<double>::infinity();
    const double open_old = opening(c_old, middle), open_new = opening(c, middle),
                 open_mean = opening(c, whole);
    if (open_old > 1e-6 && open_new > 1e-6) {
      eye.close_angle = 1.05 * open_new / 1.2;  // upper down by it, lower up by 0.2 of it: they meet
      if (open_mean > 1e-6) eye.tighten_angle = std::min(eye.close_angle, 1.05 * open_mean / 1.2);
    }
    eye.centre = c;
    // the margin polygon (sorted by angle about o) and the head vertices seen through it
    std::vector<std::pair<double, int>> around;
    for (int v : margin) {
      const Vec3& p = b.v[static_cast<std::size_t>(v)];
      around.push_back({std::atan2(p.y() - o.y(), p.x() - o.x()), v});
    }
    std::sort(around.begin(), around.end());
    std::vector<Eigen::Vector2d> poly;
    for (const auto& [ang, v] : around) {
      (void)ang;
      poly.push_back(b.v[static_cast<std::size_t>(v)].head<2>());
    }
    auto inside = [&](const Eigen::Vector2d& q) {
      bool in = false;
      for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
        if ((poly[i].y() > q.y()) != (poly[j].y() > q.y()) &&
            q.x() < (poly[j].x() - poly[i].x()) * (q.y() - poly[i].y()) / (poly[j].y() - poly[i].y()) +
                        poly[i].x())
          in = !in;
      return in;
    };
    std::vector<char> is_margin(static_cast<std::size_t>(nh), 0);
    for (int v : margin) is_margin[static_cast<std::size_t>(v)] = 1;
    std::size_t pulled = 0;
    std::vector<char> socket(static_cast<std::size_t>(nh), 0);
    for (int v = 0; v < nh; ++v) {
      Vec3& p = b.v[static_cast<std::size_t>(v)];
      if (is_margin[static_cast<std::size_t>(v)] || in_mouth[static_cast<std::size_t>(v)] ||
          (p - c).norm() > 2.5 * r || !inside(p.head<2>()))
        continue;
      socket[static_cast<std::size_t>(v)] = 1;  // the cup behind the fold
      const Vec3 d = p - c;
      if (p.z() < c.z() || d.norm() < 0.95 * r) continue;  // hidden behind or inside the eyeball
      p = c + 0.95 * r * d.normalized();
      b.mat[static_cast<std::size_t>(v)] = fm::Material::MouthInterior;  // dark if ever seen
      ++pulled;
    }
    rep.socket_vertices[static_cast<std::size_t>(e)] = pulled;
    // Lid weights from the margin found here (stop-gap: the transfer's weights, carried from the
    // generic's smaller eye opening, peak 1 cm above this head's margin; the transfer's own
    // target-side margin detection replaces this once merged). Upper lid: the vertices above the
    // line through the eye corners, 1 at the upper margin falling (smoothstep) to 0 at 9 mm from
    // it; lower lid likewise below the line, 0 at 5 mm; the lower lid fades to 0 at the corners
    // (smoothstep over the outer 30 % of the eye's width at each end) so the corners stay put, the
    // upper lid by its margin's closing share (below). The cup's lining
    // inside the eyeball's sphere turns with its lid like the margin; the rest of the cup (behind
    // the eye centre) is hidden by the eyeball and moves with neither lid.
    {
      const auto [lo_it, hi_it] = std::minmax_element(margin.begin(), margin.end(), [&](int p, int q) {
        return b.v[static_cast<std::size_t>(p)].x() < b.v[static_cast<std::size_t>(q)].x();
      });
      const Vec3 k0 = b.v[static_cast<std::size_t>(*lo_it)], k1 = b.v[static_cast<std::size_t>(*hi_it)];
      auto along = [&](const Vec3& p) { return std::clamp((p.x() - k0.x()) / (k1.x() - k0.x()), 0.0, 1.0); };
      auto above = [&](const Vec3& p) { return p.y() > k0.y() + along(p) * (k1.y() - k0.y()); };
      std::vector<int> upper_margin, lower_margin;
      for (int v : margin) (above(b.v[static_cast<std::size_t>(v)]) ? upper_margin : lower_margin).push_back(v);
      // A full blink turns each upper margin vertex onto the lower margin's rest position at its x:
      // its share of close_angle is the angle (about the eye centre, in the y–z plane) from it down
      // to the lower margin there, over close_angle — 1 in the middle, falling to 0 at the corners,
      // where the lids already meet. Upper-lid vertices take the share of their nearest margin
      // vertex (this replaces the corner fade for the upper lid).
      auto pitch = [&](const Vec3& q) { return std::atan2(q.y() - c.y(), q.z() - c.z()); };
      std::vector<std::pair<double, double>> lower_line;  // (x, angle) of the lower margin, by x
      for (int m : lower_margin)
        lower_line.push_back(
            {b.v[static_cast<std::size_t>(m)].x(), pitch(b.v[static_cast<std::size_t>(m)])});
      std::sort(lower_line.begin(), lower_line.end());
      auto lower_pitch = [&](double x) {
        if (x <= lower_line.front().first) return lower_line.front().second;
        if (x >= lower_line.back().first) return lower_line.back().second;
        const auto it =
            std::lower_bound(lower_line.begin(), lower_line.end(), std::make_pair(x, -1e9));
        const auto& [x1, a1] = *it;
        const auto& [x0, a0] = *(it - 1);
        return x1 > x0 ? a0 + (a1 - a0) * (x - x0) / (x1 - x0) : a1;
      };
      std::vector<double> share(upper_margin.size(), 1.0);
      if (!lower_line.empty() && eye.close_angle > 1e-6) {
        for (std::size_t k = 0; k < upper_margin.size(); ++k) {
          const Vec3& q = b.v[static_cast<std::size_t>(upper_margin[k])];
          share[k] = std::clamp((pitch(q) - lower_pitch(q.x())) / eye.close_angle, 0.0, 1.0);
        }
      }
      eye.upper_lid.clear(), eye.upper_lid_weights.clear();
      eye.lower_lid.clear(), eye.lower_lid_weights.clear();
      for (int v = 0; v < nh; ++v) {
        const Vec3& p = b.v[static_cast<std::size_t>(v)];
        if (in_mouth[static_cast<std::size_t>(v)] || (p - c).norm() > 3.0 * r) continue;
        // The lining of the cup (on or inside the sphere just inside the eyeball) turns with its
        // lid as the margin does: it stays hidden inside the eyeball while the lid opens (AU5) or
        // closes; left behind, the triangles from the raised margin down to it show as a band over
        // the iris.
        const bool lining =
            socket[static_cast<std::size_t>(v)] && (p - c).norm() <= 0.95 * r + 1e-9;
        if (!is_margin[static_cast<std::size_t>(v)] && !lining &&
            (socket[static_cast<std::size_t>(v)] || p.z() < c.z()))
          continue;
        const bool up = above(p);
        const auto& ring = up ? upper_margin : lower_margin;
        double d = 1e9;
        std::size_t nearest = 0;
        for (std::size_t k = 0; k < ring.size(); ++k) {
          const double dk = (b.v[static_cast<std::size_t>(ring[k])] - p).norm();
          if (dk < d) d = dk, nearest = k;
        }
        if (lining) d = 0.0;
        const double reach = up ? 0.009 : 0.005;
        const double t = std::clamp(d / reach, 0.0, 1.0);
        const double a = along(p), ea = std::clamp(a / 0.3, 0.0, 1.0), eb = std::clamp((1.0 - a) / 0.3, 0.0, 1.0);
        const double corner = up ? (share.empty() ? 0.0 : share[nearest])
                                 : ea * ea * (3.0 - 2.0 * ea) * eb * eb * (3.0 - 2.0 * eb);
        const double w = (1.0 - t * t * (3.0 - 2.0 * t)) * corner;
        if (w < 1e-3) continue;
        (up ? eye.upper_lid : eye.lower_lid).push_back(v);
        (up ? eye.upper_lid_weights : eye.lower_lid_weights).push_back(std::min(1.0, w));
      }
    }
    eye.eyeball_vertices.clear();  // the transfer's eye-hole vertices: the sphere turns instead
    const double s = r / ge.radius;
    const auto ids = copy_component(
        generic, ge.eyeball_vertices,
        [&](const Vec3& p) { return Vec3(c + s * (p - ge.centre)); }, b);
    rep.eyeball_vertices[static_cast<std::size_t>(e)] = ids.size();
    eye.eyeball_vertices = ids;
    fm::Part p;
    p.name = e == 0 ? "eyeball_r" : "eyeball_l";
    p.kind = fm::PartKind::Eyeball;
    p.side = e;
    p.vertices = ids;
    rig.parts.push_back(p);
  }

  // (The stop-gap that re-weighted the bag's jaw and bound the lower lip's front here is gone: the
  // transfer now keeps the bag out of the lips, binds by the target's own slit and weights the
  // bag's jaw by its height against the slit; docs/retarget.md "Lips".)

  // ---- Colours around the mouth (kept as a guard): the transfer may leave lip material on
  // skin vertices that the lip surface does not drive, and mouth-bag material on vertices of the
  // face's outside at the mouth corners — dark and pink spikes around the lips. Lip colour only
  // where the lip surface drives the vertex (weight ≥ 0.5); bag colour only where the surface does
  // not face forward (n_z ≤ 0.3) or lies more than 6 mm behind the lips' front.
  {
    std::vector<double> lip_w(static_cast<std::size_t>(nh), 0.0);
    double front = -1e9;
    for (const auto& lb : rig.lips.bound) {
      if (lb.vertex < nh) lip_w[static_cast<std::size_t>(lb.vertex)] = lb.weight;
      if (std::abs(b.v[static_cast<std::size_t>(lb.vertex)].x()) < 0.01)
        front = std::max(front, b.v[static_cast<std::size_t>(lb.vertex)].z());
    }
    for (int v = 0; v < nh; ++v) {
      auto& m = b.mat[static_cast<std::size_t>(v)];
      if (m == fm::Material::Lip && lip_w[static_cast<std::size_t>(v)] < 0.5) m = fm::Material::Skin;
      if (m == fm::Material::MouthInterior && in_mouth[static_cast<std::size_t>(v)] &&
          head_normals(v, 2) > 0.3 && b.v[static_cast<std::size_t>(v)].z() > front - 0.006)
        m = fm::Material::Skin;
    }
  }

  // ---- Teeth: the generic's slabs, carried by the similarity that takes the generic's mouth region
  // onto its registration on the head (Umeyama), so they sit where the generic's sit behind its lips.
  const auto& gl = generic.rig.lips;
  const int lip_end = gl.first_vertex + gl.samples_around * gl.samples_across;
  std::vector<int> mouth_ids;
  for (int v = 0; v < static_cast<int>(generic.mesh.vertices.rows()); ++v) {
    const Vec3 p = generic.mesh.vertices.row(v).transpose();
    const bool lip_outer = v >= gl.first_vertex && v < lip_end &&
                           (v - gl.first_vertex) / gl.samples_around < 4;
    const bool skin_near = generic.rig.materials[static_cast<std::size_t>(v)] == fm::Material::Skin &&
                           (p - gl.centre).norm() < 0.04 && p.z() > gl.centre.z() - 0.01;
    if (lip_outer || skin_near) mouth_ids.push_back(v);
  }
  Eigen::Matrix3Xd src(3, static_cast<long>(mouth_ids.size())), dst(3, src.cols());
  for (std::size_t k = 0; k < mouth_ids.size(); ++k) {
    src.col(static_cast<long>(k)) = generic.mesh.vertices.row(mouth_ids[k]).transpose();
    dst.col(static_cast<long>(k)) = r.registered.row(mouth_ids[k]).transpose();
  }
  const Eigen::Matrix4d sim = Eigen::umeyama(src, dst, true);
  auto mouth_map = [&](const Vec3& p) { return Vec3((sim * p.homogeneous()).head<3>()); };
  std::vector<int> upper_src, lower_src;
  std::map<int, double> gjaw;
  for (std::size_t k = 0; k < generic.rig.jaw.vertices.size(); ++k)
    gjaw[generic.rig.jaw.vertices[k]] = generic.rig.jaw.weights[k];
  for (int v = 0; v < static_cast<int>(generic.mesh.vertices.rows()); ++v)
    if (generic.rig.materials[static_cast<std::size_t>(v)] == fm::Material::Teeth)
      (gjaw.count(v) && gjaw[v] > 0.999 ? lower_src : upper_src).push_back(v);
  const auto upper = copy_component(generic, upper_src, mouth_map, b);
  const auto lower = copy_component(generic, lower_src, mouth_map, b);
  rep.upper_teeth = upper.size(), rep.lower_teeth = lower.size();
  // The similarity leaves the upper incisors' edges 2 mm above this head's lip contact line, so
  // lips parted a little (a smile: AU12 + AU25) showed a dark gap and no upper teeth. In a person
  // at rest the upper incisors' edges reach the line where the lips meet (the closed lower lip
  // covers their edge; Proffit, Contemporary Orthodontics, ch. 1: overbite 2–3 mm, the upper
  // incisors showing 1–3 mm below the relaxed upper lip). The upper row is moved straight down
  // until its edge lies 0.5 mm below the contact line (row 4 of the lip grid, mean of the upper and
  // lower lips' middle columns). Not moved forward: the muscles pull the lips back through rigid
  // teeth (no collision), and teeth 2–5 mm further forward showed in front of the upper lip in
  // fear.
  {
    const auto& cps = rig.lips.control_points;
    constexpr int kA = fm::LipGrid::kAround;
    const double contact_y = 0.5 * (cps[static_cast<std::size_t>(4 * kA + kA / 4)].y() +
                                    cps[static_cast<std::size_t>(4 * kA + 3 * kA / 4)].y());
    double edge = 1e9;
    for (int v : upper) edge = std::min(edge, b.v[static_cast<std::size_t>(v)].y());
    rep.upper_teeth_lowered = edge - (contact_y - 0.0005);
    for (int v : upper) b.v[static_cast<std::size_t>(v)].y() -= rep.upper_teeth_lowered;
  }

  // ---- Tongue: behind the lower teeth, on the floor of the mouth.
  Vec3 lo_min = Vec3::Constant(1e9), lo_max = Vec3::Constant(-1e9);
  for (int v : lower) lo_min = lo_min.cwiseMin(b.v[v]), lo_max = lo_max.cwiseMax(b.v[v]);
  const double half_w = 0.5 * (lo_max.x() - lo_min.x());
  const Vec3 tongue_a(0.8 * half_w, 0.006, 0.022);
  const Vec3 tongue_c(0.5 * (lo_min.x() + lo_max.x()), lo_max.y() - 0.004,
                      lo_min.z() - 0.001 - tongue_a.z() * 0.55);
  const std::size_t tongue_first_face = b.f.size();
  const auto tongue = add_tongue(tongue_c, tongue_a, b);
  orient_outward(b, tongue_first_face);
  rep.tongue = tongue.size();

  // ---- Mouth cavity. The head's mouth bag is a shallow pocket: its back wall stands right behind
  // the lips (MakeHuman: 9 mm behind the lips' front, in front of the teeth), so an opened mouth
  // showed a pale wall where a person shows teeth and a dark cavity. Bag vertices in front of the
  // teeth's back are moved straight back (−z) to 3 mm behind it, fully over the teeth's width and
  // height and fading out over 60 % more to the sides and 6 mm above/below, so the lining between
  // the lips and the wall becomes the mouth's inside; they are coloured as mouth interior, and a
  // vertex bound to the lip surface keeps its rest position through its offset (S(u, v) + offset).
  {
    Vec3 t_min = Vec3::Constant(1e9), t_max = Vec3::Constant(-1e9);
    for (const auto* ids : {&upper, &lower})
      for (int v : *ids) t_min = t_min.cwiseMin(b.v[v]), t_max = t_max.cwiseMax(b.v[v]);
    const double cx = 0.5 * (t_min.x() + t_max.x()), hw = 0.5 * (t_max.x() - t_min.x());
    const double back = t_min.z() - 0.003;
    std::map<int, std::size_t> bound_index;
    for (std::size_t k = 0; k < rig.lips.bound.size(); ++k)
      bound_index[rig.lips.bound[k].vertex] = k;
    for (int v = 0; v < nh; ++v) {
      if (!in_bag(v)) continue;
      Vec3& p = b.v[static_cast<std::size_t>(v)];
      if (p.z() <= back) continue;
      const double ax = std::abs(p.x() - cx);
      const double dy = std::max({0.0, t_min.y() - p.y(), p.y() - t_max.y()});
      const double s = (1.0 - smoothstep(hw, 1.6 * hw, ax)) * (1.0 - smoothstep(0.0, 0.006, dy));
      if (s <= 0.0) continue;
      const Vec3 delta(0.0, 0.0, -s * (p.z() - back));
      p += delta;
      const auto it = bound_index.find(v);
      if (it != bound_index.end()) rig.lips.bound[it->second].offset += delta;
      b.mat[static_cast<std::size_t>(v)] = fm::Material::MouthInterior;
      ++rep.mouth_cavity_vertices;
    }
    // The bag does not stay closed when the jaw opens (its lining tears at the fold), and the head
    // behind it is an open shell: an opened mouth showed the lit inside of the back of the head.
    // A dark backdrop 4 mm behind the moved wall, curving back towards the sides, 3 × the teeth's
    // width, from 10 mm above the teeth to 14 mm below them, closes the view; its rows below the
    // teeth's middle turn with the jaw (weight 1, blended over ±2 mm) so it stays behind the lower
    // teeth and tongue as the mouth opens.
    constexpr int kCols = 13, kRows = 9;
    const double x0 = cx - 1.5 * hw, x1 = cx + 1.5 * hw;
    const double y0 = t_min.y() - 0.014, y1 = t_max.y() + 0.010,
                 y_mid = 0.5 * (t_min.y() + t_max.y());
    const int first = static_cast<int>(b.v.size());
    fm::Part backdrop;
    backdrop.name = "mouth_backdrop";
    backdrop.kind = fm::PartKind::Other;
    for (int row = 0; row < kRows; ++row)
      for (int col = 0; col < kCols; ++col) {
        const double x = x0 + (x1 - x0) * col / (kCols - 1), y = y0 + (y1 - y0) * row / (kRows - 1);
        const double ax = (x - cx) / (1.5 * hw);
        const int id =
            b.add(Vec3(x, y, back - 0.004 - 0.008 * ax * ax), fm::Material::MouthInterior);
        backdrop.vertices.push_back(id);
        const double w = 1.0 - smoothstep(y_mid - 0.002, y_mid + 0.002, y);
        if (w > 0.0) rig.jaw.vertices.push_back(id), rig.jaw.weights.push_back(w);
      }
    for (int row = 0; row + 1 < kRows; ++row)
      for (int col = 0; col + 1 < kCols; ++col) {
        const int a = first + row * kCols + col;  // counter-clockwise seen from +z (the viewer)
        b.f.push_back({a, a + 1, a + kCols + 1});
        b.f.push_back({a, a + kCols + 1, a + kCols});
      }
    rig.parts.push_back(backdrop);
    rep.mouth_backdrop = backdrop.vertices.size();
  }

  for (int v : lower) rig.jaw.vertices.push_back(v), rig.jaw.weights.push_back(1.0);
  for (int v : tongue) rig.jaw.vertices.push_back(v), rig.jaw.weights.push_back(1.0);
  for (auto [ids, kind, name] :
       {std::tuple{&upper, fm::PartKind::UpperTeeth, "upper_teeth"},
        std::tuple{&lower, fm::PartKind::LowerTeeth, "lower_teeth"},
        std::tuple{&tongue, fm::PartKind::Tongue, "tongue"}}) {
    fm::Part p;
    p.name = name;
    p.kind = kind;
    p.vertices = *ids;
    std::sort(p.vertices.begin(), p.vertices.end());
    rig.parts.push_back(p);
  }

  // ---- Lashes: a ribbon on each lid margin (found above), split at the eye corners (lowest and
  // highest x) into upper and lower, each ribbon vertex in the lid list with its margin vertex's lid
  // weight (the lashes follow the lid).
  for (int e = 0; e < 2; ++e) {
    auto& eye = rig.eyes[static_cast<std::size_t>(e)];
    const std::vector<int>& ring = margins[static_cast<std::size_t>(e)];
    const auto [lo_it, hi_it] = std::minmax_element(
        ring.begin(), ring.end(), [&](int a, int c) { return b.v[a].x() < b.v[c].x(); });
    const Vec3 c0 = b.v[static_cast<std::size_t>(*lo_it)], c1 = b.v[static_cast<std::size_t>(*hi_it)];
    for (int lid = 0; lid < 2; ++lid) {
      auto& ids = lid == 0 ? eye.upper_lid : eye.lower_lid;
      auto& ws = lid == 0 ? eye.upper_lid_weights : eye.lower_lid_weights;
      std::map<int, double> weight;
      for (std::size_t k = 0; k < ids.size(); ++k) weight[ids[k]] = ws[k];
      std::vector<std::pair<double, int>> margin;  // (x, id)
      for (int v : ring) {
        const Vec3& p = b.v[static_cast<std::size_t>(v)];
        const double a = std::clamp((p.x() - c0.x()) / (c1.x() - c0.x()), 0.0, 1.0);
        const double line_y = c0.y() + a * (c1.y() - c0.y());
        if ((lid == 0) == (p.y() > line_y)) margin.push_back({p.x(), v});
      }
      if (margin.size() < 3)
        throw InvalidInput("default head: too few lid-margin vertices for lashes");
      std::sort(margin.begin(), margin.end());
      const double length = lid == 0 ? 0.0032 : 0.0013;
      const double up = lid == 0 ? 1.0 : -1.0;
      const int first = static_cast<int>(b.v.size());
      const int n = static_cast<int>(margin.size());
      // the upper lid's margin itself is lash-coloured: the lash line (the roots of the lashes and
      // the lid's grey line) that outlines the upper eyelid at a distance; the skin next to it
      // shades from it to skin colour over one ring of triangles
      if (lid == 0)
        for (const auto& [x, v] : margin) {
          (void)x;
          b.mat[static_cast<std::size_t>(v)] = fm::Material::Lash;
        }
      for (int k = 0; k < n; ++k) {
        const Vec3 m = b.v[static_cast<std::size_t>(margin[k].second)];
        const double along = n > 1 ? static_cast<double>(k) / (n - 1) : 0.5;
        const double fall = std::sin(M_PI * std::clamp(along, 0.0, 1.0));  // shorter at the corners
        const Vec3 radial = (m - eye.centre).normalized();
        const Vec3 dir = (radial + Vec3(0, 0.5 * up, 0)).normalized();
        const double len = length * (0.35 + 0.65 * fall);
        const int base = b.add(m + 0.0006 * radial, fm::Material::Lash);
        const int tip = b.add(m + 0.0006 * radial + len * dir,
                              fm::Material::Lash);
        // the margin vertex's own lid weight, else that of the nearest vertex of the lid list
        double w = 0.0;
        if (weight.count(margin[k].second)) {
          w = weight[margin[k].second];
        } else {
          double best = 1e9;
          for (const auto& [id, wt] : weight) {
            if (id >= nh) continue;
            const double d = (b.v[static_cast<std::size_t>(id)] - m).norm();
            if (d < best) best = d, w = wt;
          }
        }
        ids.push_back(base), ws.push_back(w);
        ids.push_back(tip), ws.push_back(w);
      }
      for (int k = 0; k + 1 < n; ++k) {
        const int a0 = first + 2 * k, a1 = a0 + 1, b0 = a0 + 2, b1 = a0 + 3;
        b.f.push_back({a0, b0, b1});
        b.f.push_back({a0, b1, a1});
      }
      rep.lashes += static_cast<std::size_t>(2 * n);
      fm::Part p;
      p.name = std::string(lid == 0 ? "upper" : "lower") + "_lashes_" + (e == 0 ? "r" : "l");
      p.kind = fm::PartKind::Lashes;
      p.side = e;
      for (int v = first; v < static_cast<int>(b.v.size()); ++v) p.vertices.push_back(v);
      rig.parts.push_back(p);
    }
  }

  // ---- Hair (short, dark): the head's skin vertices above the hairline
  // (facemesh::default_hairline: forehead, temples, sideburns, over the ears, nape) are `hair`, so
  // the hair is bound to the vertices and moves with the scalp; the paint draws the same hairline
  // with a soft edge where it covers the face (default_face_paint).
  {
    const fm::Hairline hairline = fm::default_hairline(rig, t.mesh.vertices);
    for (int v = 0; v < nh; ++v) {
      auto& m = b.mat[static_cast<std::size_t>(v)];
      if (m == fm::Material::Skin &&
          fm::hair_cover(hairline, b.v[static_cast<std::size_t>(v)], 0.0) > 0.5) {
        m = fm::Material::Hair;
        ++rep.hair_vertices;
      }
    }
  }

  // ---- Neck end: the flat rim left by the cut (cut_neck) closed by a fan (material and jaw weight
  // of the rim). The fan has its own copy of the rim's vertices: sharing them, the rim's normals
  // averaged the neck's (sideways) with the cap's (down) and the neck's lower end rendered as a
  // dark, spiky band under the chin (session 8).
  {
    std::map<int, double> jaw_w;
    for (std::size_t k = 0; k < rig.jaw.vertices.size(); ++k)
      jaw_w[rig.jaw.vertices[k]] = rig.jaw.weights[k];
    std::vector<Eigen::Vector3i> head_faces(b.f.begin(), b.f.begin() + t.mesh.faces.rows());
    fm::Part cap;
    cap.name = "neck_cap";
    cap.kind = fm::PartKind::Other;
    for (const auto& loop : boundary_loops(head_faces)) {
      Vec3 c = Vec3::Zero();
      bool on_cut = true;
      for (int v : loop)
        c += b.v[static_cast<std::size_t>(v)],
            on_cut &= b.v[static_cast<std::size_t>(v)].y() == y_cut;
      if (!on_cut) continue;  // only the rim the cut left
      c /= static_cast<double>(loop.size());
      double centre_w = 0.0;
      std::vector<int> copy;
      for (int v : loop) {
        const int id = b.add(b.v[static_cast<std::size_t>(v)], b.mat[static_cast<std::size_t>(v)]);
        copy.push_back(id);
        cap.vertices.push_back(id);
        const auto it = jaw_w.find(v);
        if (it != jaw_w.end() && it->second > 0.0) {
          rig.jaw.vertices.push_back(id), rig.jaw.weights.push_back(it->second);
          centre_w += it->second;
        }
      }
      centre_w /= static_cast<double>(loop.size());
      const int centre = b.add(c, fm::Material::Skin);
      cap.vertices.push_back(centre);
      if (centre_w > 0.0) rig.jaw.vertices.push_back(centre), rig.jaw.weights.push_back(centre_w);
      for (std::size_t k = 0; k < copy.size(); ++k)
        b.f.push_back({centre, copy[k], copy[(k + 1) % copy.size()]});
    }
    if (cap.vertices.empty())
      throw InvalidInput("default head: no neck rim to close under the chin");
    rep.neck_cap = cap.vertices.size();
    rig.parts.push_back(cap);
  }

  // ---- Assemble.
  fm::Face face;
  const int nv = static_cast<int>(b.v.size());
  face.mesh.vertices.resize(nv, 3);
  for (int i = 0; i < nv; ++i) face.mesh.vertices.row(i) = b.v[static_cast<std::size_t>(i)].transpose();
  face.mesh.faces.resize(static_cast<long>(b.f.size()), 3);
  for (std::size_t i = 0; i < b.f.size(); ++i) face.mesh.faces.row(static_cast<long>(i)) = b.f[i].transpose();
  rig.vertex_count = static_cast<std::size_t>(nv);
  rig.materials = b.mat;
  rig.regions.resize(static_cast<std::size_t>(nv), fm::Region::Rest);
  std::sort(rig.parts.begin(), rig.parts.end(),
            [](const fm::Part& a, const fm::Part& c) { return a.vertices.front() < c.vertices.front(); });
  face.rig = std::move(rig);
  fm::validate_mesh(face.mesh, "default head");
  fm::validate_rig(face.rig, "default head");
  if (report) *report = rep;
  return face;
}

DefaultHeadReport write_default_face_files(const std::string& dir) {
  namespace fs = std::filesystem;
  const fm::Face generic = fm::make_generic_face();
  const fm::MeshDocument doc = fm::read_mesh_document((fs::path(dir) / "makehuman_head.obj").string());
  DefaultHeadReport rep;
  const fm::Face face = build_default_head(generic, doc, &rep);
  fm::save_face((fs::path(dir) / "generic.rig").string(), generic);
  fm::save_face((fs::path(dir) / "default.rig").string(), face);
  return rep;
}

}  // namespace emoface::retarget
