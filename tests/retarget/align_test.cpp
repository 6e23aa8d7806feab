#include "emoface/retarget/align.hpp"

#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/retarget/retarget.hpp"
#include "emoface/retarget/validation.hpp"
#include "test_shapes.hpp"

namespace fm = emoface::facemesh;
namespace rt = emoface::retarget;

namespace {
const fm::Face& face() {
  static const fm::Face f = fm::make_generic_face();
  return f;
}
Eigen::Vector3d top() { return rt::landmark_position(face(), "top_of_head"); }
Eigen::Vector3d nose() { return rt::landmark_position(face(), "nose_tip"); }

// An ellipsoid "head" with a nose: the vertex nearest the front at y = −0.03 pushed forward by 3 cm.
fm::Mesh nosed_head(int* nose = nullptr) {
  auto m = rt::test::ellipsoid(0.08, 0.11, 0.09, 30, 48);
  Eigen::Index best = 0;
  for (Eigen::Index i = 0; i < m.vertices.rows(); ++i)
    if ((m.vertices.row(i) - Eigen::RowVector3d(0, -0.03, 0.09)).norm() < (m.vertices.row(best) - Eigen::RowVector3d(0, -0.03, 0.09)).norm()) best = i;
  m.vertices(best, 2) += 0.03;
  if (nose) *nose = static_cast<int>(best);
  return m;
}
}  // namespace

TEST(Align, AxisStringRoundTrip) {
  for (int i = 0; i < 6; ++i) EXPECT_EQ(rt::axis_from_string(rt::to_string(static_cast<rt::Axis>(i))), static_cast<rt::Axis>(i));
  EXPECT_THROW(rt::axis_from_string("y"), emoface::InvalidInput);
  rt::AlignOptions o;
  o.front = rt::Axis::NegY;
  o.mode = rt::AlignMode::Axes;
  EXPECT_THROW(o.validate(), emoface::InvalidInput);  // up defaults to +y in axes mode
  o.mode = rt::AlignMode::Auto;
  o.up = rt::Axis::PosY;
  EXPECT_THROW(o.validate(), emoface::InvalidInput);
  o.front = rt::Axis::PosX;
  EXPECT_NO_THROW(o.validate());
  for (auto m : {rt::AlignMode::Auto, rt::AlignMode::Axes}) EXPECT_EQ(rt::align_mode_from_string(rt::to_string(m)), m);
  EXPECT_THROW(rt::align_mode_from_string("pca"), emoface::InvalidInput);
  o.samples = 10;
  EXPECT_THROW(o.validate(), emoface::InvalidInput);
}

TEST(Align, DetectsTopNoseAndEars) {
  int nose = 0;
  const auto m = nosed_head(&nose);
  const auto lm = rt::detect_landmarks(m);
  ASSERT_EQ(lm.size(), 4u);
  EXPECT_EQ(lm[0].vertex, 0);  // the ellipsoid's top pole
  EXPECT_EQ(lm[1].vertex, nose);
  EXPECT_NEAR(m.vertices(lm[2].vertex, 0), -0.08, 0.002);  // ear_r at −x
  EXPECT_NEAR(m.vertices(lm[3].vertex, 0), 0.08, 0.002);
  EXPECT_THROW(rt::detect_landmarks(m, {"elbow"}), emoface::InvalidInput);
  EXPECT_THROW(rt::detect_landmarks(fm::Mesh{}), emoface::InvalidInput);
}

TEST(Align, RecoversAKnownSimilarity) {
  int nose = 0;
  const auto head = nosed_head(&nose);
  // Input: the head lying with its top along −z and its face along +x, 7× larger, moved.
  fm::Mesh input = head;
  for (Eigen::Index i = 0; i < head.vertices.rows(); ++i) {
    const Eigen::Vector3d p = head.vertices.row(i);
    input.vertices.row(i) = (7.0 * Eigen::Vector3d(p.z(), -p.x(), -p.y()) + Eigen::Vector3d(1, 2, 3)).transpose();
  }
  rt::AlignOptions o;
  o.mode = rt::AlignMode::Axes;
  o.up = rt::Axis::NegZ;
  o.front = rt::Axis::PosX;
  const Eigen::Vector3d top = head.vertices.row(0), nose_p = head.vertices.row(nose);
  const auto a = rt::align_to_frame(input, head, top, nose_p, o);
  EXPECT_EQ(a.report.method, rt::AlignMode::Axes);
  EXPECT_NEAR(a.report.angle_deg, 120.0, 1e-9);  // (x,y,z) -> (z,-x,-y) is 120 deg about (1,-1,1)/sqrt(3)
  EXPECT_LT(std::abs(std::abs(a.report.axis.dot(Eigen::Vector3d(1, -1, 1).normalized())) - 1.0), 1e-9);
  EXPECT_NEAR(a.scale, 1.0 / 7.0, 1e-12);
  const auto back = a.apply(input.vertices);
  EXPECT_LT((back - head.vertices).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((a.inverse(back) - input.vertices).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(a.rotation.determinant(), 1.0, 1e-12);
}

TEST(Align, DegenerateTargetsGiveClearErrors) {
  const auto& src = face();
  auto flat = nosed_head();
  flat.vertices.col(1).setZero();  // no height at all
  rt::AlignOptions axes;
  axes.mode = rt::AlignMode::Axes;
  EXPECT_THROW(rt::align_to_frame(flat, src.mesh, top(), nose(), axes), emoface::InvalidInput);
  // A source whose nose tip is not below its top of head is rejected.
  EXPECT_THROW(rt::align_to_frame(nosed_head(), src.mesh, {0, 0.0, 0}, {0, 0.1, 0.1}, axes), emoface::InvalidInput);
  // Auto: flat (all coplanar), a single triangle, NaN, empty -> clear errors.
  auto expect_message = [&](const fm::Mesh& m, const std::string& part) {
    try {
      rt::align_to_frame(m, src.mesh, top(), nose());
      ADD_FAILURE() << "no error for " << part;
    } catch (const emoface::InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  expect_message(flat, "flat");
  fm::Mesh tri;
  tri.vertices.resize(3, 3);
  tri.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  tri.faces.resize(1, 3);
  tri.faces << 0, 1, 2;
  expect_message(tri, "flat");
  auto nan = nosed_head();
  nan.vertices(5, 1) = std::nan("");
  expect_message(nan, "NaN");
  expect_message(fm::Mesh{}, "no faces");
}

TEST(Align, SphereGivesALowConfidence) {
  // Every plane through the centre is a symmetry plane and every pose matches equally badly.
  const auto sphere = rt::test::ellipsoid(0.1, 0.1, 0.1, 30, 48);
  const auto a = rt::align_to_frame(sphere, face().mesh, top(), nose());
  EXPECT_LT(a.report.confidence, 0.2) << a.report.message;
  EXPECT_LT(a.report.symmetry_margin, 0.2);
  // retarget_face refuses it with a message naming the cure.
  try {
    rt::retarget_face(face(), sphere);
    ADD_FAILURE() << "sphere accepted";
  } catch (const emoface::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("--align axes"), std::string::npos) << e.what();
  }
}

TEST(Align, SurfaceSamplesAreSeededAndFollowRotations) {
  const auto& m = face().mesh;
  const auto a = rt::sample_surface(m, 500, 3), b = rt::sample_surface(m, 500, 3), c = rt::sample_surface(m, 500, 4);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  fm::Mesh rotated = m;
  rotated.vertices = (m.vertices * r.transpose()).eval();
  const auto ar = rt::sample_surface(rotated, 500, 3);
  EXPECT_LT((ar - a * r.transpose()).cwiseAbs().maxCoeff(), 1e-9);
  // By area: a zero-area triangle gets no sample.
  fm::Mesh sq;
  sq.vertices.resize(4, 3);
  sq.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 2, 2, 0;
  sq.faces.resize(2, 3);
  sq.faces << 0, 1, 2, 0, 2, 3;  // areas 0.5 and 0 (collinear)
  const auto s = rt::sample_surface(sq, 100, 1);
  for (Eigen::Index i = 0; i < s.rows(); ++i) EXPECT_LE(s(i, 1), s(i, 0) + 1e-12);  // all in the first triangle
  EXPECT_THROW(rt::sample_surface(fm::Mesh{}, 10, 1), emoface::InvalidInput);
}

// Any rotation (seeded random), scale and translation of the default face and of warped variants: the
// frame is recovered within a few degrees, with a high confidence.
TEST(Align, RecoversArbitraryRotations) {
  emoface::core::Rng rng(2026, 0);
  std::vector<rt::SyntheticWarp> warps(4);
  warps[1].width = 1.1;
  warps[1].nose = 0.006;
  warps[2].taper = 0.1;
  warps[2].chin = 0.01;
  warps[3].height = 0.92;
  warps[3].depth = 1.08;
  double worst = 0;
  for (std::size_t k = 0; k < warps.size(); ++k)
    for (int trial = 0; trial < 3; ++trial) {
      const Eigen::Quaterniond q(rng.normal(), rng.normal(), rng.normal(), rng.normal());
      const Eigen::Matrix3d truth = q.normalized().toRotationMatrix();
      const double scale = std::exp(rng.uniform(-3, 3));
      const Eigen::Vector3d shift(rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5));
      fm::Mesh input = face().mesh;
      input.vertices = warps[k].apply(input.vertices);
      for (Eigen::Index i = 0; i < input.vertices.rows(); ++i)
        input.vertices.row(i) = (scale * (truth * Eigen::Vector3d(input.vertices.row(i))) + shift).transpose();
      const auto a = rt::align_to_frame(input, face().mesh, top(), nose());
      const double err = Eigen::AngleAxisd(a.rotation * truth).angle() * 180 / 3.14159265358979323846;
      worst = std::max(worst, err);
      // The non-rigid warps have no exact rigid truth (y × 0.92 with z × 1.08 turns 45° lines by 4.6°).
      EXPECT_LT(err, k == 0 ? 0.5 : 5.0) << "warp " << k << " trial " << trial << ": " << a.report.message;
      EXPECT_GT(a.report.confidence, 0.3) << a.report.message;
      EXPECT_TRUE(a.report.nose_on_plane && a.report.top_on_plane);
      if (k == 0) EXPECT_NEAR(a.scale * scale, 1.0, 1e-3);
    }
  std::printf("worst rotation error %.2f deg\n", worst);
}

TEST(Align, HintsRestrictThePoses) {
  // The head lying on its back (face along +y): with the hints up = -z, front = +y the pose is found and
  // the report says the hints were used; hints that contradict the geometry leave no pose.
  fm::Mesh input = face().mesh;
  const Eigen::Matrix3d r = Eigen::AngleAxisd(-1.5707963267948966, Eigen::Vector3d::UnitX()).toRotationMatrix();
  input.vertices = (face().mesh.vertices * r.transpose()).eval();
  rt::AlignOptions o;
  o.up = rt::Axis::NegZ;
  o.front = rt::Axis::PosY;
  const auto a = rt::align_to_frame(input, face().mesh, top(), nose(), o);
  EXPECT_TRUE(a.report.hints_used);
  EXPECT_LT(Eigen::AngleAxisd(a.rotation * r).angle(), 0.05);
  o.up = rt::Axis::PosX;
  o.front = rt::Axis::PosZ;
  EXPECT_THROW(rt::align_to_frame(input, face().mesh, top(), nose(), o), emoface::InvalidInput);
}
