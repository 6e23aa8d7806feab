// The built-in default face, generated procedurally (thesis §2.3: a closed polygonal head, denser in the
// expressive parts, 11 regions, B-spline lips stitched to the face, eyeballs, jaw, landmarks, muscles).
//
// Construction: a (azimuth u, elevation v) grid over a tapered ellipsoid with non-uniform spacing
// (dense at the front and between brow and chin), plus a frontal height field for the face relief
// (sockets, brow ridge, nose, cheekbones, mouth, chin). Elliptical eye and mouth holes are cut out and
// their rims snapped to the ellipses; eyeballs are separate spheres closed off by socket caps; the
// mouth hole is filled by the lip B-spline surface (24×6 control grid, §2.3.2) sampled on a fixed
// grid, stitched to the rim and closed inside by a mouth-cavity cap.
#include "emoface/facemesh/default_face.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "emoface/facemesh/bspline.hpp"

namespace emoface::facemesh {
namespace {

constexpr double kPi = 3.14159265358979323846;

double smoothstep(double e0, double e1, double x) {
  double t = (x - e0) / (e1 - e0);
  t = std::min(1.0, std::max(0.0, t));
  return t * t * (3.0 - 2.0 * t);
}
double gauss(double x, double y, double cx, double cy, double sx, double sy) {
  const double dx = (x - cx) / sx, dy = (y - cy) / sy;
  return std::exp(-dx * dx - dy * dy);
}

// ---- Proportions (metres). Eye level y = 0, head centre near the ears. ----
constexpr double kEyeX = 0.032;        // eye centres at x = ±kEyeX
constexpr double kEyeHoleA = 0.0128;   // eye opening semi-axes
constexpr double kEyeHoleB = 0.0058;
constexpr double kEyeballR = 0.0122;
constexpr double kLidR = 0.0140;       // radius of the lid sphere around the eyeball centre
constexpr double kMouthY = -0.066;
constexpr double kMouthA = 0.0235;     // mouth (lip) hole semi-axes
constexpr double kMouthB = 0.0098;
constexpr double kMouthCy = kMouthY - 0.001;

// Frontal relief added along +z, as a function of frontal coordinates (x, y).
double relief(double x, double y) {
  const double ax = std::abs(x);
  double h = 0.0;
  // lower face forward (jaw, muzzle): the ellipsoid alone recedes too fast below the nose
  h += 0.030 * smoothstep(0.0, -0.075, y) * (1.0 - smoothstep(-0.10, -0.135, y)) * std::exp(-std::pow(x / 0.05, 2));
  // flatten the forehead/face front a little at the sides
  h += 0.004 * gauss(x, y, 0.0, 0.04, 0.05, 0.05);
  // eye sockets and brow ridge
  h -= 0.013 * gauss(ax, y, kEyeX, -0.001, 0.020, 0.014);
  h += 0.007 * gauss(ax, y, 0.030, 0.021, 0.028, 0.0075);
  // glabella
  h += 0.002 * gauss(x, y, 0.0, 0.012, 0.008, 0.01);
  // nose: bridge to tip, growing in height and width
  {
    const double t = std::min(1.0, std::max(0.0, (0.008 - y) / 0.047));  // 0 at the root, 1 at the tip
    const double height = 0.004 + 0.022 * std::pow(t, 1.4);
    const double width = 0.0055 + 0.0085 * t;
    double fall = 1.0;
    const double tip_y = 0.008 - 0.047;
    if (y < tip_y) fall = std::exp(-std::pow((y - tip_y) / 0.0065, 2));
    if (y > 0.008) fall = std::exp(-std::pow((y - 0.008) / 0.01, 2));
    h += height * fall * std::exp(-std::pow(x / width, 2));
    // nasal wings (alae)
    h += 0.0085 * gauss(ax, y, 0.0135, -0.035, 0.0065, 0.0065);
    // tip rounding
    h += 0.003 * gauss(x, y, 0.0, -0.036, 0.006, 0.006);
  }
  // cheekbones and cheeks
  h += 0.006 * gauss(ax, y, 0.046, -0.022, 0.018, 0.016);
  h += 0.003 * gauss(ax, y, 0.038, -0.05, 0.02, 0.02);
  // philtrum / mouth area protrusion
  h += 0.006 * gauss(x, y, 0.0, -0.062, 0.022, 0.016);
  // chin and the groove above it
  h += 0.008 * gauss(x, y, 0.0, -0.104, 0.017, 0.011);
  h -= 0.0025 * gauss(x, y, 0.0, -0.087, 0.016, 0.0045);
  // nasolabial fold hint
  h -= 0.0015 * gauss(ax, y, 0.026, -0.05, 0.004, 0.012);
  return h;
}

// Base surface point for grid direction (u azimuth, v elevation).
Eigen::Vector3d head_point(double u, double v) {
  const double dx = std::cos(v) * std::sin(u), dy = std::sin(v), dz = std::cos(v) * std::cos(u);
  const double ay = dy > 0 ? 0.112 : 0.128;
  double y = ay * dy + 0.004;
  const double az = dz > 0 ? 0.092 : 0.104;
  double ax = 0.079;
  ax *= 1.0 - 0.22 * smoothstep(-0.03, -0.13, y);   // narrower jaw and chin
  double z = az * dz;
  if (dz < 0) z *= 1.0 + 0.08 * smoothstep(-0.05, 0.06, y);  // occiput
  if (dz < 0 && y < -0.04) z *= 1.0 - 0.35 * smoothstep(-0.04, -0.12, y);  // neck side tapers
  const double x = ax * dx;
  const double front = smoothstep(0.0, 0.06, z);
  z += front * relief(x, y);
  // ears: small bumps on the sides
  const double side = std::abs(dx);
  if (side > 0.6) {
    const double e = gauss(z, y, -0.005, -0.005, 0.014, 0.024) * smoothstep(0.6, 0.95, side);
    return {x + (x > 0 ? 1.0 : -1.0) * 0.011 * e, y, z};
  }
  return {x, y, z};
}

// Surface point of the front of the head whose frontal projection is (x, y): solves head_point(u, v)
// = (x, y, ·) by a damped fixed-point iteration (the map is smooth and nearly linear at the front).
double front_z(double x, double y) {
  double u = std::atan2(x, 0.09), v = std::asin(std::max(-0.99, std::min(0.99, (y - 0.004) / 0.125)));
  for (int it = 0; it < 40; ++it) {
    const Eigen::Vector3d p = head_point(u, v);
    u += 0.8 * (x - p.x()) / 0.085;
    v += 0.8 * (y - p.y()) / 0.12;
    v = std::max(-1.5, std::min(1.5, v));
  }
  return head_point(u, v).z();
}

// Samples n points on [a, b] with spacing inversely proportional to density(x).
template <class Density>
std::vector<double> sample_density(double a, double b, int n, Density density, bool include_end) {
  const int m = 4000;
  std::vector<double> cdf(m + 1, 0.0);
  for (int i = 1; i <= m; ++i) {
    const double x = a + (b - a) * (i - 0.5) / m;
    cdf[static_cast<std::size_t>(i)] = cdf[static_cast<std::size_t>(i - 1)] + density(x);
  }
  std::vector<double> out;
  const int count = include_end ? n - 1 : n;
  for (int k = 0; k < n; ++k) {
    const double target = cdf[m] * k / count;
    const auto it = std::lower_bound(cdf.begin(), cdf.end(), target);
    const auto i = static_cast<int>(std::max<long>(1, it - cdf.begin()));
    const double c0 = cdf[static_cast<std::size_t>(i - 1)], c1 = cdf[static_cast<std::size_t>(i)];
    const double f = c1 > c0 ? (target - c0) / (c1 - c0) : 0.0;
    out.push_back(a + (b - a) * (i - 1 + f) / m);
  }
  return out;
}

struct Hole {
  Eigen::Vector2d centre;
  double a, b;
  double radius(const Eigen::Vector3d& p) const {
    const double dx = (p.x() - centre.x()) / a, dy = (p.y() - centre.y()) / b;
    return std::sqrt(dx * dx + dy * dy);
  }
};

// Height of the lid sphere at (x, y) around an eye centre, if inside its silhouette.
double lid_z(const Eigen::Vector3d& c, double x, double y) {
  const double d2 = (x - c.x()) * (x - c.x()) + (y - c.y()) * (y - c.y());
  return c.z() + std::sqrt(std::max(0.0, kLidR * kLidR - d2));
}

int nearest(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& target, double min_z = -1e9) {
  int best = -1;
  double bd = 1e300;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (pts[i].z() < min_z) continue;
    const double d = (pts[i] - target).squaredNorm();
    if (d < bd) bd = d, best = static_cast<int>(i);
  }
  return best;
}

// Nearest vertex in frontal projection (x, y) among front-facing vertices of a candidate set.
int nearest_xy(const std::vector<Eigen::Vector3d>& pts, const std::vector<int>& candidates, double x, double y) {
  int best = -1;
  double bd = 1e300;
  for (int i : candidates) {
    const auto& p = pts[static_cast<std::size_t>(i)];
    const double d = (p.x() - x) * (p.x() - x) + (p.y() - y) * (p.y() - y);
    if (d < bd) bd = d, best = i;
  }
  return best;
}

// Brows (step 7): signed vertical distance (m) from the brow band's edge, < 0 inside. The band
// follows brow_y(|x|) for 0.010 < |x| < 0.05, half thickness 4.2 mm tapering laterally.
double brow_distance(double x, double y) {
  const double ax = std::abs(x);
  if (ax <= 0.010 || ax >= 0.05) return 1.0;
  const double brow_y = 0.019 + 0.006 * std::exp(-std::pow((ax - 0.03) / 0.012, 2)) -
                        0.004 * std::max(0.0, (ax - 0.04) / 0.01);
  const double half = 0.0042 - 0.04 * std::max(0.0, ax - 0.042);
  return std::abs(y - brow_y) - half;
}
// Hairline height at a point of the head (x, z): lower at the sides and behind.
double hair_line(double x, double z) {
  const double front = z / std::sqrt(x * x + z * z + 1e-12);  // cos(azimuth)
  return 0.076 - 0.085 * (1.0 - front) / 2.0 - 0.03 * smoothstep(0.0, -1.0, front);
}

}  // namespace

Face make_generic_face() {
  // ---- 1. grid ----
  const int nu = 84, nv = 52;
  auto du = [](double u) { return 1.0 + 3.2 * std::exp(-std::pow(u / 0.75, 2)); };
  auto dv = [](double v) { return 1.0 + 2.2 * std::exp(-std::pow((v + 0.28) / 0.6, 2)); };
  const auto us = sample_density(-kPi, kPi, nu, du, false);
  auto vs = sample_density(-kPi / 2, kPi / 2, nv + 2, dv, true);  // includes both poles
  std::vector<Eigen::Vector3d> pts;
  std::vector<int> grid(static_cast<std::size_t>(nu * nv));
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      grid[static_cast<std::size_t>(j * nu + i)] = static_cast<int>(pts.size());
      pts.push_back(head_point(us[static_cast<std::size_t>(i)], vs[static_cast<std::size_t>(j + 1)]));
    }
  }
  const int bottom_pole = static_cast<int>(pts.size());
  pts.push_back(head_point(0.0, -kPi / 2));
  const int top_pole = static_cast<int>(pts.size());
  pts.push_back(head_point(0.0, kPi / 2));

  // Eye centres: behind the lid sphere so that the lids meet the relief smoothly.
  std::array<Eigen::Vector3d, 2> eye_c;
  for (int e = 0; e < 2; ++e) {
    const double x = e == 0 ? -kEyeX : kEyeX;  // [0] right eye (subject's right = -x)
    const double zf = front_z(x, 0.0);
    eye_c[static_cast<std::size_t>(e)] = {x, 0.0, zf - kLidR + 0.003};
  }
  std::array<Hole, 2> eye_holes{Hole{{-kEyeX, 0.0}, kEyeHoleA, kEyeHoleB}, Hole{{kEyeX, 0.0}, kEyeHoleA, kEyeHoleB}};
  const Hole mouth{{0.0, kMouthCy}, kMouthA, kMouthB};

  // Lids hug the eyeball: blend z towards the lid sphere near each eye opening.
  for (auto& p : pts) {
    if (p.z() < 0.03) continue;
    for (int e = 0; e < 2; ++e) {
      const double r = eye_holes[static_cast<std::size_t>(e)].radius(p);
      if (r < 2.1) {
        const double w = 1.0 - smoothstep(1.2, 2.1, r);
        const double zs = lid_z(eye_c[static_cast<std::size_t>(e)], p.x(), p.y());
        p.z() = (1.0 - w) * p.z() + w * std::max(zs, p.z() - 0.004);
      }
    }
  }

  // ---- 2. triangles, holes ----
  auto inside_hole = [&](const Eigen::Vector3d& p) {
    if (p.z() < 0.03) return -1;
    for (int e = 0; e < 2; ++e) {
      if (eye_holes[static_cast<std::size_t>(e)].radius(p) < 1.0) return e;
    }
    if (mouth.radius(p) < 1.0) return 2;
    return -1;
  };
  std::vector<int> hole_of(pts.size());
  for (std::size_t k = 0; k < pts.size(); ++k) hole_of[k] = inside_hole(pts[k]);
  std::vector<std::array<int, 3>> tris;
  std::vector<int> touches(pts.size(), -1);  // vertex kept but next to a removed triangle of hole h
  auto add = [&](int a, int b, int c) {
    const int h = std::max({hole_of[static_cast<std::size_t>(a)], hole_of[static_cast<std::size_t>(b)], hole_of[static_cast<std::size_t>(c)]});
    if (h >= 0) {
      for (int id : {a, b, c}) {
        if (hole_of[static_cast<std::size_t>(id)] < 0) touches[static_cast<std::size_t>(id)] = h;
      }
      return;
    }
    tris.push_back({a, b, c});
  };
  auto g = [&](int i, int j) { return grid[static_cast<std::size_t>(j * nu + ((i % nu) + nu) % nu)]; };
  // Rows go bottom to top (v increasing), columns go with u increasing = towards +x at the front.
  for (int j = 0; j + 1 < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const int a = g(i, j), b = g(i + 1, j), c = g(i + 1, j + 1), d = g(i, j + 1);
      // outward (counter-clockwise seen from outside)
      if ((i + j) % 2 == 0) {
        add(a, b, c), add(a, c, d);
      } else {
        add(a, b, d), add(b, c, d);
      }
    }
  }
  for (int i = 0; i < nu; ++i) {
    add(bottom_pole, g(i + 1, 0), g(i, 0));
    add(top_pole, g(i, nv - 1), g(i + 1, nv - 1));
  }
  // Snap rims onto the hole ellipses (eyes: onto the lid sphere too).
  std::array<std::vector<int>, 3> rims;
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const int h = touches[k];
    if (h < 0) continue;
    auto& p = pts[k];
    const Hole& hole = h < 2 ? eye_holes[static_cast<std::size_t>(h)] : mouth;
    const double r = hole.radius(p);
    const Eigen::Vector2d c = hole.centre;
    p.x() = c.x() + (p.x() - c.x()) / r;
    p.y() = c.y() + (p.y() - c.y()) / r;
    if (h < 2) p.z() = lid_z(eye_c[static_cast<std::size_t>(h)], p.x(), p.y());
    rims[static_cast<std::size_t>(h)].push_back(static_cast<int>(k));
  }
  for (int h = 0; h < 3; ++h) {
    const Hole& hole = h < 2 ? eye_holes[static_cast<std::size_t>(h)] : mouth;
    auto angle = [&](int id) {
      const auto& p = pts[static_cast<std::size_t>(id)];
      double a = std::atan2((p.y() - hole.centre.y()) / hole.b, (p.x() - hole.centre.x()) / hole.a);
      return a < 0 ? a + 2 * kPi : a;
    };
    std::sort(rims[static_cast<std::size_t>(h)].begin(), rims[static_cast<std::size_t>(h)].end(),
              [&](int x, int y) { return angle(x) < angle(y); });
  }
  // Relax the skin around the mouth rim (uniform Laplacian in x/y, rim fixed, then back onto the
  // head surface) so that the cut does not leave skinny triangles.
  {
    std::vector<std::vector<int>> nb(pts.size());
    for (const auto& t : tris) {
      for (int k = 0; k < 3; ++k) nb[static_cast<std::size_t>(t[k])].push_back(t[(k + 1) % 3]), nb[static_cast<std::size_t>(t[k])].push_back(t[(k + 2) % 3]);
    }
    std::vector<int> band;
    for (std::size_t k = 0; k < pts.size(); ++k) {
      if (hole_of[k] < 0 && touches[k] != 2 && pts[k].z() > 0.03 && mouth.radius(pts[k]) < 1.9) band.push_back(static_cast<int>(k));
    }
    for (int it = 0; it < 8; ++it) {
      for (int k : band) {
        Eigen::Vector2d avg = Eigen::Vector2d::Zero();
        for (int n : nb[static_cast<std::size_t>(k)]) avg += pts[static_cast<std::size_t>(n)].head<2>();
        avg /= static_cast<double>(nb[static_cast<std::size_t>(k)].size());
        const double w = 0.5 * (1.0 - smoothstep(1.3, 1.9, mouth.radius(pts[static_cast<std::size_t>(k)])));
        pts[static_cast<std::size_t>(k)].head<2>() = (1.0 - w) * pts[static_cast<std::size_t>(k)].head<2>() + w * avg;
      }
    }
    for (int k : band) pts[static_cast<std::size_t>(k)].z() = front_z(pts[static_cast<std::size_t>(k)].x(), pts[static_cast<std::size_t>(k)].y());
    for (int k : rims[2]) pts[static_cast<std::size_t>(k)].z() = front_z(pts[static_cast<std::size_t>(k)].x(), pts[static_cast<std::size_t>(k)].y());
  }
  // Compact: drop vertices inside holes.
  std::vector<int> remap(pts.size(), -1);
  std::vector<Eigen::Vector3d> kept;
  for (std::size_t k = 0; k < pts.size(); ++k) {
    if (hole_of[k] < 0) {
      remap[k] = static_cast<int>(kept.size());
      kept.push_back(pts[k]);
    }
  }
  for (auto& t : tris) {
    for (auto& id : t) id = remap[static_cast<std::size_t>(id)];
  }
  for (auto& rim : rims) {
    for (auto& id : rim) id = remap[static_cast<std::size_t>(id)];
  }
  pts = std::move(kept);
  const int skin_count = static_cast<int>(pts.size());
  const int top_of_head = remap[static_cast<std::size_t>(top_pole)];

  Face face;
  Rig& rig = face.rig;
  std::vector<Material> materials(pts.size(), Material::Skin);

  // ---- 3. eye sockets and eyeballs ----
  for (int e = 0; e < 2; ++e) {
    const auto& c = eye_c[static_cast<std::size_t>(e)];
    const auto& rim = rims[static_cast<std::size_t>(e)];
    const int cap = static_cast<int>(pts.size());
    pts.push_back(c - Eigen::Vector3d(0, 0, 1.2 * kEyeballR));
    materials.push_back(Material::Skin);
    for (std::size_t k = 0; k < rim.size(); ++k) tris.push_back({rim[k], rim[(k + 1) % rim.size()], cap});
    // UV sphere with its pole looking forward (+z) so iris/pupil are rings.
    Eye& eye = rig.eyes[static_cast<std::size_t>(e)];
    eye.centre = c;
    eye.radius = kEyeballR;
    const int rings = 11, segs = 18;
    const int front = static_cast<int>(pts.size());
    pts.push_back(c + Eigen::Vector3d(0, 0, kEyeballR));
    materials.push_back(Material::Pupil);
    eye.eyeball_vertices.push_back(front);
    std::vector<int> ring_start;
    for (int r = 1; r <= rings; ++r) {
      const double polar = kPi * r / (rings + 1) * (r <= 3 ? 0.8 : 1.0);
      ring_start.push_back(static_cast<int>(pts.size()));
      for (int s = 0; s < segs; ++s) {
        const double az = 2 * kPi * s / segs;
        pts.push_back(c + kEyeballR * Eigen::Vector3d(std::sin(polar) * std::cos(az), std::sin(polar) * std::sin(az), std::cos(polar)));
        eye.eyeball_vertices.push_back(static_cast<int>(pts.size()) - 1);
        materials.push_back(polar < 0.2 ? Material::Pupil : polar < 0.5 ? Material::Iris : Material::EyeWhite);
      }
    }
    const int back = static_cast<int>(pts.size());
    pts.push_back(c - Eigen::Vector3d(0, 0, kEyeballR));
    materials.push_back(Material::EyeWhite);
    eye.eyeball_vertices.push_back(back);
    // Orientation: seen from the front (+z), azimuth increases counter-clockwise.
    for (int s = 0; s < segs; ++s) tris.push_back({front, ring_start[0] + s, ring_start[0] + (s + 1) % segs});
    for (int r = 0; r + 1 < rings; ++r) {
      for (int s = 0; s < segs; ++s) {
        const int a = ring_start[static_cast<std::size_t>(r)] + s, b = ring_start[static_cast<std::size_t>(r)] + (s + 1) % segs;
        const int c2 = ring_start[static_cast<std::size_t>(r + 1)] + (s + 1) % segs, d = ring_start[static_cast<std::size_t>(r + 1)] + s;
        tris.push_back({a, d, c2});
        tris.push_back({a, c2, b});
      }
    }
    for (int s = 0; s < segs; ++s) tris.push_back({back, ring_start.back() + (s + 1) % segs, ring_start.back() + s});
    eye.close_angle = 0.80;
    eye.open_angle = 0.26;  // AU5 shows the white above the iris (was 0.18, issue 14)
    eye.yaw_limit = 0.55;
    eye.pitch_limit = 0.38;
  }

  // ---- 4. lips (thesis §2.3.2) ----
  LipGrid& lips = rig.lips;
  lips.centre = {0.0, kMouthCy, 0.0};
  {
    // Per row: x scale, upper y scale, lower y scale, z offset (m) relative to the face surface.
    struct Row { double sx, up, down, dz; };
    const Row rows[LipGrid::kAcross] = {{1.00, 1.00, 1.00, 0.0000}, {0.97, 0.78, 0.80, 0.0016},
                                        {0.945, 0.50, 0.52, 0.0025}, {0.925, 0.22, 0.24, 0.0019},
                                        {0.91, 0.02, 0.02, 0.0004}, {0.86, 0.10, 0.12, -0.0060}};
    const double contact_y = kMouthCy + 0.0012;  // upper lip a little thinner than the lower
    lips.control_points.resize(LipGrid::kAround * LipGrid::kAcross);
    for (int r = 0; r < LipGrid::kAcross; ++r) {
      for (int c = 0; c < LipGrid::kAround; ++c) {
        const double t = 2 * kPi * c / LipGrid::kAround;
        const double st = std::sin(t);
        const Row& row = rows[r];
        const double x = kMouthA * row.sx * std::cos(t);
        double y;
        // flatter than an ellipse: |sin|^0.75 widens the lips towards the corners
        const double sh = (st >= 0 ? 1.0 : -1.0) * std::pow(std::abs(st), 0.75);
        if (r == 0) {
          y = kMouthCy + kMouthB * st;
        } else {
          const double span = st >= 0 ? (kMouthCy + kMouthB - contact_y) : (contact_y - (kMouthCy - kMouthB));
          y = contact_y + span * (st >= 0 ? row.up : row.down) * sh;
        }
        // face surface height under the lip border, then the lip's own relief (fuller in the middle)
        const double zf = front_z(x, y);
        const double fullness = 0.55 + 0.45 * std::pow(std::abs(st), 0.7);
        const double z = zf + row.dz * (r == 0 ? 0.0 : fullness);
        lips.control_points[static_cast<std::size_t>(r * LipGrid::kAround + c)] = {x, y, z};
      }
    }
    // Row 0 sits exactly under the rim: use the rim's own depth for a tight stitch.
    lips.samples_around = 48;
    lips.samples_across = 8;
    lips.first_vertex = static_cast<int>(pts.size());
    const LipSampler sampler(lips.samples_around, lips.samples_across);
    Vertices samples(sampler.sample_count(), 3);
    sampler.evaluate(lips.control_points, samples, 0);
    for (long s = 0; s < samples.rows(); ++s) {
      pts.push_back(samples.row(s));
      // the border row is skin: the zipper triangles to the rim then carry no colour edge; the two
      // innermost rows, which roll into the mouth, are its dark interior (seen when the lips part)
      const long row = s / lips.samples_around;
      materials.push_back(row == 0                         ? Material::Skin
                          : row >= lips.samples_across - 2 ? Material::MouthInterior
                                                           : Material::Lip);
    }
    const int na = lips.samples_around, nac = lips.samples_across;
    auto L = [&](int i, int j) { return lips.first_vertex + j * na + ((i % na) + na) % na; };
    for (int j = 0; j + 1 < nac; ++j) {
      for (int i = 0; i < na; ++i) {
        tris.push_back({L(i, j), L(i + 1, j), L(i + 1, j + 1)});
        tris.push_back({L(i, j), L(i + 1, j + 1), L(i, j + 1)});
      }
    }
    // Stitch row 0 to the mouth rim: zipper by angle.
    const auto& rim = rims[2];
    auto ang = [&](const Eigen::Vector3d& p) {
      double a = std::atan2((p.y() - kMouthCy) / kMouthB, p.x() / kMouthA);
      return a < 0 ? a + 2 * kPi : a;
    };
    const int nb = static_cast<int>(rim.size());
    int bi = 0, li = 0;
    // Start both loops at the first element after angle 0.
    while (bi < nb + 0 && li < na) {
      const double ab = ang(pts[static_cast<std::size_t>(rim[static_cast<std::size_t>((bi + 1) % nb)])]) + (bi + 1 >= nb ? 2 * kPi : 0.0);
      const double al = ang(pts[static_cast<std::size_t>(L(li + 1, 0))]) + (li + 1 >= na ? 2 * kPi : 0.0);
      if (ab <= al) {
        tris.push_back({rim[static_cast<std::size_t>(bi)], rim[static_cast<std::size_t>((bi + 1) % nb)], L(li, 0)});
        ++bi;
      } else {
        tris.push_back({L(li + 1, 0), L(li, 0), rim[static_cast<std::size_t>(bi % nb)]});
        ++li;
      }
    }
    while (bi < nb) {
      tris.push_back({rim[static_cast<std::size_t>(bi)], rim[static_cast<std::size_t>((bi + 1) % nb)], L(li, 0)});
      ++bi;
    }
    while (li < na) {
      tris.push_back({L(li + 1, 0), L(li, 0), rim[static_cast<std::size_t>(bi % nb)]});
      ++li;
    }
    // Mouth cavity cap.
    const int cavity = static_cast<int>(pts.size());
    pts.push_back({0.0, kMouthCy, lips.control_points[static_cast<std::size_t>(5 * LipGrid::kAround)].z() - 0.03});
    materials.push_back(Material::MouthInterior);
    for (int i = 0; i < na; ++i) tris.push_back({L(i, nac - 1), L(i + 1, nac - 1), cavity});
  }
  const int lip_begin = lips.first_vertex;

  // ---- 4b. teeth (issue 14): an upper and a lower row seen when the lips part, as curved strips
  // behind the lips' inner edge; the upper row is fixed to the skull, the lower one rides on the
  // jaw.
  std::vector<int> lower_teeth;
  {
    const double contact_y = kMouthCy + 0.0012;
    const double z0 =
        front_z(0.0, contact_y) - 0.0110;  // incisors' front, behind the inner lip rows
    const int n = 18;  // columns; every third one is a gap between two teeth (set back 0.8 mm)
    // Each row is a closed slab (front and back grids 2.5 mm apart, joined along the border) so
    // that the head stays a closed surface.
    auto add_strip = [&](double y_top, double y_bottom, double back, std::vector<int>* ids) {
      const int rows = 3, cols = n + 1;
      const int first = static_cast<int>(pts.size());
      for (int side = 0; side < 2; ++side) {
        for (int j = 0; j < rows; ++j) {
          const double y = y_top + (y_bottom - y_top) * j / (rows - 1);
          for (int i = 0; i < cols; ++i) {
            const double x = -0.019 + 0.038 * i / n;
            const double gap = side == 0 && i % 3 == 0 ? 0.0008 : 0.0;
            pts.push_back({x, y, z0 - back - gap - 32.0 * x * x - 0.0025 * side});
            materials.push_back(Material::Teeth);
            if (ids) ids->push_back(static_cast<int>(pts.size()) - 1);
          }
        }
      }
      auto F = [&](int j, int i) { return first + j * cols + i; };
      auto B = [&](int j, int i) { return first + rows * cols + j * cols + i; };
      // a quad a-b-c-d split in two, turned so that its normal points along `out`
      auto quad = [&](int a, int b, int c, int d, const Eigen::Vector3d& out) {
        const Eigen::Vector3d n1 =
            (pts[static_cast<std::size_t>(b)] - pts[static_cast<std::size_t>(a)])
                .cross(pts[static_cast<std::size_t>(c)] - pts[static_cast<std::size_t>(a)]);
        if (n1.dot(out) >= 0.0)
          tris.push_back({a, b, c}), tris.push_back({a, c, d});
        else
          tris.push_back({a, c, b}), tris.push_back({a, d, c});
      };
      const Eigen::Vector3d ex(1, 0, 0), ey(0, 1, 0), ez(0, 0, 1);
      for (int j = 0; j + 1 < rows; ++j) {
        for (int i = 0; i + 1 < cols; ++i) {
          quad(F(j, i), F(j + 1, i), F(j + 1, i + 1), F(j, i + 1), ez);
          quad(B(j, i), B(j + 1, i), B(j + 1, i + 1), B(j, i + 1), -ez);
        }
        quad(F(j, 0), F(j + 1, 0), B(j + 1, 0), B(j, 0), -ex);
        quad(F(j, n), F(j + 1, n), B(j + 1, n), B(j, n), ex);
      }
      for (int i = 0; i + 1 < cols; ++i) {
        quad(F(0, i), F(0, i + 1), B(0, i + 1), B(0, i), ey);
        quad(F(rows - 1, i), F(rows - 1, i + 1), B(rows - 1, i + 1), B(rows - 1, i), -ey);
      }
    };
    // the edges stay clear of the lips' contact line, so closed lips show a dark seam, not teeth
    add_strip(contact_y + 0.0090, contact_y + 0.0022, 0.0, nullptr);
    add_strip(contact_y - 0.0030, contact_y - 0.0100, 0.0012, &lower_teeth);
  }
  // ---- 5. mesh ----
  face.mesh.vertices.resize(static_cast<long>(pts.size()), 3);
  for (std::size_t k = 0; k < pts.size(); ++k) face.mesh.vertices.row(static_cast<long>(k)) = pts[k];
  face.mesh.faces.resize(static_cast<long>(tris.size()), 3);
  for (std::size_t f = 0; f < tris.size(); ++f) face.mesh.faces.row(static_cast<long>(f)) << tris[f][0], tris[f][1], tris[f][2];
  rig.mesh_file = "generic_face.obj";
  rig.vertex_count = pts.size();

  // ---- 6. regions (thesis §2.3.1) ----
  rig.regions.assign(pts.size(), Region::Rest);
  const double middle_top = 0.009;  // boundary middle/upper face (just above the eye opening)
  for (int k = 0; k < skin_count; ++k) {
    const auto& p = pts[static_cast<std::size_t>(k)];
    if (p.z() < 0.025 || std::abs(p.x()) > 0.072 || p.y() > 0.085 || p.y() < -0.135) continue;
    const bool right = p.x() <= 0.0;
    const int e = right ? 0 : 1;
    const double r = eye_holes[static_cast<std::size_t>(e)].radius(p);
    Region reg;
    if (r < 2.0 && p.y() < 0.02) {
      reg = p.y() >= 0.0 ? (right ? Region::RightUpperEyelid : Region::LeftUpperEyelid)
                         : (right ? Region::RightLowerEyelid : Region::LeftLowerEyelid);
    } else if (p.y() >= middle_top) {
      reg = right ? Region::RightUpperFace : Region::LeftUpperFace;
    } else if (p.y() >= kMouthCy) {
      reg = right ? Region::RightMiddleFace : Region::LeftMiddleFace;
    } else {
      reg = right ? Region::RightLowerFace : Region::LeftLowerFace;
    }
    rig.regions[static_cast<std::size_t>(k)] = reg;
  }

  // ---- 7. materials: brows and hair ----
  for (int k = 0; k < skin_count; ++k) {
    const auto& p = pts[static_cast<std::size_t>(k)];
    if (p.z() > 0.03 && brow_distance(p.x(), p.y()) < 0.0)
      materials[static_cast<std::size_t>(k)] = Material::Brow;
    if (p.y() > hair_line(p.x(), p.z())) materials[static_cast<std::size_t>(k)] = Material::Hair;
  }
  rig.materials = materials;

  // ---- 8. eyelids ----
  for (int e = 0; e < 2; ++e) {
    Eye& eye = rig.eyes[static_cast<std::size_t>(e)];
    for (int k = 0; k < skin_count; ++k) {
      const auto& p = pts[static_cast<std::size_t>(k)];
      if (p.z() < 0.03) continue;
      const double r = eye_holes[static_cast<std::size_t>(e)].radius(p);
      if (r > 2.3) continue;
      const double w = 1.0 - smoothstep(1.35, 2.3, r);
      if (w <= 0.0) continue;
      if (p.y() >= 0.0) {
        eye.upper_lid.push_back(k);
        eye.upper_lid_weights.push_back(w);
      } else {
        eye.lower_lid.push_back(k);
        eye.lower_lid_weights.push_back(w);
      }
    }
  }

  // ---- 9. jaw (thesis §2.4.4) ----
  rig.jaw.pivot = {0.0, -0.022, -0.005};
  rig.jaw.max_angle = 0.40;
  for (int k = 0; k < skin_count; ++k) {
    const auto& p = pts[static_cast<std::size_t>(k)];
    if (p.y() > kMouthCy + 0.002) continue;
    double w = smoothstep(kMouthCy + 0.002, kMouthCy - 0.012, p.y());
    w *= 1.0 - smoothstep(0.035, 0.075, std::abs(p.x()));
    w *= smoothstep(-0.02, 0.04, p.z());
    if (w > 1e-3) {
      rig.jaw.vertices.push_back(k);
      rig.jaw.weights.push_back(std::min(1.0, w));
    }
  }
  for (int v : lower_teeth) {
    rig.jaw.vertices.push_back(v);
    rig.jaw.weights.push_back(1.0);
  }
  rig.head_pivot = {0.0, -0.09, -0.02};

  // ---- 10. landmarks ----
  std::vector<int> front_skin;
  for (int k = 0; k < skin_count; ++k) {
    if (pts[static_cast<std::size_t>(k)].z() > 0.02) front_skin.push_back(k);
  }
  std::vector<int> lip_outer, lip_inner;
  for (int i = 0; i < lips.samples_around; ++i) {
    lip_outer.push_back(lip_begin + i);
    lip_inner.push_back(lip_begin + 5 * lips.samples_around + i);
  }
  // iBUG 0–16: the subject's right (−x) ear level -> chin -> left (+x) ear level, like 36 (right eye
  // outer) and 48 (right mouth corner); earlier versions ran it from +x, mirroring 0–16 and jaw_r/jaw_l.
  auto jawline = [&](double t) {  // t in [0,1]
    const double a = kPi * (1.0 - t);  // angle from +x: π at t = 0 (−x), 0 at t = 1 (+x)
    const double x = 0.068 * std::cos(a);
    const double y = -0.005 - 0.112 * std::sin(a);
    return std::pair<double, double>(x, y);
  };
  for (int i = 0; i <= 16; ++i) {
    auto [x, y] = jawline(i / 16.0);
    rig.ibug68.push_back(nearest_xy(pts, front_skin, x, y));
  }
  const double brow[5][2] = {{-0.048, 0.016}, {-0.040, 0.022}, {-0.031, 0.025}, {-0.022, 0.024}, {-0.013, 0.021}};
  for (auto& b : brow) rig.ibug68.push_back(nearest_xy(pts, front_skin, b[0], b[1]));
  for (int i = 4; i >= 0; --i) rig.ibug68.push_back(nearest_xy(pts, front_skin, -brow[i][0], brow[i][1]));
  for (int i = 0; i < 4; ++i) rig.ibug68.push_back(nearest_xy(pts, front_skin, 0.0, 0.004 - 0.0125 * i));
  const double nostril[5][2] = {{-0.011, -0.041}, {-0.006, -0.043}, {0.0, -0.044}, {0.006, -0.043}, {0.011, -0.041}};
  for (auto& n : nostril) rig.ibug68.push_back(nearest_xy(pts, front_skin, n[0], n[1]));
  for (int e = 0; e < 2; ++e) {
    // iBUG eye order: right eye 36 outer, 37-38 upper, 39 inner, 40-41 lower; left eye 42 inner, ...
    // in image order (x increasing): outer→inner for the right eye, inner→outer for the left
    const double cx = e == 0 ? -kEyeX : kEyeX;
    const double a = kEyeHoleA * 1.02, b = kEyeHoleB * 1.05;
    const double pts6[6][2] = {{-a, 0}, {-a * 0.4, b * 0.95}, {a * 0.4, b * 0.95}, {a, 0}, {a * 0.4, -b * 0.95}, {-a * 0.4, -b * 0.95}};
    for (auto& q : pts6) rig.ibug68.push_back(nearest_xy(pts, front_skin, cx + q[0], q[1]));
  }
  // Mouth outer 48–59 and inner 60–67 on the lip samples (counter-clockwise from the right corner in
  // image space = clockwise seen by the subject; on our grid angle π is the right corner).
  auto lip_at = [&](const std::vector<int>& ring, double angle) {
    const int n = lips.samples_around;
    int idx = static_cast<int>(std::lround(angle / (2 * kPi) * n)) % n;
    if (idx < 0) idx += n;
    return ring[static_cast<std::size_t>(idx)];
  };
  // iBUG outer lip: 48 right corner, 49–53 along the upper lip to 54 left corner, 55–59 back along the lower.
  for (int i = 0; i < 12; ++i) rig.ibug68.push_back(lip_at(lip_outer, kPi - 2 * kPi * i / 12.0));
  const double inner_angles[8] = {kPi, 3 * kPi / 4, kPi / 2, kPi / 4, 0.0, -kPi / 4, -kPi / 2, -3 * kPi / 4};
  for (double a : inner_angles) rig.ibug68.push_back(lip_at(lip_inner, a));

  auto named = [&](const std::string& name, int v) { rig.retarget_landmarks.push_back({name, v}); };
  named("top_of_head", top_of_head);
  named("nose_tip", nearest_xy(pts, front_skin, 0.0, -0.037));
  named("nose_root", nearest_xy(pts, front_skin, 0.0, 0.006));
  named("chin", nearest_xy(pts, front_skin, 0.0, -0.112));
  named("mouth_corner_r", lip_at(lip_outer, kPi));
  named("mouth_corner_l", lip_at(lip_outer, 0.0));
  named("upper_lip_centre", lip_at(lip_outer, kPi / 2));
  named("lower_lip_centre", lip_at(lip_outer, -kPi / 2));
  named("eye_outer_r", rig.ibug68[36]);
  named("eye_inner_r", rig.ibug68[39]);
  named("eye_inner_l", rig.ibug68[42]);
  named("eye_outer_l", rig.ibug68[45]);
  named("brow_centre_r", rig.ibug68[19]);
  named("brow_centre_l", rig.ibug68[24]);
  named("forehead_centre", nearest_xy(pts, front_skin, 0.0, 0.055));
  named("cheek_r", nearest_xy(pts, front_skin, -0.045, -0.03));
  named("cheek_l", nearest_xy(pts, front_skin, 0.045, -0.03));
  named("jaw_r", rig.ibug68[3]);
  named("jaw_l", rig.ibug68[13]);
  const std::vector<Eigen::Vector3d> skin(pts.begin(), pts.begin() + skin_count);
  named("ear_r", nearest(skin, {-0.09, -0.005, -0.005}));
  named("ear_l", nearest(skin, {0.09, -0.005, -0.005}));
  named("back_of_head", nearest(skin, {0.0, 0.0, -0.12}));

  // ---- 11. muscles (Table 2.1, Appendix B), right side; mirrored for the left ----
  auto P = [&](double x, double y, double depth) { return Eigen::Vector3d(x, y, front_z(x, y) - depth); };
  struct Def {
    const char* parameter;
    const char* suffix;
    Eigen::Vector3d head, tail;
    double omega, rs_f, rf_f, k;
    std::vector<Region> regions;  // right-side regions
    bool lips;
    int nw;
    double wh;
  };
  using R = Region;
  const std::vector<Def> defs = {
      {"zygomatic_major",
       "",
       P(-0.066, -0.026, 0.010),
       P(-0.026, -0.066, 0.002),
       0.42,
       0.75,
       1.35,
       0.0221,  // 17 mm until session 7: the smile at 0.9 read neutral as often as happy
                // (docs/muscles.md)
       {R::RightLowerFace, R::RightMiddleFace},
       true,
       0,
       0.0},
      {"zygomatic_minor",
       "",
       P(-0.046, -0.016, 0.008),
       P(-0.017, -0.058, 0.002),
       0.35,
       0.75,
       1.3,
       0.0195,  // with the major (×1.3, session 7)
       {R::RightMiddleFace},
       true,
       0,
       0.0},
      {"triangularis",
       "",
       P(-0.046, -0.116, 0.018),
       P(-0.026, -0.068, 0.002),
       0.40,
       0.75,
       1.3,
       0.014,
       {R::RightLowerFace, R::RightMiddleFace},
       true,
       0,
       0.0},
      {"risorius",
       "",
       P(-0.070, -0.072, 0.015),
       P(-0.026, -0.067, 0.002),
       0.30,
       0.8,
       1.3,
       0.011,
       {R::RightLowerFace, R::RightMiddleFace},
       true,
       0,
       0.0},
      {"depressor_labii",
       "",
       P(-0.016, -0.106, 0.008),
       P(-0.010, -0.076, 0.002),
       0.45,
       0.75,
       1.35,
       0.0100,
       {R::RightLowerFace},
       true,
       0,
       0.0},
      {"mentalis",
       "",
       P(-0.006, -0.082, 0.012),
       P(-0.006, -0.106, 0.002),
       0.55,
       0.75,
       1.4,
       0.006,
       {R::RightLowerFace},
       true,
       2,
       0.0006},
      {"frontalis_medialis",
       "_0",
       P(-0.007, 0.080, 0.006),
       P(-0.008, 0.022, 0.001),
       0.40,
       0.75,
       1.2,
       0.0120,
       {R::RightUpperFace, R::LeftUpperFace, R::RightUpperEyelid, R::RightMiddleFace,
        R::LeftMiddleFace},
       false,
       3,
       0.0016},
      {"frontalis_medialis",
       "_1",
       P(-0.018, 0.080, 0.006),
       P(-0.019, 0.022, 0.001),
       0.40,
       0.75,
       1.2,
       0.0120,
       {R::RightUpperFace, R::LeftUpperFace, R::RightUpperEyelid, R::RightMiddleFace,
        R::LeftMiddleFace},
       false,
       3,
       0.0016},
      {"frontalis_lateralis",
       "_0",
       P(-0.032, 0.080, 0.006),
       P(-0.034, 0.022, 0.001),
       0.40,
       0.75,
       1.2,
       0.0154,  // issue 14 round 4: 11 -> 15.4 mm, the outer brow rises with the inner (AU2)
       {R::RightUpperFace, R::RightUpperEyelid, R::RightMiddleFace},
       false,
       3,
       0.0016},
      {"frontalis_lateralis",
       "_1",
       P(-0.051, 0.078, 0.006),
       P(-0.053, 0.020, 0.001),
       0.40,
       0.75,
       1.2,
       0.0168,  // 12 -> 16.8 mm (as _0: × 1.4)
       {R::RightUpperFace, R::RightUpperEyelid, R::RightMiddleFace},
       false,
       3,
       0.0016},
      {"levator_labii_nasi",
       "",
       P(-0.010, 0.004, 0.006),
       P(-0.015, -0.040, 0.002),
       0.28,
       0.8,
       1.35,
       0.0065,
       {R::RightMiddleFace, R::RightUpperFace},
       true,
       3,
       0.0005},
      {"levator_labii_superioris",
       "",
       P(-0.027, -0.016, 0.006),
       P(-0.014, -0.058, 0.002),
       0.32,
       // session 8: the zone reaches the upper lip's middle (rs, rf 0.8, 1.3 → 1.15, 1.6 of the
       // length), so AU10 raises the upper lip and bares the upper teeth (the middle rose 1.3 mm,
       // now 5.3 mm on the default head); the solver keeps it off the lower lip
       // (reaches_lip_column)
       1.15,
       1.6,
       0.0100,
       {R::RightMiddleFace, R::RightUpperFace},
       true,
       0,
       0.0},
      {"depressor_supercilii",
       "",
       P(-0.008, -0.002, 0.006),
       P(-0.015, 0.023, 0.001),
       0.40,
       0.8,
       1.35,
       0.0090,  // AU4 group ×2 (session 7): a full AU4 lowers the brow by several millimetres
       {R::RightMiddleFace, R::RightUpperFace},
       false,
       0,
       0.0},
      {"corrugator_supercilii",
       "",
       // Origin at the medial end of the superciliary arch, 8 mm above the eye centres (issue 14,
       // session 6; was 18 mm, level with the brow's lower edge, so the muscle drew the brow
       // inwards almost horizontally): "the eyebrow wrinkler which depresses the middle portion of
       // the eyebrows" (thesis Appendix B, muscle 14); origin medial superciliary arch, insertion
       // the skin of the middle of the brow, pulling it down and in (Gray's Anatomy, corrugator
       // supercilii).
       P(-0.005, 0.008, 0.007),
       P(-0.030, 0.025, 0.001),
       // session 7: the zone reaches the lateral brow (rs, rf 1.6 times session 6's 20.8 / 33.8 mm,
       // a 0.6 rad cone) and the strength doubles, so that the whole brow comes down and in (AU4),
       // not only its middle: the skin between the insertion and the brow's tail follows the
       // insertion in a face, and Waters' zone is the model's only way to say so
       0.60,
       1.101,
       1.789,
       0.0160,
       {R::RightMiddleFace, R::RightUpperFace},
       false,
       2,
       0.0006},
      {"depressor_glabellae",
       "",
       P(-0.003, -0.014, 0.006),
       P(-0.004, 0.020, 0.001),
       0.30,
       0.8,
       1.3,
       0.0045,  // unchanged in session 7: it is also AU9's brow (faceweights), and its nose wrinkle
       {R::RightMiddleFace, R::RightUpperFace},
       false,
       2,
       0.0005},
  };
  for (int side = 0; side < 2; ++side) {
    const double mx = side == 0 ? 1.0 : -1.0;
    const std::string s = side == 0 ? "_r" : "_l";
    for (const auto& d : defs) {
      MuscleSpec m;
      m.parameter = std::string(d.parameter) + s;
      m.name = m.parameter + d.suffix;
      m.kind = MuscleKind::Vector;
      m.head = {mx * d.head.x(), d.head.y(), d.head.z()};
      m.tail = {mx * d.tail.x(), d.tail.y(), d.tail.z()};
      const double len = (m.tail - m.head).norm();
      m.omega = d.omega;
      m.rs = d.rs_f * len;
      m.rf = d.rf_f * len;
      m.k = d.k;
      for (auto r : d.regions) {
        const int ri = static_cast<int>(r);
        m.regions.push_back(side == 0 ? r : static_cast<Region>(ri < 5 ? ri + 5 : ri >= 5 && ri < 10 ? ri - 5 : ri));
      }
      m.moves_lips = d.lips;
      m.wrinkle_count = d.nw;
      m.wrinkle_height = d.wh;
      rig.muscles.push_back(m);
    }
    // Orbicularis Oculi, pars orbitalis: a Waters sphincter around the eye (thesis §2.4.3).
    MuscleSpec oo;
    oo.parameter = "orbicularis_oculi_orbitalis" + s;
    oo.name = oo.parameter;
    oo.kind = MuscleKind::Sphincter;
    oo.head = {-mx * kEyeX, 0.0, eye_c[static_cast<std::size_t>(side)].z()};
    oo.semi_axes = {0.030, 0.026};
    oo.k = 0.0045;
    oo.regions = side == 0 ? std::vector<Region>{Region::RightMiddleFace, Region::RightUpperFace}
                           : std::vector<Region>{Region::LeftMiddleFace, Region::LeftUpperFace};
    oo.wrinkle_count = 0;
    rig.muscles.push_back(oo);
  }
  return face;
}

namespace {

// Paint frame: frontal (x, y) of the neutral face, 0.25 mm per texel.
constexpr double kPaintX0 = -0.086, kPaintX1 = 0.086, kPaintY0 = -0.140, kPaintY1 = 0.128;
constexpr double kPaintTexel = 0.00025;
const Eigen::Vector3f kPaintSkin(0.87f, 0.69f, 0.58f);
const Eigen::Vector3f kPaintBrow(0.17f, 0.115f, 0.085f);
const Eigen::Vector3f kPaintHair(0.25f, 0.17f, 0.115f);

Paint build_generic_face_paint() {
  const Face face = make_generic_face();
  Paint paint;
  paint.width = static_cast<int>(std::lround((kPaintX1 - kPaintX0) / kPaintTexel));
  paint.height = static_cast<int>(std::lround((kPaintY1 - kPaintY0) / kPaintTexel));
  // Depth of the head's front surface on a 1 mm grid (bilinear in between) for the hairline, which
  // depends on the azimuth; only needed where hair can be (y > 1 cm).
  const double zs = 0.001;
  const int zw = static_cast<int>(std::ceil((kPaintX1 - kPaintX0) / zs)) + 1;
  const int zh = static_cast<int>(std::ceil((kPaintY1 - 0.010) / zs)) + 1;
  std::vector<double> zgrid(static_cast<std::size_t>(zw) * zh);
  for (int j = 0; j < zh; ++j)
    for (int i = 0; i < zw; ++i)
      zgrid[static_cast<std::size_t>(j) * zw + i] = front_z(kPaintX0 + i * zs, 0.010 + j * zs);
  auto z_at = [&](double x, double y) {
    const double fx = std::clamp((x - kPaintX0) / zs, 0.0, zw - 1.001),
                 fy = std::clamp((y - 0.010) / zs, 0.0, zh - 1.001);
    const int i = static_cast<int>(fx), j = static_cast<int>(fy);
    const double a = fx - i, b = fy - j;
    auto g = [&](int ii, int jj) { return zgrid[static_cast<std::size_t>(jj) * zw + ii]; };
    return (1 - b) * ((1 - a) * g(i, j) + a * g(i + 1, j)) +
           b * ((1 - a) * g(i, j + 1) + a * g(i + 1, j + 1));
  };
  const double soft = 0.0003;  // half width of the anti-aliased edges, m
  paint.texels.resize(static_cast<std::size_t>(paint.width) * paint.height);
  for (int j = 0; j < paint.height; ++j) {
    const double y = kPaintY0 + (j + 0.5) * kPaintTexel;
    for (int i = 0; i < paint.width; ++i) {
      const double x = kPaintX0 + (i + 0.5) * kPaintTexel;
      Eigen::Vector3f c = kPaintSkin;
      // brows inside the Brow material's band, slimmer than it (the band is as wide as the coarse
      // grid needs): 2.4 mm half height medially tapering to 1.0 mm at the tail, rounded head, soft
      // edges; a little lighter towards the tail
      {
        const double ax = std::abs(x);
        const double t = std::clamp((ax - 0.011) / (0.050 - 0.011), 0.0, 1.0);
        const double half = 0.0024 - 0.0014 * t * t;
        // a gentle arch peaking two thirds of the way out (t^1·(1 − t)^0.55 peaks at t = 0.645)
        const double arch = t * std::pow(1.0 - t, 0.55) / 0.3652;
        const double centre = 0.0203 + 0.0045 * arch - 0.0010 * t;
        const double ends = smoothstep(0.0100, 0.0150, ax) * (1.0 - smoothstep(0.0460, 0.0505, ax));
        const double brow =
            ends * (1.0 - smoothstep(half - 2 * soft, half + soft, std::abs(y - centre)));
        if (brow > 0.0) c += static_cast<float>(brow * (0.85 - 0.3 * t)) * (kPaintBrow - c);
      }
      if (y > 0.010) {
        const double hair = smoothstep(-2 * soft, 2 * soft, y - hair_line(x, z_at(x, y)));
        c += static_cast<float>(hair) * (kPaintHair - c);
      }
      paint.texels[static_cast<std::size_t>(j) * paint.width + i] = {c.x(), c.y(), c.z(), 1.0f};
    }
  }
  // Coordinates: skin/brow/hair vertices of the front half (not the eye-socket caps) and the lips'
  // border row (skin stitched to the rim); lips, eyes and the back of the head keep vertex colours.
  const auto& X = face.mesh.vertices;
  const auto& rig = face.rig;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  paint.uv.assign(static_cast<std::size_t>(X.rows()), Eigen::Vector2f(nan, nan));
  std::vector<char> socket(static_cast<std::size_t>(X.rows()), 0);
  for (const auto& eye : rig.eyes) {
    for (long v = 0; v < X.rows(); ++v)
      if ((X.row(v).transpose() - (eye.centre - Eigen::Vector3d(0, 0, 1.2 * eye.radius))).norm() <
          1e-9)
        socket[static_cast<std::size_t>(v)] = 1;  // the cap closing the socket behind the eyeball
  }
  for (long v = 0; v < X.rows(); ++v) {
    const Material m = rig.materials[static_cast<std::size_t>(v)];
    if (m != Material::Skin && m != Material::Brow && m != Material::Hair) continue;
    if (X(v, 2) <= 0.0 || socket[static_cast<std::size_t>(v)]) continue;
    if (v >= rig.lips.first_vertex && X(v, 2) < front_z(X(v, 0), X(v, 1)) - 0.02)
      continue;  // mouth cavity
    paint.uv[static_cast<std::size_t>(v)] = {
        static_cast<float>((X(v, 0) - kPaintX0) / (kPaintX1 - kPaintX0)),
        static_cast<float>((X(v, 1) - kPaintY0) / (kPaintY1 - kPaintY0))};
  }
  paint.validate(static_cast<std::size_t>(X.rows()));
  return paint;
}

}  // namespace

const Paint& generic_face_paint() {
  static const Paint paint = build_generic_face_paint();
  return paint;
}

}  // namespace emoface::facemesh
