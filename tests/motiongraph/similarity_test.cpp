#include "emoface/motiongraph/similarity.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "emoface/core/errors.hpp"

namespace emoface::motiongraph {
namespace {

SimilarityOptions with_lambda(double l) {
  SimilarityOptions o;
  o.lambda = l;
  return o;
}

// eq. (1) by hand: landmark 1 dist 1, velocities at 90° (vinfl 1) → 1 + λ; landmark 2 dist 5,
// velocities opposite (vinfl 0) → 5. λ = 0.5 → 6.5.
TEST(Similarity, HandComputedValue) {
  Eigen::RowVectorXd pa(4), pb(4), va(4), vb(4);
  pa << 0, 0, 3, 4;
  pb << 1, 0, 0, 0;
  va << 1, 0, 1, 1;
  vb << 0, 1, -2, -2;
  EXPECT_DOUBLE_EQ(similarity(pa, va, pb, vb, 2, with_lambda(0.5)), 6.5);
  EXPECT_DOUBLE_EQ(similarity(pa, va, pb, vb, 2, with_lambda(0.0)), 6.0);
  EXPECT_DOUBLE_EQ(similarity(pa, va, pb, vb, 2, with_lambda(2.0)), 8.0);
}

// 45°: vinfl = 1 − 1/√2 = 0.2928932188; dist 2, λ = 0.5 → 2 + 0.5·0.29289·2 = 2.2928932188.
TEST(Similarity, FortyFiveDegrees) {
  Eigen::RowVectorXd pa(2), pb(2), va(2), vb(2);
  pa << 0, 0;
  pb << 0, 2;
  va << 1, 0;
  vb << 3, 3;
  EXPECT_NEAR(similarity(pa, va, pb, vb, 2, with_lambda(0.5)), 2.2928932188134525, 1e-12);
  const double v1[2] = {1, 0}, v2[2] = {3, 3};
  EXPECT_NEAR(velocity_influence(v1, v2, 2, 1e-6), 1.0 - std::sqrt(0.5), 1e-12);
}

TEST(Similarity, ThreeDimensionsAndStillLandmarks) {
  Eigen::RowVectorXd pa(3), pb(3), v0 = Eigen::RowVectorXd::Zero(3), v1(3);
  pa << 1, 2, 2;  // dist 3 from the origin
  pb << 0, 0, 0;
  v1 << 0, 0, 1;
  EXPECT_DOUBLE_EQ(similarity(pa, v0, pb, v0, 3, with_lambda(1.0)), 3.0);  // both still: vinfl 0
  EXPECT_DOUBLE_EQ(similarity(pa, v0, pb, v1, 3, with_lambda(1.0)), 6.0);  // one still: vinfl 1
}

TEST(Similarity, Properties) {
  Eigen::RowVectorXd pa = Eigen::RowVectorXd::Random(10), pb = Eigen::RowVectorXd::Random(10);
  Eigen::RowVectorXd va = Eigen::RowVectorXd::Random(10), vb = Eigen::RowVectorXd::Random(10);
  const auto o = with_lambda(0.7);
  EXPECT_DOUBLE_EQ(similarity(pa, va, pa, vb, 2, o), 0.0);  // identity of positions
  EXPECT_DOUBLE_EQ(similarity(pa, va, pb, vb, 2, o), similarity(pb, vb, pa, va, 2, o));  // symmetric
  const double plain = similarity(pa, va, pb, vb, 2, with_lambda(0.0));
  const double s = similarity(pa, va, pb, vb, 2, o);
  EXPECT_GE(s, plain);
  EXPECT_LE(s, (1.0 + 0.7) * plain + 1e-12);
  // Reversing a velocity does not change the value (onset vs offset, §4.2).
  EXPECT_DOUBLE_EQ(similarity(pa, va, pb, -vb, 2, o), s);
}

TEST(Similarity, BadInput) {
  Eigen::RowVectorXd a(4), b(3);
  a.setZero();
  b.setZero();
  EXPECT_THROW(similarity(a, a, b, b, 2, {}), InvalidInput);
  EXPECT_THROW(similarity(b, b, b, b, 2, {}), InvalidInput);
  EXPECT_THROW(with_lambda(-1).validate(), InvalidInput);
}

}  // namespace
}  // namespace emoface::motiongraph
