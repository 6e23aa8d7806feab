#include "emoface/retarget/align.hpp"

#include <cmath>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "test_shapes.hpp"

namespace fm = emoface::facemesh;
namespace rt = emoface::retarget;

namespace {
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
  o.up = rt::Axis::NegZ;
  o.front = rt::Axis::PosX;
  const Eigen::Vector3d top = head.vertices.row(0), nose_p = head.vertices.row(nose);
  const auto a = rt::align_to_frame(input, top, nose_p, o);
  EXPECT_NEAR(a.scale, 1.0 / 7.0, 1e-12);
  const auto back = a.apply(input.vertices);
  EXPECT_LT((back - head.vertices).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((a.inverse(back) - input.vertices).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(a.rotation.determinant(), 1.0, 1e-12);
}

TEST(Align, DegenerateTargetsGiveClearErrors) {
  auto flat = nosed_head();
  flat.vertices.col(1).setZero();  // no height at all
  EXPECT_THROW(rt::align_to_frame(flat, {0, 0.1, 0}, {0, 0, 0.1}), emoface::InvalidInput);
  // A source whose nose tip is not below its top of head is rejected.
  EXPECT_THROW(rt::align_to_frame(nosed_head(), {0, 0.0, 0}, {0, 0.1, 0.1}), emoface::InvalidInput);
}
