// Vertices driven by the lip B-spline surface through LipBinding (rig format 1.1).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "emoface/core/errors.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/muscles/solver.hpp"

namespace emoface::muscles {
namespace {

namespace fm = facemesh;

const fm::Face& face() {
  static const fm::Face f = fm::make_generic_face();
  return f;
}

// de Boor's algorithm for a cubic B-spline with knot vector `t` at x (independent of bspline.cpp).
Eigen::Vector3d de_boor(const std::vector<double>& t, const std::vector<Eigen::Vector3d>& c, double x) {
  constexpr int p = 3;
  const int n = static_cast<int>(c.size());
  int k = p;  // knot span: t[k] <= x < t[k+1], the last non-empty span at the end of the domain
  while (k + 1 < n && !(x < t[static_cast<std::size_t>(k + 1)])) ++k;
  std::vector<Eigen::Vector3d> d(c.begin() + (k - p), c.begin() + k + 1);
  for (int r = 1; r <= p; ++r) {
    for (int j = p; j >= r; --j) {
      const double a0 = t[static_cast<std::size_t>(j + k - p)], a1 = t[static_cast<std::size_t>(j + 1 + k - r)];
      const double alpha = (x - a0) / (a1 - a0);
      d[static_cast<std::size_t>(j)] = (1.0 - alpha) * d[static_cast<std::size_t>(j - 1)] + alpha * d[static_cast<std::size_t>(j)];
    }
  }
  return d[p];
}

// S(u, v): clamped cubic across (knots 0,0,0,0,1/3,2/3,1,1,1,1 on the 6 rows), then the periodic
// uniform cubic around (24 columns, extended by wrapping: Q_k = P[(k − 1) mod 24], knots 0, 1, 2, ...;
// parameter 24·u + 3) — the convention of thesis §2.3.2 as implemented (S(c/24, ·) = (P[c−1] + 4P[c] +
// P[c+1])/6 along a row).
Eigen::Vector3d surface(const std::vector<Eigen::Vector3d>& cps, double u, double v) {
  constexpr int na = fm::LipGrid::kAround, nr = fm::LipGrid::kAcross;
  const std::vector<double> across = {0, 0, 0, 0, 1.0 / 3, 2.0 / 3, 1, 1, 1, 1};
  std::vector<Eigen::Vector3d> column(nr), ring(na);
  for (int c = 0; c < na; ++c) {
    for (int r = 0; r < nr; ++r) column[static_cast<std::size_t>(r)] = cps[static_cast<std::size_t>(r * na + c)];
    ring[static_cast<std::size_t>(c)] = de_boor(across, column, v);
  }
  std::vector<Eigen::Vector3d> q;
  std::vector<double> knots;
  for (int k = 0; k < na + 3; ++k) q.push_back(ring[static_cast<std::size_t>(((k - 1) % na + na) % na)]);
  for (int k = 0; k < na + 7; ++k) knots.push_back(k);
  return de_boor(knots, q, na * u + 3.0);
}

TEST(DeBoorReference, MatchesTheUniformCubicAtAKnot) {
  // a hand-computable case: around only, all rows equal, S(c/24) = (P[c-1] + 4 P[c] + P[c+1]) / 6
  std::vector<Eigen::Vector3d> cps(144);
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 24; ++c) cps[static_cast<std::size_t>(r * 24 + c)] = Eigen::Vector3d(c * c, c, 1.0);
  }
  const Eigen::Vector3d s = surface(cps, 5.0 / 24, 0.37);
  EXPECT_NEAR(s.x(), (16.0 + 4 * 25.0 + 36.0) / 6.0, 1e-12);
  EXPECT_NEAR(s.y(), 5.0, 1e-12);
  // wrap-around at column 0: (P[23] + 4 P[0] + P[1]) / 6
  EXPECT_NEAR(surface(cps, 0.0, 0.5).x(), (529.0 + 0.0 + 1.0) / 6.0, 1e-12);
}

// A hand-made rig: 5×3 vertices on the default lip surface (u in [0.1, 0.3], v in [0.2, 0.8]), all
// bound; vertex 0 carries an offset, vertex 1 has weight 0.5 and rotates fully with the jaw.
struct HandMade {
  fm::Face face;
  std::vector<double> us, vs;
};

HandMade hand_made() {
  HandMade h;
  const auto& cps = face().rig.lips.control_points;
  auto& mesh = h.face.mesh;
  mesh.vertices.resize(15, 3);
  const Eigen::Vector3d offset0(0.001, -0.0005, 0.002);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 5; ++i) {
      const int k = j * 5 + i;
      h.us.push_back(0.1 + 0.05 * i);
      h.vs.push_back(0.2 + 0.3 * j);
      Eigen::Vector3d p = surface(cps, h.us.back(), h.vs.back());
      if (k == 0) p += offset0;
      mesh.vertices.row(k) = p.transpose();
    }
  }
  mesh.faces.resize(16, 3);
  int f = 0;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 4; ++i) {
      const int a = j * 5 + i, b = a + 1, c = a + 6, d = a + 5;
      mesh.faces.row(f++) << a, b, c;
      mesh.faces.row(f++) << a, c, d;
    }
  }
  fm::Rig& rig = h.face.rig;
  const fm::Rig& def = face().rig;
  rig.vertex_count = 15;
  rig.regions.assign(15, fm::Region::Rest);
  rig.materials.assign(15, fm::Material::Lip);
  rig.lips = def.lips;
  rig.lips.samples_in_mesh = false;
  rig.lips.first_vertex = 0;
  for (int k = 0; k < 15; ++k) {
    fm::LipBinding b;
    b.vertex = k;
    b.u = h.us[static_cast<std::size_t>(k)];
    b.v = h.vs[static_cast<std::size_t>(k)];
    if (k == 0) b.offset = offset0;
    if (k == 1) b.weight = 0.5;
    rig.lips.bound.push_back(b);
  }
  rig.jaw = def.jaw;
  rig.jaw.vertices = {1};
  rig.jaw.weights = {1.0};
  rig.eyes = def.eyes;
  for (auto& eye : rig.eyes) {
    eye.eyeball_vertices.clear(), eye.upper_lid.clear(), eye.lower_lid.clear();
    eye.upper_lid_weights.clear(), eye.lower_lid_weights.clear();
  }
  rig.head_pivot = def.head_pivot;
  rig.muscles = def.muscles;  // they move the lip control points; no vertex is in their regions
  return h;
}

std::vector<double> lip_values() {
  std::vector<double> v(kParameterCount, 0.0);
  v[parameter_index("masseter")] = 0.6;
  v[parameter_index("orbicularis_oris_funneler")] = 0.7;
  v[parameter_index("zygomatic_major_l")] = 1.0;
  v[parameter_index("triangularis_r")] = 0.8;
  return v;
}

TEST(LipBinding, BoundVerticesFollowTheDeformedSurface) {
  const HandMade h = hand_made();
  const FaceSolver solver(h.face.mesh, h.face.rig);
  const Deformation rest = solver.deform(std::vector<double>(kParameterCount, 0.0));
  EXPECT_LT((rest.vertices - h.face.mesh.vertices).cwiseAbs().maxCoeff(), 1e-15);
  const auto values = lip_values();
  const Deformation d = solver.deform(values);
  // the lips did move (else this test could not fail)
  double moved = 0.0;
  for (std::size_t c = 0; c < d.lip_control_points.size(); ++c) {
    moved = std::max(moved, (d.lip_control_points[c] - h.face.rig.lips.control_points[c]).norm());
  }
  EXPECT_GT(moved, 0.003);
  const double jaw = values[parameter_index("masseter")] * h.face.rig.jaw.max_angle;
  for (int k = 0; k < 15; ++k) {
    const Eigen::Vector3d s = surface(d.lip_control_points, h.us[static_cast<std::size_t>(k)], h.vs[static_cast<std::size_t>(k)]);
    const Eigen::Vector3d x = d.vertices.row(k).transpose();
    if (k == 0) {
      EXPECT_LT((x - (s + Eigen::Vector3d(0.001, -0.0005, 0.002))).norm(), 1e-12);  // offset kept
    } else if (k == 1) {
      // weight 0.5: halfway between the jaw-rotated vertex and the surface
      const Eigen::Vector3d pivot = h.face.rig.jaw.pivot;
      const Eigen::Vector3d p0 = h.face.mesh.vertices.row(1).transpose();
      const Eigen::Vector3d rotated = pivot + Eigen::AngleAxisd(jaw, Eigen::Vector3d::UnitX()) * (p0 - pivot);
      EXPECT_LT((x - 0.5 * (rotated + s)).norm(), 1e-12);
      EXPECT_GT((rotated - s).norm(), 1e-3);  // the blend is not trivially one of its ends
    } else {
      EXPECT_LT((x - s).norm(), 1e-12) << "vertex " << k;
    }
  }
  Deformation r;
  solver.deform_reference(values, r);
  EXPECT_LT((r.vertices - d.vertices).cwiseAbs().maxCoeff(), 1e-12);
}

// The built-in face with its lip samples turned into bindings (their own (u, v), offset 0, weight 1)
// and the grid taken out of the mesh.
fm::Rig bound_default_rig() {
  fm::Rig rig = face().rig;
  const auto& lips = rig.lips;
  rig.lips.samples_in_mesh = false;
  for (int j = 0; j < lips.samples_across; ++j) {
    for (int i = 0; i < lips.samples_around; ++i) {
      fm::LipBinding b;
      b.vertex = lips.first_vertex + j * lips.samples_around + i;
      b.u = static_cast<double>(i) / lips.samples_around;
      b.v = static_cast<double>(j) / (lips.samples_across - 1);
      rig.lips.bound.push_back(b);
    }
  }
  return rig;
}

TEST(LipBinding, BuiltInFaceThroughBindingsEqualsTheGrid) {
  const FaceSolver grid(face().mesh, face().rig);
  const FaceSolver bound(face().mesh, bound_default_rig());
  DeformWorkspace wa, wb;
  Deformation a, b;
  for (std::size_t p = 0; p < kParameterCount; ++p) {
    std::vector<double> values(kParameterCount, 0.0);
    values[p] = p < kSideParameterCount ? 1.0 : 0.3;
    grid.deform(values, a, wa);
    bound.deform(values, b, wb);
    EXPECT_LT((a.vertices - b.vertices).cwiseAbs().maxCoeff(), 1e-12) << parameter_names()[p];
    EXPECT_EQ(a.crease, b.crease) << parameter_names()[p];
  }
  std::vector<double> all(kParameterCount, 0.7);
  for (std::size_t p = kSideParameterCount; p < kParameterCount; ++p) all[p] = 0.1;
  grid.deform(all, a, wa);
  bound.deform(all, b, wb);
  EXPECT_LT((a.vertices - b.vertices).cwiseAbs().maxCoeff(), 1e-12);
  Deformation r;
  bound.deform_reference(all, r);
  EXPECT_LT((r.vertices - b.vertices).cwiseAbs().maxCoeff(), 1e-9);  // the fast path's own tolerance
}

TEST(LipBinding, NoGridResamplingWhenTheSamplesAreNotInTheMesh) {
  fm::Rig rig = face().rig;
  rig.lips.samples_in_mesh = false;  // and no bindings: the old sample vertices are ordinary vertices
  const FaceSolver grid(face().mesh, face().rig), free(face().mesh, rig);
  std::vector<double> values(kParameterCount, 0.0);
  values[parameter_index("orbicularis_oris_funneler")] = 1.0;  // moves the control points only
  const Deformation a = grid.deform(values), b = free.deform(values);
  const long first = rig.lips.first_vertex, count = rig.lips.samples_around * rig.lips.samples_across;
  EXPECT_GT((a.vertices.middleRows(first, count) - face().mesh.vertices.middleRows(first, count)).cwiseAbs().maxCoeff(), 1e-3);
  EXPECT_EQ(b.vertices, face().mesh.vertices);
}

// The border's jaw weights (rig format 1.2, LipGrid::border_jaw): the solver's own derivation
// stored in the rig changes nothing; explicit weights turn each border control point about the jaw
// axis (parallel to x through the pivot) by masseter · max_angle · weight, and the innermost row by
// the thesis' weight alone (§2.4.4: lower lip middle 1), whatever the border's.
TEST(LipBorderJaw, StoredWeightsAreUsedAndTheDerivedOnesChangeNothing) {
  const auto derived = lip_border_jaw_weights(face().mesh, face().rig);
  ASSERT_EQ(derived.size(), static_cast<std::size_t>(fm::LipGrid::kAround));
  double sum = 0.0;
  for (double w : derived) {
    EXPECT_GE(w, 0.0);
    EXPECT_LE(w, 1.0);
    sum += w;
  }
  EXPECT_GT(sum, 1.0);  // the lower lip's border follows the chin
  fm::Rig stored = face().rig;
  stored.lips.border_jaw = derived;
  std::vector<double> values(kParameterCount, 0.0);
  values[parameter_index("masseter")] = 1.0;
  EXPECT_EQ(FaceSolver(face().mesh, face().rig).deform(values).vertices,
            FaceSolver(face().mesh, stored).deform(values).vertices);

  fm::Rig half = face().rig;
  half.lips.border_jaw.assign(fm::LipGrid::kAround, 0.5);
  const Deformation d = FaceSolver(face().mesh, half).deform(values);
  const auto& cps = half.lips.control_points;
  const Eigen::Vector3d pivot = half.jaw.pivot;
  auto angle = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {  // about x, yz plane
    const Eigen::Vector2d p = (a - pivot).tail<2>(), q = (b - pivot).tail<2>();
    return std::abs(std::atan2(p.x() * q.y() - p.y() * q.x(), p.dot(q)));
  };
  const int na = fm::LipGrid::kAround;
  for (int c : {0, 6, 12, 18}) {
    const auto i = static_cast<std::size_t>(c);
    EXPECT_NEAR(angle(cps[i], d.lip_control_points[i]), 0.5 * half.jaw.max_angle, 1e-12) << c;
    EXPECT_DOUBLE_EQ(d.lip_control_points[i].x(), cps[i].x());
  }
  const auto inner = static_cast<std::size_t>((fm::LipGrid::kAcross - 1) * na + 18);  // sin = −1
  EXPECT_NEAR(angle(cps[inner], d.lip_control_points[inner]), half.jaw.max_angle, 1e-12);

  fm::Rig bad = face().rig;
  bad.lips.border_jaw.assign(5, 0.5);
  EXPECT_THROW(FaceSolver(face().mesh, bad), InvalidInput);
  bad.lips.border_jaw.assign(fm::LipGrid::kAround, 1.5);
  EXPECT_THROW(FaceSolver(face().mesh, bad), InvalidInput);
  bad = face().rig;
  bad.jaw.vertices.push_back(static_cast<int>(face().mesh.vertices.rows()));
  bad.jaw.weights.push_back(1.0);
  EXPECT_THROW(lip_border_jaw_weights(face().mesh, bad), InvalidInput);
}

}  // namespace
}  // namespace emoface::muscles
