// Synthetic validation suite (issue #6): the default face under known warps, re-tessellated and moved,
// fitted back; surface distance (FLANN) and landmark error against the known truth.
#include "emoface/retarget/validation.hpp"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/retarget/retarget.hpp"
#include "test_shapes.hpp"

namespace fm = emoface::facemesh;
namespace rt = emoface::retarget;

namespace {
const fm::Face& face() {
  static const fm::Face f = fm::make_default_face();
  return f;
}

struct Case {
  const char* name;
  rt::SyntheticWarp warp;
  bool subdivide = false;
  rt::Axis up = rt::Axis::PosY, front = rt::Axis::PosZ;
};

struct Outcome {
  double mean_pct, p95_pct, landmark_pct, initial_error, final_error;
};

// Front skin of the deformed face: skin material, z > 0, above the source chin.
std::vector<std::uint8_t> front_mask(const fm::Face& f, double chin_y) {
  std::vector<std::uint8_t> m(f.mesh.vertex_count(), 0);
  for (Eigen::Index i = 0; i < f.mesh.vertices.rows(); ++i)
    m[static_cast<std::size_t>(i)] = f.rig.materials[static_cast<std::size_t>(i)] == fm::Material::Skin &&
                                     f.mesh.vertices(i, 2) > 0.0 && f.mesh.vertices(i, 1) > chin_y;
  return m;
}

Outcome run_case(const Case& c, const rt::RetargetOptions& options) {
  fm::Mesh target = face().mesh;
  target.vertices = c.warp.apply(target.vertices);
  if (c.subdivide) target = fm::subdivide_midpoint(target);
  rt::RetargetOptions o = options;
  o.align.up = c.up;
  o.align.front = c.front;
  const auto r = rt::retarget_face(face(), target, o);
  const double chin_y = rt::landmark_position(face(), "chin").y();
  const double head = rt::landmark_position(face(), "top_of_head").y() - chin_y;  // thesis-frame head height
  const auto d = rt::surface_distance(r.face.mesh, r.aligned_target, front_mask(r.face, chin_y));
  double lm = 0;
  int n = 0;
  for (std::size_t i = 0; i < r.landmark_names.size(); ++i) {
    if (r.detected[i] || r.landmark_names[i] == "back_of_head") continue;
    const Eigen::Vector3d truth = r.alignment.apply(c.warp.apply(Eigen::Vector3d(r.source_landmarks.row(static_cast<Eigen::Index>(i)))));
    lm += (truth - r.target_landmarks.row(static_cast<Eigen::Index>(i)).transpose()).norm();
    ++n;
  }
  return {100 * d.mean / head, 100 * d.p95 / head, 100 * lm / n / head, r.ga.initial_error, r.ga.best_error};
}

std::vector<Case> suite() {
  std::vector<Case> cases;
  auto add = [&](const char* name, auto edit, bool subdivide = false, rt::Axis up = rt::Axis::PosY, rt::Axis front = rt::Axis::PosZ) {
    Case c{name, {}, subdivide, up, front};
    edit(c.warp);
    cases.push_back(c);
  };
  add("wide", [](rt::SyntheticWarp& w) { w.width = 1.12; });
  add("narrow", [](rt::SyntheticWarp& w) { w.width = 0.9; });
  add("long", [](rt::SyntheticWarp& w) { w.height = 1.1; });
  add("short_deep", [](rt::SyntheticWarp& w) { w.height = 0.92; w.depth = 1.08; });
  add("taper", [](rt::SyntheticWarp& w) { w.taper = 0.1; });
  add("big_nose", [](rt::SyntheticWarp& w) { w.nose = 0.008; });
  add("long_chin", [](rt::SyntheticWarp& w) { w.chin = 0.01; });
  add("subdivided_wide", [](rt::SyntheticWarp& w) { w.width = 1.08; w.nose = 0.005; }, true);
  add("z_up_scaled_moved", [](rt::SyntheticWarp& w) {
    w.width = 1.05;
    w.rotation = Eigen::Vector3d(0, -1.5707963267948966, 0);  // pitch −90°: top along −z, face along +y
    w.scale = 10.0;
    w.translation = Eigen::Vector3d(3, -2, 5);
  }, false, rt::Axis::NegZ, rt::Axis::PosY);
  return cases;
}
}  // namespace

TEST(SurfaceDistance, SphereToSphereIsTheRadiusGap) {
  const auto a = emoface::retarget::test::ellipsoid(0.1, 0.1, 0.1, 30, 48);
  const auto b = emoface::retarget::test::ellipsoid(0.12, 0.12, 0.12, 60, 96);
  const auto d = rt::surface_distance(a, b);
  EXPECT_NEAR(d.mean, 0.02, 5e-4);
  EXPECT_NEAR(d.p95, 0.02, 5e-4);
  EXPECT_LE(d.p95, d.max);
  const auto self = rt::surface_distance(a, a);
  EXPECT_LT(self.max, 1e-12);
  EXPECT_THROW(rt::surface_distance(a, b, std::vector<std::uint8_t>(3, 1)), emoface::InvalidInput);
  EXPECT_THROW(rt::surface_distance(a, b, std::vector<std::uint8_t>(a.vertex_count(), 0)), emoface::InvalidInput);
}

TEST(SurfaceDistance, ClosestPointOnTriangle) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(rt::closest_point_on_triangle({0.2, 0.2, 1}, a, b, c).isApprox(Eigen::Vector3d(0.2, 0.2, 0)));
  EXPECT_TRUE(rt::closest_point_on_triangle({-1, -1, 0}, a, b, c).isApprox(a));
  EXPECT_TRUE(rt::closest_point_on_triangle({1, 1, 0}, a, b, c).isApprox(Eigen::Vector3d(0.5, 0.5, 0)));
  EXPECT_TRUE(rt::closest_point_on_triangle({0.5, -2, 0}, a, b, c).isApprox(Eigen::Vector3d(0.5, 0, 0)));
}

TEST(SyntheticWarp, IdentityByDefaultAndValidated) {
  const rt::SyntheticWarp w;
  const Eigen::Vector3d p(0.01, -0.08, 0.05);
  EXPECT_TRUE(w.apply(p).isApprox(p));
  rt::SyntheticWarp bad;
  bad.width = 0.0;
  EXPECT_THROW(bad.validate(), emoface::InvalidInput);
}

// The whole suite with the default options: labelled slow (ctest -L slow).
TEST(ValidationSuite, SyntheticTargets) {
  rt::RetargetOptions o;
  for (const auto& c : suite()) {
    const auto out = run_case(c, o);
    std::printf("%-20s mean %.3f%%  p95 %.3f%%  landmarks %.3f%%  E %.3g -> %.3g\n", c.name, out.mean_pct, out.p95_pct,
                out.landmark_pct, out.initial_error, out.final_error);
    EXPECT_LE(out.final_error, out.initial_error) << c.name;
    EXPECT_LT(out.mean_pct, 1.0) << c.name;
    EXPECT_LT(out.p95_pct, 3.0) << c.name;
  }
}
